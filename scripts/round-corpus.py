#!/usr/bin/env python3
"""Writes data/collision/round.json (issue #17): the round pairs of `gacompare
collide`. Hand-placed sphere-sphere and sphere-box pairs in each region of the
box (face, edge, vertex, inside) touching, apart and overlapping, then seeded
random spheres against boxes, tetrahedra, octahedra, icosahedra and hulls at
random orientations (seed 2026), about half of them overlapping. Rerun it to
regenerate the file bit for bit."""
import json, math, random, sys

def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]

def rotate(q, v):  # q = (w, x, y, z), unit
    w, x, y, z = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    return [sum(r[i][j] * v[j] for j in range(3)) for i in range(3)]

cases = []
def add(name, a, b):
    cases.append({"name": name, "a": a, "b": b})

# Sphere-sphere: radii 0.5 and 0.3 along a generic direction.
d = unit([0.3, -0.5, 0.8])
for label, dist in (("touching", 0.8), ("apart", 1.0), ("overlapping", 0.6), ("deep", 0.1)):
    add("sphere-sphere " + label, {"sphere": 0.5, "position": [0.1, 0.2, -0.3]},
        {"sphere": 0.3, "position": [0.1 + dist * d[0], 0.2 + dist * d[1], -0.3 + dist * d[2]]})

# A 0.3 sphere against a unit box turned about a generic axis, in each region.
q = unit([0.9, 0.2, -0.3, 0.25])
regions = {"face": ([0.2, 0.1, 0.5], [0, 0, 1]),
           "edge": ([0.5, 0.1, 0.5], unit([1, 0, 1])),
           "vertex": ([0.5, 0.5, 0.5], unit([1, 1, 1]))}
for region, (foot, out) in regions.items():
    for label, gap in (("touching", 0.0), ("apart", 0.1), ("overlapping", -0.05)):
        local = [foot[i] + (0.3 + gap) * out[i] for i in range(3)]
        add(f"sphere-box {region} {label}", {"box": [1, 1, 1], "position": [0, 0, 0], "orientation": q},
            {"sphere": 0.3, "position": rotate(q, local)})
add("sphere inside box", {"sphere": 0.3, "position": rotate(q, [0.1, 0.0, 0.3])},
    {"box": [1, 1, 1], "position": [0, 0, 0], "orientation": q})
add("sphere on a slab, touching", {"box": [2, 2, 0.2], "position": [0, 0, -0.1]},
    {"sphere": 0.1, "position": [0.3, -0.2, 0.1]})

rng = random.Random(2026)
def orientation():
    return unit([rng.gauss(0, 1) for _ in range(4)])
def polyhedron():
    kind = rng.choice(["box", "tetrahedron", "octahedron", "icosahedron", "hull"])
    if kind == "box":
        s = [rng.uniform(0.3, 1.5) for _ in range(3)]
        return {"box": s}, 0.5 * math.sqrt(sum(x * x for x in s))
    if kind == "hull":
        axes = [rng.uniform(0.3, 1) for _ in range(3)]
        pts = []
        for _ in range(rng.randint(4, 40)):
            p = unit([rng.gauss(0, 1) for _ in range(3)])
            pts.append([round(axes[i] * p[i], 12) for i in range(3)])
        return {"hull": pts}, max(axes)
    size = rng.uniform(0.3, 1)
    return {kind: size}, size
for i in range(60):
    r = rng.uniform(0.2, 0.8)
    shape, radius = polyhedron()
    d = unit([rng.gauss(0, 1) for _ in range(3)])
    dist = rng.uniform(0.2, 1.3) * (r + radius)
    centre = [rng.uniform(-1, 1) for _ in range(3)]
    poly = dict(shape, position=centre, orientation=orientation())
    ball = {"sphere": round(r, 12), "position": [centre[k] + dist * d[k] for k in range(3)]}
    a, b = (poly, ball) if i % 2 == 0 else (ball, poly)
    add(f"random round {i}", a, b)
for i in range(20):
    ra, rb = rng.uniform(0.1, 1), rng.uniform(0.1, 1)
    d = unit([rng.gauss(0, 1) for _ in range(3)])
    dist = rng.uniform(0.2, 1.5) * (ra + rb)
    c = [rng.uniform(-1, 1) for _ in range(3)]
    add(f"random sphere-sphere {i}", {"sphere": ra, "position": c},
        {"sphere": rb, "position": [c[k] + dist * d[k] for k in range(3)]})

json.dump(cases, sys.stdout, indent=1)
print()
