#!/bin/bash
# One 4K still at 4096 spp split over 16 Slurm array tasks of 256 spp each; a second job,
# dependent on the array, merges the parts. Submit from a directory every node sees:
#   jobid=$(sbatch --parsable slurm-array.sh)
#   sbatch --dependency=afterok:$jobid --wrap 'pathtrace merge parts/*.ptfilm -o still.exr'
# A failed task is re-run with `sbatch --array=<its index> slurm-array.sh`; `pathtrace merge`
# names any range still missing and refuses overlapping ones.
#SBATCH --job-name=pathtrace-still
#SBATCH --array=0-15
#SBATCH --cpus-per-task=8
#SBATCH --output=logs/%A_%a.log
set -euo pipefail
SPP=4096
PARTS=16
PER=$((SPP / PARTS))
A=$((SLURM_ARRAY_TASK_ID * PER))
B=$((A + PER))
mkdir -p parts
pathtrace render scene.toml --size 3840x2160 --spp "$SPP" --seed 1 \
    --threads "$SLURM_CPUS_PER_TASK" --sample-range "$A..$B" \
    -o "parts/part-$SLURM_ARRAY_TASK_ID.exr" --film-out "parts/part-$SLURM_ARRAY_TASK_ID.ptfilm" -q
