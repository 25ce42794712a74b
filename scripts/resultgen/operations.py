"""docs/results/operations.md: the multiplies and adds each algebra's point
transform, composition and face test compile to (scripts/count-flops.py),
side by side. Needs a compiler and objdump, not the build."""
import json
import os

from .common import strip_command_line

# The README rows: (finding, [(label, kernel)]), multiplies + adds at -O1.
HEADLINE = [
    ("Moving a point, multiplies + adds in the compiled code: pga motor, quaternion + translation, "
     "3×3 matrix, cga motor sandwich",
     [("pga", "point_pga_apply"), ("quaternion", "point_quaternion"), ("matrix", "point_matrix"),
      ("cga", "point_cga_motor")], "#moving-a-point"),
    ("Composing two rigid motions, the same: pga motor, (quaternion, translation), 4×4 matrix, cga motor",
     [("pga", "compose_pga"), ("quaternion", "compose_quaternion_translation"), ("4×4", "compose_matrix4"),
      ("cga", "compose_cga_motor")], "#composing-two-motions"),
]
MAIN = "-O1 -g1 -DNDEBUG"  # the flags of the table's main columns (count-flops.py FLAGS)


def generate(ctx):
    counts_path = os.path.join(ctx.scratch_dir("operations"), "counts.json")
    table = strip_command_line(ctx.run(["python3", "scripts/count-flops.py", "--json", counts_path],
                                       quote="python3 scripts/count-flops.py --json FILE"))
    check = ctx.run(["python3", "scripts/count-flops.py", "--check"]).strip()
    with open(counts_path) as f:
        counts = json.load(f)

    def cost(kernel):
        # A loop's count is of its body: take the -O3 figure, where it is unrolled.
        c = counts[kernel][MAIN]
        if c["loop"]:
            c = next(v for v in counts[kernel].values() if not v["loop"])
        return f"{c['mul']} + {c['add']}"

    headline = [{"finding": finding, "value": ", ".join(f"{label} {cost(k)}" for label, k in kernels),
                 "anchor": anchor} for finding, kernels, anchor in HEADLINE]
    return {"blocks": {"table": table, "check": f"`{check}`"}, "headline": headline}
