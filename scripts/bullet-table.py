#!/usr/bin/env python3
"""The Bullet comparison table from a `gacompare compare` folder:
per collision scene and backend, the moving body's first bounce apexes, where
it ends (position, speed), how far the total linear momentum moved over the
run (scenes without gravity, where it is conserved), and the wall time per
simulated second (median of the repeats).

  gacompare compare data/scenes/cube_*.json ... --repeat 3 --out reports/response
  python3 scripts/bullet-table.py reports/response
"""
import json
import math
import pathlib
import statistics
import sys


def apexes(samples, body, count=3):
    out = []
    for a, b in zip(samples, samples[1:]):
        va, vb = a["bodies"][body]["velocity"][2], b["bodies"][body]["velocity"][2]
        if va > 0 >= vb:
            out.append(max(a["bodies"][body]["position"][2], b["bodies"][body]["position"][2]))
    return out[:count]


def main():
    root = pathlib.Path(sys.argv[1])
    print(f"Command: `python3 scripts/bullet-table.py {root}` over `gacompare compare` results\n")
    print("| scene | backend | apexes of the moving body (m) | final position (m) | final speed (m/s) | "
          "momentum change (N s) | wall ms per simulated s |")
    print("|---|---|---|---|---:|---:|---:|")
    for f in sorted(root.glob("*/results.json")):
        r = json.loads(f.read_text())
        duration = r["runs"][0]["samples"][-1]["t"]
        for run in r["runs"]:
            s = run["samples"]
            body = list(s[0]["bodies"])[-1]
            last = s[-1]["bodies"][body]
            up = ", ".join(f"{z:.4f}" for z in apexes(s, body)) or "–"
            pos = "(" + ", ".join(f"{x:.4f}" for x in last["position"]) + ")"
            speed = math.hypot(*last["velocity"])
            dp = math.dist(s[0]["linear_momentum"], s[-1]["linear_momentum"])
            wall = run["wall_seconds"]["median"] if isinstance(run["wall_seconds"], dict) else run["wall_seconds"]
            print(f"| {f.parent.name} | {run['backend']} | {up} | {pos} | {speed:.3g} | {dp:.2g} | "
                  f"{1e3 * wall / duration:.1f} |")


if __name__ == "__main__":
    main()
