"""docs/results/algebra.md: what the algebra and the conformal geometry cost
against their traditional twins, and how precise they stay far from the
origin."""
from .common import first_number, ratios, strip_command_line, tables


def _by_impl(markdown):
    """{(op, impl): median ns} from a bench-ratios table."""
    out = {}
    for t in tables(markdown):
        for row in t[1:]:
            if len(row) >= 3:
                out[(row[0], row[1])] = first_number(row[2])
    return out


def generate(ctx):
    algebra = ratios(ctx, "algebra_bench", "eigen", 15, 3)
    geometry = ratios(ctx, "geometry_bench", "traditional", 10, 3)
    cases = "100" if ctx.quick else "1000"
    precision = strip_command_line(ctx.run([ctx.tool("bench", "geometry_precision"), cases]))
    headline = []
    ns = _by_impl(algebra)
    speedups = [ns[(op, "dense")] / ns[(op, "sparse")] for (op, impl) in ns
                if impl == "sparse" and (op, "dense") in ns and ns[(op, "sparse")]]
    if speedups:
        headline.append({"finding": "Compile-time sparse multivectors against the 2003-style dense ones",
                         "value": f"{min(speedups):.0f}–{max(speedups):.0f}× faster", "anchor": "#the-algebra"})
    g = [first_number(row[3]) for t in tables(geometry) for row in t[1:] if len(row) >= 4 and row[1] == "cga"]
    g = [x for x in g if x is not None]
    if g:
        headline.append({"finding": "Conformal geometry operations (meets, reflections, spheres), cga / traditional",
                         "value": f"{min(g):.2f}–{max(g):.2f}×", "anchor": "#the-conformal-geometry"})
    return {"blocks": {"algebra": algebra, "geometry": geometry, "precision": precision}, "headline": headline}
