# Shared by slurm-compare.sh and slurm-sweep.sh (sourced, not run).
#
# Run directly, a script submits itself as a SLURM job array of $SHARDS tasks
# (or only the tasks in $INDICES, to resubmit dead ones); inside the array each
# task runs one shard with --resume, so a task killed, cancelled or requeued
# and then resubmitted finishes its shard without redoing a point. Everything
# is an environment variable with a default; the array size comes from SHARDS,
# so the two cannot disagree.

: "${SHARDS:=4}"        # shards = array tasks; point k belongs to shard k mod SHARDS + 1
: "${CPUS:=1}"          # cores per task (--cpus-per-task; impact --threads)
: "${TIME:=24:00:00}"   # time limit per task
: "${INDICES:=}"        # resubmit only these array indices, e.g. 3 or 2,5
: "${PARTITION:=}"      # a partition; default: the cluster's default
: "${LOGS:=logs}"       # task logs, one per array index, appended across requeues

# The binary: $IMPACT, else `impact` on PATH (cargo install --path .), else
# this checkout's release build. Resolved once, at submission, so every task
# runs the same file.
resolve_impact() {
  if [[ -n "${IMPACT:-}" ]]; then
    :
  elif command -v impact >/dev/null 2>&1; then
    IMPACT=$(command -v impact)
  elif [[ -x "$(dirname "$0")/../target/release/impact" ]]; then
    IMPACT="$(dirname "$0")/../target/release/impact"
  else
    echo "no impact binary: install it with 'cargo install --path .' or set IMPACT=/path/to/impact" >&2
    exit 2
  fi
  IMPACT=$(readlink -f "$IMPACT")
  [[ -x "$IMPACT" ]] || { echo "IMPACT=$IMPACT is not an executable" >&2; exit 2; }
}

# submit NAME OUT: makes the output directory OUT, submits this script as the
# array and exits: a run outside the array only submits. (SLURM opens --output
# before the task starts, so the log directory is made here, at submission.)
submit() {
  local name=$1 out=$2
  mkdir -p "$out"
  resolve_impact
  [[ "$SHARDS" =~ ^[1-9][0-9]*$ ]] || { echo "SHARDS must be a whole number >= 1 (got '$SHARDS')" >&2; exit 2; }
  mkdir -p "$LOGS"
  local array=${INDICES:-1-$SHARDS}
  local args=(--job-name="impact-$name" --array="$array" --cpus-per-task="$CPUS"
    --time="$TIME" --requeue --open-mode=append
    --output="$LOGS/impact-$name-%a.log" --export=ALL,IMPACT="$IMPACT",SHARDS="$SHARDS")
  [[ -n "$PARTITION" ]] && args+=(--partition="$PARTITION")
  sbatch --parsable "${args[@]}" "$0"
  exit 0
}
