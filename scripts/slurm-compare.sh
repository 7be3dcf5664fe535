#!/usr/bin/env bash
# `impact compare` on a SLURM cluster: one shard per array task.
#
#   OUT=paper-compare X=0.005:0.995:0.005 ALPHA=0.005:0.995:0.005 N=10000 \
#     SHARDS=200 CPUS=8 scripts/slurm-compare.sh       # prints the job id
#   impact merge paper-compare/points-shard-*-of-200.jsonl --out paper-compare
#
# Resubmit dead tasks (the same variables, and INDICES): INDICES=3,17 ...
# The README's "Running it on a SLURM cluster" says how to find them.
set -euo pipefail
: "${OUT:=compare-report}"       # report directory; journals go inside it
: "${X:=0.05:0.95:0.05}"         # x grid START:STOP:STEP (or one value)
: "${ALPHA:=0.05:0.95:0.05}"     # alpha grid
: "${N:=1000}"                   # chain sizes, e.g. 250,500,1000
: "${EXTRA:=}"                   # further impact compare flags
if [[ -z "${SLURM_ARRAY_TASK_ID:-}" ]]; then
  # submission (SLURM runs a copy of this file, so only here is it beside its helper)
  source "$(dirname "$(readlink -f "$0")")/slurm-array.sh"
  submit compare "$OUT"
fi
# shellcheck disable=SC2086 # EXTRA is a list of flags
exec "$IMPACT" compare --x "$X" --alpha "$ALPHA" --n "$N" --no-timing \
  --threads "${SLURM_CPUS_PER_TASK:-1}" --out "$OUT" \
  --shard "$SLURM_ARRAY_TASK_ID/$SHARDS" --resume $EXTRA
