#!/usr/bin/env python3
"""What sleeping saves on a settled pile, and what it costs in accuracy.

  bench/scale/sleep.py --binary build/ci/compare/gacompare --sizes 125,1000 --repeat 3

The pile: k x k columns of `--layers` 0.2 m cubes (1 kg) on a static slab,
each cube dropped 1 mm onto the one below, the columns 0.3 m apart, with the
stacking family's settings (restitution 0.2, penetration tolerance 1e-4 m,
collision step 1 ms, RK4 at 1 ms, the direct contact solver). N is the number
of cubes; k = ceil(sqrt(N / layers)), and the last row may be short.

Each size runs through traditional and cga with the collisions effect's
`sleep` off and on (its defaults: 0.01 m/s for 0.5 s), each for two
durations: `--settle` and `--settle + --span` simulated seconds with sleep
off, `--settle` and `--settle + --span-asleep` with it on. The pile settles
and (with sleep on) falls asleep within `--settle`; the difference of the
two runs' times over the span is the cost per simulated second of the
settled pile alone, with the settling left out. The sleeping pile costs so
little that its span is longer (30 s by default), or the noise of the
settling, in both runs, would swamp it. Settings and durations
alternate within each repeat (off, on, off, on, ...), and the backends'
order alternates between repeats, so a slow spell of a shared machine falls
on both. Quoted: medians over the repeats (min-max), the ratio on/off of
the settled cost, and the largest distance between a body's position with
sleep on and off at the end of the shorter runs (`--settle`). Bullet is left
out: its columns do not stand (docs/results/stacking.md), so its pile never
settles, and a span of an unsettled pile says nothing about sleeping (its
cost falls as cubes fall off the slab).
"""
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs  # noqa: E402
from runs import cell  # noqa: E402

CUBE = 0.2
GAP = 0.001
PITCH = 0.3


def pile(n, layers, duration, sleep):
    k = max(1, math.ceil(math.sqrt(n / layers)))
    half = k * PITCH / 2 + 0.5
    bodies = [{"name": "slab", "shape": {"box": [2 * half, 2 * half, 0.2]}, "mass": 1,
               "position": [0, 0, -0.1], "static": True}]
    count = 0
    for i in range(k):
        for j in range(k):
            for level in range(layers):
                if count == n:
                    break
                count += 1
                x, y = (i - (k - 1) / 2) * PITCH, (j - (k - 1) / 2) * PITCH
                z = CUBE / 2 + level * (CUBE + GAP) + GAP
                bodies.append({"name": f"c{count}", "shape": {"box": [CUBE, CUBE, CUBE]}, "mass": 1,
                               "position": [x, y, z]})
    collisions = {"type": "collisions", "restitution": 0.2, "penetration_tolerance": 1e-4, "step": 0.001}
    if sleep:
        collisions["sleep"] = {}
    return {"name": f"pile_{n}", "description": f"{n} cubes in columns of {layers} on a slab",
            "duration": duration, "output": {"every": duration},
            "solver": {"method": "rk4", "dt": 0.001},
            "effects": [{"type": "gravity"}, collisions], "bodies": bodies}


def run(args, scene, folder, backends):
    out = {}
    for backend, r in runs.compare(args.binary, scene, folder, backends).items():
        final = {name: b["position"] for name, b in r["samples"][-1]["bodies"].items()}
        out[backend] = {"wall": r["wall_seconds"]["median"], "counters": r["counters"], "final": final}
    return out


def main():
    ap = runs.parser(__doc__)
    ap.add_argument("--layers", type=int, default=5)
    ap.add_argument("--settle", type=float, default=1.5)
    ap.add_argument("--span", type=float, default=2.0)
    ap.add_argument("--span-asleep", type=float, default=30.0)
    args, sizes, tmp = runs.start(ap, [("N", True), ("backend", False), ("settled s per simulated s, sleep off", True),
                                       ("sleep on", True), ("on / off", True), ("sleeping body-steps", True),
                                       ("islands slept", True), ("largest offset on vs off (m)", True)])
    backends = ["traditional", "cga"]
    for n in sizes:
        cost = {(b, s): [] for b in backends for s in (False, True)}
        last = {}
        for rep in range(args.repeat):
            order = backends if rep % 2 == 0 else backends[::-1]
            for sleep in (False, True):
                span = args.span_asleep if sleep else args.span
                walls = {}
                for d in (args.settle, args.settle + span):
                    folder = os.path.join(tmp, f"n{n}_r{rep}_{'on' if sleep else 'off'}_{d}")
                    walls[d] = run(args, pile(n, args.layers, d, sleep), folder, order)
                for b in backends:
                    cost[(b, sleep)].append((walls[args.settle + span][b]["wall"] - walls[args.settle][b]["wall"]) / span)
                last[sleep] = walls
        for b in backends:
            off, on = cost[(b, False)], cost[(b, True)]
            ratio = statistics.median(on) / statistics.median(off)
            # Positions compared at the same time, the end of the shorter runs.
            fa, fb = last[True][args.settle][b]["final"], last[False][args.settle][b]["final"]
            offset = max((math.dist(fa[k], fb[k]) for k in fa if k in fb), default=float("nan"))
            c = last[True][args.settle + args.span_asleep][b]["counters"]
            print(f"| {n} | {b} | {cell(off)} | {cell(on)} | {ratio:.3f} | {c.get('sleeping_body_steps', '–')} | "
                  f"{c.get('sleep_islands', '–')} | {offset:.2g} |")


if __name__ == "__main__":
    main()
