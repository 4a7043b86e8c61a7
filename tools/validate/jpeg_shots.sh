#!/usr/bin/env bash
# The JPEG-shot variant of a validation scene (issue 12, item 6): the six HDR shots as a phone
# takes them — one 8-bit sRGB JPEG each, exposed for the mid-tones, the lamp and the sun clipped —
# and insitu run on them with the exposure factor that brings them back to the photo's unit.
#   bash tools/validate/jpeg_shots.sh OUT_DIR [SPP]      (after run.sh has filled OUT_DIR)
# Exposure: k = 0.18 / (mean luminance of the floor shot), as an auto-exposure centres the
# mid-tones; every shot is multiplied by k, sRGB-encoded, clipped to 8 bits (quality 95), and the
# scene's "exposure" is 1/k. Writes OUT_DIR/jpeg/, OUT_DIR/scene_jpeg.json and
# OUT_DIR/insitu_jpeg_SPP.exr, and prints the metrics' line.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$(cd "${1:?the folder run.sh wrote}" && pwd)
spp=${2:-256}
insitu=${INSITU:-$root/build/insitu}
mkdir -p "$out/jpeg"
mean=$(oiiotool --stats "$out/shots/shot_down.exr" | sed -n 's/.*Stats Avg: \([^ ]*\) \([^ ]*\) \([^ ]*\).*/\1 \2 \3/p')
k=$(python3 -c "import sys; r, g, b = map(float, sys.argv[1:]); print(0.18 / (0.2126 * r + 0.7152 * g + 0.0722 * b))" $mean)
for f in "$out"/shots/shot_*.exr; do
  oiiotool "$f" --ch R,G,B --mulc "$k" --clamp:min=0:max=1 --colorconvert linear sRGB -d uint8 \
    --attrib Compression jpeg:95 -o "$out/jpeg/$(basename "$f" .exr).jpg"
done
python3 - "$out" "$k" <<'PY'
import json, os, sys
out, k = sys.argv[1], float(sys.argv[2])
s = json.load(open(os.path.join(out, "scene.json")))
shots = s["environment"]["shots"]
for key, v in shots.items():
    if isinstance(v, str) and v.endswith(".exr"):
        shots[key] = "jpeg/" + os.path.basename(v)[:-4] + ".jpg"
s["environment"]["exposure"] = 1.0 / k
json.dump(s, open(os.path.join(out, "scene_jpeg.json"), "w"), indent=2)
PY
"$insitu" render "$out/scene_jpeg.json" --spp "$spp" -o "$out/insitu_jpeg_$spp.exr" --layers none
blender -b --factory-startup --python "$here/metrics.py" -- "$out" "insitu_jpeg_$spp.exr" 2>/dev/null | sed -n 's/^METRICS //p'
