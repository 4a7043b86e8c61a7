#!/bin/bash
# The per-task overhead of a catalogue batch without Slurm (issue 17, docs/farm.md):
#   bash bench/farm/startup.sh [INSITU] [--big]
# A batch of 4 entries of the demo room (one object each, 64 spp, as tests/slurm/local-cluster.sh
# submits), rendered as 4 tasks of 1 entry (`insitu batch --index I`) and as 1 task of 4
# (`--per-task 4`); for each task its wall time, the entries' render seconds (what the report
# says the render loop took), and the rest: the overhead, start-up to exit (process start, reading
# the batch, the room's load, the integrator's preparation, writing the outputs). Then the
# all-done rerun of one task (start, read, hash) and `insitu --version` (the process alone).
# --big: also one entry at 1920 × 1440 (the demo's photo resized 3×, its clicked points scaled),
# with its layers EXR and with "layers": "none".
# Needs /usr/bin/python3 with OpenImageIO (Debian's python3-openimageio) for --big.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
insitu=$(realpath "${1:-$repo/build/insitu}")
big=0
[ "${2:-}" = "--big" ] && big=1
work=$(mktemp -d /tmp/insitu-startup.XXXXXX)
trap 'rm -rf "$work"' EXIT
cp -r "$repo/scenes/demo" "$work/room" && rm -rf "$work/room/out"

batch() {  # $1: room folder, $2: entries, $3: "none" for no layers EXR; writes $work/$1$3.json
  /usr/bin/python3 - "$work" "$1" "$2" "${3:-}" <<'PY'
import json, sys
work, room, n, layers = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
s = json.load(open(f"{work}/{room}/scene.json"))
out = lambda i: {"image": f"out/entry{i}{layers}.exr", **({"layers": "none"} if layers else {})}
entries = [{"objects": [s["objects"][i % len(s["objects"])]], "render": {"spp": 64}, "output": out(i)} for i in range(n)]
json.dump({"scene": f"{room}/scene.json", "entries": entries}, open(f"{work}/{room}{layers}.json", "w"), indent=2)
PY
}

task() {  # $@: the batch command's arguments; prints wall, render sum, overhead
  local t0 t1
  t0=$(date +%s.%N)
  "$insitu" batch "$@" > /dev/null 2> "$work/task.log"
  t1=$(date +%s.%N)
  /usr/bin/python3 - "$t0" "$t1" "$work/task.log" "$*" <<'PY'
import re, sys
t0, t1, log, args = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], sys.argv[4]
text = open(log).read()
render = sum(float(r) for r in re.findall(r"render ([0-9.]+) s", text))
loads = re.findall(r"load ([0-9.]+) s(?: \(room shared\))?, prepare ([0-9.]+) s", text)
wall = t1 - t0
share = f"{100 * (wall - render) / render:.1f} % of the render" if render > 0 else "nothing rendered"
print(f"startup: batch {args.split('/')[-1]}: wall {wall:.2f} s, render {render:.2f} s, overhead {wall - render:.2f} s "
      f"({share}); load/prepare per entry: {', '.join(f'{l}/{p}' for l, p in loads)}")
PY
}

cd "$work"
batch room 4
for i in 0 1 2 3; do task room.json --index "$i"; done
rm -rf room/out
task room.json --index 0 --per-task 4
task room.json --index 0 --per-task 4  # every entry done: start, read, hash
t0=$(date +%s.%N); "$insitu" --version > /dev/null; t1=$(date +%s.%N)
echo "startup: insitu --version: $(/usr/bin/python3 -c "print(f'{$t1 - $t0:.2f}')") s"

if [ "$big" = 1 ]; then
  /usr/bin/python3 "$repo/bench/big_demo.py" "$work/big"
  batch big 1
  task big.json --index 0
  batch big 1 none
  task bignone.json --index 0
fi
