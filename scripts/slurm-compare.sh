#!/usr/bin/env bash
# Example SLURM job array: the paper's full (x, alpha) grid compared at the
# paper's N = 10^4, split into 200 shards. Each array task runs one shard and
# journals into the shared report directory; a task killed by the scheduler
# (time limit, preemption) is simply resubmitted: --resume finishes it without
# redoing a point. When every task is done, join the shards:
#
#   impact merge paper-compare/points-shard-*-of-200.jsonl --out paper-compare
#
# Submit with:  sbatch scripts/slurm-compare.sh
#SBATCH --job-name=impact-compare
#SBATCH --array=1-200
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
#SBATCH --requeue
#SBATCH --output=logs/impact-compare-%A_%a.out
set -euo pipefail

SHARDS=200
OUT=paper-compare
mkdir -p logs "$OUT"

impact compare \
  --x 0.005:0.995:0.005 --alpha 0.005:0.995:0.005 \
  --n 10000 --no-timing \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --out "$OUT" \
  --shard "${SLURM_ARRAY_TASK_ID}/${SHARDS}" \
  --resume
