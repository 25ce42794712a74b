#!/usr/bin/env python3
"""Stacks at scale: square pyramids of L layers (bench/scale/pyramid_scene.py:
the stacking family's square pyramid made larger) through traditional, cga
and Bullet in one `gacompare compare` per size.

  bench/scale/pyramids.py --binary build/ci/compare/gacompare --sizes 3,5,10 --duration 0.3

The sizes are layers (3, 5, 10 layers: 14, 55, 385 cubes). The first ~0.05 s
are the landings (each level falls 1 mm more than the one below), the rest
the resting pyramid. Quoted per run: seconds of run time per simulated
second, the contact points and the direct solve's factorisations and
active-set changes per collision step (traditional and cga), and the
farthest any cube is from its rest at the end (the statics answer: where it
was placed, (level + 1) mm lower), which a standing pyramid keeps within the
penetration tolerance (1e-4 m) of each contact below it: the last column
says whether every cube stayed within L tolerances of its rest (the top
cube has L contacts below it, the slab's included) and moved at no more
than 1e-6 m/s at every sample from LANDED s on (the end alone where the
run is shorter; --every sets the samples, by default only the end). The
farthest and fastest columns are the worst over those samples. Medians over the
repeats (min-max) for the times; the rest from the last repeat (the runs are
deterministic). Backends in the order given, alternated between repeats.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pyramid_scene  # noqa: E402
import runs  # noqa: E402
from runs import cell  # noqa: E402


LANDED = 0.5  # s: every level has landed by then (a 20-layer pyramid's top cube falls 20 mm, some 0.06 s)


def main():
    ap = runs.parser(__doc__, sizes="3,5,10", repeat=1)
    ap.add_argument("--duration", type=float, default=0.3)
    ap.add_argument("--every", type=float, default=0.0, help="seconds between samples (default: the duration)")
    ap.add_argument("--backends", default="traditional,cga,bullet")
    args, sizes, scratch = runs.start(ap, [("layers", True), ("cubes", True), ("backend", False),
                                           ("s per simulated s", True), ("contacts per step", True),
                                           ("factorisations per step", True), ("active-set changes", True),
                                           ("farthest from rest (m)", True), ("fastest once landed (m/s)", True),
                                           ("stands", False)])
    backends = args.backends.split(",")
    for layers in sizes:
        scene = pyramid_scene.scene(layers, args.duration, args.every or args.duration)
        rest = {name: at for name, _, at in pyramid_scene.cubes(layers)}
        times = {b: [] for b in backends}
        last = {}
        for k in range(args.repeat):
            order = backends if k % 2 == 0 else backends[::-1]
            got = runs.compare(args.binary, scene, os.path.join(scratch, f"pyramid_{layers}_{k}"), order)
            for b, r in got.items():
                times[b].append(r["wall_seconds"]["median"] / args.duration)
                last[b] = r
        for b in backends:
            r = last[b]
            c = r.get("counters", {})
            steps = c.get("collision_steps", 0)
            per_step = lambda key: f"{c[key] / steps:.3g}" if steps and key in c else "–"
            since = min(LANDED, r["samples"][-1]["t"])
            held = [sample["bodies"] for sample in r["samples"] if sample["t"] >= since]
            far = max(math.dist(at_t[name]["position"], at) for at_t in held for name, at in rest.items())
            fastest = max(math.hypot(*at_t[name]["velocity"]) for at_t in held for name in rest)
            stands = far <= layers * pyramid_scene.TOLERANCE and fastest <= 1e-6
            print(f"| {layers} | {len(rest)} | {b} | {cell(times[b])} | {per_step('contacts')} | "
                  f"{per_step('direct_factorisations')} | {c.get('direct_pivots', '–')} | {far:.2g} | "
                  f"{fastest:.2g} | {'yes' if stands else 'NO'} |")


if __name__ == "__main__":
    main()
