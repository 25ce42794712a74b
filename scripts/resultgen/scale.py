"""docs/results/scale.md: boxes of 27 to 1,000 bodies through traditional,
cga and Bullet (bench/scale/scale.py), the same boxes with no impact search
(scale.py --time-of-impact none) and without a search to 100,000 bodies on
two threads, what the accuracy settings cost on the 10,000-body box
(bench/scale/settings.py), what the narrowphase's reuse saves
(bench/scale/reuse.py), what sleeping saves on a settled pile
(bench/scale/sleep.py), what a second thread buys (bench/scale/threads.py)
and what the boxes cost once piled (bench/scale/piled.py)."""
import json
import os
import re

from .common import strip_command_line


def series(ctx, name, args):
    """One run of bench/scale/scale.py with `args`: its table (command line
    stripped) and its scale.json."""
    out = ctx.scratch_dir(name)
    ctx.run(["python3", "bench/scale/scale.py", "--binary", ctx.gacompare, *args, "--out", out],
            quote=f"python3 bench/scale/scale.py --binary {ctx.gacompare} {' '.join(args)} --out DIR")
    with open(os.path.join(out, "scale.md")) as f:
        table = strip_command_line(f.read())
    with open(os.path.join(out, "scale.json")) as f:
        return table, json.load(f)


def penetration(rows, backends, rule="penetration"):
    """Each backend's deepest sample of a depth rule (bench/scale/runs.py RULES:
    into a wall, or two moving bodies into each other) as a headline cell,
    FAILS marked."""
    return [f"{b} {rows[b][rule]['value']} m" + ("" if rows[b][rule]["pass"] else " (FAILS)")
            for b in backends if rule in rows.get(b, {})]


def generate(ctx):
    # Not --long: with every impact found within the tolerance, the 10,000-body
    # box's pile costs a quarter of an hour per simulated second per backend
    # (docs/results/scale.md says why), several hours for the three repeats.
    size = ["--sizes", "27,125,1000", "--repeat", "1" if ctx.quick else "3"]
    scale, data = series(ctx, "scale", size)
    # The same boxes with no impact search: what the tolerance costs, each
    # backend against Bullet in its own process (the two series are two runs).
    unsearched, data_none = series(ctx, "scale-none", [*size, "--time-of-impact", "none"])
    # To 100,000 bodies: without a search, on two threads, one repeat (about
    # twenty minutes); Bullet, on one thread whatever --threads says, up to
    # 10,000 only (at 100,000 it would take over an hour). Samples every
    # 0.5 s: 100,000 bodies' samples every 0.05 s would take 6.6 GB.
    large, data_large = series(ctx, "scale-large",
                               ["--sizes", "125,1000" if ctx.quick else "125,1000,10000,100000", "--repeat", "1",
                                "--time-of-impact", "none", "--threads", "2", "--every", "0.5",
                                "--bullet-up-to", "10000"])
    reuse_args = ["--sizes", "125,1000", "--repeat", "1" if ctx.quick else "3", "--duration", "0.2"]
    reuse = strip_command_line(ctx.run(["python3", "bench/scale/reuse.py", "--binary", ctx.gacompare, *reuse_args]))
    # The boxes' second simulated second, once piled, against their first.
    piled_args = ["--sizes", "125" if ctx.quick else "125,1000", "--repeat", "1" if ctx.quick else "3"]
    piled = strip_command_line(ctx.run(["python3", "bench/scale/piled.py", "--binary", ctx.gacompare, *piled_args]))
    sleep_args = ["--sizes", "125,1000", "--repeat", "1" if ctx.quick else "3"]
    sleep = strip_command_line(ctx.run(["python3", "bench/scale/sleep.py", "--binary", ctx.gacompare, *sleep_args]))
    headline = []
    largest = str(max(data["sizes"]))
    r = data["results"][largest]
    cells = [f"{b} {r[b]['per_simulated_second']:.3g} s" for b in ("traditional", "cga", "bullet") if b in r]
    if cells:
        headline.append({"finding": f"{int(largest):,} bodies in a box: run time per simulated second "
                                    "(each backend's own pile: the scene is chaotic)",
                         "value": ", ".join(cells), "anchor": "#bodies-in-a-box"})
    deep = penetration(r, ("traditional", "cga", "bullet"))
    if deep:
        headline.append({"finding": f"{int(largest):,} bodies in a box: the deepest any body went into a wall "
                                    "(penetration tolerance 1e-4 m; the sanity rule allows ten)",
                         "value": ", ".join(deep), "anchor": "#bodies-in-a-box"})
    squeezed = penetration(r, ("traditional", "cga", "bullet"), "overlap")
    if squeezed:
        headline.append({"finding": f"{int(largest):,} bodies in a box: the deepest two moving bodies went into each "
                                    "other at a sample (the sanity rule allows ten tolerances; Bullet's also one step's "
                                    "travel of both)",
                         "value": ", ".join(squeezed), "anchor": "#bodies-in-a-box"})
    rn = data_none["results"].get(largest, {})
    ratio = lambda rows, b: rows[b]["per_simulated_second"] / rows["bullet"]["per_simulated_second"]
    cost = [f"{b} {ratio(r, b):.2f}× Bullet's time searched, {ratio(rn, b):.2f}× without"
            for b in ("traditional", "cga") if b in r and b in rn and "bullet" in r and "bullet" in rn]
    if cost:
        headline.append({"finding": f"What the penetration tolerance costs on {int(largest):,} bodies in a box: every "
                                    "impact searched to 1e-4 m, against time_of_impact none (each measured against "
                                    "Bullet in its own run)",
                         "value": "; ".join(cost), "anchor": "#without-a-search"})
    deep_none = penetration(rn, ("traditional", "cga"))
    squeezed_none = penetration(rn, ("traditional", "cga"), "overlap")
    if squeezed_none:
        headline.append({"finding": f"{int(largest):,} bodies in a box without a search: the deepest two moving "
                                    "bodies went into each other at a sample (the rule allows ten tolerances and one "
                                    "step's travel of both)",
                         "value": ", ".join(squeezed_none), "anchor": "#without-a-search"})
    if deep_none:
        headline.append({"finding": f"{int(largest):,} bodies in a box without a search: the deepest any body went "
                                    "into a wall at a sample (the rule allows ten tolerances and one step's travel)",
                         "value": ", ".join(deep_none), "anchor": "#without-a-search"})
    for line in scale.splitlines():
        m = re.match(r"- (\w+): p = ([0-9.]+)", line)
        if m:
            headline.append({"finding": f"Cost ∝ N^p from 125 bodies up, {m.group(1)}", "value": f"p = {m.group(2)}",
                             "anchor": "#bodies-in-a-box"})
    most = str(max(data_large["sizes"]))
    rl = data_large["results"][most]
    cells = [f"{b} {rl[b]['per_simulated_second']:.3g} s" + (" (failed)" if rl[b]["error"] else "")
             for b in ("traditional", "cga") if b in rl]
    deep_large = penetration(rl, ("traditional", "cga"))
    if cells:
        headline.append({"finding": f"{int(most):,} bodies in a box without a search, on two threads: run time per "
                                    "simulated second, and the deepest any body went into a wall at a sample",
                         "value": ", ".join(cells) + ("; " + ", ".join(deep_large) if deep_large else ""),
                         "anchor": "#to-100000-bodies"})
    exponents = [f"{m.group(1)} {m.group(2)}" for m in (re.match(r"- (traditional|cga): p = ([0-9.]+)", line)
                                                       for line in large.splitlines()) if m]
    if exponents:
        headline.append({"finding": f"Cost ∝ N^p from 125 to {int(most):,} bodies without a search, on two threads",
                         "value": "p = " + ", ".join(exponents), "anchor": "#to-100000-bodies"})
    # What the accuracy settings cost where the time goes: the 10,000-body box
    # without a search on two threads, collision step by penetration tolerance.
    settings_args = (["--sizes", "1000", "--repeat", "1", "--duration", "0.3"] if ctx.quick
                     else ["--sizes", "10000", "--repeat", "3"])
    settings = strip_command_line(ctx.run(["python3", "bench/scale/settings.py", "--binary", ctx.gacompare,
                                           *settings_args]))
    grid = {}  # (step ms, tolerance) -> (N, median s per simulated s)
    for line in settings.splitlines():
        cols = [c.strip() for c in line.strip("|").split("|")]
        if len(cols) == 9 and cols[0].isdigit():
            grid[(float(cols[1]), float(cols[2]))] = (int(cols[0]), cols[3].split(" ")[0])
    own = (1.0, 1e-4)  # box_scene.py's collision step (ms) and tolerance (m)
    if own in grid:
        cheapest = max(grid)
        n = grid[own][0]
        headline.append({"finding": f"What accuracy costs on {n:,} bodies in a box without a search, on two threads: "
                                    f"run time per simulated second at the box's collision step and penetration "
                                    f"tolerance, and at the coarsest of the grid",
                         "value": f"{grid[own][1]} s at {own[0]:g} ms and {own[1]:g} m; {grid[cheapest][1]} s at "
                                  f"{cheapest[0]:g} ms and {cheapest[1]:g} m",
                         "anchor": "#what-accuracy-costs-at-10000-bodies"})
    # Five alternated repeats: a spell of this shared machine's second core
    # busy with other work slows the two-thread runs in every stage at once
    # (one page's three two-thread runs of this box all read some 25 % slower
    # than the same build's by hand in the same hour).
    thread_args = ["--sizes", "1000", "--repeat", "1" if ctx.quick else "5"]
    threads = strip_command_line(ctx.run(["python3", "bench/scale/threads.py", "--binary", ctx.gacompare, *thread_args,
                                          "--duration", "1"]))
    # The same without a search, on the largest box two threads are asked to
    # speed up: five alternated repeats, as above, and since this machine's
    # one-thread runs of it spread by some 5 %, as much as the speed-up is
    # asked to move.
    unsearched_args = ["--sizes", "1000" if ctx.quick else "10000", "--repeat", "1" if ctx.quick else "5"]
    threads_unsearched = strip_command_line(ctx.run(["python3", "bench/scale/threads.py", "--binary", ctx.gacompare,
                                                     *unsearched_args, "--duration", "1", "--time-of-impact", "none"]))

    def two_threads(table, what):
        speedups = {}  # N -> (speed-up, same answer), traditional
        for line in table.splitlines():
            cols = [c.strip() for c in line.strip("|").split("|")]
            if len(cols) == 6 and cols[0].isdigit() and cols[1] == "traditional":
                speedups[int(cols[0])] = (cols[4], cols[5] == "yes")
        if speedups:
            n = max(speedups)
            speedup, same = speedups[n]
            headline.append({"finding": f"{n:,} bodies in a box{what} on two threads against one, traditional",
                             "value": f"{speedup}× one thread's speed, the same answer bit for bit" if same
                             else f"{speedup}×, and the answers DIFFER",
                             "anchor": "#what-a-second-thread-buys"})

    two_threads(threads, "")
    two_threads(threads_unsearched, " without a search")
    once = {}  # N -> backend -> (second second's median, second / first)
    for line in piled.splitlines():
        cols = [c.strip() for c in line.strip("|").split("|")]
        if len(cols) == 6 and cols[0].isdigit():
            once.setdefault(int(cols[0]), {})[cols[1]] = (cols[3].split(" ")[0], cols[4])
    if once:
        n = max(once)
        headline.append({"finding": f"{n:,} bodies in a box without a search, once piled: its second simulated "
                                    "second's time, and that against its first's (one thread)",
                         "value": ", ".join(f"{b} {t} s ({g}×)" for b, (t, g) in once[n].items()),
                         "anchor": "#once-piled"})
    asleep = {}  # N -> backend -> settled cost asleep / awake
    for line in sleep.splitlines():
        cols = [c.strip() for c in line.strip("|").split("|")]
        if len(cols) == 8 and cols[0].isdigit():
            asleep.setdefault(int(cols[0]), {})[cols[1]] = float(cols[4])
    if asleep:
        n = max(asleep)
        headline.append({"finding": f"A settled pile of {n:,} cubes asleep: its time per simulated second, "
                                    "against the same pile awake",
                         "value": ", ".join(f"{b} {r:.1%}" for b, r in asleep[n].items()),
                         "anchor": "#what-sleeping-saves"})
    return {"blocks": {"scale": scale, "scale_unsearched": unsearched, "scale_large": large, "reuse": reuse,
                       "sleep": sleep, "settings": settings, "piled": piled,
                       "threads": threads, "threads_unsearched": threads_unsearched}, "headline": headline}
