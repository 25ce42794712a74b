#!/usr/bin/env python3
"""Writes data/collision/round.json: the round pairs of `gacompare
collide`. Hand-placed sphere-sphere and sphere-box pairs in each region of the
box (face, edge, vertex, inside) touching, apart and overlapping, then seeded
random spheres against boxes, tetrahedra, octahedra, icosahedra and hulls at
random orientations (seed 2026), about half of them overlapping. Rerun it to
regenerate the file bit for bit.

With --capsules it writes data/collision/capsule.json instead: hand-placed
capsule pairs (lying on a face, end down, across an edge, along an edge,
inside and through a box; capsule-capsule aligned, crossed and turned by
1e-9; capsule-sphere) touching, apart and overlapping, then seeded random
capsules (seed 2027) against polyhedra, spheres and capsules."""
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
capsules = "--capsules" in sys.argv[1:]
def add(name, a, b):
    cases.append({"name": name, "a": a, "b": b})

def capsule_corpus():
    q = unit([0.9, 0.2, -0.3, 0.25])
    box = {"box": [1, 1, 1], "position": [0, 0, 0], "orientation": q}
    x_axis = [math.cos(math.pi / 4), 0, math.sin(math.pi / 4), 0]  # local z to x
    y_axis = [math.cos(math.pi / 4), -math.sin(math.pi / 4), 0, 0]  # local z to y
    def qmul(a, b):
        w1, x1, y1, z1 = a
        w2, x2, y2, z2 = b
        return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]
    for label, gap in (("touching", 0.0), ("apart", 0.1), ("overlapping", -0.05)):
        h = 0.5 + 0.1 + gap
        for name, local, o in (("flat on face", [0.1, 0.05, h], x_axis), ("end down", [0.1, 0.05, h + 0.3], [1, 0, 0, 0]),
                               ("across an edge", [0.5, 0.05, h], x_axis)):
            add(f"capsule-box {name} {label}", box,
                {"capsule": [0.1, 0.6], "position": rotate(q, local), "orientation": qmul(q, o)})
        e = [0.5 + (0.1 + gap) / math.sqrt(2), 0, 0.5 + (0.1 + gap) / math.sqrt(2)]
        add(f"capsule-box along an edge {label}", box,
            {"capsule": [0.1, 0.6], "position": rotate(q, e), "orientation": qmul(q, y_axis)})
        d = 0.5 + gap
        for name, o in (("aligned", [1, 0, 0, 0]), ("crossed", x_axis),
                        ("turned 1e-9", [math.cos(0.5e-9), math.sin(0.5e-9), 0, 0])):
            add(f"capsule-capsule {name} {label}", {"capsule": [0.2, 1], "position": [0.1, 0.2, -0.3], "orientation": q},
                {"capsule": [0.3, 0.8], "position": [0.1 + x for x in rotate(q, [0, d, 0.1])], "orientation": qmul(q, o)})
        add(f"capsule-sphere beside {label}", {"capsule": [0.2, 1], "position": [0, 0, 0], "orientation": q},
            {"sphere": 0.25, "position": rotate(q, [0.45 + gap, 0, 0.1])})
    add("capsule inside box", box, {"capsule": [0.1, 0.6], "position": rotate(q, [0.1, 0, 0.2]), "orientation": qmul(q, x_axis)})
    add("capsule through box", {"capsule": [0.1, 2], "position": rotate(q, [0, 0.1, 0.3]), "orientation": qmul(q, x_axis)}, box)
    add("capsule on a slab, touching", {"box": [2, 2, 0.2], "position": [0, 0, -0.1]},
        {"capsule": [0.1, 0.4], "position": [0.3, -0.2, 0.1], "orientation": x_axis})
    rng = random.Random(2027)
    def orientation():
        return unit([rng.gauss(0, 1) for _ in range(4)])
    def capsule():
        r, l = rng.uniform(0.1, 0.5), rng.uniform(0.1, 1.5)
        return {"capsule": [round(r, 12), round(l, 12)]}, r + l / 2
    for i in range(60):
        shape, radius = capsule()
        other, other_radius = polyhedron(rng)
        d = unit([rng.gauss(0, 1) for _ in range(3)])
        dist = rng.uniform(0.2, 1.3) * (radius + other_radius)
        centre = [rng.uniform(-1, 1) for _ in range(3)]
        poly = dict(other, position=centre, orientation=orientation())
        cap = dict(shape, position=[centre[k] + dist * d[k] for k in range(3)], orientation=orientation())
        a, b = (poly, cap) if i % 2 == 0 else (cap, poly)
        add(f"random capsule-polyhedron {i}", a, b)
    for i in range(30):
        (sa, ra), (sb, rb) = capsule(), capsule()
        if i % 3 == 0:
            r = rng.uniform(0.1, 0.8)
            sb, rb = {"sphere": round(r, 12)}, r
        d = unit([rng.gauss(0, 1) for _ in range(3)])
        dist = rng.uniform(0.2, 1.3) * (ra + rb)
        c = [rng.uniform(-1, 1) for _ in range(3)]
        b = dict(sb, position=[c[k] + dist * d[k] for k in range(3)])
        if "capsule" in sb:
            b["orientation"] = orientation()
        add(f"random capsule-round {i}", dict(sa, position=c, orientation=orientation()), b)

def polyhedron(rng):
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

if capsules:
    capsule_corpus()
    json.dump(cases, sys.stdout, indent=1)
    print()
    sys.exit(0)

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
for i in range(60):
    r = rng.uniform(0.2, 0.8)
    shape, radius = polyhedron(rng)
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
