"""docs/results/summary.md: every bundled scene through every backend, what
`bash scripts/run-all.sh` runs, and the verdict per category and pair of
backends (cga / traditional, pga / traditional, pga / cga)."""
import glob
import json
import os
import re
import shutil

from .common import ROOT


def _demote(markdown):
    """The summary report's headings one level down, under the page's own."""
    return re.sub(r"^(#+) ", lambda m: "#" + m.group(1) + " ", markdown, flags=re.M)


def pairs(summary):
    """Each pair summary.json compares, as (numerator, denominator, block with
    "scenes" and "categories"): cga / traditional at its top level, then each
    of "pairs"."""
    yield "cga", "traditional", summary
    for p in summary.get("pairs", []):
        yield p["numerator"], p["denominator"], p


def label(num, den, block, category):
    """'cga (rotor) / traditional (matrix)' where every compared scene of the
    category stores rotations alike on each side: a headline on bodies names
    the representations it compares. The bare pair otherwise."""
    forms = {(s["rotation"][num], s["rotation"][den]) for s in block["scenes"]
             if s["category"] == category and "rotation" in s and "not_compared" not in s}
    if len(forms) == 1:
        (a, b), = forms
        # traditional-quaternion is the traditional backend, named by its form
        return f"{num.split('-')[0]} ({a}) / {den.split('-')[0]} ({b})"
    return f"{num} / {den}"


def overall(block, category):
    """The category's whole-run ratio, its verdict and the scenes behind it;
    the scenes whose backends parted are named as left out of it."""
    c = block["categories"].get(category)
    if not c:
        return None
    o = c["overall"]
    parted = c.get("parted", [])
    left_out = f"; {' and '.join(parted)} parted, left out" if parted else ""
    if not o["scenes"]:
        return f"no verdict: every scene parted{left_out}"
    lo, hi = o["ci95"] if o["ci95"] and None not in o["ci95"] else (None, None)
    interval = f" [{lo:.2f}, {hi:.2f}]" if lo is not None else ""
    return f"{o['ratio']:.2f}{interval}, {o['verdict']} ({o['scenes']} scenes{left_out})"


def generate(ctx):
    out = ctx.scratch_dir("summary")
    scenes = sorted(glob.glob(os.path.join(ROOT, "data", "scenes", "*.json")))
    repeat = "5"
    ctx.run([ctx.gacompare, "compare", *scenes, "--repeat", repeat, "--out", out, "--quiet"],
            quote=f"{ctx.gacompare} compare data/scenes/*.json --repeat {repeat} --out DIR")
    with open(os.path.join(out, "report.md")) as f:
        report = f.read()
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    # The report's own first heading names the folder; the page has its title.
    report = re.sub(r"^# .*\n+", "", report, count=1)
    # Its links lead into the report folder, which the page does not carry; its
    # commit is in the page's provenance.
    report = re.sub(r"\[([^\]]+)\]\([^)]*report\.md\)", r"\1", report)
    report = re.sub(r",? commit [0-9a-f]+(?: with uncommitted changes)?", "", report)
    # The forest plot, beside the page's other figures.
    if os.path.exists(os.path.join(out, "forest.svg")):
        os.makedirs(os.path.join(ROOT, "docs", "results", "img"), exist_ok=True)
        shutil.copyfile(os.path.join(out, "forest.svg"), os.path.join(ROOT, "docs", "results", "img", "summary_forest.svg"))
        report = report.replace("](forest.svg)", "](img/summary_forest.svg)")
    return {"blocks": {"report": _demote(report)}, "headline": headline(summary)}


def headline(summary):
    """The README rows: each category's whole-run ratio for every pair that
    ran, then the particle scenes (cga / traditional: the same formulas)."""
    rows = []
    for category, finding in (("rigid bodies", "Rigid bodies without contact: whole run, {} at equal tolerance"),
                              ("collisions", "Scenes with collisions: whole run, {}")):
        for num, den, block in pairs(summary):
            value = overall(block, category)
            if value:
                rows.append({"finding": finding.format(label(num, den, block, category)), "value": value, "anchor": ""})
    same = [s["name"] for s in summary["scenes"] if s["trajectories"] == "identical"]
    parts = [s for s in summary["scenes"] if s["category"] == "particles"]
    if parts:
        rows.append({"finding": "Particle scenes (the same formulas in every backend)",
                     "value": f"identical trajectories on {sum(s['name'] in same for s in parts)} of {len(parts)}; "
                              + (overall(summary, "particles") or ""),
                     "anchor": ""})
    return rows
