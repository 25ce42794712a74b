#!/usr/bin/env python3
"""What a box costs once its bodies have piled up: its second simulated
second against its first.

  bench/scale/piled.py --binary build/ci/compare/gacompare --sizes 125,1000 --repeat 3

The boxes of bench/scale/box_scene.py (seed 1) without an impact search, as
scale.py --time-of-impact none runs them for their first second, in which
the bodies fly, meet and pile up. In the second the pile has formed and
keeps moving (the bodies are frictionless, restitution 0.7), and every step
solves its contacts as one group of thousands of rows. Each size runs for 1
and for 2 simulated seconds through traditional, cga and Bullet in one
`gacompare compare` each (one thread, the order of the backends alternating
between repeats); the second second's cost is the difference of the two
runs' times. The scene is chaotic, so each backend builds its own pile, as
in the other box tables. Quoted: medians over the repeats (min-max), the
second second against the first, and against Bullet's second second.
"""
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import box_scene  # noqa: E402
import runs  # noqa: E402
from runs import cell  # noqa: E402


def main():
    ap = runs.parser(__doc__)
    ap.add_argument("--seed", type=int, default=1)
    args, sizes, tmp = runs.start(ap, [("N", True), ("backend", False), ("first second (s)", True),
                                       ("second second (s)", True), ("second / first", True),
                                       ("second second / Bullet's", True)])
    backends = ["traditional", "cga", "bullet"]
    for n in sizes:
        first = {b: [] for b in backends}
        second = {b: [] for b in backends}
        for rep in range(args.repeat):
            order = backends if rep % 2 == 0 else backends[::-1]
            wall = {}
            for duration in (1.0, 2.0):
                scene = box_scene.scene(n, args.seed, duration, duration, "none")
                folder = os.path.join(tmp, f"n{n}_r{rep}_{duration:g}")
                got = runs.compare(args.binary, scene, folder, order)
                wall[duration] = {b: got[b]["wall_seconds"]["median"] for b in backends}
            for b in backends:
                first[b].append(wall[1.0][b])
                second[b].append(wall[2.0][b] - wall[1.0][b])
        for b in backends:
            growth = statistics.median(second[b]) / statistics.median(first[b])
            against = statistics.median(second[b]) / statistics.median(second["bullet"])
            print(f"| {n} | {b} | {cell(first[b])} | {cell(second[b])} | {growth:.3g} | {against:.3g} |")


if __name__ == "__main__":
    main()
