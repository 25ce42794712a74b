"""docs/results/stacking.md: the stacking family (columns, pyramids, mass
ratios, friction stacks) through our three backends' contact solvers and Bullet,
each case held to its statics answer for 10 simulated seconds, and square
pyramids of up to 385 cubes (bench/scale/pyramids.py)."""
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
    # Stacks at scale: square pyramids of up to 385 cubes, landing and resting.
    layers = "3,5" if ctx.quick else "3,5,10"
    pyramids = strip_command_line(ctx.run(["python3", "bench/scale/pyramids.py", "--binary", ctx.gacompare,
                                           "--sizes", layers, "--duration", "0.3"]))
    headline = [{"finding": "Stacks, pyramids and mass ratios held to their statics for 10 s",
                 "value": ", ".join(f"{c} {n[0]}/{n[1]}" for c, n in counts.items()),
                 "anchor": "#the-family"}]
    return {"blocks": {"table": strip_command_line(table), "pgs": strip_command_line(pgs), "pyramids": pyramids},
            "headline": headline}
