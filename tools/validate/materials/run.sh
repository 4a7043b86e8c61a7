#!/usr/bin/env bash
# Materials against Cycles (issue 49; docs/validation.md "Materials"): each material scene of
# make.py rendered by insitu, and by Cycles through insitu's own Blender export (Blender's glTF
# importer reads the same file), each as two halves of SPP with seeds 1 and 2 (their noise);
# compare.py measures the object's pixels. The times are the two halves' wall clock, Blender's
# start-up and glTF import included. Heavy: not part of CI.
#   bash tools/validate/materials/run.sh OUT_DIR [SPP]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
out=${1:?an output folder}
spp=${2:-1024}
insitu=${INSITU:-$root/build/insitu}
command -v blender >/dev/null || { echo "materials: blender is not installed (apt-get install blender): skipped"; exit 0; }
python3 "$here/make.py" "$out" ${HDRI:-}
echo "| material | insitu s | Cycles s | relative RMSE | insitu's noise | Cycles's noise | excess | brightness |"
echo "|---|---|---|---|---|---|---|---|"
for scene in "$out"/*.json; do
  name=$(basename "$scene" .json)
  start=$(date +%s.%N)
  for seed in 1 2; do
    "$insitu" render "$scene" --spp $((spp / 2)) --seed "$seed" -o "$out/insitu_${name}_$seed.exr" --layers none \
      > "$out/insitu_${name}_$seed.log" 2>&1
  done
  t_insitu=$(echo "$(date +%s.%N) - $start" | bc)
  "$insitu" export-blender "$scene" -o "$out/cycles_$name.py" > "$out/export_$name.log" 2>&1
  start=$(date +%s.%N)
  for seed in 1 2; do
    blender -b --factory-startup --python "$out/cycles_$name.py" -- --render "$out/cycles_${name}_$seed.exr" \
      --samples $((spp / 2)) --seed "$seed" > "$out/cycles_${name}_$seed.log" 2>&1
  done
  t_cycles=$(echo "$(date +%s.%N) - $start" | bc)
  m=$(blender -b --factory-startup --python "$here/compare.py" -- "$out/insitu_${name}_1.exr" "$out/insitu_${name}_2.exr" \
      "$out/cycles_${name}_1.exr" "$out/cycles_${name}_2.exr" 2>/dev/null | sed -n 's/^METRICS //p')
  python3 - "$name" "$t_insitu" "$t_cycles" "$m" <<'PY'
import json, sys
name, ti, tc, m = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), json.loads(sys.argv[4])
pc = lambda k: f"{100 * m[k]:.2f} %"
print(f"| {name} | {ti:.1f} | {tc:.1f} | {pc('relative_rmse')} | {pc('insitu_noise')} | {pc('cycles_noise')} | "
      f"{pc('excess')} | {m['brightness']:.3f} |")
PY
done
