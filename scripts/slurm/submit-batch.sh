#!/bin/bash
# Renders every entry of a batch file on a Slurm cluster, one array task per entry:
#   scripts/slurm/submit-batch.sh BATCH.json
# prints the array job's id.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
INSITU=${INSITU:-insitu}
n=$("$INSITU" batch "$1" --count)
sbatch --parsable --array=0-$((n - 1)) "$here/batch.sbatch" "$1"
