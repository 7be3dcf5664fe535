#!/usr/bin/env python3
"""The viscous run's error bound against chains four times as fine.

`impact run` on a viscous scene answers with chains of 250, 500 and 1000
masses: `restitution` is the chain of 1000, and `error_bound` how far it
may be from the chain's N -> infinity limit. This draws random viscous
scenes (1 to 3 layers, moduli over 2.5 decades, densities over one,
relaxation times 10^-2.5 to 1 or a layer's `restitution` 0.3 to 0.97, some
layers elastic, either wall law), runs each as `impact run` does and as one
chain of 4000 masses, and sets the bound against the gap between the two,
times 4/3: at first order in N, the chain of 1000 is that far from the
limit. A ratio over 1 is a bound that does not hold. The binary is
`$IMPACT`, else `target/release/impact`.
"""

import argparse
import json
import os
import random
import subprocess
import tempfile


def draw(rng):
    layers = []
    for _ in range(rng.randint(1, 3)):
        layer = {
            "length": 10 ** rng.uniform(-1, 0.3),
            "modulus": 10 ** rng.uniform(-1, 1.5),
            "density": 10 ** rng.uniform(-0.5, 0.5),
        }
        r = rng.random()
        if r < 0.45:
            layer["relaxation_time"] = 10 ** rng.uniform(-2.5, 0)
        elif r < 0.9:
            layer["restitution"] = rng.uniform(0.3, 0.97)
        layers.append(layer)
    if not any("relaxation_time" in l or "restitution" in l for l in layers):
        layers[0]["restitution"] = 0.8
    scene = {"impact_speed": 1.0, "layers": layers}
    if rng.random() < 0.5:
        scene["wall_contact"] = "unilateral"
    return scene


def run(binary, path, extra):
    out = subprocess.run([binary, "run", path, "--json", *extra], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr.strip())
    return json.loads(out.stdout)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", type=int, default=10, help="scenes to draw (default 10)")
    parser.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    args = parser.parse_args()
    binary = os.environ.get("IMPACT", "target/release/impact")
    rng = random.Random(args.seed)
    worst = 0.0
    print("scene  layers  wall        e(N=1000)  bound    e(N=4000)  4/3 gap  ratio  clean")
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.scenes):
            scene = draw(rng)
            path = os.path.join(tmp, f"scene{k}.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            ladder = run(binary, path, [])
            fine = run(binary, path, ["--n", "4000"])
            bound = ladder["error_bound"]
            gap = abs(ladder["restitution"] - fine["restitution"]) * 4 / 3
            worst = max(worst, gap / bound)
            print(
                f"{k:5d}  {len(scene['layers']):6d}  {scene.get('wall_contact', 'paper'):10s}  "
                f"{ladder['restitution']:.6f}  {bound:.1e}  {fine['restitution']:.6f}   "
                f"{gap:.1e}  {gap / bound:5.2f}  {ladder['extrapolation']['clean']}",
                flush=True,
            )
    print(f"{args.scenes} scenes (seed {args.seed}): the largest gap is {worst:.2f} of its bound")


if __name__ == "__main__":
    main()
