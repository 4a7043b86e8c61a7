#!/usr/bin/env bash
# The side-by-side benchmark (issue 16): insitu against Blender 3.4's Cycles (Debian's `blender`) on
# a validation scene of tools/validate/, in one run on this machine. Each renderer renders the
# scene with the objects at a ladder of samples per pixel and a reference with another seed; its
# noise is its relative RMSE over the objects + the pixels they change (the validation's
# mask_all.png) against its own reference; the time to 2 % follows from the 1/√spp law
# (bench/cycles/side_by_side.py). Heavy (the reference renders): not part of CI.
#
#   bash bench/cycles/run.sh tools/validate/open_ground OUT_DIR
#   LADDER=16,64,256,1024 REFERENCE=4096 bash bench/cycles/run.sh ...   (the defaults)
#
# It needs the scene's validation output (insitu's inputs and the masks) in OUT_DIR/validation
# (or VALIDATION_OUT): a copy of the committed truths of tests/data/validation/<scene> completed
# by tools/validate/run.sh --reuse, or the whole of run.sh where none is committed. Skips with a
# message without blender.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
scene_dir=$(cd "${1:?a validation scene folder (tools/validate/open_ground)}" && pwd)
out=${2:?an output folder}
insitu=${INSITU:-$root/build/insitu}
ladder=${LADDER:-16,64,256,1024}
reference=${REFERENCE:-4096}
command -v blender >/dev/null || { echo "bench/cycles: blender is not installed (apt-get install blender): skipped"; exit 0; }
[ -x "$insitu" ] || { echo "bench/cycles: $insitu is not built" >&2; exit 2; }
val=${VALIDATION_OUT:-$out/validation}
committed="$root/tests/data/validation/$(basename "$scene_dir")"
if [ ! -f "$val/scene.json" ] && [ -f "$committed/scene.json" ]; then
  mkdir -p "$val" && cp -r "$committed"/. "$val"/
fi
if [ ! -f "$val/scene.json" ] || [ ! -f "$val/mask_all.png" ]; then
  reuse=""
  [ -f "$val/scene.json" ] && reuse=--reuse  # the truth is there: only the masks are missing
  echo "bench/cycles: making the validation output $val first (tools/validate/run.sh $reuse)"
  SPP_LADDER=16 bash "$root/tools/validate/run.sh" "$scene_dir" "$val" $reuse
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)

echo "bench/cycles: Cycles, spp $ladder and a $reference-spp reference"
blender -b --factory-startup --python "$root/tools/validate/cycles_render.py" -- \
  "$scene_dir/scene.json" "$out" --ladder "$ladder" --reference "$reference" > "$out/cycles.log" 2>&1

# insitu: each render a process of its own, timed whole (loading the room included).
echo "bench/cycles: insitu, spp $ladder and a $reference-spp reference"
: > "$out/insitu_times.csv"
for entry in $(echo "$ladder" | tr , ' ') "reference:$reference"; do
  name=${entry%%:*} spp=${entry##*:} seed=1
  [ "$name" = reference ] && seed=2
  start=$EPOCHREALTIME
  "$insitu" render "$val/scene.json" --spp "$spp" --seed "$seed" -o "$out/insitu_$name.exr" --layers none \
    > /dev/null 2> "$out/insitu_$name.log"
  awk -v n="$name" -v s="$spp" -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%s,%s,%.3f\n", n, s, b - a }' \
    >> "$out/insitu_times.csv"
done

/usr/bin/python3 "$here/side_by_side.py" "$out" "$val/mask_all.png" "$val/mask_objects.png"
