#!/bin/bash
# Renders every entry of a batch file on a Slurm cluster, K entries per array task (default 1):
#   scripts/slurm/submit-batch.sh BATCH.json [K]
# prints the array job's id. K > 1 pays the room's start-up (load, light recovery, the irradiance
# grids) once per K stills.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
INSITU=${INSITU:-insitu}
k=${2:-1}
n=$("$INSITU" batch "$1" --count --per-task "$k")
PER_TASK=$k sbatch --parsable --export=ALL --array=0-$((n - 1)) "$here/batch.sbatch" "$1"
