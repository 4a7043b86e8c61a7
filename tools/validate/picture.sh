#!/usr/bin/env bash
# The validation picture (docs/validation.md): insitu | Cycles | |ΔY| × 4, in sRGB.
#   bash tools/validate/picture.sh OUT_DIR insitu_1024.exr docs/images/validation_closed_room.png
set -euo pipefail
out=${1:?the folder run.sh wrote}
image=${2:?an insitu render in it}
png=${3:?the picture to write}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
oiiotool "$out/$image" --ch R,G,B --colorconvert linear sRGB -o "$tmp/a.png"
oiiotool "$out/truth.exr" --ch R,G,B --colorconvert linear sRGB -o "$tmp/b.png"
oiiotool "$out/truth.exr" --ch R,G,B "$out/$image" --ch R,G,B --sub --abs \
  --chsum:weight=0.2126,0.7152,0.0722 --mulc 4 --ch 0,0,0 --colorconvert linear sRGB -o "$tmp/c.png"
oiiotool "$tmp/a.png" "$tmp/b.png" "$tmp/c.png" --mosaic 3x1 -o "$png"
