#!/usr/bin/env python3
"""Whether a block's response ends in a few decaying modes: the question a
"modal tail" (a response's long end carried as a few complex exponentials,
summed by a recursion instead of traced and convolved) must answer first.

Reads what `crates/wave/examples/block_taps.rs` writes (each answered
block's traced response, per input and output port, on the port's
lattice) and fits the taps from `K` on by `J` damped modes (the matrix
pencil method on a window of `W` taps), then says how far the fitted modes
are from the traced taps over the whole rest of the response, as a share
of its largest tap. A tail of `J` modes is as good as this share.

    cargo run --release -p impact-wave --example block_taps -- SCENE.json 0.2 1.0 > taps.json
    python3 scripts/block-tail.py taps.json [--modes 4,16,64] [--from 0.05,0.125] [--window 1000]

Needs numpy. `--check` first fits a sum of three known modes, which it
must find to rounding.
"""

import argparse
import json
import sys

import numpy as np


def pencil(y, modes):
    """`modes` damped modes `z` and amplitudes `c` with y[k] ~ sum c z^k."""
    n = len(y)
    rows = n // 2
    hankel = np.array([y[i:i + n - rows + 1] for i in range(rows)])
    _, _, vh = np.linalg.svd(hankel, full_matrices=False)
    v = vh.conj().T[:, :modes]
    z = np.linalg.eigvals(np.linalg.pinv(v[:-1, :]) @ v[1:, :])
    basis = np.vander(z, n, increasing=True).T
    c = np.linalg.lstsq(basis, y, rcond=None)[0]
    return z, c


def modal(z, c, n):
    k = np.arange(n)
    return (c[None, :] * z[None, :] ** k[:, None]).sum(1).real


def check():
    k = np.arange(600)
    y = 0.7 * 0.999 ** k * np.cos(0.3 * k) + 0.2 * 0.99 ** k + 1e-3 * 0.95 ** k * np.sin(1.1 * k)
    z, c = pencil(y[:300], 5)
    err = np.abs(modal(z, c, 600) - y).max()
    assert err < 1e-9, err
    print(f"check: three known modes (five exponentials) found, the rest predicted to {err:.1e}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("taps", nargs="?")
    parser.add_argument("--modes", default="4,16,64", help="mode counts to try (default 4,16,64)")
    parser.add_argument("--from", dest="start", default="0.05,0.125",
                        help="where the tail starts, as shares of the traced taps (default 0.05,0.125)")
    parser.add_argument("--window", type=int, default=1000, help="taps fitted (default 1000)")
    parser.add_argument("--check", action="store_true", help="check the fit on known modes first")
    args = parser.parse_args()
    if args.check:
        check()
    if not args.taps:
        return 0
    modes = [int(m) for m in args.modes.split(",")]
    starts = [float(s) for s in args.start.split(",")]
    for block in json.loads(open(args.taps).read()):
        for i, ports in enumerate(block["inputs"]):
            for o, port in enumerate(ports):
                h = np.array(port["taps"])
                n = len(h)
                scale = np.abs(h).max() if n else 0.0
                if n < 4 * max(modes) or scale == 0.0:
                    print(f"block {block['lower']}..={block['upper']} input {i} port {o}: {n} taps, too few")
                    continue
                for share in starts:
                    k0 = int(share * n)
                    w = min(args.window, (n - k0) // 2)
                    line = []
                    for m in modes:
                        if 2 * m >= w:
                            continue
                        z, c = pencil(h[k0:k0 + w], m)
                        off = np.abs(modal(z, c, n - k0) - h[k0:]).max() / scale
                        line.append(f"{m} modes {off:.1e}")
                    print(f"block {block['lower']}..={block['upper']} input {i} port {o}: {n} taps "
                          f"(spacing {port['spacing']:.2e}), from tap {k0} (|h| there "
                          f"{np.abs(h[k0:k0 + 50]).max() / scale:.1e} of the largest): " + ", ".join(line))
    return 0


if __name__ == "__main__":
    sys.exit(main())
