"""The dynamics pages: particles (work-precision sweeps), rigid bodies
(stability, steps and time at equal accuracy, what each representation costs),
the long horizon (the Lie-group integrators over thousands of periods),
meshes (mass properties, hulls) and integrators (the SciML rigid body)."""
import json
import os
import re
import shutil

from .common import RESULTS, ratio_of, ratios, strip_command_line, tables

IMG = os.path.join(RESULTS, "img")


def _sweep(ctx, scene, extra, quick_extra):
    out = ctx.scratch_dir("sweep-" + scene)
    args = extra + (quick_extra if ctx.quick else [])
    ctx.run([ctx.gacompare, "sweep", f"data/scenes/{scene}.json", *args, "--out", out],
            quote=f"{ctx.gacompare} sweep data/scenes/{scene}.json {' '.join(args)} --out DIR".replace("  ", " "))
    with open(os.path.join(out, "sweep.md")) as f:
        text = f.read()
    os.makedirs(IMG, exist_ok=True)
    svg = f"{scene}_work_precision.svg"
    shutil.copyfile(os.path.join(out, svg), os.path.join(IMG, svg))
    text = re.sub(r"^# .*\n+", "", text, count=1)
    text = re.sub(r"^(#+) ", lambda m: "##" + m.group(1) + " ", text, flags=re.M)
    return f"![{scene}: work-precision](img/{svg})\n\n" + text


def particles(ctx):
    quick = ["--tolerances", "1e-3:1e-8", "--steps", "1e-2:3", "--repeat", "1"]
    blocks = {
        "pendulum": _sweep(ctx, "pendulum", [], quick),
        "kepler": _sweep(ctx, "kepler", [], quick),
        "hanging_net": _sweep(ctx, "hanging_net", ["--max-duration", "2"], quick),
    }
    return {"blocks": blocks, "headline": []}


def _accuracy(ctx, scenes, target, repeat):
    out = ctx.scratch_dir(f"accuracy-{target}")
    paths = [f"data/scenes/{s}.json" for s in scenes]
    ctx.run([ctx.gacompare, "compare", *paths, "--accuracy", target, "--repeat", repeat, "--out", out, "--quiet"],
            quote=f"{ctx.gacompare} compare {' '.join(paths)} --accuracy {target} --repeat {repeat} --out DIR")
    with open(os.path.join(out, "accuracy.md")) as f:
        text = f.read()
    return re.sub(r"^(#+) ", lambda m: "##" + m.group(1) + " ", re.sub(r"^# .*\n+", "", text, count=1), flags=re.M)


def _accuracy_ratio(markdown, scene, backend="cga", over="traditional"):
    """`backend`/`over` of `scene` in accuracy.md: the cell of its row under
    "time / OVER" in the first table after the scene's own heading."""
    m = re.search(r"^#+ " + re.escape(scene) + r"\s*$", markdown, flags=re.M)
    if not m:
        return None
    for t in tables(markdown[m.end():]):
        head = [h.lower() for h in t[0]]
        if "backend" in head:
            b = head.index("backend")
            column = f"time / {over}"
            if column not in head:
                return None
            row = next((r for r in t[1:] if r[b] == backend), None)
            return row[head.index(column)] if row else None
    return None


def rigid_bodies(ctx):
    steps = ["--steps", "10000"] if ctx.quick else []
    stability = ctx.run([ctx.tool("bench", "rigid_stability"), *steps])
    equal_steps = ctx.run(["python3", "scripts/steps-at-equal-accuracy.py", "--gacompare", ctx.gacompare])
    repeat = "5" if ctx.quick else "21"
    tight = _accuracy(ctx, ["spinning_top"], "1e-6", repeat)
    loose = _accuracy(ctx, ["spinning_top", "dzhanibekov"], "1e-3", repeat)
    sweep = _sweep(ctx, "spinning_top", ["--solvers", "cash_karp45,rk4"],
                   ["--tolerances", "1e-3:1e-9", "--steps", "1e-2:3", "--repeat", "1"])
    costs = ratios(ctx, "rigid_bench", "matrix", 10, 3)
    headline = []
    r = _accuracy_ratio(tight, "spinning_top")
    if r:
        headline.append({"finding": "Rigid bodies at equal accuracy: spinning top to 1e-6 rad, cga (rotor) / traditional (matrix) time",
                         "value": r, "anchor": "#time-at-equal-accuracy"})
    d = _accuracy_ratio(loose, "dzhanibekov")
    if d:
        headline.append({"finding": "The same on the Dzhanibekov flip, to 1e-3 rad", "value": d,
                         "anchor": "#time-at-equal-accuracy"})
    # The rotor's algebraic twin, the quaternion, beside the matrix: a fair
    # headline names which traditional form it compares with.
    for backend, form in (("cga", "rotor"), ("pga", "motor")):
        for over, name in (("traditional", "matrix"), ("traditional-quaternion", "quaternion")):
            if (backend, over) == ("cga", "traditional"):
                continue  # the first row above
            v = _accuracy_ratio(tight, "spinning_top", backend, over)
            if v:
                headline.append({"finding": f"The same, {backend} ({form}) / traditional ({name}): spinning top to 1e-6 rad",
                                 "value": v, "anchor": "#time-at-equal-accuracy"})
    for op, label in (("derivative", "Rotor derivative / matrix derivative"),
                      ("vertices", "Moving a mesh: rotor sandwich / matrix product")):
        v = ratio_of(costs, op, "rotor")
        if v:
            headline.append({"finding": label, "value": v + "×", "anchor": "#what-the-representations-cost"})
    blocks = {"stability": strip_command_line(stability), "equal-steps": strip_command_line(equal_steps),
              "accuracy-tight": tight, "accuracy-loose": loose, "sweep": sweep, "costs": costs}
    return {"blocks": blocks, "headline": headline}


def long_horizon(ctx):
    periods = "1000" if ctx.quick else "10000"
    table = ctx.run([ctx.tool("bench", "long_horizon"), "--periods", periods, "--repeat", "3", "--markdown"])
    return {"blocks": {"tables": table}, "headline": []}


def _hulls(ctx):
    reps = "3" if ctx.quick else "5"
    text = ctx.run([ctx.tool("bench", "hull_bench"), f"--benchmark_repetitions={reps}",
                    "--benchmark_report_aggregates_only=true", "--benchmark_format=json"])
    data = json.loads(text)
    what = {"BM_HullOfSphere": "Qhull and the mesh, {} points on a sphere",
            "BM_HullBodyReady": "the body ready to collide, {} points on a sphere",
            "BM_HullOfFlatPoints": "Qhull, 1,000 points within 1e-{} m of a plane"}
    rows = ["| benchmark | what | median CPU time | repetitions |", "|---|---|---:|---:|"]
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        t = b["cpu_time"]
        unit = b.get("time_unit", "ns")
        seconds = t * {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[unit]
        shown = f"{seconds * 1e3:.3g} ms" if seconds < 1 else f"{seconds:.3g} s"
        name, _, arg = b["run_name"].partition("/")
        label = what.get(name, "{}").format(f"{int(arg):,}" if name != "BM_HullOfFlatPoints" else arg)
        rows.append(f"| `{b['run_name']}` | {label} | {shown} | {b.get('repetitions', reps)} |")
    return "\n".join(rows)


def integrators(ctx):
    out = ctx.run([ctx.tool("bench", "rigid_body_sciml"), *(["--quick"] if ctx.quick else [])])
    parts = dict(re.findall(r"<!-- part: ([a-z-]+) -->\n(.*?)(?=<!-- part: |\Z)", out, re.S))
    return {"blocks": parts, "headline": []}


def meshes(ctx):
    mass = ctx.run([ctx.tool("bench", "mass_properties_sweep"), *(["--quick"] if ctx.quick else [])])
    return {"blocks": {"mass-properties": strip_command_line(mass), "hulls": _hulls(ctx)}, "headline": []}
