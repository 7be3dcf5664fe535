#!/usr/bin/env python3
"""How long the exact engine takes on random layered rods: the measure of
issue 10's goal (every rod of 1 to 8 layers with transit-time ratios up to
10^6 finishes by default in under 1 s).

Draws seeded random rods (2 to 8 layers; lengths uniform in [0.2, 1.2],
densities log-uniform in [0.1, 10], wave speeds log-uniform over SPEEDS
decades, redrawn until the transit-time ratio is at most 10^SPEEDS), runs
`impact run SCENE --json` on each with the default settings, one at a time,
and prints one line per rod (layers, ratio, seconds, events, peak memory,
e, error bound) and a summary: median, 90th percentile and largest time,
how many took over 1 s, how many did not finish within --timeout, and the
largest peak memory (the process's resident set, from `wait4`).

    python3 scripts/survey-layers.py                 # 40 rods, seed 7
    python3 scripts/survey-layers.py --rods 100 --seed 1 --timeout 120
    IMPACT=path/to/impact python3 scripts/survey-layers.py
    python3 scripts/survey-layers.py --keep rods/    # keep the scenes (rodNNN.json)
    python3 scripts/survey-layers.py --fast-bottom --seed 11 --timeout 60   # heavy tops, fast bottom groups
    python3 scripts/survey-layers.py --materials --seed 5   # stacks of the table's real materials, SI units
    python3 scripts/survey-layers.py --exact-events 8e6   # merged bounds against exact runs
    python3 scripts/survey-layers.py --fine-budget 1e8    # merged bounds against finer ladders
    python3 scripts/survey-layers.py --against old/impact # this binary beside another, rod by rod

With --exact-events N, each rod whose default run merged fronts is run again
exactly (`--resolution exact --max-events N`); where that finishes, the line
adds the exact `e` and how far the merged `e` is from it in units of its
bound (and whether the run said its estimate may be low), and the summary
says whether every such bound held (exit 1 if not) and how many of those
outside had said so. A rod reported exact after its ladder's levels did
not converge (the exact run allowed the ladder's budget; `ladder_set_aside`
in the JSON) says so on its line, with how far the ladder's `e` was from
it in units of the ladder's bound.

With --fine-budget N, each merged rod is run again with a ladder allowed N
events and aiming at `1e-12` (`--event-budget N --target 1e-12`), so it
goes on to finer lattices: the check for rods no exact run can finish. The
line adds the fine `e`, its bound, how far the default `e` is from it in
units of the default bound, and whether the default run said its estimate
may be low (its levels not seen converging); the default bound held if the
two differ by at most the sum of both bounds. A fine run whose own bound
is not under a quarter of the default's says little about it and is
counted apart ("inconclusive"), as is one that does not finish within
--timeout; the summary counts both, and exit 1 if a conclusive check failed.

With --against OTHER, each rod is run with the binary OTHER too, one run
each, alternately first and second (the machine's drift then falls on both
alike): the line adds OTHER's time and how far `e` moved, in units of the
sum of the two bounds ("same" when `e` and the bound are the same to the
bit), and the summary sets OTHER's median, 90th percentile, slowest and
count over 1 s beside this binary's, with how many rods moved and the
largest move. What a change to the engine does to speed and to results, in
one sitting.

Not run by CI (minutes, and timings). Needs only Python 3 and the binary
(cargo builds it when target/release/impact is missing).
"""

import argparse
import json
import math
import os
import random
import resource
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def draw(rng, speeds):
    """One rod as a scene: 2 to 8 layers, transit ratio <= 10^speeds."""
    n = rng.randint(2, 8)
    while True:
        layers = []
        for _ in range(n):
            length = rng.uniform(0.2, 1.2)
            density = 10 ** rng.uniform(-1, 1)
            speed = 10 ** rng.uniform(0, speeds)
            layers.append({"length": length, "modulus": density * speed * speed, "density": density})
        transits = [l["length"] / math.sqrt(l["modulus"] / l["density"]) for l in layers]
        if max(transits) / min(transits) <= 10**speeds:
            return {"impact_speed": 1.0, "layers": layers}


def draw_fast_bottom(rng):
    """One rod with a group of fast layers at the bottom (--fast-bottom): a
    bottom of transit 10^-5.5 to 10^-3.5, two or three layers 10 to 300
    times faster on it, then one or two slow ones (10^-2 to 1); impedances
    log-uniform over seven decades whatever the transit, so densities span
    up to thirteen and a heavy top may ride a soft layer for many of its
    transits."""
    tb = 10 ** rng.uniform(-5.5, -3.5)
    top = 10 ** rng.uniform(-2, 0)
    fast = [tb * 10 ** rng.uniform(-2.5, -1) for _ in range(rng.randint(2, 3))]

    def layer(transit):
        impedance = 10 ** rng.uniform(-1, 6)
        length = rng.uniform(0.2, 1.2)
        speed = length / transit
        density = impedance / speed
        return {"length": length, "modulus": density * speed * speed, "density": density}

    layers = [layer(tb)] + [layer(t) for t in fast] + [layer(top)]
    if rng.random() < 0.5:
        layers.append(layer(10 ** rng.uniform(-2, 0)))
    return {"impact_speed": 1.0, "layers": layers}


def draw_materials(rng, table):
    """One stack of real materials (--materials): 2 to 5 layers, each a
    material of `data/materials.json` named as a user writes it, 0.1 mm to
    10 cm long (log-uniform), hit at 0.1 to 10 m/s: SI units throughout,
    the scenes a physicist with a drawer of samples would run."""
    layers = [{"material": rng.choice(table)["name"].replace("-", " "),
               "length": 10 ** rng.uniform(-4, -1)}
              for _ in range(rng.randint(2, 5))]
    return {"impact_speed": 10 ** rng.uniform(-1, 1), "layers": layers}


def resolved(layer, table):
    """A layer's length, modulus and density, a named material's from the table."""
    named = next((m for m in table if m["name"] == layer.get("material", "").replace(" ", "-")), {})
    return layer["length"], layer.get("modulus", named.get("modulus")), layer.get("density", named.get("density"))


def run_measured(cmd, timeout):
    """Runs `cmd` to its end: (exit code, stdout, stderr, seconds, peak
    resident memory in MiB, floor in MiB). Raises
    `subprocess.TimeoutExpired` (the process killed) after `timeout`
    seconds. The child is reaped with `os.wait4`, whose resource usage is
    the child's own (`getrusage` of all children gives only the largest
    so far). Its peak counts what it held before `exec`, a fork of this
    interpreter: the floor, this interpreter's own peak, is the least any
    child's peak can be."""
    unit = 1024 * 1024 if sys.platform == "darwin" else 1024  # ru_maxrss: bytes or KiB
    floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / unit
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=out, stderr=err)
        reaped = {}

        def reap():
            _, status, usage = os.wait4(proc.pid, 0)
            reaped["seconds"] = time.perf_counter() - start
            reaped["code"] = os.waitstatus_to_exitcode(status)
            reaped["mib"] = usage.ru_maxrss / unit

        waiter = threading.Thread(target=reap)
        waiter.start()
        waiter.join(timeout)
        if waiter.is_alive():
            proc.kill()
            waiter.join()
            proc.returncode = reaped["code"]
            raise subprocess.TimeoutExpired(cmd, timeout)
        # (reaped here: Popen must not wait for it again)
        proc.returncode = reaped["code"]
        out.seek(0)
        err.seek(0)
        return (reaped["code"], out.read().decode(), err.read().decode(), reaped["seconds"],
                reaped["mib"], floor)


def fine_check(impact, path, out, budget, timeout):
    """The default run `out` against a ladder allowed `budget` events: the
    line's addition, and `(distance in default bounds, held)`, or None when
    the fine run says little (did not finish, or its bound is not under a
    quarter of the default's)."""
    try:
        code, stdout, stderr, seconds, _, _ = run_measured(
            [impact, "run", str(path), "--json", "--event-budget", str(int(budget)),
             "--target", "1e-12"], timeout)
    except subprocess.TimeoutExpired:
        return f"  (fine run over {timeout:.0f} s)", None
    if code != 0:
        return f"  (fine run exit {code})", None
    fine = json.loads(stdout)
    d = abs(out["restitution"] - fine["restitution"])
    share = d / out["error_bound"] if out["error_bound"] > 0 else math.inf
    warned = out["error_estimate"].get("merged_converging") is False
    line = (f"  fine {fine['restitution']:.10f} +- {fine['error_bound']:.1e} in {seconds:.1f} s, "
            f"off by {share:.2f} of the bound" + (" (which says it may be low)" if warned else ""))
    if not fine["error_bound"] < 0.25 * out["error_bound"]:
        return line + " (inconclusive)", None
    return line, (share, d <= out["error_bound"] + fine["error_bound"])


def memory(mib, floor):
    """A peak in MiB, six wide; one within 5 % of the floor is at most it."""
    return f"{'<=' + format(floor, '.0f'):>6}" if mib <= 1.05 * floor else f"{mib:6.1f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rods", type=int, default=40, help="rods to draw (default 40)")
    parser.add_argument("--seed", type=int, default=7, help="random seed (default 7)")
    parser.add_argument("--speeds", type=float, default=6.0,
                        help="decades of wave speed, and the largest transit ratio's (default 6)")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per rod (default 60)")
    parser.add_argument("--exact-events", type=float, default=0, metavar="N",
                        help="check merged rods against exact runs of at most N events (default: no check)")
    parser.add_argument("--fine-budget", type=float, default=0, metavar="N",
                        help="check merged rods against ladders allowed N events (default: no check)")
    parser.add_argument("--fast-bottom", action="store_true",
                        help="draw rods with a group of fast layers at the bottom instead (see draw_fast_bottom)")
    parser.add_argument("--materials", action="store_true",
                        help="draw stacks of the table's real materials in SI units instead (see draw_materials)")
    parser.add_argument("--keep", type=Path, metavar="DIR",
                        help="write each rod's scene to DIR/rodNNN.json (to rerun one alone)")
    parser.add_argument("--against", metavar="OTHER",
                        help="run each rod with the binary OTHER too, alternately first, and compare")
    args = parser.parse_args()
    if args.rods < 1 or args.timeout <= 0 or not 0 < args.speeds <= 12 or not 0 <= args.exact_events < 1e15 \
            or not 0 <= args.fine_budget < 1e15:
        print("error: --rods >= 1, --timeout > 0, --speeds in (0, 12], --exact-events and --fine-budget "
              "in [0, 1e15)",
              file=sys.stderr)
        return 2

    impact = os.environ.get("IMPACT") or str(ROOT / "target/release/impact")
    if args.against and not os.access(args.against, os.X_OK):
        print(f"error: --against {args.against}: not an executable file", file=sys.stderr)
        return 2
    if not os.access(impact, os.X_OK):
        print("== building impact (cargo build --release)", flush=True)
        subprocess.run(["cargo", "build", "--release", "--locked", "--quiet"], cwd=ROOT, check=True)

    if args.fast_bottom and args.materials:
        print("error: --fast-bottom and --materials draw different rods: give one", file=sys.stderr)
        return 2
    table = json.loads((ROOT / "data/materials.json").read_text())["materials"]
    rng = random.Random(args.seed)
    times, unfinished, failed = [], 0, 0
    peak, peak_rod, peak_floor, floor = 0.0, None, 0.0, 0.0
    checked, held, exact_furthest, outside_warned = 0, 0, 0.0, 0
    again = 0
    fine_checked, fine_held, fine_closest, fine_open = 0, 0, 0.0, 0
    other_times, moved, furthest = [], 0, (-1.0, None)
    print(f"rod  layers  ratio      seconds       events     MiB  e             bound")
    with tempfile.TemporaryDirectory(prefix="impact-survey-") as work:
        for k in range(args.rods):
            if args.materials:
                scene = draw_materials(rng, table)
            else:
                scene = draw_fast_bottom(rng) if args.fast_bottom else draw(rng, args.speeds)
            path = Path(work) / f"rod{k:03d}.json"
            path.write_text(json.dumps(scene))
            if args.keep:
                args.keep.mkdir(parents=True, exist_ok=True)
                (args.keep / path.name).write_text(json.dumps(scene, indent=1))
            transits = [length / math.sqrt(modulus / density)
                        for length, modulus, density in (resolved(l, table) for l in scene["layers"])]
            ratio = max(transits) / min(transits)
            other = None
            try:
                if args.against and k % 2 == 0:
                    other = run_other(args.against, path, args.timeout)
                code, stdout, stderr, seconds, mib, at_least = run_measured(
                    [impact, "run", str(path), "--json"], args.timeout)
                if args.against and k % 2 == 1:
                    other = run_other(args.against, path, args.timeout)
            except subprocess.TimeoutExpired:
                unfinished += 1
                print(f"{k:3d}  {len(transits):6d}  {ratio:9.1e}  over {args.timeout:.0f} s (stopped)", flush=True)
                continue
            floor = max(floor, at_least)
            shown = memory(mib, at_least)
            if mib > peak:
                peak, peak_rod, peak_floor = mib, k, at_least
            if code != 0:
                failed += 1
                print(f"{k:3d}  {len(transits):6d}  {ratio:9.1e}  {seconds:7.2f}  exit {code}: "
                      f"{stderr.strip().splitlines()[-1] if stderr.strip() else ''}", flush=True)
                continue
            times.append(seconds)
            out = json.loads(stdout)
            exact = ""
            if args.exact_events and out["truncation"]["merged_fronts"] > 0:
                ref = subprocess.run([impact, "run", str(path), "--json", "--resolution", "exact",
                                      "--max-events", str(int(args.exact_events))],
                                     capture_output=True, text=True)
                if ref.returncode == 0:
                    x = json.loads(ref.stdout)
                    d = abs(out["restitution"] - x["restitution"])
                    share = d / out["error_bound"] if out["error_bound"] > 0 else math.inf
                    checked += 1
                    within = d <= out["error_bound"] + x["error_bound"]
                    warned = out["error_estimate"].get("merged_converging") is False
                    held += within
                    outside_warned += (not within) and warned
                    exact_furthest = max(exact_furthest, share)
                    exact = (f"  exact {x['restitution']:.10f}, off by {share:.2f} of the bound"
                             + (" (which says it may be low)" if warned else ""))
                else:
                    exact = f"  (exact run over {args.exact_events:.0e} events)"
            set_aside = (out.get("error_estimate") or {}).get("ladder_set_aside")
            if set_aside:
                # exact after a ladder whose levels did not converge
                again += 1
                off = abs(set_aside["restitution"] - out["restitution"])
                bound = set_aside["merged_bound"]
                exact += (f"  exact after the ladder (its levels at order "
                          f"{set_aside.get('observed_order', float('nan')):.1f} gave "
                          f"{set_aside['restitution']:.10f} ± {bound:.1e}, "
                          f"{off / bound if bound > 0 else math.inf:.2f} of that bound away)")
            if args.fine_budget and out["truncation"]["merged_fronts"] > 0:
                verdict, share = fine_check(impact, path, out, args.fine_budget, args.timeout)
                exact += verdict
                if share is None:
                    fine_open += 1
                else:
                    fine_checked += 1
                    fine_held += share[1]
                    fine_closest = max(fine_closest, share[0])
            if other is not None:
                other_seconds, theirs = other
                other_times.append(other_seconds)
                if theirs is None:
                    exact += f"  against: {other_seconds:.2f} s, failed or over --timeout"
                elif (theirs["restitution"], theirs["error_bound"]) == (out["restitution"], out["error_bound"]):
                    exact += f"  against: {other_seconds:.2f} s, same"
                else:
                    moved += 1
                    both = out["error_bound"] + theirs["error_bound"]
                    share = abs(out["restitution"] - theirs["restitution"]) / both if both > 0 else math.inf
                    furthest = max(furthest, (share, k), key=lambda x: x[0])
                    exact += (f"  against: {other_seconds:.2f} s, e {theirs['restitution']:.10f} "
                              f"± {theirs['error_bound']:.1e}, moved {share:.2g} of the two bounds")
            print(f"{k:3d}  {len(transits):6d}  {ratio:9.1e}  {seconds:7.2f}  {out['events']:11d}  "
                  f"{shown}  {out['restitution']:.10f}  {out['error_bound']:.1e}{exact}", flush=True)
    times.sort()
    over = sum(t > 1.0 for t in times)
    p90 = times[min(len(times) - 1, int(0.9 * len(times)))] if times else float("nan")
    drawn = ("fast bottom groups" if args.fast_bottom else "stacks of real materials" if args.materials
             else f"ratios up to 1e{args.speeds:g}")
    print(f"{args.rods} rods (seed {args.seed}, {drawn}); of the {len(times)} "
          f"that finished: median {statistics.median(times) if times else float('nan'):.2f} s, "
          f"90th percentile {p90:.2f} s, largest finished {max(times) if times else float('nan'):.2f} s; "
          f"{over} over 1 s, {unfinished} not finished within {args.timeout:g} s, {failed} failed; "
          f"largest peak memory {memory(peak, peak_floor).strip()} MiB"
          + (f" (rod {peak_rod})" if peak_rod is not None and peak > 1.05 * peak_floor else "")
          + f" ('<=': within 5 % of the {floor:.0f} MiB a fork of this interpreter starts from)")
    if args.exact_events:
        print(f"merged rods run exactly within {args.exact_events:.0e} events: {checked}; "
              f"within their bound: {held} of {checked}"
              + (f" (the furthest at {exact_furthest:.2f} of its bound)" if checked else "")
              + (f"; of the {checked - held} outside, {outside_warned} said their estimate may be low"
                 if held < checked else ""))
    if again:
        print(f"exact after a ladder whose levels did not converge (the exact run allowed the ladder's "
              f"budget): {again} rods")
    if args.fine_budget:
        print(f"merged rods run again with --event-budget {args.fine_budget:.0e}: {fine_checked} conclusive, "
              f"{fine_held} of them within the sum of the two bounds"
              + (f" (the furthest at {fine_closest:.2f} of the default bound)" if fine_checked else "")
              + f"; {fine_open} inconclusive (fine bound not under a quarter of the default's, or over "
              f"--timeout)")
    if args.against:
        theirs = sorted(other_times)
        print(f"against {args.against}, the same {len(theirs)} rods: median {spread(theirs)} "
              f"(this binary: {spread(times)}); {moved} moved e or its bound"
              + (f", the furthest by {furthest[0]:.2g} of the sum of the two bounds (rod {furthest[1]})"
                 if moved else ""))
    return 1 if failed or held < checked or fine_held < fine_checked else 0


def run_other(binary, path, timeout):
    """`binary run path --json`: its seconds and output (None if it failed
    or ran over `timeout`)."""
    try:
        code, stdout, _, seconds, _, _ = run_measured([binary, "run", str(path), "--json"], timeout)
    except subprocess.TimeoutExpired:
        return timeout, None
    return seconds, json.loads(stdout) if code == 0 else None


def spread(times):
    """Median, 90th percentile, slowest and count over 1 s of sorted times."""
    if not times:
        return "none"
    p90 = times[min(len(times) - 1, int(0.9 * len(times)))]
    return (f"{statistics.median(times):.2f} s, 90th percentile {p90:.2f} s, slowest {max(times):.2f} s, "
            f"{sum(t > 1.0 for t in times)} over 1 s")


if __name__ == "__main__":
    sys.exit(main())
