"""docs/results/stacking.md: the stacking family (columns, pyramids, mass
ratios, friction stacks) through our three backends' contact solvers and Bullet,
each case held to its statics answer for 10 simulated seconds, and square
pyramids of up to 2,870 cubes (bench/scale/pyramids.py)."""
from .common import strip_command_line, tables


def passed(markdown):
    """{column: (passed, cases)} from stacking_table's table."""
    t = next(t for t in tables(markdown) if t[0][0] == "case")
    columns = t[0][2:]
    out = {c: [0, 0] for c in columns}
    for row in t[1:]:
        for c, cell in zip(columns, row[2:]):
            out[c][1] += 1
            out[c][0] += cell.startswith("pass")
    return out


def seconds(markdown, case, column):
    """The run time per simulated second in one cell of stacking_table's
    table ("pass 1.2e-09, 0.0864 s"), or None where the case is not in it."""
    t = next(t for t in tables(markdown) if t[0][0] == "case")
    at = t[0].index(column)
    for row in t[1:]:
        if row[0] == case:
            return float(row[at].rsplit(",", 1)[1].split()[0])
    return None


def cost_against_bullet(table):
    """Headline rows: our time per simulated second over Bullet's on the two
    stacks the cost goal names, in one stacking_table run (the cases run one
    after the other in one process; Bullet's stacks fall, so its time is that
    of a stack falling)."""
    rows = []
    for case, what in (("column/cubes/20", "A 20-cube column"), ("pyramid/wall/10", "A 10-layer wall pyramid")):
        bullet = seconds(table, case, "bullet")
        if bullet is None:
            continue
        ours = {c: seconds(table, case, c) for c in ("traditional", "cga")}
        rows.append({"finding": f"{what} held at rest for 10 s: time per simulated second / Bullet's (whose stack falls)",
                     "value": ", ".join(f"{c} {t / bullet:.2f}×" for c, t in ours.items()),
                     "anchor": "#the-family"})
    return rows


def pyramids_against_bullet(markdown):
    """A headline row: each pyramid's time per simulated second over
    Bullet's in the same `gacompare compare`, for the pyramids of 100 cubes
    or more in bench/scale/pyramids.py's table (landing and at rest, 0.3 s)."""
    t = next(t for t in tables(markdown) if t[0][0] == "layers")
    seconds = {}
    for row in t[1:]:
        seconds.setdefault(int(row[1]), {})[row[2]] = float(row[3].split()[0])
    parts = []
    for cubes, by in sorted(seconds.items()):
        if cubes < 100 or "bullet" not in by:
            continue
        ratios = ", ".join(f"{b} {by[b] / by['bullet']:.2f}×" for b in ("traditional", "cga") if b in by)
        parts.append(f"{cubes:,} cubes: {ratios}")
    if not parts:
        return []
    return [{"finding": "Square pyramids landing and at rest (0.3 s): time per simulated second / Bullet's",
             "value": "; ".join(parts), "anchor": "#stacks-at-scale"}]


def pyramid_held(markdown, duration):
    """A headline row: whether the long-run pyramid in bench/scale/pyramids.py's
    table stood, how far from its rest its farthest cube went and how fast
    its fastest cube moved once landed, by backend."""
    t = next(t for t in tables(markdown) if t[0][0] == "layers")
    head = t[0]
    far, fast = head.index("farthest from rest (m)"), head.index("fastest once landed (m/s)")
    stands = head.index("stands")
    cubes = int(t[1][1])
    value = ", ".join(f"{row[2]} {'stands' if row[stands] == 'yes' else 'FAILS'} ({row[far]} m, {row[fast]} m/s)"
                      for row in t[1:])
    return [{"finding": f"A square pyramid of {cubes:,} cubes for {duration:g} s: whether it stands, its farthest "
                        "cube from rest (a tolerance per level allowed) and its fastest (1e-6 m/s allowed), over every sample from 0.5 s",
             "value": value, "anchor": "#a-pyramid-at-scale-over-ten-seconds"}]


def generate(ctx):
    args = [ctx.tool("bench", "stacking_table")]
    if ctx.quick:  # the short cases only, without Gauss-Seidel's column
        args += ["--columns", "traditional,cga,pga,bullet", "--filter", "ratio"]
    table = ctx.run(args)
    counts = passed(table)
    # Gauss-Seidel against the direct solve on the columns, where its sweeps
    # grow with the height (the pyramids with it take tens of minutes).
    pgs_args = [ctx.tool("bench", "stacking_table"), "--columns", "traditional,traditional-pgs", "--filter",
                "ratio" if ctx.quick else "column"]
    pgs = ctx.run(pgs_args)
    # Kept contacts against every pair tested, where stacks rest longest.
    kept = "\n\n".join(strip_command_line(ctx.run([ctx.tool("bench", "stacking_table"), "--columns",
                                                  "traditional,traditional-tested", "--filter", f]))
                      for f in (("ratio/heavy",) if ctx.quick else ("column/cubes", "pyramid/wall")))
    # Stacks at scale: square pyramids of up to 2,870 cubes, landing and
    # resting (the 20-layer one alone takes some 15 minutes of the page).
    layers = "3,5" if ctx.quick else "3,5,10,15,20"
    pyramids = strip_command_line(ctx.run(["python3", "bench/scale/pyramids.py", "--binary", ctx.gacompare,
                                           "--sizes", layers, "--duration", "0.3"]))
    # One pyramid at scale held for as long as the family's cases.
    long_layers, long_duration = ("3", 2.0) if ctx.quick else ("10", 10.0)
    held = strip_command_line(ctx.run(["python3", "bench/scale/pyramids.py", "--binary", ctx.gacompare,
                                       "--sizes", long_layers, "--duration", f"{long_duration:g}",
                                       "--every", "0.5"]))
    headline = [{"finding": "Stacks, pyramids and mass ratios held to their statics for 10 s",
                 "value": ", ".join(f"{c} {n[0]}/{n[1]}" for c, n in counts.items()),
                 "anchor": "#the-family"}] + cost_against_bullet(table) + pyramids_against_bullet(pyramids) + \
        pyramid_held(held, long_duration)
    return {"blocks": {"table": strip_command_line(table), "pgs": strip_command_line(pgs), "kept": kept,
                       "pyramids": pyramids, "pyramid_held": held},
            "headline": headline}
