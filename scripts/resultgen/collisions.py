"""docs/results/collisions.md: collision detection per stage (whole scenes)
and per pair (the corpus, the micro benchmarks), each algebra against the
others, with the referees' agreement."""
import json
import os

from .common import ROOT, ratios, tables


def collision_scenes(skip=()):
    names = []
    for f in sorted(os.listdir(os.path.join(ROOT, "data", "scenes"))):
        with open(os.path.join(ROOT, "data", "scenes", f)) as s:
            scene = json.load(s)
        if any(e.get("type") == "collisions" for e in scene.get("effects", [])) and f[:-5] not in skip:
            names.append(f[:-5])
    return names


def _per_stage(ctx):
    # The 27-body box is most of the time; a quick run leaves it out.
    names = collision_scenes(skip=("bodies_in_box",) if ctx.quick else ())
    out = ctx.scratch_dir("collision-stages")
    paths = [f"data/scenes/{n}.json" for n in names]
    ctx.run([ctx.gacompare, "compare", *paths, "--backends", "traditional,cga,pga", "--repeat", "5", "--out", out,
             "--quiet"],
            quote=f"{ctx.gacompare} compare <the {len(names)} scenes that list collisions"
                  f"{', less bodies_in_box' if ctx.quick else ''}> --backends traditional,cga,pga --repeat 5 --out DIR")
    with open(os.path.join(out, "report.md")) as f:
        report = f.read()
    # One category × stage table per pair of backends (cga / traditional,
    # pga / traditional, pga / cga): their collision rows, the pair first.
    lines = ["| pair | stage | scenes | denominator | numerator | ratio [95% CI] | verdict |",
             "|---|---|---:|---:|---:|---:|---|"]
    by_pair = {}
    for t in tables(report):
        head = [h.lower() for h in t[0]]
        if head[:2] != ["category", "stage"] or len(head) < 7:
            continue
        pair = head[5].split(" [")[0]
        # "collisions", or "collisions (2 parted, left out)" where scenes parted
        rows = [r[1:] for r in t[1:] if r[0].split(" (")[0] == "collisions"]
        by_pair[pair] = rows
        lines += ["| " + pair + " | " + " | ".join(r) + " |" for r in rows]
    if not by_pair or not all(by_pair.values()):
        raise SystemExit("results: collisions: the summary report has no collision rows in its category × stage "
                         "tables")
    return "\n".join(lines), by_pair, names


def _collide(ctx, files, repeat, name):
    folder = ctx.scratch_dir("collide")
    table = os.path.join(folder, name + ".md")
    ctx.run([ctx.gacompare, "collide", *files, "--repeat", repeat, "--out", os.path.join(folder, name + ".json"),
             "--table", table],
            quote=f"{ctx.gacompare} collide {' '.join(files)} --repeat {repeat} --out FILE.json --table FILE.md")
    with open(table) as f:
        return f.read().strip()


def _row(markdown, method):
    for t in tables(markdown):
        head = [h.lower() for h in t[0]]
        for row in t[1:]:
            if row and row[0] == method:
                return dict(zip(head, row))
    return {}


def generate(ctx):
    stages, stage_rows, names = _per_stage(ctx)
    q = ctx.quick
    corpus = _collide(ctx, ["data/collision/random.json", "data/collision/hand.json"], "3" if q else "9", "corpus")
    round_ = _collide(ctx, ["data/collision/round.json"], "21" if q else "201", "round")
    capsule = _collide(ctx, ["data/collision/capsule.json"], "21" if q else "201", "capsule")
    detect = ratios(ctx, "narrowphase_bench", "traditional", 5, 3,
                    "BM_(narrowphase_|contacts_|manifold_boxes|point_in_body|segment)")
    pairs = ratios(ctx, "narrowphase_bench", "traditional", 9, 3, "BM_pair_")
    round_pairs = ratios(ctx, "narrowphase_bench", "traditional", 15, 3, "BM_round")
    support = ratios(ctx, "narrowphase_bench", "traditional_scan", 5, 3, "BM_support_")
    spheres = ratios(ctx, "bounding_volume_bench", "traditional", 5, 3)
    broad = ratios(ctx, "broadphase_bench", "traditional_sweep", 5, 1, "_(100|1000)/" if q else None,
                   "candidates,tree_updates,pairs_kept,pairs,grown_pairs")
    headline = []
    for pair in ("cga / traditional", "pga / traditional"):
        row = next((r for r in stage_rows.get(pair, []) if r[0].strip("`*") == "narrowphase"), None)
        if row is not None:
            headline.append({"finding": f"Scenes with collisions: the narrowphase stage, {pair}",
                             "value": f"{row[4]}, {row[5]}", "anchor": "#per-stage"})
    rows = {m: _row(corpus, m) for m in ("traditional_manifold", "cga_manifold", "pga_manifold")}
    times = next((k for k in rows["cga_manifold"] if k.startswith("×")), None)
    if times:
        headline.append({"finding": "One pair as the simulation meets it (separating axes, contact manifold), "
                                    "cga and pga / traditional",
                         "value": f"cga {rows['cga_manifold'][times]}×, pga {rows['pga_manifold'][times]}×",
                         "anchor": "#agreement-and-time-per-pair"})
    agree = next((k for k in rows["traditional_manifold"] if k.startswith("yes/no")), None)
    if agree and all(r.get(agree) for r in rows.values()):
        headline.append({"finding": "Agreement with our exact separating-axis reference, yes/no over the corpus",
                         "value": ", ".join(f"{m.split('_')[0]} {r[agree]}" for m, r in rows.items()),
                         "anchor": "#agreement-and-time-per-pair"})
    blocks = {"stages": stages, "corpus": corpus, "round": round_, "capsule": capsule, "detect": detect,
              "pairs": pairs, "round-pairs": round_pairs, "support": support, "spheres": spheres, "broadphase": broad}
    return {"blocks": blocks, "headline": headline}
