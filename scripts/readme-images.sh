#!/usr/bin/env bash
# Regenerates the README's pictures and figures from the demo scene with the current build:
# docs/images/demo-{photo,path,chair,realtime,shadow-ratio,ab}.png and docs/tradeoff/ (the table in the
# "Speed against accuracy" of docs/performance.md is printed by the last step). Run after the build:
#   bash scripts/readme-images.sh            (about 13 minutes on 2 cores; --no-tradeoff: 7)
set -euo pipefail
cd "$(dirname "$0")/.."
insitu=build/insitu
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=scenes/demo/scene.json

"$insitu" render "$scene"  # the README's first command: scenes/demo/out/composite.png, layers.exr
cp scenes/demo/out/composite.png docs/images/demo-path.png
oiiotool scenes/demo/photo.jpg -o docs/images/demo-photo.png
# The glTF armchair, at 1024 spp: the floor under its glass top is lit only through the glass.
"$insitu" render scenes/demo/scene_chair.json --spp 1024 -o "$tmp/chair.png" --layers none
cp "$tmp/chair.png" docs/images/demo-chair.png
"$insitu" render "$scene" --integrator realtime --spp 16 -o "$tmp/realtime.png" --layers none
cp "$tmp/realtime.png" docs/images/demo-realtime.png
# The shadow ratio W/N, white = 1 (ratios above 1, bounce light, clip to white), sRGB-encoded.
oiiotool scenes/demo/out/layers.exr --ch shadow_ratio.R,shadow_ratio.G,shadow_ratio.B --chnames R,G,B \
  --clamp:min=0:max=1 --colorconvert linear sRGB -d uint8 -o docs/images/demo-shadow-ratio.png
"$insitu" compare "$tmp/realtime.png" scenes/demo/out/composite.png -o docs/images/demo-ab.png
if [ "${1:-}" != "--no-tradeoff" ]; then
  "$insitu" tradeoff "$scene" -o docs/tradeoff --ladder 1,4,16,64,256 --reference-spp 1024 --noise-targets 0.04,0.02,0.01
fi
