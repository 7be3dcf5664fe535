#!/usr/bin/env bash
# `impact sweep` on a SLURM cluster: one shard per array task, each journaling
# into $OUT/part-I-of-SHARDS.jsonl.
#
#   OUT=chain-grid ENGINE=chain N=10000 SHARDS=64 scripts/slurm-sweep.sh
#   impact merge chain-grid/part-*-of-64.jsonl --out chain-grid.csv
#
# Resubmit dead tasks (the same variables, and INDICES): INDICES=5 ...
set -euo pipefail
: "${OUT:=sweep-journals}"       # directory of the shards' journals
: "${X:=0.05:0.95:0.05}"         # x grid START:STOP:STEP (or one value)
: "${ALPHA:=0.05:0.95:0.05}"     # alpha grid
: "${ENGINE:=wave}"              # wave, chain, rigid-bottom or auto
: "${N:=2000}"                   # masses of the chain
: "${EXTRA:=}"                   # further impact sweep flags
if [[ -z "${SLURM_ARRAY_TASK_ID:-}" ]]; then
  # submission (SLURM runs a copy of this file, so only here is it beside its helper)
  source "$(dirname "$(readlink -f "$0")")/slurm-array.sh"
  submit sweep "$OUT"
fi
# shellcheck disable=SC2086 # EXTRA is a list of flags
exec "$IMPACT" sweep --x "$X" --alpha "$ALPHA" --engine "$ENGINE" --n "$N" --no-timing \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --out "$OUT/part-$SLURM_ARRAY_TASK_ID-of-$SHARDS.jsonl" \
  --shard "$SLURM_ARRAY_TASK_ID/$SHARDS" --resume $EXTRA
