#!/usr/bin/env bash
# Proves that a change renders nothing differently (issue 11: a restructuring must not change an
# image). `record DIR` renders the demo with every integrator and irradiance mode (linear EXR
# and its layers) and every tone map (PNG) at a few samples per pixel; `check DIR` renders the same again and compares every
# pixel of every channel with idiff at threshold 0 (EXR metadata such as DateTime may differ).
#   bash scripts/bit-identity.sh record /tmp/before   # on the old commit's build
#   bash scripts/bit-identity.sh check /tmp/before    # on the new one
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:?record or check}
dir=${2:?a folder}
insitu=${INSITU:-build/insitu}
scene=scenes/demo/scene.json
out=$dir
[ "$mode" = check ] && out=$(mktemp -d)
mkdir -p "$out"
for integrator in realtime irradiance path; do
  "$insitu" render "$scene" --integrator "$integrator" --spp 4 -o "$out/$integrator.exr" --layers "$out/$integrator.layers.exr" >/dev/null 2>&1
done
# The irradiance integrator above ran in its default mode, exact; now the other modes.
for irradiance in gaussian sh9 volume; do
  "$insitu" render "$scene" --integrator irradiance --irradiance "$irradiance" --spp 4 -o "$out/irradiance-$irradiance.exr" --layers "$out/irradiance-$irradiance.layers.exr" >/dev/null 2>&1
done
for tonemap in photo adaptive_log reinhard linear; do
  "$insitu" render "$scene" --integrator path --spp 4 --tonemap "$tonemap" -o "$out/$tonemap.png" --layers none >/dev/null 2>&1
done
[ "$mode" = record ] && { echo "bit-identity: recorded in $dir"; exit 0; }
status=0
for f in "$dir"/*.exr "$dir"/*.png; do
  name=$(basename "$f")
  if idiff -q -fail 0 -warn 0 -a "$f" "$out/$name" >/dev/null; then echo "identical  $name"; else echo "DIFFERENT  $name"; status=1; fi
done
rm -rf "$out"
exit $status
