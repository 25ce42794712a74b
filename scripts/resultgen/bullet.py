"""docs/results/bullet.md: our backends against Bullet run whole, on every
scene that lists collisions."""
import statistics

from .collisions import collision_scenes
from .common import first_number, strip_command_line, tables


def generate(ctx):
    names = collision_scenes(skip=("bodies_in_box",) if ctx.quick else ())
    repeat = "1" if ctx.quick else "3"
    out = ctx.scratch_dir("bullet")
    paths = [f"data/scenes/{n}.json" for n in names]
    ctx.run([ctx.gacompare, "compare", *paths, "--repeat", repeat, "--out", out, "--quiet"],
            quote=f"{ctx.gacompare} compare <the {len(names)} scenes that list collisions"
                  f"{', less bodies_in_box' if ctx.quick else ''}> --repeat {repeat} --out DIR")
    table = strip_command_line(ctx.run(["python3", "scripts/bullet-table.py", out],
                                       quote="python3 scripts/bullet-table.py DIR"))
    # traditional / Bullet wall time per simulated second, per scene.
    t = next(t for t in tables(table) if t[0][0] == "scene")
    wall = {}
    for row in t[1:]:
        wall.setdefault(row[0], {})[row[1]] = first_number(row[-1])
    ratios = [w["traditional"] / w["bullet"] for w in wall.values()
              if w.get("bullet") and w.get("traditional") is not None]
    headline = []
    if ratios:
        headline.append({"finding": "Whole collision scenes against Bullet: our traditional backend's time / Bullet's, per simulated second",
                         "value": f"median {statistics.median(ratios):.2f} over {len(ratios)} scenes "
                                  f"({min(ratios):.2f}–{max(ratios):.2f})",
                         "anchor": "#the-table"})
    return {"blocks": {"table": table}, "headline": headline}
