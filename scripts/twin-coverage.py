#!/usr/bin/env python3
"""How often a merged bound covers the rod's own chaos: for each merged rod
whose twin says its contacts flip on a nudge, the reported level's lattice is
run again with the bottom's modulus nudged by k 1e-12, k = -K..K
(`crates/wave/examples/nudge_spread.rs`), and the script counts the nudged
runs whose `e` lies within the reported bound of the reported `e`.

A twin is one sample of how far such flips move `e` (ARCHITECTURE.md, "the
twins"): this measures, rod by rod, how much of that spread the bound holds.
It also sets the spread of the nudged runs (the largest distance from the
reported `e`) against the first twin's difference, the one sample that
decides whether the further twins run (`ONE_SAMPLE_LOW` in
crates/wave/src/twins.rs). The nudged runs sit on the reported lattice, so
they measure the chaos alone, not the lattice's error; the k = 0 run is the
reported level's own run, and the script says so where its `e` differs from
the reported one by over 1e-12 (a wrong lattice, or a changed engine).

    python3 scripts/survey-layers.py --seed 7 --keep /tmp/s7   # scenes
    IMPACT=target/release/impact NUDGE=target/release/examples/nudge_spread \\
        python3 scripts/twin-coverage.py /tmp/s7/rod*.json [--k 12]
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys

SPACINGS = re.compile(r"lattice spacings ([0-9.e+-]+) of each transit, ([0-9.e+-]+) of the longest")
# the chaos term as the method names it: one twin, or the largest of several
ONE_TWIN = re.compile(r"changed by 1e-12 \(([0-9.e+-]+)\)")
FURTHER = re.compile(r"the largest difference over (\d+) twins.*?\(([0-9.e+-]+); the first twin's, ([0-9.e+-]+)")
# the ladder's coarsest lattice (`LADDER_START`)
START = (0.2, 4e-3)
# a twin under this moved no contact (`twins.rs`, AMPLIFIED)
FLIPS = 1e-10


def run_json(impact, scene):
    out = subprocess.run([impact, "run", scene, "--json"], capture_output=True, text=True, timeout=600)
    if out.returncode != 0:
        return None
    return json.loads(out.stdout)


def nudged(nudge, scene, p, l, k):
    out = subprocess.run([nudge, scene, repr(p), repr(l), str(k)], capture_output=True, text=True,
                         timeout=1800, check=True)
    runs = {}
    for line in out.stdout.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[0].lstrip("-").isdigit():
            runs[int(parts[0])] = float(parts[1])
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--k", type=int, default=12, help="nudges -K..K (default 12: 24 nudged runs)")
    args = parser.parse_args()
    impact = os.environ.get("IMPACT", "target/release/impact")
    nudge = os.environ.get("NUDGE", "target/release/examples/nudge_spread")
    rows = []
    print("scene                                    twins  first     spread    bound     within  furthest (of the bound)")
    for scene in args.scenes:
        result = run_json(impact, scene)
        if result is None:
            continue
        method = result["error_estimate"]["method"]
        lattice = SPACINGS.search(method)
        further = FURTHER.search(method)
        one = ONE_TWIN.search(method)
        if lattice is None or (further is None and one is None):
            continue
        first = float(further.group(3)) if further else float(one.group(1))
        if first <= FLIPS:
            continue
        twins = int(further.group(1)) if further else 1
        # the method prints the spacings rounded: the ladder's lattices are
        # its start halved, the two spacings in a ratio of 50
        # (`LADDER_START` in crates/wave/src/ladder.rs)
        halvings = round(math.log2(START[0] / float(lattice.group(1))))
        p, l = START[0] / 2 ** halvings, START[1] / 2 ** halvings
        e, bound = result["restitution"], result["error_bound"]
        runs = nudged(nudge, scene, p, l, args.k)
        # the k = 0 run is the reported level's own: the same number, or
        # the check measures another run than the one reported
        same = abs(runs[0] - e) <= 1e-12 * max(1.0, abs(e))
        others = [v for j, v in runs.items() if j != 0]
        within = sum(1 for v in others if abs(v - e) <= bound)
        spread = max(abs(v - e) for v in others)
        furthest = spread / bound if bound > 0 else float("inf")
        rows.append((scene, twins, within, len(others), furthest, same, spread / first))
        print(f"{scene[-40:]:40} {twins:5}  {first:.1e}  {spread:.1e}  {bound:.1e}  {within:3}/{len(others):<3} {furthest:.2f}"
              + ("" if same else f"  (k = 0 gave {runs[0]:.12f}, not the reported {e:.12f})"))
        sys.stdout.flush()
    if not rows:
        print("no merged rod whose twin flips contacts")
        return
    total = sum(r[3] for r in rows)
    inside = sum(r[2] for r in rows)
    whole = sum(1 for r in rows if r[2] == r[3])
    print(f"{len(rows)} rods whose twin flips contacts; {inside} of {total} nudged runs within the bound "
          f"({100.0 * inside / total:.0f} %); every nudged run within it on {whole} rods; "
          f"the furthest at {max(r[4] for r in rows):.2f} of its bound"
          + ("" if all(r[5] for r in rows) else f"; {sum(1 for r in rows if not r[5])} rods' k = 0 run differs"))
    ratios = sorted(r[6] for r in rows)
    print("the nudged runs' spread over the first twin's difference: median "
          f"{ratios[len(ratios) // 2]:.1f}, largest {ratios[-1]:.0f}; over 30 on {sum(1 for q in ratios if q > 30)} rods")


if __name__ == "__main__":
    main()
