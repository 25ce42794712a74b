#!/usr/bin/env python3
"""Steps at equal orientation accuracy: rotor (cga) and quaternion against the
matrix state, on the bundled spinning_top and dzhanibekov scenes.

Each scene runs with Cash-Karp at tolerances 1e-4 ... 1e-11 (abs = rel) in three
representations; the error is the angle of q^-1 q' between the final
orientation and that of the same scene at tolerance 1e-14 (traditional,
quaternion), computed as 4 atan2(|q - q'|, |q + q'|) with q' signed so that
q.q' >= 0 (the angle between q and q' as 4-vectors is half the rotation's).
Each curve (error, steps accepted) is interpolated log-log at the matrix's
errors, so the ratios compare steps at the same achieved error, not at the
same tolerance.

  python3 scripts/steps-at-equal-accuracy.py [--gacompare build/release/compare/gacompare]
"""
import argparse
import json
import math
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def angle(q, p):
    if sum(a * b for a, b in zip(q, p)) < 0:
        p = [-x for x in p]
    d = math.sqrt(sum((a - b) ** 2 for a, b in zip(q, p)))
    s = math.sqrt(sum((a + b) ** 2 for a, b in zip(q, p)))
    return 4 * math.atan2(d, s)


def run(gac, tmp, scene, tol, rotation, backend):
    s = json.load(open(os.path.join(ROOT, "data", "scenes", scene + ".json")))
    s["solver"] = {"method": "cash_karp45", "dt": 0.001, "abs_tol": tol, "rel_tol": tol}
    s["rigid_body"] = {"rotation": rotation}
    s["output"] = {"every": s["duration"]}
    s.pop("check", None)
    f = os.path.join(tmp, f"{scene}_{rotation}_{backend}_{tol:g}.json")
    json.dump(s, open(f, "w"))
    subprocess.run([gac, "run", f, "--backend", backend, "--out", f + ".d", "--repeat", "1", "--quiet"], check=True,
                   capture_output=True)
    r = json.load(open(os.path.join(f + ".d", "results.json")))["runs"][0]
    body = list(r["samples"][-1]["bodies"].values())[0]
    return body["orientation"], r["solver"]["steps_accepted"]


def steps_at(points, error):
    points = sorted(points)
    for (e0, n0), (e1, n1) in zip(points, points[1:]):
        if 0 < e0 <= error <= e1:
            t = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0)))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--gacompare", default=os.path.join(ROOT, "build", "release", "compare", "gacompare"))
    args = ap.parse_args()
    reps = {"matrix": ("matrix", "traditional"), "quaternion": ("quaternion", "traditional"), "rotor": ("matrix", "cga"),
            "motor": ("matrix", "pga")}
    print("| scene | orientation error | matrix steps | rotor / matrix | motor / matrix | quaternion / matrix |")
    print("|---|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ["spinning_top", "dzhanibekov"]:
            ref, _ = run(args.gacompare, tmp, scene, 1e-14, "quaternion", "traditional")
            curves = {name: [] for name in reps}
            for name, (rotation, backend) in reps.items():
                for e in range(4, 12):
                    q, n = run(args.gacompare, tmp, scene, 10.0 ** -e, rotation, backend)
                    curves[name].append((angle(q, ref), n))
            for error, n in curves["matrix"]:
                r, q = steps_at(curves["rotor"], error), steps_at(curves["quaternion"], error)
                mo = steps_at(curves["motor"], error)
                cell = lambda x: f"{x / n:.2f}" if x else "–"
                print(f"| {scene} | {error:.1e} | {n} | {cell(r)} | {cell(mo)} | {cell(q)} |")


if __name__ == "__main__":
    main()
