#!/usr/bin/env python3
"""What the narrowphase's reuse saves in a whole run: the
scale scenes (bench/scale/box_scene.py) with the collisions effect's `reuse` on
(each body's narrowphase geometry built once per detection, each pair's
separating axis remembered) and off (both bodies rebuilt for every pair,
nothing remembered: the same run, tested), through traditional and cga.

  bench/scale/reuse.py --binary build/release/compare/gacompare --sizes 125,1000 --repeat 3

Each size and setting is one `gacompare compare` of the two backends (their
order alternating in each repeat); the settings alternate too (on, off, on,
off, ...), one repeat each, so that a slow spell of the shared machine falls
on both. The table quotes medians over the repeats (min-max) of the
narrowphase stage's seconds and the whole run's, per simulated second, and
the counters that say why (pairs, shapes built, pairs their remembered axis
decided).
"""
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import box_scene  # noqa: E402
import runs  # noqa: E402
from runs import cell  # noqa: E402


def run(args, scene, folder):
    out = {}
    for backend, r in runs.compare(args.binary, scene, folder, ["traditional", "cga"]).items():
        out[backend] = {"wall": r["wall_seconds"]["median"] / args.duration,
                        "narrowphase": r["stages"]["narrowphase"]["seconds"] / args.duration,
                        "counters": r["counters"]}
    return out


def main():
    ap = runs.parser(__doc__)
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--seed", type=int, default=1)
    args, sizes, tmp = runs.start(
        ap, [("N", True), ("backend", False), ("reuse", False), ("narrowphase s", True), ("whole run s", True),
             ("narrowphase pairs", True), ("shapes built", True), ("axes kept", True)],
        " (seconds per simulated second, median (min–max) of the repeats; counters of one run)")
    for n in sizes:
        data = {}
        for rep in range(args.repeat):
            for reuse in (True, False) if rep % 2 == 0 else (False, True):
                scene = box_scene.scene(n, args.seed, args.duration, args.duration / 4)
                for e in scene["effects"]:
                    if e["type"] == "collisions":
                        e["reuse"] = reuse
                got = run(args, scene, os.path.join(tmp, f"box_{n}_{reuse}_{rep}"))
                for backend, r in got.items():
                    data.setdefault((backend, reuse), []).append(r)
        for backend in ("traditional", "cga"):
            for reuse in (True, False):
                rs = data[(backend, reuse)]
                c = rs[0]["counters"]
                print(f"| {n} | {backend} | {'on' if reuse else 'off'} | {cell([r['narrowphase'] for r in rs])} | "
                      f"{cell([r['wall'] for r in rs])} | {c.get('narrowphase_pairs', 0)} | "
                      f"{c.get('narrowphase_shapes', 0)} | {c.get('narrowphase_axes_kept', 0)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
