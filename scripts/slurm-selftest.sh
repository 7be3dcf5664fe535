#!/usr/bin/env bash
# End-to-end test of the SLURM scripts on a real one-node SLURM.
#
# Installs Debian's slurm-wlm and munge if missing, writes a one-node
# slurm.conf in a temporary directory (no cgroups: proctrack/linuxproc,
# task/none), starts munged, slurmctld and slurmd by hand on private ports and
# sockets, and stops exactly those processes at the end. Then, for
# scripts/slurm-sweep.sh and scripts/slurm-compare.sh on small grids with 4
# shards: one task is killed mid-run (kill -9) and another cancelled
# (scancel); merge must refuse and name the two shards; they are resubmitted
# as the README says (INDICES=...); the merged result must equal an unsharded
# run byte for byte.
#
#   scripts/slurm-selftest.sh            # needs root (apt-get, daemons)
#   IMPACT=target/debug/impact scripts/slurm-selftest.sh   # skip the build
#   scripts/slurm-selftest.sh -- bash    # instead: a shell on the cluster
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")/.."
repo=$PWD

if [[ $(id -u) -ne 0 ]]; then
  echo "slurm-selftest: skipped: needs root to install and start SLURM and munge" >&2
  exit 0
fi
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "== installing slurm-wlm and munge from Debian"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi
if [[ -z "${IMPACT:-}" ]]; then
  cargo build --release --locked --quiet
  IMPACT=$repo/target/release/impact
fi
export IMPACT=$(readlink -f "$IMPACT")

work=$(mktemp -d /tmp/impact-slurm-XXXXXX)
chmod 755 "$work"
pids=()
stop() {
  # only the daemons this script started, by PID
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [[ "${KEEP:-0}" != 1 ]]; then rm -rf "$work"; else echo "kept $work"; fi
}
trap stop EXIT

# munge, on a private socket, as the munge user
mkdir -p "$work/munge"
chown munge:munge "$work/munge"
chmod 755 "$work/munge" # munged wants its socket directory searchable by all
setpriv --reuid=munge --regid=munge --init-groups /usr/sbin/munged -F \
  --socket="$work/munge/socket" --pid-file="$work/munge/pid" \
  --log-file="$work/munge/log" --seed-file="$work/munge/seed" 2>>"$work/munged.log" &
pids+=($!)

host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
ClusterName=impactselftest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=3600
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=selftest Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
for _ in $(seq 50); do [[ -S "$work/munge/socket" ]] && break; sleep 0.1; done
/usr/sbin/slurmctld -D -i -f "$SLURM_CONF" >>"$work/slurmctld.out" 2>&1 &
pids+=($!)
/usr/sbin/slurmd -D -f "$SLURM_CONF" >>"$work/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
sinfo -h -o %t | grep -q idle || { echo "SLURM did not come up"; tail -n 20 "$work"/*.log; exit 1; }
echo "== one-node SLURM up ($cpus CPUs, daemons ${pids[*]})"

if [[ "${1:-}" == "--" ]]; then
  shift
  echo "== SLURM_CONF=$SLURM_CONF; the cluster stops when this command ends"
  cd "$repo"
  "$@"
  exit
fi

# waits for every task of job $1 to leave the queue
wait_job() {
  for _ in $(seq 1200); do
    [[ -z "$(squeue -h -j "$1" 2>/dev/null)" ]] && return 0
    sleep 0.25
  done
  echo "job $1 did not finish"; exit 1
}

# runs one script's scenario: $1 script, $2 the journal glob (for merge),
# $3 the merged output, $4 an unsharded command's output to compare with
scenario() {
  local script=$1 glob=$2 merged=$3
  shift 3
  cd "$work"
  local job
  job=$("$repo/scripts/$script")
  echo "== $script: job $job"
  # kill -9 the process of task 2 once it has journaled a point; cancel task 3
  local journal
  for _ in $(seq 400); do
    journal=$(ls $glob 2>/dev/null | grep -E '(shard-2-of-4|part-2-of-4)' || true)
    [[ -n "$journal" && $(wc -l <"$journal") -ge 2 ]] && break
    sleep 0.05
  done
  pkill -9 -f -- "--shard 2/4" || { echo "task 2 was not running: nothing was killed"; exit 1; }
  scancel "${job}_3"
  wait_job "$job"
  if "$IMPACT" merge $glob --out "$merged" 2>"$work/merge.err"; then
    echo "merge did not notice the dead tasks"; exit 1
  fi
  grep -q "in shards 2-3 of 4" "$work/merge.err" || { cat "$work/merge.err"; exit 1; }
  echo "   merge refuses and names them: $(cat "$work/merge.err")"
  job=$(INDICES=2,3 "$repo/scripts/$script")
  echo "   resubmitted 2,3 as job $job"
  wait_job "$job"
  "$IMPACT" merge $glob --out "$merged"
  "$@"
}

X=0.05:0.95:0.05 ALPHA=0.2:0.8:0.2 ENGINE=chain N=2000 SHARDS=4 OUT=$work/sweep \
  LOGS=$work/logs scenario slurm-sweep.sh "sweep/part-*-of-4.jsonl" "$work/sweep.csv" \
  "$IMPACT" sweep --x 0.05:0.95:0.05 --alpha 0.2:0.8:0.2 --engine chain --n 2000 \
  --no-timing --out "$work/sweep-whole.csv"
cmp "$work/sweep.csv" "$work/sweep-whole.csv"
echo "   sweep: merged CSV equals the unsharded run byte for byte"

X=0.1:0.9:0.1 ALPHA=0.2:0.8:0.3 N=1500 SHARDS=4 OUT=$work/compare LOGS=$work/logs \
  scenario slurm-compare.sh "compare/points-shard-*-of-4.jsonl" "$work/compare" \
  "$IMPACT" compare --x 0.1:0.9:0.1 --alpha 0.2:0.8:0.3 --n 1500 --no-timing \
  --out "$work/compare-whole"
for f in report.json points.csv index.html heatmap-de.svg heatmap-bounces.svg; do
  cmp "$work/compare/$f" "$work/compare-whole/$f"
done
echo "   compare: merged report equals the unsharded run byte for byte"
echo "slurm-selftest: ok"
