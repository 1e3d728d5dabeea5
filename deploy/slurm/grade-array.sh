#!/usr/bin/env bash
# A class graded by a Slurm job array against a ShadeLab server or cluster: each task takes its
# shard, all write into one shared folder, and a task that fails can be resubmitted alone
# (sbatch --array=3 ...): it resumes from the journal. Submit with
#   sbatch --array=0-7 deploy/slurm/grade-array.sh /shared/class https://shadelab.example.edu /shared/grades
#SBATCH --job-name=shadelab-grade
#SBATCH --cpus-per-task=1
#SBATCH --time=00:30:00
set -euo pipefail
submissions=$1 server=$2 out=$3
# Shards count from 0 whatever the array's first index is (--array=1-8 works as well as 0-7).
shard=$((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN))
exec shadelab grade --submissions "$submissions" --server "$server" --reference "${REFERENCE:-specular}" \
  --shard "$shard/$SLURM_ARRAY_TASK_COUNT" --concurrency 4 --out "$out"
