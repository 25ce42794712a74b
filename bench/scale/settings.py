#!/usr/bin/env python3
"""What the collisions effect's accuracy settings cost at scale: the box of N
bodies without an impact search (bench/scale/box_scene.py --time-of-impact
none) under each collision step and penetration tolerance of a grid, RK4 at
half the step (the box's own ratio), on two threads.

  bench/scale/settings.py --sizes 10000 --steps 1,4 --tolerances 1e-4,1e-3,5e-3 --repeat 3

The box's own settings are a step of 1 ms and a tolerance of 1e-4 m. Each
run is one `gacompare compare` of one backend; in each repeat every setting
of the grid runs once, in the grid's order and then reversed in the next
repeat, so that a slow spell of the shared machine falls on all of them.
The table quotes, per setting: seconds of run time per simulated second,
median (min-max) of the repeats; the counters of the first repeat that say
where the time goes (narrowphase pairs, push-out detections, islands
stepped again alone); and the two depth rules of the report's physical
sanity checks (compare/sanity.cpp) at the samples: the deepest any body went
into a wall, and the deepest two moving bodies went into each other, each
FAILS where it broke the rule (ten tolerances, and one step's travel). Two
settings' runs part within tenths of a second (the box is chaotic), so each
setting's pile is its own.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import box_scene  # noqa: E402
import runs  # noqa: E402
from runs import cell  # noqa: E402


def numbers(text, what):
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        raise SystemExit(f"settings.py: --{what}: expected numbers separated by commas, got '{text}'")
    if not values or any(not v > 0 for v in values):
        raise SystemExit(f"settings.py: --{what}: every value must be above 0, got '{text}'")
    return values


def scene_with(n, args, step_ms, tolerance):
    scene = box_scene.scene(n, args.seed, args.duration, args.every, "none")
    scene["solver"]["dt"] = step_ms / 2000
    for e in scene["effects"]:
        if e["type"] == "collisions":
            e["step"] = step_ms / 1000
            e["penetration_tolerance"] = tolerance
    scene["description"] += f" Collision step {step_ms:g} ms, RK4 at half of it, penetration tolerance {tolerance:g} m."
    return scene


def depth(rules, key):
    r = rules.get(key)
    if r is None:
        return "–"
    return r["value"] + ("" if r["pass"] else " (FAILS)")


def main():
    ap = runs.parser(__doc__, sizes="10000")
    ap.add_argument("--steps", default="1,4", help="collision steps in ms")
    ap.add_argument("--tolerances", default="1e-4,1e-3,5e-3", help="penetration tolerances in m")
    ap.add_argument("--backend", default="traditional", choices=["traditional", "cga", "pga"])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--every", type=float, default=0.05)
    ap.add_argument("--seed", type=int, default=1)
    given = ap.parse_known_args()[0]  # the grid checked before the table's header is printed
    grid = [(s, t) for s in numbers(given.steps, "steps") for t in numbers(given.tolerances, "tolerances")]
    args, sizes, tmp = runs.start(
        ap, [("N", True), ("step (ms)", True), ("tolerance (m)", True), ("s per simulated s", True),
             ("narrowphase pairs", True), ("push-out detections", True), ("islands stepped alone", True),
             ("deepest into a wall (m)", True), ("deepest between bodies (m)", True)],
        " (seconds of run time per simulated second, median (min–max) of the repeats; counters and depths of the "
        "first repeat)")
    for n in sizes:
        wall = {g: [] for g in grid}
        first = {}
        for rep in range(args.repeat):
            for step_ms, tol in grid if rep % 2 == 0 else grid[::-1]:
                folder = os.path.join(tmp, f"box_{n}_{step_ms:g}ms_{tol:g}_{rep}")
                got = runs.compare(args.binary, scene_with(n, args, step_ms, tol), folder, [args.backend],
                                   threads=args.threads)[args.backend]
                wall[(step_ms, tol)].append(got["wall_seconds"]["median"] / args.duration)
                first.setdefault((step_ms, tol), (got["counters"], got["sanity"]))
        for step_ms, tol in grid:
            c, rules = first[(step_ms, tol)]
            print(f"| {n} | {step_ms:g} | {tol:g} | {cell(wall[(step_ms, tol)])} | {c.get('narrowphase_pairs', 0):,} | "
                  f"{c.get('push_out_detections', 0):,} | {c.get('islands_stepped_alone', 0):,} | "
                  f"{depth(rules, 'penetration')} | {depth(rules, 'overlap')} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
