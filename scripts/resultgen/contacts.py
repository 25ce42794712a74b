"""docs/results/contacts.md (and contact-table.md, the family in full):
the degenerate contact cases against their analytic outcomes, the friction
scenes against theirs, and what the time-of-impact search costs."""
import re
from collections import OrderedDict

from .common import first_number, strip_command_line, tables


def family(case):
    """The row a case counts in: slides free or on a floor, rows, stacks, the ridge."""
    parts = case.split()[0].split("/")
    if parts[0] == "slide":
        return "slides on a floor" if "floor" in parts else "slides, free"
    return {"row": "rows", "stack": "stacks", "edge": "a cube on a ridge (rest, bounce)"}.get(parts[0], parts[0])


def counts(markdown):
    """{family: {backend: (passed, cases)}} from contact_table's table."""
    t = next(t for t in tables(markdown) if t[0][0] == "case")
    backends = t[0][1:]
    out = OrderedDict()
    for row in t[1:]:
        f = out.setdefault(family(row[0]), {b: [0, 0] for b in backends})
        for b, cell in zip(backends, row[1:]):
            f[b][1] += 1
            f[b][0] += cell.startswith("pass")
    return out, backends


def family_table(manifold, report):
    m, backends = counts(manifold)
    r, rb = counts(report)
    head = ["family", "cases"] + backends + [f"fig. 7 contacts (`--method report`), {' / '.join(rb)}"]
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    total = {b: [0, 0] for b in backends}
    rtotal = {b: [0, 0] for b in rb}
    for name, f in m.items():
        cases = next(iter(f.values()))[1]
        cells = [f"{f[b][0]} pass" for b in backends]
        rep = " / ".join(str(r.get(name, {}).get(b, [0])[0]) for b in rb)
        lines.append(f"| {name} | {cases} | " + " | ".join(cells) + f" | {rep} |")
        for b in backends:
            total[b][0] += f[b][0]
            total[b][1] += f[b][1]
        for b in rb:
            rtotal[b][0] += r.get(name, {}).get(b, [0, 0])[0]
    cases = next(iter(total.values()))[1]
    lines.append(f"| **all** | **{cases}** | " + " | ".join(f"**{total[b][0]}**" for b in backends) +
                 " | **" + " / ".join(str(rtotal[b][0]) for b in rb) + "** |")
    return "\n".join(lines), total, cases


def worst_errors(friction):
    """The largest relative error per backend column of the friction table."""
    t = next(t for t in tables(friction) if t[0][0] == "scene")
    out = {}
    for i, b in enumerate(t[0][3:], start=3):
        rel = [first_number(m.group(1)) for row in t[1:] for m in [re.search(r"\(rel ([^)]+)\)", row[i])] if m]
        out[b] = max(x for x in rel if x is not None) if rel else None
    return out


def generate(ctx):
    q = ctx.quick
    manifold = ctx.run([ctx.tool("bench", "contact_table")])
    report = ctx.run([ctx.tool("bench", "contact_table"), "--method", "report", "--backends", "traditional,cga"])
    summary, total, cases = family_table(manifold, report)
    friction = strip_command_line(ctx.run([ctx.tool("bench", "friction_table")]))
    reps = "1" if q else "3"
    tolerance = strip_command_line(ctx.run([ctx.tool("bench", "time_of_impact_sweep"), reps, "cube_drop_flat"]))
    methods_args = ["--methods", reps] + (["cube_drop_corner", "contact_stack5"] if q else [])
    methods = strip_command_line(ctx.run([ctx.tool("bench", "time_of_impact_sweep"), *methods_args]))
    headline = [{"finding": "Degenerate contact cases (faces on faces, offsets of 1e-9, stacks, rows) passed",
                 "value": ", ".join(f"{b} {n[0]}" for b, n in total.items()) + f" of {cases}",
                 "anchor": "#the-degenerate-cases"}]
    worst = worst_errors(friction)
    if worst:
        headline.append({"finding": "Friction and rolling scenes: worst relative error against the analytic answer",
                         "value": ", ".join(f"{b} {e:.1e}" for b, e in worst.items() if e is not None),
                         "anchor": "#friction-and-rolling"})
    blocks = {"families": summary, "friction": friction, "tolerance": tolerance, "methods": methods}
    # The family case by case is a page of its own.
    return {"blocks": blocks, "headline": headline, "also": {"contact-table": {"table": strip_command_line(manifold)}}}
