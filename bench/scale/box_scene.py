#!/usr/bin/env python3
"""Writes a scale scene: N mixed bodies thrown about in a closed box
at constant density, the bundled bodies_in_box scaled up.

  bench/scale/box_scene.py --bodies 1000 --seed 1 > box_1000.json

The bodies (cubes of 0.12 m, tetrahedra of 0.2 m, octahedra of 0.09 m, density
500, chosen at random) start on a cubic grid of pitch 0.3 m, k = ceil(N^(1/3))
per side, in the first N cells; the six static walls (0.1 m thick) enclose the
grid with 0.15 m to spare on every side, as in bodies_in_box (k = 3: walls at
+-0.65 m). Velocities are uniform in [-2, 2] m/s per component, angular
velocities in [-5, 5] rad/s, orientations uniform on SO(3) (Shoemake's
method), all from one seeded generator, so the same N and seed always give the
same file. Gravity, restitution 0.7, penetration tolerance 1e-4 m, collision
step 1 ms and RK4 at 0.5 ms are bodies_in_box's. --time-of-impact none writes
the same box with no impact search (what the tolerance costs, scale.py).

Names are b<index>; the walls are wall_x-, wall_x+, ... as in bodies_in_box.
"""
import argparse
import json
import math
import random
import sys

PITCH = 0.3
SHAPES = [{"box": [0.12, 0.12, 0.12]}, {"tetrahedron": 0.2}, {"octahedron": 0.09}]
TOLERANCE = 1e-4  # the collision scenes' penetration tolerance (m)


def unit_quaternion(rng):
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return [a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3),
            b * math.cos(2 * math.pi * u3)]


def scene(bodies, seed, duration, every, time_of_impact=None):
    if bodies < 1:
        raise SystemExit("box_scene: --bodies must be at least 1")
    rng = random.Random(seed)
    k = 1
    while k ** 3 < bodies:
        k += 1
    half = 0.5 * PITCH * (k - 1) + 0.3  # inner half-size: 0.15 m beyond a body's cell (bodies_in_box: 0.6)
    span = 2 * half + 0.2
    walls = []
    for axis, name in enumerate("xyz"):
        for sign, tag in ((-1, "-"), (1, "+")):
            size = [span, span, span]
            size[axis] = 0.1
            pos = [0.0, 0.0, 0.0]
            pos[axis] = sign * (half + 0.05)
            walls.append({"name": f"wall_{name}{tag}", "shape": {"box": size}, "mass": 10, "position": pos,
                          "static": True})
    out = []
    offset = 0.5 * PITCH * (k - 1)
    for index in range(bodies):
        i, j, l = index // (k * k), (index // k) % k, index % k
        out.append({
            "name": f"b{index:05d}",
            "shape": rng.choice(SHAPES),
            "density": 500,
            "position": [i * PITCH - offset, j * PITCH - offset, l * PITCH - offset],
            "orientation": unit_quaternion(rng),
            "velocity": [rng.uniform(-2, 2) for _ in range(3)],
            "angular_velocity": [rng.uniform(-5, 5) for _ in range(3)],
        })
    out = collision_scene(
        f"box_{bodies}",
        f"{bodies} mixed bodies thrown about in a closed box at constant density (the scale "
        f"benchmark's scene, bench/scale/box_scene.py --bodies {bodies} --seed {seed}); chaotic, so the backends "
        "part and the divergence check is bounded by the box.",
        duration, every, 0.0005, 0.7, walls + out)
    if time_of_impact:
        out["description"] += f" The collisions effect's time_of_impact is {time_of_impact}."
        for effect in out["effects"]:
            if effect["type"] == "collisions":
                effect["time_of_impact"] = time_of_impact
    out["check"] = {"max_divergence": 2 * span}
    return out


def collision_scene(name, description, duration, every, dt, restitution, bodies):
    """A scene of `bodies` under gravity with collisions (penetration tolerance
    1e-4 m, collision step 1 ms) integrated by RK4 at `dt`: the scale scenes'
    common part (pyramid_scene.py uses it too)."""
    return {
        "name": name,
        "description": description,
        "duration": duration,
        "output": {"every": every},
        "solver": {"method": "rk4", "dt": dt},
        "effects": [
            {"type": "gravity", "g": [0, 0, -9.81]},
            {"type": "collisions", "restitution": restitution, "penetration_tolerance": TOLERANCE, "step": 0.001},
        ],
        "bodies": bodies,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bodies", type=int, required=True)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--duration", type=float, default=0.5)
    ap.add_argument("--every", type=float, default=0.05)
    ap.add_argument("--time-of-impact", default=None,
                    help="the collisions effect's time_of_impact (default: the scene format's, bisection; "
                         "none: no search, docs/collision-response.md)")
    args = ap.parse_args()
    json.dump(scene(args.bodies, args.seed, args.duration, args.every, args.time_of_impact), sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
