#!/usr/bin/env python3
"""The scale table: seconds of run time per simulated second for
boxes of N bodies (bench/scale/box_scene.py) through traditional, cga and
Bullet, each stage's share, and the exponent p of cost ~ N^p.

  bench/scale/scale.py --binary build/release/compare/gacompare              # N = 27, 125, 1000
  bench/scale/scale.py --binary build/release/compare/gacompare --long       # and 10,000 (tens of minutes)
  bench/scale/scale.py --sizes 27,125 --repeat 3 --out reports/scale
  bench/scale/scale.py --time-of-impact none                                 # the same boxes with no impact search
  bench/scale/scale.py --sizes 125,1000,10000,100000 --time-of-impact none --threads 2 --every 0.5 \
      --bullet-up-to 10000                                                   # to 100,000 bodies (twenty minutes)

Every size runs as one `gacompare compare` of the three backends, which
alternates their order in each repeat and quotes medians with min-max; the
table quotes those. The exponent is the least-squares slope of log(cost)
against log(N) over the sizes from 125 up (the issue's range), with the
slope between each pair of neighbouring sizes beside it. The scene files, each
size's results folder and the table (scale.md, scale.json) go to --out.
--threads is gacompare's (Bullet's world always runs on one thread);
--bullet-up-to leaves Bullet out above that size; --every sets the samples
(the penetration check reads them: 100,000 bodies' samples every 0.05 s
would take 6.6 GB).
"""
import argparse
import datetime
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import box_scene  # noqa: E402
from runs import RULES, sanity  # noqa: E402

STAGES = ["forces", "integrate", "broadphase", "narrowphase", "time_of_impact", "response"]


def slope(points):
    """Least-squares slope of log y against log x."""
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def run_size(args, n):
    scene = box_scene.scene(n, args.seed, args.duration, args.every, args.time_of_impact)
    path = os.path.join(args.out, f"box_{n}.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    folder = os.path.join(args.out, f"box_{n}")
    backends = [b for b in args.backends.split(",")
                if b != "bullet" or args.bullet_up_to is None or n <= args.bullet_up_to]
    cmd = [args.binary, "compare", path, "--backends", ",".join(backends), "--repeat", str(args.repeat),
           "--threads", str(args.threads), "--out", folder]
    print(f"scale: N = {n}: {' '.join(cmd)}", file=sys.stderr, flush=True)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, text=True)
    if not os.path.exists(os.path.join(folder, "results.json")):
        raise SystemExit(f"scale: N = {n}: gacompare exited {done.returncode} and wrote no results")
    results = json.load(open(os.path.join(folder, "results.json")))
    rows = {}
    for run in results["runs"]:
        wall = run["wall_seconds"]
        stages = {s: run["stages"][s]["seconds"] for s in STAGES if s in run["stages"]}
        total = sum(stages.values())
        rows[run["backend"]] = {
            "per_simulated_second": wall["median"] / args.duration,
            "min": wall["min"] / args.duration,
            "max": wall["max"] / args.duration,
            "shares": {s: v / total for s, v in stages.items()} if total > 0 else {},
            "error": run.get("error"),
            "counters": {k: run["counters"][k] for k in ("largest_island", "islands_stepped_alone",
                                                          "island_bodies_stepped_alone", "impact_searches",
                                                          "narrowphase_pairs", "island_narrowphase_pairs",
                                                          "links_apart", "broadphase_candidates",
                                                          "impact_searches_unresolved", "push_out_detections",
                                                          "push_out_left_deep")
                         if k in run.get("counters", {})},
        }
    for backend, lines in sanity(os.path.join(folder, "report.md")).items():
        if backend in rows:
            rows[backend].update(lines)
    if done.returncode != 0:
        print(f"scale: N = {n}: gacompare exited {done.returncode}", file=sys.stderr)
    return rows


def table(args, sizes, data):
    backends = args.backends.split(",")
    options = "".join(f" --{flag} {value}" for flag, value, default in (
        ("time-of-impact", args.time_of_impact, None), ("threads", args.threads, 1), ("every", args.every, 0.05),
        ("backends", args.backends, "traditional,cga,bullet"), ("bullet-up-to", args.bullet_up_to, None))
        if value != default)
    out = [f"Command: `bench/scale/scale.py --sizes {','.join(map(str, sizes))} --repeat {args.repeat} "
           f"--duration {args.duration} --seed {args.seed}{options}` ({args.repeat} repeat(s) per size, median "
           f"(min–max); {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d')}, {os.cpu_count()} cores, "
           f"{args.threads} thread(s)).", "",
           "| N | " + " | ".join(f"{b} s per simulated s" for b in backends) + " | cga / traditional | traditional / bullet |",
           "|---:|" + "---:|" * (len(backends) + 2)]
    for n in sizes:
        r = data[n]
        cells = []
        for b in backends:
            x = r.get(b)
            cells.append("–" if not x else (f"{x['per_simulated_second']:.3g} ({x['min']:.3g}–{x['max']:.3g})" +
                                            (" **failed**" if x["error"] else "")))
        ratio = lambda a, b: (f"{r[a]['per_simulated_second'] / r[b]['per_simulated_second']:.2f}"
                              if a in r and b in r else "–")
        out.append(f"| {n} | " + " | ".join(cells) + f" | {ratio('cga', 'traditional')} | {ratio('traditional', 'bullet')} |")
    out += ["", "Exponent p of cost ∝ N^p (least squares over N ≥ 125; between neighbouring sizes in brackets):", ""]
    for b in backends:
        pts = [(n, data[n][b]["per_simulated_second"]) for n in sizes if n >= 125 and b in data[n]]
        steps = [f"{slope(pts[i:i + 2]):.2f}" for i in range(len(pts) - 1)]
        p = f"{slope(pts):.2f}" if len(pts) >= 2 else "–"
        out.append(f"- {b}: p = {p}" + (f" [{', '.join(steps)}]" if steps else ""))
    bound = ("ten penetration tolerances and one step's travel for every backend: none searches"
             if args.time_of_impact == "none" else "ten penetration tolerances; Bullet's adds one step's travel")
    out += ["", f"Physical sanity at the samples (every {args.every:g} s): the deepest any body went into a wall, and "
            f"the deepest two moving bodies went into each other, against the rules' bound ({bound}; for two bodies, "
            "both bodies' travel) — a run that fails them is wrong physics, and its time is no measure:", "",
            "| N | " + " | ".join(f"{b}: wall / bodies (m)" for b in backends) + " |", "|---:|" + "---:|" * len(backends)]
    for n in sizes:
        cells = []
        for b in backends:
            parts = []
            for key in RULES:
                x = data[n].get(b, {}).get(key)
                parts.append("–" if not x else f"{x['value']}" + ("" if x["pass"] else f" **FAILS** (bound {x['bound']})"))
            cells.append(" / ".join(parts))
        out.append(f"| {n} | " + " | ".join(cells) + " |")
    out += ["", "Share of stage time (" + ", ".join(STAGES) + "):", "",
            "| N | backend | " + " | ".join(STAGES) + " |", "|---:|---|" + "---:|" * len(STAGES)]
    for n in sizes:
        for b in backends:
            x = data[n].get(b)
            if not x:
                continue
            out.append(f"| {n} | {b} | " + " | ".join(f"{100 * x['shares'][s]:.0f}%" if s in x["shares"] else "–"
                                                     for s in STAGES) + " |")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default="build/release/compare/gacompare")
    ap.add_argument("--sizes", default="27,125,1000")
    ap.add_argument("--long", action="store_true", help="add N = 10,000 (tens of minutes)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--every", type=float, default=0.05)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--backends", default="traditional,cga,bullet")
    ap.add_argument("--time-of-impact", default=None,
                    help="the boxes' time_of_impact (box_scene.py); none: no impact search")
    ap.add_argument("--threads", type=int, default=1, help="gacompare's --threads (Bullet runs on one)")
    ap.add_argument("--bullet-up-to", type=int, default=None, help="run Bullet only on boxes of at most this many bodies")
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    if args.threads < 1:
        raise SystemExit("scale.py: --threads must be at least 1")
    if not args.every > 0:
        raise SystemExit("scale.py: --every must be positive")
    sizes = sorted({int(s) for s in args.sizes.split(",")} | ({10000} if args.long else set()))
    if args.out is None:
        args.out = os.path.join("reports", "scale-" + datetime.datetime.now().strftime("%Y%m%dT%H%M%S"))
    os.makedirs(args.out, exist_ok=True)
    data = {n: run_size(args, n) for n in sizes}
    text = table(args, sizes, data)
    with open(os.path.join(args.out, "scale.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "scale.json"), "w") as f:
        json.dump({"sizes": sizes, "duration": args.duration, "seed": args.seed, "repeat": args.repeat,
                   "results": {str(n): data[n] for n in sizes}}, f, indent=1)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
