#!/usr/bin/env python3
"""Writes a scene restarted from one sample of a run: each moving body's
position, orientation, velocity and angular velocity at that sample, the rest
of the scene as it was, and the time left after the sample as its duration.

  build/ci/compare/gacompare run box.json --backend traditional --out run
  bench/scale/restart_scene.py box.json run/trajectories.csv --at 0.9 > pile.json
  build/ci/bench/collision_step_bench --scene pile.json --settle 0.02

Only the bodies' state carries over: the collision step's memories (the
pairs' remembered axes and kept contacts, the warm starts, the broadphase's
trees) start empty, so the restarted run parts from the original within a
few steps. It is for measuring a phase of a run, such as a pile, without
running up to it each time (a builds' comparison can then alternate many
short runs), not for continuing one.

Every digit is kept: trajectories.csv writes each number so that it reads
back to the same double. A body's orientation is normalised again, as the
scene format asks for a unit quaternion to within 1e-6.
"""
import argparse
import csv
import json
import math
import sys


def fail(message):
    sys.exit(f"restart_scene: {message}")


def sample_states(path, at, backend):
    """{name: row} of the sample at time `at` (the nearest within 1e-9 s) of one backend."""
    rows, backends, times = {}, set(), set()
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            need = {"t", "backend", "kind", "name", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx",
                    "wy", "wz"}
            if reader.fieldnames is None or not need <= set(reader.fieldnames):
                fail(f"{path}: not a trajectories.csv (its header lacks {sorted(need - set(reader.fieldnames or []))})")
            for line, row in enumerate(reader, start=2):
                try:
                    t = float(row["t"])
                except ValueError:
                    fail(f"{path}:{line}: t is not a number: {row['t']!r}")
                backends.add(row["backend"])
                times.add(t)
                if abs(t - at) <= 1e-9 and (backend is None or row["backend"] == backend) and row["kind"] == "body":
                    if (row["backend"], row["name"]) in rows:
                        fail(f"{path}:{line}: body {row['name']!r} twice at t = {at}")
                    rows[(row["backend"], row["name"])] = row
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    if backend is None and len(backends) > 1:
        fail(f"{path} holds several backends ({', '.join(sorted(backends))}): name one with --backend")
    if backend is not None and backend not in backends:
        fail(f"{path} has no backend {backend!r} (it has {', '.join(sorted(backends))})")
    if not rows:
        near = sorted(times, key=lambda t: abs(t - at))[:3]
        fail(f"{path} has no sample at t = {at} (the nearest: {', '.join(str(t) for t in near)})")
    return {name: row for (_, name), row in rows.items()}


def number(row, key, name):
    try:
        value = float(row[key])
    except ValueError:
        fail(f"body {name!r}: {key} is not a number: {row[key]!r}")
    if not math.isfinite(value):
        fail(f"body {name!r}: {key} is {value} at the sample")
    return value


def restart(scene, states, at, duration):
    if scene.get("particles"):
        fail("the scene has particles; only bodies are restarted")
    bodies = scene.get("bodies", [])
    for body in bodies:
        if body.get("static"):
            continue
        name = body.get("name")
        row = states.get(name)
        if row is None:
            fail(f"the sample has no body {name!r}")
        q = [number(row, k, name) for k in ("qw", "qx", "qy", "qz")]
        norm = math.sqrt(sum(c * c for c in q))
        if not abs(norm - 1) <= 1e-6:
            fail(f"body {name!r}: its orientation at the sample is not a unit quaternion (norm {norm})")
        body["position"] = [number(row, k, name) for k in ("x", "y", "z")]
        body["orientation"] = [c / norm for c in q]
        body["velocity"] = [number(row, k, name) for k in ("vx", "vy", "vz")]
        body["angular_velocity"] = [number(row, k, name) for k in ("wx", "wy", "wz")]
    left = scene.get("duration", 0) - at
    scene["duration"] = duration if duration is not None else left
    if not scene["duration"] > 0:
        fail(f"nothing is left of the scene after t = {at} (its duration is {at + left}); give --duration")
    every = scene.get("output", {}).get("every")
    if every is not None and every > scene["duration"]:
        scene["output"]["every"] = scene["duration"]
    if scene.get("description"):
        scene["description"] += f" Restarted from its state at t = {at} s (bench/scale/restart_scene.py)."
    return scene


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scene", help="the scene file the run ran")
    p.add_argument("trajectories", help="the run's trajectories.csv")
    p.add_argument("--at", type=float, required=True, help="the sample's time, s")
    p.add_argument("--backend", help="the backend whose state to take (needed where the file holds several)")
    p.add_argument("--duration", type=float, help="the restarted scene's duration, s (default: what is left)")
    args = p.parse_args()
    try:
        with open(args.scene) as f:
            scene = json.load(f)
    except OSError as e:
        fail(f"{args.scene}: {e.strerror}")
    except json.JSONDecodeError as e:
        fail(f"{args.scene}:{e.lineno}: not JSON: {e.msg}")
    states = sample_states(args.trajectories, args.at, args.backend)
    json.dump(restart(scene, states, args.at, args.duration), sys.stdout)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
