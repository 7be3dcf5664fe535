#!/usr/bin/env bash
# The paper's elastic chain in impact and in LAMMPS, side by side in one run.
#
# LAMMPS (Debian's package, installed if missing) runs the same chain: units
# lj, atoms on a line, `bond_style harmonic` with K = k/2 (LAMMPS's energy is
# K (r - r0)^2), the wall element as `fix wall/harmonic` on the bottom atom
# (epsilon = k/2, pushing only while compressed; its plane sits 10 below the
# bottom mass's rest position, cutoff 10 + rest length, so LAMMPS never sees
# an atom behind it),
# `fix nve` (velocity Verlet, whose positions are Beeman's: the wall impulse,
# and so e, depends on positions only). First e must agree to 1e-9 on three
# canonical bilayers at N = 200; then both run N = 10^4 and the script prints
# ns per atom-step for each and the ratio. The third peer is the plainest
# C of the same chain, integrated as the paper writes Beeman's scheme
# (`scripts/peers/naive_beeman.c`, `cc -O3 -march=native`): the baseline of
# what a direct implementation gets; it too must agree on e to 1e-9. Not run
# by CI (minutes); runs on a fresh machine (needs root for apt-get, python3,
# a C compiler, the Rust toolchain).
#
#   scripts/bench-peers.sh                    # N = 10^4, 20000 LAMMPS steps
#   N=100000 STEPS=2000 scripts/bench-peers.sh
set -euo pipefail
cd "$(dirname "$(readlink -f "$0")")/.."
: "${N:=10000}"          # masses of the timed run
: "${STEPS:=20000}"      # LAMMPS steps of the timed run (impact runs to escape)

if ! command -v lmp >/dev/null; then
  echo "== installing Debian's lammps"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq lammps >/dev/null
fi
if ! command -v cc >/dev/null; then
  echo "== installing Debian's gcc"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gcc libc6-dev >/dev/null
fi
if [[ -z "${IMPACT:-}" ]]; then
  cargo build --release --locked --quiet
  IMPACT=target/release/impact
fi
work=$(mktemp -d /tmp/impact-peers-XXXXXX)
trap 'rm -rf "$work"' EXIT

# lammps X ALPHA N STEPS: writes the chain of the canonical bilayer (bottom
# layer: length 1 - x, modulus 1 - alpha; top: x, alpha; density 1, impact
# speed 1) as impact lays it out (crates/chain/src/layout.rs: masses in
# proportion to the lengths, element 0 the wall spring, the paper's time step
# min 2 pi sqrt(m/k) / 100), runs it, prints "vcm loop_seconds".
lammps() {
  python3 - "$@" "$work" <<'EOF'
import math, subprocess, sys
x, alpha, n, steps, work = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
layers = [(1 - x, 1 - alpha), (x, alpha)]          # (length, modulus), density 1
# The model is linear (and its wall switches at zero compression), so e does
# not depend on the impact speed; impact's unit speed compresses the bottom
# element past its rest length (strain v/c > 1), where LAMMPS's bonds, which
# see only |r|, would let the atoms pass each other. 1e-2 keeps strains small.
V0 = 1e-2
counts = [round(n * length) for length, _ in layers]
assert sum(counts) == n and all(abs(c - n * l) < 1e-9 for c, (l, _) in zip(counts, layers)), "choose x with N x whole"
l0 = [length / c for (length, _), c in zip(layers, counts)]
k = [modulus / d for (_, modulus), d in zip(layers, l0)]
m = [d for d in l0]                                 # rho l0, rho = 1
dt = min(2 * math.pi * math.sqrt(mi / ki) / 100 for mi, ki in zip(m, k))
kind = [0] * counts[0] + [1] * counts[1]            # layer of element j and mass j
height, h = [], 0.0
for j in range(n):
    h += l0[kind[j]]
    height.append(h)
with open(f"{work}/chain.data", "w") as f:
    f.write(f"impact chain\n\n{n} atoms\n{n - 1} bonds\n2 atom types\n2 bond types\n\n")
    f.write(f"-20.0 {height[-1] + 20.0} xlo xhi\n-0.5 0.5 ylo yhi\n-0.5 0.5 zlo zhi\n\n")
    f.write(f"Masses\n\n1 {m[0]!r}\n2 {m[1]!r}\n\nAtoms # bond\n\n")
    f.writelines(f"{j + 1} 1 {kind[j] + 1} {height[j]!r} 0 0\n" for j in range(n))
    f.write("\nBonds\n\n")
    f.writelines(f"{j} {kind[j] + 1} {j} {j + 1}\n" for j in range(1, n))
with open(f"{work}/in.chain", "w") as f:
    f.write(f"""units lj
boundary f p p
atom_style bond
atom_modify map array sort 0 0.0
read_data {work}/chain.data
pair_style none
bond_style harmonic
bond_coeff 1 {k[0] / 2!r} {l0[0]!r}
bond_coeff 2 {k[1] / 2!r} {l0[1]!r}
neigh_modify every 1000000000 delay 0 check no
group bottom id 1
fix wall bottom wall/harmonic xlo -10.0 {k[0] / 2!r} 0.0 {10.0 + l0[0]!r}
fix integrate all nve
velocity all set {-V0!r} 0.0 0.0
timestep {dt!r}
variable vx equal vcm(all,x)
thermo_style custom step v_vx
thermo_modify format float %.17g
thermo {steps}
run {steps}
print "VCM ${{vx}}"
""")
out = subprocess.run(["lmp", "-in", f"{work}/in.chain", "-log", "none"], capture_output=True, text=True, check=True).stdout
vcm = next(float(l.split()[1]) for l in out.splitlines() if l.startswith("VCM"))
loop = next(float(l.split()[3]) for l in out.splitlines() if l.startswith("Loop time"))
print(vcm / V0, loop)
EOF
}

field() { python3 -c "import json,sys; print(json.load(sys.stdin)['$1'])"; }

cc -O3 -march=native -o "$work/naive_beeman" scripts/peers/naive_beeman.c -lm

echo "== e at N = 200: impact's chain against LAMMPS and the naive C (must agree to 1e-9)"
for point in "0.5 0.5" "0.3 0.2" "0.8 0.05"; do
  set -- $point
  json=$("$IMPACT" run --x "$1" --alpha "$2" --engine chain --n 200 --json)
  e=$(field restitution <<<"$json")
  steps=$(field steps <<<"$json")
  read -r vcm _ < <(lammps "$1" "$2" 200 "$((steps + 100))")
  read -r naive _ < <("$work/naive_beeman" "$1" "$2" 200 "$((steps + 100))")
  python3 - "$1" "$2" "$e" "$vcm" "$naive" <<'EOF'
import sys
x, a = sys.argv[1], sys.argv[2]
e, vcm, naive = (float(v) for v in sys.argv[3:6])
d, dn = abs(e - vcm), abs(e - naive)
print(f"x = {x}, alpha = {a}: e impact {e:.12f}, LAMMPS {vcm:.12f} (|difference| {d:.1e}), naive C {naive:.12f} ({dn:.1e})")
sys.exit(0 if max(d, dn) <= 1e-9 else 1)
EOF
done

echo "== time at N = $N (one core each)"
json=$("$IMPACT" run --x 0.5 --alpha 0.5 --engine chain --n "$N" --json)
impact_ns=$(python3 -c "import json,sys; j=json.loads(sys.argv[1]); print(1e9*j['elapsed_seconds']/(j['steps']*$N))" "$json")
read -r _ loop < <(lammps 0.5 0.5 "$N" "$STEPS")
lammps_ns=$(python3 -c "print(1e9*$loop/($STEPS*$N))")
read -r _ naive_loop < <("$work/naive_beeman" 0.5 0.5 "$N" "$STEPS")
naive_ns=$(python3 -c "print(1e9*$naive_loop/($STEPS*$N))")
python3 - "$impact_ns" "$lammps_ns" "$naive_ns" <<EOF
import sys
i, l, c = (float(v) for v in sys.argv[1:4])
print(f"impact chain: {i:.2f} ns per mass-step (whole run, to escape)")
print(f"LAMMPS:       {l:.2f} ns per atom-step ($STEPS steps)")
print(f"naive C:      {c:.2f} ns per mass-step ($STEPS steps)")
print(f"LAMMPS / impact: {l / i:.1f}x; naive C / impact: {c / i:.1f}x")
EOF
