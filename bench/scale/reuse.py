#!/usr/bin/env python3
"""What the narrowphase's reuse saves in a whole run: the
scale scenes (bench/scale/box_scene.py) with one of the collisions effect's
settings on and off, through traditional and cga:
  --setting reuse (the default): each body's narrowphase geometry built once
    per detection, each pair's separating axis remembered; off, both bodies
    rebuilt for every pair and nothing remembered (the same run, tested);
  --setting reuse_contacts: a pair's face manifold kept between detections
    while its relative pose stays within a bound; off, every pair tested
    every time (not the same run: kept points may sit up to the bound
    sideways of the tested ones).

  bench/scale/reuse.py --binary build/release/compare/gacompare --sizes 125,1000 --repeat 3
  bench/scale/reuse.py --binary build/release/compare/gacompare --sizes 1000 --setting reuse_contacts

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
    ap.add_argument("--setting", choices=["reuse", "reuse_contacts"], default="reuse")
    setting = ap.parse_known_args()[0].setting  # the table's header names it
    args, sizes, tmp = runs.start(
        ap, [("N", True), ("backend", False), (setting, False), ("narrowphase s", True), ("whole run s", True),
             ("narrowphase pairs", True), ("shapes built", True), ("axes kept", True), ("contacts kept", True)],
        " (seconds per simulated second, median (min–max) of the repeats; counters of one run)")
    for n in sizes:
        data = {}
        for rep in range(args.repeat):
            for reuse in (True, False) if rep % 2 == 0 else (False, True):
                scene = box_scene.scene(n, args.seed, args.duration, args.duration / 4)
                for e in scene["effects"]:
                    if e["type"] == "collisions":
                        e[args.setting] = reuse
                got = run(args, scene, os.path.join(tmp, f"box_{n}_{reuse}_{rep}"))
                for backend, r in got.items():
                    data.setdefault((backend, reuse), []).append(r)
        for backend in ("traditional", "cga"):
            for reuse in (True, False):
                rs = data[(backend, reuse)]
                c = rs[0]["counters"]
                print(f"| {n} | {backend} | {'on' if reuse else 'off'} | {cell([r['narrowphase'] for r in rs])} | "
                      f"{cell([r['wall'] for r in rs])} | {c.get('narrowphase_pairs', 0)} | "
                      f"{c.get('narrowphase_shapes', 0)} | {c.get('narrowphase_axes_kept', 0)} | "
                      f"{c.get('narrowphase_contacts_kept', 0)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
