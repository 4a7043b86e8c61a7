#!/usr/bin/env bash
# Validation against Cycles (issue 12; docs/validation.md). Renders a validation scene's ground
# truth with Blender 3.4 (Debian's `blender`), runs insitu on it over a ladder of samples per pixel,
# and measures each render against the truth (tools/validate/metrics.py). Heavy: not part of CI.
#   bash tools/validate/run.sh tools/validate/open_ground OUT_DIR [--reuse]
# --reuse keeps OUT_DIR's Cycles renders and only runs insitu and the metrics again.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
scene_dir=$(cd "${1:?a validation scene folder}" && pwd)
out=${2:?an output folder}
insitu=${INSITU:-$root/build/insitu}
command -v blender >/dev/null || { echo "validate: blender is not installed (apt-get install blender): skipped"; exit 0; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
if [ "${3:-}" != --reuse ]; then
  start=$(date +%s)
  blender -b --factory-startup --python "$here/cycles_render.py" -- "$scene_dir/scene.json" "$out" > "$out/cycles.log" 2>&1
  echo "validate: Cycles renders in $(( $(date +%s) - start )) s ($out/cycles.log)"
fi
echo "| spp | seconds | objects + changed | objects | changed | objects' brightness | truth's noise (all) |"
echo "|---|---|---|---|---|---|---|"
for spp in ${SPP_LADDER:-16 64 256 1024}; do
  log=$("$insitu" render "$out/scene.json" --spp "$spp" -o "$out/insitu_$spp.exr" --layers none 2>&1 >/dev/null)
  seconds=$(echo "$log" | sed -n 's/.*render \([0-9.]*\) s$/\1/p')
  m=$(blender -b --factory-startup --python "$here/metrics.py" -- "$out" "insitu_$spp.exr" 2>/dev/null | sed -n 's/^METRICS //p')
  python3 - "$spp" "$seconds" "$m" <<'PY'
import json, sys
spp, seconds, m = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
pc = lambda r: f"{100 * r['relative_rmse']:.1f} %"
print(f"| {spp} | {seconds} | {pc(m['all'])} | {pc(m['objects'])} | {pc(m['changed'])} | "
      f"{m['objects']['brightness']:.3f} | {100 * m['all'].get('truth_noise', 0):.1f} % |")
PY
done
