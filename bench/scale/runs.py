"""What the scale scripts share: their common options, one `gacompare
compare` of a generated scene, the report's depth rules, and a median
(min-max) cell."""
import argparse
import atexit
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile


def compare(binary, scene, folder, backends, threads=1):
    """Writes `scene` beside `folder`, runs the backends on it in one
    `gacompare compare` (one repeat, in the order given, on `threads`
    threads) and returns its results.json runs by backend, each with the
    report's depth rules as "sanity" (sanity() below); a run that stopped
    stops the script with its reason. The scene and the folder are removed
    once read: a 10,000-body run's folder holds some 200 MB."""
    path = folder + ".json"
    with open(path, "w") as f:
        json.dump(scene, f)
    cmd = [binary, "compare", path, "--backends", ",".join(backends), "--repeat", "1", "--out", folder,
           "--threads", str(threads)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "results.json")) as f:
        runs = json.load(f)["runs"]
    rules = sanity(os.path.join(folder, "report.md"))
    shutil.rmtree(folder, ignore_errors=True)
    os.remove(path)
    for r in runs:
        r["sanity"] = rules.get(r["backend"], {})
        if r.get("error"):
            raise SystemExit(f"{os.path.basename(folder)}: {r['backend']} stopped: {r['error']}")
    return {r["backend"]: r for r in runs}


RULES = {"penetration": "sanity: penetration into a static body (m)",
         "overlap": "sanity: overlap of two moving bodies (m)"}


def sanity(report):
    """Each backend's lines of the report's two depth rules (compare/sanity.cpp):
    the deepest any body went into a wall, and the deepest two moving bodies
    went into each other, at a sample, each with its bound and verdict. A run
    whose bodies end steps inside the walls or squeezed into each other is
    wrong physics, however fast."""
    out = {}
    if not os.path.exists(report):
        return out
    for line in open(report):
        cols = [c.strip() for c in line.strip().strip("|").split("|")]
        for key, rule in RULES.items():
            if len(cols) == 6 and cols[2] == rule:
                verdict = cols[5].replace("**", "")
                out.setdefault(cols[1], {})[key] = {"value": cols[3], "bound": cols[4], "pass": verdict.startswith("pass"),
                                                    "note": verdict}
    return out


def cell(xs):
    return f"{statistics.median(xs):.3g} ({min(xs):.3g}–{max(xs):.3g})"


def parser(doc, sizes="125,1000", repeat=3):
    """The options every scale script takes: the binary, the sizes, the repeats."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default="build/ci/compare/gacompare")
    ap.add_argument("--sizes", default=sizes)
    ap.add_argument("--repeat", type=int, default=repeat)
    return ap


def start(ap, columns, note=""):
    """Parses the options, prints the command that gives this table (every
    option but the binary, defaults included) and the table's header row
    (`columns`: (title, right-aligned) pairs); returns the options, the sizes
    and a scratch folder."""
    args = ap.parse_args()
    script = os.path.basename(sys.argv[0])
    options = " ".join(f"--{k.replace('_', '-')} {v}" for k, v in vars(args).items() if k != "binary")
    print(f"Command: `bench/scale/{script} {options}`{note}\n")
    print("| " + " | ".join(title for title, _ in columns) + " |")
    print("|" + "|".join("---:" if right else "---" for _, right in columns) + "|")
    scratch = tempfile.mkdtemp(prefix=script.split(".")[0] + "-")
    atexit.register(shutil.rmtree, scratch, ignore_errors=True)
    return args, [int(n) for n in args.sizes.split(",")], scratch
