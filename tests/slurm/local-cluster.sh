#!/usr/bin/env bash
# The Slurm test of issue 17, end to end on a single-node cluster on 127.0.0.1: munge, slurmctld
# and slurmd from Debian's packages (installed here if missing), a minimal slurm.conf written
# here, every file in a temporary folder. It submits
#   1. a batch of 4 entries (scripts/slurm/submit-batch.sh), on 1 slot and on 2, one entry per
#      task and then 4 and 2 entries per task, after clearing the outputs: the throughput of each;
#   2. a split still of 4 parts and their merge as a dependent job (scripts/slurm/submit-still.sh),
# waits (bounded), checks the outputs (the merged still bit-identical to one render of the same
# spp, each batch entry present with its report), prints the figures and stops its daemons.
# Needs root (the daemons, apt-get). Not in CI (.ci/run): about 8 minutes on 2 cores.
#   bash tests/slurm/local-cluster.sh [BUILD_DIR]
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$repo/build}" && pwd)
insitu=$build/insitu
[ -x "$insitu" ] || { echo "slurm-test: no $insitu: build first" >&2; exit 2; }
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi
work=$(mktemp -d /tmp/insitu-slurm.XXXXXX)
chmod 755 "$work"
conf=$work/slurm.conf
stop() {  # pid files...: each daemon ended, and waited for (bounded)
  for f in "$@"; do
    [ -f "$f" ] || continue
    local pid=$(cat "$f")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    rm -f "$f"
  done
}
cleanup() { stop "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munged.pid"; }
trap cleanup EXIT

# $1: CPUs the node declares; a task takes 2 (scripts/slurm/*.sbatch), so CPUs / 2 tasks run at
# once. config_overrides lets the node declare more CPUs than the machine has (4 on 2 cores: two
# tasks sharing the cores, to measure what a second slot gains).
start_cluster() {
  stop "$work/slurmd.pid" "$work/slurmctld.pid"
  rm -rf "$work/state" "$work/spool" && mkdir -p "$work/state" "$work/spool"
  cat > "$conf" <<CONF
ClusterName=insitu-test
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CryptoType=crypto/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
SlurmdParameters=config_overrides
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$1 State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
  export SLURM_CONF=$conf
  mkdir -p /etc/munge /run/munge /var/lib/munge /var/log/munge
  [ -f /etc/munge/munge.key ] || { dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null; chmod 400 /etc/munge/munge.key; }
  [ -f "$work/munged.pid" ] || munged --force --pid-file="$work/munged.pid"
  slurmctld -f "$conf"
  slurmd -f "$conf"
  for _ in $(seq 60); do
    sinfo -h -o %T 2>/dev/null | grep -q idle && return 0
    sleep 1
  done
  echo "slurm-test: the local cluster did not come up" >&2
  tail -n 20 "$work/slurmctld.log" "$work/slurmd.log" >&2
  exit 1
}

wait_for() {  # job ids...; bounded at 15 minutes
  local deadline=$(( $(date +%s) + 900 ))
  while squeue -h -j "$(IFS=,; echo "$*")" 2>/dev/null | grep -q .; do
    [ "$(date +%s)" -lt "$deadline" ] || { echo "slurm-test: jobs $* still queued after 15 minutes" >&2; exit 1; }
    sleep 1
  done
}

# The scene: the demo (640 × 480, path, 32 spp for the split still); the batch's entries one object
# each at 64 spp (the typical still of the overhead goal).
cp -r "$repo/scenes/demo" "$work/room"
rm -rf "$work/room/out"
/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
s = json.load(open(f"{work}/room/scene.json"))
s["render"]["spp"] = 32
s["output"] = {"image": "out/room.exr"}
json.dump(s, open(f"{work}/room/scene.json", "w"), indent=2)
entries = [{"objects": [s["objects"][i % len(s["objects"])]], "render": {"spp": 64}, "output": {"image": f"out/entry{i}.exr"}}
           for i in range(4)]
json.dump({"scene": "room/scene.json", "entries": entries}, open(f"{work}/batch.json", "w"), indent=2)
PY
export INSITU=$insitu
cd "$work"

run_batch() {  # $1: CPUs (2 per slot); $2: entries per task
  start_cluster "$1"
  rm -rf "$work/room/out/entry"*
  mkdir -p "$work/slots$(( $1 / 2 ))-k$2" && cd "$work/slots$(( $1 / 2 ))-k$2"
  local t0=$(date +%s.%N)
  local job=$(bash "$repo/scripts/slurm/submit-batch.sh" "$work/batch.json" "$2")
  wait_for "$job"
  local t1=$(date +%s.%N)
  for i in 0 1 2 3; do
    [ -f "$work/room/out/entry$i.exr.report.json" ] || { echo "slurm-test: entry $i has no output"; cat insitu-batch-*.log; exit 1; }
  done
  echo "slurm-test: batch of 4 entries on $(( $1 / 2 )) slot(s), $2 per task: $(python3 -c "print(f'{$t1 - $t0:.1f}')") s"
  grep -h "insitu: entry" insitu-batch-*.log | sed 's/^/slurm-test:   /'
  # A rerun: every entry is done, each task exits at once (the per-task cost of Slurm and start-up).
  t0=$(date +%s.%N)
  job=$(bash "$repo/scripts/slurm/submit-batch.sh" "$work/batch.json" "$2")
  wait_for "$job"
  t1=$(date +%s.%N)
  echo "slurm-test: the same batch again, all done already: $(python3 -c "print(f'{$t1 - $t0:.1f}')") s"
  cd "$work"
}
run_batch 2 1
run_batch 4 1
run_batch 2 4
run_batch 4 2

# The split still: 4 parts and the merge, against one render.
t0=$(date +%s.%N)
merge=$(bash "$repo/scripts/slurm/submit-still.sh" "$work/room/scene.json" "$work/split.exr" 32 4)
wait_for "$merge"
t1=$(date +%s.%N)
[ -f "$work/split.exr" ] || { echo "slurm-test: no merged still"; cat insitu-merge-*.log insitu-part-*.log; exit 1; }
echo "slurm-test: split still of 4 parts + merge on 2 slots: $(python3 -c "print(f'{$t1 - $t0:.1f}')") s"
grep -h "insitu: .*samples" insitu-part-*.log | sed 's/^/slurm-test: /'
"$insitu" render "$work/room/scene.json" -o "$work/whole.exr" 2> "$work/whole.log" >/dev/null
grep "insitu: .*render" "$work/whole.log" | sed 's/^/slurm-test: one process: /'
/usr/bin/python3 - "$work" <<'PY'
import sys, OpenImageIO as oiio, numpy as np
w = sys.argv[1]
for a, b in [("split.exr", "whole.exr"), ("split.layers.exr", "whole.layers.exr")]:
    x, y = (oiio.ImageBuf(f"{w}/{f}").get_pixels() for f in (a, b))
    if x.shape != y.shape or not np.array_equal(x, y):
        sys.exit(f"slurm-test: {a} differs from {b}")
print("slurm-test: the merged still is bit-identical to one render")
PY
echo "slurm-test: passed"
