#!/usr/bin/env bash
# impact's exact engine beside the independent Python tracker (scripts/tracker.py),
# in one run on one machine, on the 20 hardest points of the paper's grid:
# x = 0.9, 0.905, ..., 0.995 at alpha = 0.005 (t2/t1 from 127 to 2800, up to
# 28,000 events a point).
#
# impact runs the 20 points in ONE process (`impact sweep --threads 1`, one core,
# like Python); the Python tracker runs them in one process too (`--points`).
# Both write their rows to standard output, redirected to a file (`--out -`:
# a sweep's own --out FILE writes a temporary file and renames it, 0.4 ms on
# ext4 that neither computation needs).
# Both are timed as whole processes, best of REPEATS; the start-up of each (an
# `impact run` and a tracker run of a trivial point, best of 10) is measured and
# subtracted, and the net ratio Python / impact is the headline. The two must
# agree on e to 1e-9 (the script fails otherwise). Not run by CI (seconds, but
# timings); runs on a fresh Debian machine (apt-get python3 if missing, needs
# root then; cargo builds impact if target/release/impact is missing).
#
#   scripts/bench-tracker.sh            # best of 3
#   scripts/bench-tracker.sh --quick    # best of 1, the last 5 points only
#   REPEATS=7 IMPACT=path/to/impact PYTHON=python3 scripts/bench-tracker.sh
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")/.."

: "${REPEATS:=3}"
X_RANGE=0.9:0.995:0.005
POINTS=20
if [[ "${1:-}" == "--quick" ]]; then
  REPEATS=1
  X_RANGE=0.975:0.995:0.005
  POINTS=5
elif [[ $# -gt 0 ]]; then
  echo "usage: $0 [--quick]" >&2
  exit 2
fi

if [[ -z "${PYTHON:-}" ]]; then
  if [[ -x /usr/bin/python3 ]]; then
    PYTHON=/usr/bin/python3 # Debian's, not a version manager's shim (a shim adds start-up)
  elif command -v python3 >/dev/null; then
    PYTHON=python3
  else
    echo "== installing Debian's python3"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3 >/dev/null
    PYTHON=/usr/bin/python3
  fi
fi
if [[ -z "${IMPACT:-}" ]]; then
  IMPACT="${CARGO_TARGET_DIR:-target}/release/impact"
  if [[ ! -x "$IMPACT" ]]; then
    echo "== building impact (cargo build --release)"
    cargo build --release --locked --quiet
  fi
fi
work=$(mktemp -d /tmp/impact-tracker-XXXXXX)
trap 'rm -rf "$work"' EXIT

# The points exactly as impact's sweep makes them, for the tracker to read.
"$IMPACT" sweep --x "$X_RANGE" --alpha 0.005 --threads 1 --no-timing --out "$work/impact.csv" 2>/dev/null
"$PYTHON" - "$work" "$POINTS" <<'EOF'
import csv, sys
work, expected = sys.argv[1], int(sys.argv[2])
rows = list(csv.DictReader(open(f"{work}/impact.csv")))
xs = [float(r["x"]) for r in rows]
want = [round(0.995 - 0.005 * k, 3) for k in range(expected)][::-1]
assert len(rows) == expected and all(abs(a - b) < 1e-12 for a, b in zip(xs, want)), f"sweep points: {xs}"
assert all(float(r["alpha"]) == 0.005 for r in rows)
with open(f"{work}/points.txt", "w") as f:
    f.writelines(f"{r['x']} {r['alpha']}\n" for r in rows)
EOF

# best SECONDS of N runs of a command (stdout to $work/last.out)
best_of() {
  local n=$1
  shift
  "$PYTHON" - "$n" "$work/last.out" "$@" <<'EOF'
import subprocess, sys, time
n, out, cmd = int(sys.argv[1]), sys.argv[2], sys.argv[3:]
best = float("inf")
for _ in range(n):
    with open(out, "w") as f:
        start = time.perf_counter()
        subprocess.run(cmd, stdout=f, stderr=subprocess.DEVNULL, check=True)
        best = min(best, time.perf_counter() - start)
print(f"{best:.6f}")
EOF
}

echo "== $POINTS points x = $X_RANGE, alpha = 0.005; best of $REPEATS; $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "   impact: $IMPACT   python: $PYTHON ($("$PYTHON" --version 2>&1))"
impact_start=$(best_of 10 "$IMPACT" run --x 0.5 --alpha 0.5 --json)
python_start=$(best_of 10 "$PYTHON" scripts/tracker.py --x 0.5 --alpha 0.5 --json)
impact_total=$(best_of "$REPEATS" "$IMPACT" sweep --x "$X_RANGE" --alpha 0.005 --threads 1 --no-timing --out -)
python_total=$(best_of "$REPEATS" "$PYTHON" scripts/tracker.py --points "$work/points.txt")
cp "$work/last.out" "$work/python.jsonl"
# Each tool's own clock around each point's computation (no start-up, no output),
# from one more sweep that keeps impact's elapsed_seconds column.
"$IMPACT" sweep --x "$X_RANGE" --alpha 0.005 --threads 1 --out "$work/impact-timed.csv" 2>/dev/null

"$PYTHON" - "$work" "$impact_start" "$python_start" "$impact_total" "$python_total" <<'EOF'
import csv, json, sys
work = sys.argv[1]
impact_start, python_start, impact_total, python_total = map(float, sys.argv[2:])
rows = list(csv.DictReader(open(f"{work}/impact.csv")))
runs = [json.loads(line) for line in open(f"{work}/python.jsonl")]
assert [float(r["x"]) for r in rows] == [p["x"] for p in runs]
diff = max(abs(float(r["restitution"]) - p["restitution"]) for r, p in zip(rows, runs))
impact_events = sum(int(r["events"]) for r in rows)
python_events = sum(p["events"] for p in runs)
impact_net = max(impact_total - impact_start, 1e-9)
python_net = max(python_total - python_start, 1e-9)
n = len(rows)
print(f"   e agrees: max |e_impact - e_python| = {diff:.1e} over {n} points (must be <= 1e-9)")
print(f"   bounces N_b equal at every point: {all(int(r['bounces']) == p['bounces'] for r, p in zip(rows, runs))}")
print(f"{'':8} {'total s':>9} {'start-up s':>11} {'net s':>9} {'ms/point':>9} {'events':>9} {'ns/event':>9}")
for name, total, start, net, events in (
    ("impact", impact_total, impact_start, impact_net, impact_events),
    ("python", python_total, python_start, python_net, python_events),
):
    print(f"{name:8} {total:9.4f} {start:11.4f} {net:9.4f} {net / n * 1e3:9.3f} {events:9d} {net / events * 1e9:9.1f}")
print(f"ratio python / impact: {python_net / impact_net:.0f}x net of start-up "
      f"({python_total / impact_total:.0f}x whole processes; per event {python_net / python_events / (impact_net / impact_events):.0f}x)")
impact_own = sum(float(r["elapsed_seconds"]) for r in csv.DictReader(open(f"{work}/impact-timed.csv")))
python_own = sum(p["elapsed_seconds"] for p in runs)
print(f"in-process clocks, summed over the points (one run each): impact {impact_own * 1e3:.1f} ms, "
      f"python {python_own * 1e3:.0f} ms: {python_own / impact_own:.0f}x")
if diff > 1e-9:
    sys.exit(f"e differs by {diff:.1e} > 1e-9")
EOF
