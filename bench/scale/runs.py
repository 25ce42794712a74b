"""What the scale scripts share: their common options, one `gacompare
compare` of a generated scene, and a median (min-max) cell."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def compare(binary, scene, folder, backends, threads=1):
    """Writes `scene` beside `folder`, runs the backends on it in one
    `gacompare compare` (one repeat, in the order given, on `threads`
    threads) and returns its results.json runs by backend; a run that
    stopped stops the script with its reason."""
    path = folder + ".json"
    with open(path, "w") as f:
        json.dump(scene, f)
    cmd = [binary, "compare", path, "--backends", ",".join(backends), "--repeat", "1", "--out", folder,
           "--threads", str(threads)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "results.json")) as f:
        runs = json.load(f)["runs"]
    for r in runs:
        if r.get("error"):
            raise SystemExit(f"{os.path.basename(folder)}: {r['backend']} stopped: {r['error']}")
    return {r["backend"]: r for r in runs}


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
    return args, [int(n) for n in args.sizes.split(",")], tempfile.mkdtemp(prefix=script.split(".")[0] + "-")
