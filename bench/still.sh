#!/bin/bash
# A catalogue still (issue 50; docs/performance.md, "A catalogue still"): the demo room at
# 1920 × 1440 with `path`, by samples per pixel, the seconds it takes and its error against a
# converged reference over the objects and the pixels they change, as rendered and denoised.
#   bash bench/still.sh [INSITU] [WORK]
# WORK (default a new temporary folder, kept) holds the room (bench/big_demo.py), the renders and
# the table; what is there already is not rendered again. Two references with other seeds (101,
# 102) of STILL_REFERENCE_SPP samples each (default 256: 40 minutes of 2 cores), whose own noise
# bench/still_error.py takes out; the ladder is one render of 64 spp (seed 1) split into the
# parts 0:4, 4:8, 8:16, 16:32 and 32:64, whose prefixes `insitu merge` adds, as they are and with
# --denoise. The seconds: load and prepare (the first part's), the parts' render seconds added,
# and the denoiser's. STILL_TOWARD_OBJECTS=F renders the ladder with the path integrator's
# render.toward_objects set to F (its files named -tF; the references are the same converged
# image whatever it is). Needs /usr/bin/python3 with numpy and OpenImageIO (python3-openimageio).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
insitu=$(realpath "${1:-$repo/build/insitu}")
work=${2:-$(mktemp -d /tmp/insitu-still.XXXXXX)}
ref_spp=${STILL_REFERENCE_SPP:-256}
[ -d "$work/room" ] || /usr/bin/python3 "$repo/bench/big_demo.py" "$work/room"
cd "$work/room"
mkdir -p out
for seed in 101 102; do
  [ -f "out/ref$seed.layers.exr" ] ||
    "$insitu" render scene.json --spp "$ref_spp" --seed "$seed" -o "out/ref$seed.exr" 2> "out/ref$seed.log" > /dev/null
done
scene=scene.json
tag=
if [ -n "${STILL_TOWARD_OBJECTS:-}" ]; then
  tag=-t$STILL_TOWARD_OBJECTS
  scene=scene$tag.json
  /usr/bin/python3 -c 'import json, sys; s = json.load(open("scene.json")); s["render"]["toward_objects"] = float(sys.argv[1]); json.dump(s, open(sys.argv[2], "w"), indent=2)' \
    "$STILL_TOWARD_OBJECTS" "$scene"
fi
ends=(4 8 16 32 64)
begin=0
parts=()
for end in "${ends[@]}"; do
  part="out/p$begin-$end$tag.part"
  [ -f "$part" ] ||
    "$insitu" render "$scene" --spp 64 --seed 1 --samples "$begin:$end" --part "$part" 2> "out/p$begin-$end$tag.log" > /dev/null
  parts+=("$part")
  for denoise in "" --denoise; do
    out="out/still$end$tag${denoise:+-denoised}.exr"
    [ -f "${out%.exr}.layers.exr" ] ||
      "$insitu" merge "${parts[@]}" --allow-partial $denoise -o "$out" 2> /dev/null > /dev/null
  done
  begin=$end
done
/usr/bin/python3 - "$repo/bench" "$tag" "${ends[@]}" <<'PY' | tee "$work/still$tag.md"
import json, re, sys
sys.path.insert(0, sys.argv[1])
import still_error
tag = sys.argv[2]
ends = [int(e) for e in sys.argv[3:]]
first = open(f"out/p0-{ends[0]}{tag}.log").read()
load, prepare = (float(v) for v in re.search(r"load ([0-9.]+) s, prepare ([0-9.]+) s", first).groups())
tests = [f"out/still{e}{tag}{d}.layers.exr" for e in ends for d in ("", "-denoised")]
count, size, noise, out = still_error.errors("out/ref101.layers.exr", "out/ref102.layers.exr", tests)
print(f"region: {count} of {size} pixels; the reference's own noise {100 * noise:.2f} % (taken out)\n")
print("| spp | seconds | error | seconds, denoised | error, denoised |\n|---|---|---|---|---|")
pct = lambda e: f"{100 * e:.2f} %" if e is not None else "below the reference's noise"
for k, e in enumerate(ends):
    report = json.load(open(f"out/still{e}{tag}-denoised.exr.report.json"))
    seconds = load + prepare + report["seconds"]["render"]
    print(f"| {e} | {seconds:.1f} | {pct(out[2 * k][1])} | {seconds + report['denoise']['seconds']:.1f} "
          f"| {pct(out[2 * k + 1][1])} |")
PY
