#!/usr/bin/env python3
"""What a second thread buys, and that it changes nothing: the scale scenes
(bench/scale/box_scene.py, N bodies thrown about in a box) through
traditional and cga on one thread and on two (gacompare --threads).

  bench/scale/threads.py --binary build/ci/compare/gacompare --sizes 1000,10000 --repeat 3
  bench/scale/threads.py --binary build/ci/compare/gacompare --sizes 10000 --repeat 2 --duration 1 --time-of-impact none

Each size runs `--duration` simulated seconds per setting; the thread counts
alternate within each repeat (1, 2, 2, 1, ...) and the backends' order
alternates between repeats. Quoted per backend: the run's seconds per
simulated second, median (min-max), for 1 and 2 threads, the speed-up (the
ratio of the medians), and whether every sample of every body (positions,
orientations, velocities) and every counter came out the same on two
threads as on one: each run's state hash (results.json "state_hash", the
SHA-256 of every sample's doubles to the bit, the solver's steps and every
counter; core/run.hpp), equal or not. `--time-of-impact` sets the boxes'
time_of_impact as scale.py's does (none: no impact search).
"""
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import box_scene  # noqa: E402
import runs  # noqa: E402
from runs import cell  # noqa: E402


def main():
    ap = runs.parser(__doc__, sizes="1000")
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--time-of-impact", default=None,
                    help="the boxes' time_of_impact (box_scene.py); none: no impact search")
    args, sizes, tmp = runs.start(ap, [("N", True), ("backend", False), ("1 thread, s per simulated s", True),
                                       ("2 threads", True), ("speed-up", True), ("same answer", False)])
    backends = ["traditional", "cga"]
    for n in sizes:
        scene = box_scene.scene(n, args.seed, args.duration, args.duration, args.time_of_impact)
        wall = {(b, t): [] for b in backends for t in (1, 2)}
        hashes = {(b, t): set() for b in backends for t in (1, 2)}
        for rep in range(args.repeat):
            order = backends if rep % 2 == 0 else backends[::-1]
            for t in (1, 2) if rep % 2 == 0 else (2, 1):
                got = runs.compare(args.binary, scene, os.path.join(tmp, f"box_{n}_{t}_{rep}"), order, threads=t)
                for b in backends:
                    wall[(b, t)].append(got[b]["wall_seconds"]["median"] / args.duration)
                    hashes[(b, t)].add(got[b]["state_hash"])
        for b in backends:
            speedup = statistics.median(wall[(b, 1)]) / statistics.median(wall[(b, 2)])
            same = len(hashes[(b, 1)] | hashes[(b, 2)]) == 1
            print(f"| {n} | {b} | {cell(wall[(b, 1)])} | {cell(wall[(b, 2)])} | {speedup:.2f} | "
                  f"{'yes' if same else 'NO'} |")
            if not same:
                print(f"threads.py: {b} on {n} bodies gave different answers on 1 and 2 threads", file=sys.stderr)
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
