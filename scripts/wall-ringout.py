#!/usr/bin/env python3
"""How long a rod's bottom group rings at the wall: the question a "block at
the wall" (a response for the fast layers resting on the wall) must answer
first.

A block's response is traced until what it holds is under a 1e-13 share of
its input (`REST`, crates/wave/src/block/response.rs), and a port sums it
over as many of its lattice points as it rings for. While the rod rests on
the wall, the bottom group (the layers under the first one at least eight
times slower than all of them, as `bottom_group` in crates/wave/src/group.rs
chooses it) is linear and its wall is fixed, so its response to a front
from the layer above is a sum of damped modes: the roots `w` (Im w > 0, time
as exp(i w t)) of

    D(w) = Z_above v_top(w) + s_top(w),

with (v, s) carried from the wall (v = 0, s = 1) up through each layer by
its transfer matrix [[cos wt, i sin(wt) / Z], [i Z sin(wt), cos wt]]. The
wall's stress for a unit velocity step coming down is 2 / D, so mode `n`
moves it by `2 |2 / (D'(w_n) w_n)|` (a pair of conjugates), and decays at
`Im w_n`. This prints, per scene, when the sum of those amplitudes falls
under THRESHOLD of the step's static stress (2): the length a response at
the wall rings for. `--below K` keeps only the modes under `K / t0` (`t0`
the bottom's transit): a merged lattice of spacing `p t0` smooths modes of
a period under a few cells, so K = 15.7 (a period of 0.4 t0, eight cells
at the third level, p = 0.05) and K = 4 bracket what a lattice keeps.

    python3 scripts/wall-ringout.py SCENE.json [SCENE.json ...] [--threshold 1e-13] [--below K]

Needs numpy. Checked on one layer under a half-space, whose modes decay at
`-ln|R| / (2 t0)` with `R` the reflection at its top (`--check`).
"""

import argparse
import cmath
import json
import math
import sys

import numpy as np


def layers_of(path):
    """(transit, impedance) per layer, bottom first, per unit area."""
    scene = json.loads(open(path).read())
    out = []
    for layer in scene["layers"]:
        if "modulus" not in layer:
            raise SystemExit(f"{path}: give modulus and density (named materials are not read here)")
        c = math.sqrt(layer["modulus"] / layer["density"])
        out.append((layer["length"] / c, math.sqrt(layer["modulus"] * layer["density"])))
    return out


def group_top(transits):
    """The largest `top` with layers 0..top each eight times faster than it."""
    best, slowest = None, 0.0
    for top in range(1, len(transits)):
        slowest = max(slowest, transits[top - 1])
        if transits[top] >= 8.0 * slowest:
            best = top
    return best


def characteristic(w, group, z_above):
    v, s = 0j, 1 + 0j
    for t, z in group:
        c, sn = cmath.cos(w * t), cmath.sin(w * t)
        v, s = v * c + 1j * s * sn / z, s * c + 1j * z * v * sn
    return z_above * v + s


def characteristic_on(ws, group, z_above):
    v = np.zeros_like(ws, dtype=complex)
    s = np.ones_like(ws, dtype=complex)
    for t, z in group:
        c, sn = np.cos(ws * t), np.sin(ws * t)
        v, s = v * c + 1j * s * sn / z, s * c + 1j * z * v * sn
    return z_above * v + s


def derivative(w, group, z_above):
    h = 1e-7 * max(abs(w), 1.0)
    return (characteristic(w + h, group, z_above) - characteristic(w - h, group, z_above)) / (2 * h)


def root_near(w, group, z_above):
    for _ in range(100):
        d = derivative(w, group, z_above)
        if d == 0:
            return None
        step = characteristic(w, group, z_above) / d
        w -= step
        if abs(step) < 1e-13 * abs(w):
            return w
    return None


def modes(group, z_above, highest):
    """The damped modes up to `highest`, from the minima of |D| on the real
    axis (forty points between neighbouring modes), each polished by Newton."""
    span = sum(t for t, _ in group)
    n = min(int(highest / (math.pi / span) * 40) + 1000, 4_000_000)
    ws = np.linspace(1e-9, highest, n)
    a = np.abs(characteristic_on(ws, group, z_above))
    found = {}
    for i in np.where((a[1:-1] < a[:-2]) & (a[1:-1] < a[2:]))[0] + 1:
        w = root_near(complex(ws[i], 0.0), group, z_above)
        if w is not None and w.real > 0 and w.imag > 0:
            found[round(w.real, 3)] = w
    return list(found.values())


def rings_for(amplitudes, threshold):
    """When the modes' amplitudes, decaying, sum under `threshold`."""
    def total(t):
        return sum(a * math.exp(-w.imag * t) for w, a in amplitudes)

    lo, hi = 0.0, 1e-12
    while total(hi) > threshold and hi < 1e15:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if total(mid) > threshold else (lo, mid)
    return hi


def check():
    for z0, za in [(1.0, 100.0), (100.0, 1.0), (1.0, 3.0)]:
        w = root_near(complex(math.pi / 2 + 0.01, 0.0), [(1.0, z0)], za)
        expected = -math.log(abs((za - z0) / (za + z0))) / 2
        assert abs(w.imag - expected) < 1e-9 * expected, (z0, za, w, expected)
    print("check: one layer under a half-space decays at -ln|R| / (2 t0)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="*")
    parser.add_argument("--threshold", type=float, default=1e-13,
                        help="share of the static wall stress (default 1e-13, the traces' REST)")
    parser.add_argument("--below", type=float, default=None, metavar="K",
                        help="only modes under K / t0 (default: up to 4 pi over the fastest group layer's transit)")
    parser.add_argument("--check", action="store_true", help="check the modes on one layer first")
    args = parser.parse_args()
    if args.check:
        check()
    for path in args.scenes:
        layers = layers_of(path)
        transits = [t for t, _ in layers]
        top = group_top(transits)
        if top is None:
            print(f"{path}: no layer eight times slower than all below it")
            continue
        group, z_above = layers[:top], layers[top][1]
        highest = 4 * math.pi / min(t for t, _ in group)
        if args.below is not None:
            highest = min(highest, args.below / transits[0])
        found = modes(group, z_above, highest)
        amplitudes = [(w, 2 * abs(2 / (derivative(w, group, z_above) * w))) for w in found]
        if not amplitudes:
            print(f"{path}: no mode found below {highest:.3e}")
            continue
        ring = rings_for(amplitudes, 2 * args.threshold)
        largest = max(amplitudes, key=lambda m: m[1])
        print(f"{path}: layers 0..{top - 1} under a layer of transit {transits[top]:.2e}; "
              f"{len(found)} modes; under {args.threshold:.0e} after {ring:.3e} "
              f"({ring / transits[0]:.2e} bottom transits, {ring / transits[top]:.2e} of the layer above's); "
              f"the largest mode decays at {largest[0].imag:.2e}, the slowest at "
              f"{min(w.imag for w in found):.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
