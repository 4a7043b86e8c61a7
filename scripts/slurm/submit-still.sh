#!/bin/bash
# Splits one still into N parts on a Slurm cluster and merges them when all have succeeded:
#   scripts/slurm/submit-still.sh SCENE OUT SPP N
# prints the merge job's id. The parts and the merge are written beside OUT (a shared folder).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
scene=$1 out=$2 spp=$3 n=$4
parts=$(sbatch --parsable --array=0-$((n - 1)) "$here/still-part.sbatch" "$scene" "$out" "$spp")
sbatch --parsable --dependency=afterok:"${parts%%;*}" "$here/still-merge.sbatch" "$out" "$n"
