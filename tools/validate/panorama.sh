#!/usr/bin/env bash
# The panorama variant of a validation scene (issue 48): the empty room from the insertion point
# as one equirectangular 8-bit JPEG, as a 360° camera or a phone's panorama mode gives it, and
# insitu run on it in place of the six shots.
#   bash tools/validate/panorama.sh tools/validate/closed_room OUT_DIR [SPP] [WIDTH]
# (after run.sh has filled OUT_DIR from the same scene folder)
# Cycles renders OUT_DIR/pano.exr (cycles_render.py --panorama WIDTH, default 1024). It is exposed
# as jpeg_shots.sh exposes the shots — k = 0.18 / (mean luminance of the floor shot), sRGB, 8 bits,
# quality 95 — so the two JPEG rows compare like for like, and the scene's "exposure" is 1/k.
# Writes OUT_DIR/pano.jpg, OUT_DIR/scene_pano.json and OUT_DIR/insitu_pano_SPP.exr, and prints the
# metrics' line.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
scene_dir=$(cd "${1:?a validation scene folder}" && pwd)
out=$(cd "${2:?the folder run.sh wrote}" && pwd)
spp=${3:-256}
width=${4:-1024}
insitu=${INSITU:-$root/build/insitu}
if [ ! -f "$out/pano.exr" ]; then
  blender -b --factory-startup --python "$here/cycles_render.py" -- "$scene_dir/scene.json" "$out" --panorama "$width" \
    > "$out/cycles_pano.log" 2>&1
fi
mean=$(oiiotool --stats "$out/shots/shot_down.exr" | sed -n 's/.*Stats Avg: \([^ ]*\) \([^ ]*\) \([^ ]*\).*/\1 \2 \3/p')
k=$(python3 -c "import sys; r, g, b = map(float, sys.argv[1:]); print(0.18 / (0.2126 * r + 0.7152 * g + 0.0722 * b))" $mean)
oiiotool "$out/pano.exr" --ch R,G,B --mulc "$k" --clamp:min=0:max=1 --colorconvert linear sRGB -d uint8 \
  --attrib Compression jpeg:95 -o "$out/pano.jpg"
python3 - "$out" "$k" <<'PY'
import json, os, sys
out, k = sys.argv[1], float(sys.argv[2])
s = json.load(open(os.path.join(out, "scene.json")))
env = {key: v for key, v in s["environment"].items() if key not in ("shots", "register")}
env.update({"image": "pano.jpg", "exposure": 1.0 / k})
s["environment"] = env
json.dump(s, open(os.path.join(out, "scene_pano.json"), "w"), indent=2)
PY
"$insitu" render "$out/scene_pano.json" --spp "$spp" -o "$out/insitu_pano_$spp.exr" --layers none
blender -b --factory-startup --python "$here/metrics.py" -- "$out" "insitu_pano_$spp.exr" 2>/dev/null | sed -n 's/^METRICS //p'
