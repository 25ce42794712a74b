#!/usr/bin/env python3
"""Writes a stack at scale: a square pyramid of L layers of 0.2 m cubes, the
stacking family's square pyramid (answers/stacking_family.cpp) made larger.

  bench/scale/pyramid_scene.py --layers 20 > pyramid_20.json   # 2,870 cubes

Layer l (0 at the bottom) is a square of L - l cubes a side, 2 cm apart in each
row, each cube resting on four below; every level starts 1 mm above the one
below (so each cube falls l + 1 mm to its rest) on a static slab whose top is
at z = 0. Frictionless, without bounce (restitution 0), as the family's
frictionless pyramids; RK4 at 1 ms, collision step 1 ms, penetration
tolerance 1e-4 m, 1 kg cubes. Every cube's answer is its rest: where it was
placed, 1 mm per level lower.

Names are c<index>, bottom layer first; the slab is "ground".
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import box_scene  # noqa: E402

CUBE, DROP, GAP = 0.2, 0.001, 0.02
TOLERANCE = box_scene.TOLERANCE


def cubes(layers):
    """Each cube as (name, where it starts, its rest), bottom layer first."""
    pitch = CUBE + GAP
    out = []
    for level in range(layers):
        row = layers - level
        start = -(row - 1) * pitch / 2
        for i in range(row):
            for j in range(row):
                rest = (start + i * pitch, start + j * pitch, CUBE / 2 + level * CUBE)
                out.append((f"c{len(out) + 1}", (rest[0], rest[1], rest[2] + (level + 1) * DROP), rest))
    return out


def scene(layers, duration, every):
    if layers < 1:
        raise SystemExit("pyramid_scene: --layers must be at least 1")
    side = layers * (CUBE + GAP) + 1
    bodies = [{"name": "ground", "shape": {"box": [side, side, 0.2]}, "mass": 100, "position": [0, 0, -0.1],
               "static": True}]
    for name, start, _ in cubes(layers):
        bodies.append({"name": name, "shape": {"box": [CUBE, CUBE, CUBE]}, "mass": 1.0, "position": list(start)})
    count = len(bodies) - 1
    return box_scene.collision_scene(
        f"pyramid_{layers}",
        f"A square pyramid of {layers} layers ({count} cubes of 0.2 m, 2 cm apart in each row, each on four below), "
        "each level dropped 1 mm onto the one below, frictionless and without bounce "
        f"(bench/scale/pyramid_scene.py --layers {layers}): every cube comes to rest where it was placed.",
        duration, every, 0.001, 0, bodies)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--layers", type=int, required=True)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--every", type=float, default=0.01)
    args = ap.parse_args()
    json.dump(scene(args.layers, args.duration, args.every), sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
