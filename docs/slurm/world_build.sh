#!/usr/bin/env bash
# A world built by a Slurm job array, then finished by one dependent job
# (docs/distributed.md, "On a batch scheduler"). Submit it from a login node:
#
#   docs/slurm/world_build.sh SCENE OUT_DIR SHARDS [world-build options...]
#   docs/slurm/world_build.sh /shared/sponza.obj /shared/worlds/sponza 64 --resolution 65536 --colours
#
# Every job reads SCENE itself and writes into OUT_DIR: both on a filesystem all nodes
# share. A shard that fails or is preempted can be resubmitted alone (sbatch --array=K ...);
# it resumes from the chunk files it wrote. VOXRAY (default: voxray on PATH) names the tool.
set -euo pipefail
scene=$1 out=$2 shards=$3
shift 3
voxray=${VOXRAY:-voxray}
options=$(printf ' %q' "$@")

# K = SLURM_ARRAY_TASK_ID, 0 .. SHARDS-1. --cpus-per-task: the build threads of a shard.
array=$(sbatch --parsable --job-name=voxray-shards --array=0-$((shards - 1)) --cpus-per-task=8 --mem=16G \
    --wrap="$voxray world-build $(printf %q "$scene") --out $(printf %q "$out")$options --threads 8 --shard \$SLURM_ARRAY_TASK_ID/$shards")
# The finish runs once every shard has ended well (afterok), on one node.
sbatch --job-name=voxray-finish --dependency=afterok:$array --cpus-per-task=8 --mem=16G \
    --wrap="$voxray world-build $(printf %q "$scene") --out $(printf %q "$out")$options --threads 8 --finish"
echo "submitted: shards as job $array, the finish after them"
