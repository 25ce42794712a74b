#!/usr/bin/env python3
"""Writes the measurement pages under docs/results/ and the headline table of
README.md from them. Every figure in those files comes from here: each page
runs the project's own tools (gacompare, the bench binaries, the scripts
beside this one) and records the machine, its load, the commit and the
commands at its top.

  python3 scripts/results.py                    # every page (an hour or more on two cores)
  python3 scripts/results.py --only scale       # one page (or several: --only a,b)
  python3 scripts/results.py --quick            # smaller runs, labelled as such on each page
  python3 scripts/results.py --only readme      # the README table alone, from the stored figures
  python3 scripts/results.py --list             # the pages and what each runs

It uses the `ci` build (`bash scripts/build.sh ci`); --build picks another.
The headline figures of each page are kept in docs/results/headline.json, so
regenerating one page redraws the README table with the others unchanged.
"""
import argparse
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from resultgen import algebra, bullet, collisions, contacts, dynamics, operations, scale, stacking, summary  # noqa: E402
from resultgen.common import RESULTS, ROOT, Context, Provenance, fill, write_page  # noqa: E402

# name: (what it measures, generator). The order is the README table's.
PAGES = {
    "summary": ("every bundled scene through every backend: the verdict per category and pair", summary.generate),
    "rigid-bodies": ("stability, steps and time at equal accuracy, what each rotation costs", dynamics.rigid_bodies),
    "long-horizon": ("the Lie-group integrators over 10,000 periods, each rotation representation", dynamics.long_horizon),
    "particles": ("work-precision sweeps of the particle scenes", dynamics.particles),
    "collisions": ("detection per stage and per pair, the referees' agreement", collisions.generate),
    "contacts": ("degenerate contact cases, friction, the time-of-impact search", contacts.generate),
    "stacking": ("columns, pyramids and mass ratios against their statics", stacking.generate),
    "bullet": ("the collision scenes against Bullet run whole", bullet.generate),
    "scale": ("boxes of 27 to 1,000 bodies", scale.generate),
    "algebra": ("the algebra and the conformal geometry against their twins", algebra.generate),
    "operations": ("multiplies and adds per operation in the compiled code, each algebra", operations.generate),
    "meshes": ("mass properties by the report's voxels against exact integrals; hulls", dynamics.meshes),
    "integrators": ("the SciML rigid body: work-precision of the embedded pairs and Odeint's steppers",
                    dynamics.integrators),
}
# Pages that run no built binary (a compiler and objdump only).
WITHOUT_BUILD = {"operations"}
HEADLINE = os.path.join(RESULTS, "headline.json")
README = os.path.join(ROOT, "README.md")


def readme_table(stored):
    lines = ["| finding | measured | detail |", "|---|---|---|"]
    for page in PAGES:
        entry = stored.get(page)
        if not entry:
            continue
        note = " (quick run)" if entry.get("quick") else ""
        for row in entry["rows"]:
            link = f"docs/results/{page}.md{row.get('anchor', '')}"
            lines.append(f"| {row['finding']} | {row['value']} | [{page}]({link}){note} |")
    return "\n".join(lines)


def write_readme(stored):
    with open(README) as f:
        text = f.read()
    new = fill(text, {"headline": readme_table(stored)}, "README.md")
    with open(README + ".tmp", "w") as f:
        f.write(new)
    os.replace(README + ".tmp", README)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default="", help="comma-separated pages (see --list), or 'readme'")
    ap.add_argument("--quick", action="store_true", help="smaller runs, labelled on each page")
    ap.add_argument("--build", default="build/ci", help="the build folder whose binaries run (default build/ci)")
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args()
    if args.list:
        for name, (what, _) in PAGES.items():
            print(f"{name:14} docs/results/{name}.md: {what}")
        return 0
    wanted = [p for p in args.only.split(",") if p] or list(PAGES)
    unknown = [p for p in wanted if p not in PAGES and p != "readme"]
    if unknown:
        print(f"results: no page {', '.join(unknown)} (pages: {', '.join(PAGES)}, readme)", file=sys.stderr)
        return 2
    needs_build = any(p in PAGES and p not in WITHOUT_BUILD for p in wanted)
    if needs_build and not os.access(os.path.join(ROOT, args.build, "compare", "gacompare"), os.X_OK):
        print(f"results: {args.build}/compare/gacompare is not built: run `bash scripts/build.sh ci` first",
              file=sys.stderr)
        return 2
    stored = {}
    if os.path.exists(HEADLINE):
        with open(HEADLINE) as f:
            stored = json.load(f)
    with tempfile.TemporaryDirectory(prefix="gacompare-results-") as scratch:
        for page in (p for p in PAGES if p in wanted):
            ctx = Context(args.build, args.quick, os.path.join(scratch, page))
            provenance = Provenance()
            result = PAGES[page][1](ctx)
            opts = (f" --build {args.build}" if args.build != "build/ci" else "")
            command = f"python3 scripts/results.py --only {page}{opts}" + (" --quick" if args.quick else "")
            head = provenance.block(command, args.quick, f"python3 scripts/results.py --only {page}{opts}",
                                    ctx.commands)
            write_page(page, {"provenance": head, **result["blocks"]})
            for other, blocks in result.get("also", {}).items():
                write_page(other, {"provenance": head, **blocks})
            stored[page] = {"quick": args.quick, "rows": result["headline"]}
            with open(HEADLINE + ".tmp", "w") as f:
                json.dump(stored, f, indent=1, ensure_ascii=False)
                f.write("\n")
            os.replace(HEADLINE + ".tmp", HEADLINE)
            print(f"results: wrote docs/results/{page}.md", file=sys.stderr)
    write_readme(stored)
    return 0


if __name__ == "__main__":
    sys.exit(main())
