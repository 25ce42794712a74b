#!/usr/bin/env python3
"""Runs a Google Benchmark binary whose benchmarks are named BM_<op>/<impl>,
repeated and randomly interleaved, and prints a markdown table: each
implementation's median time per item with its min-max over the repetitions,
and the ratios of each to a reference implementation, per repetition (so the
ratio and its spread come from runs made close together). --counters adds
the median of the named benchmark counters as columns.

  scripts/bench-ratios.py build/release/bench/algebra_bench --reference eigen --repetitions 15
"""
import argparse
import json
import statistics
import subprocess
import sys
from collections import defaultdict


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("--reference", default="eigen", help="implementation the ratios divide by")
    ap.add_argument("--repetitions", type=int, default=15)
    ap.add_argument("--min-time", default="0.05")
    ap.add_argument("--filter", default=".")
    ap.add_argument("--counters", default="", help="comma-separated benchmark counters to add as columns (median)")
    args = ap.parse_args()
    counters = [c for c in args.counters.split(",") if c]

    cmd = [args.binary, f"--benchmark_repetitions={args.repetitions}", "--benchmark_enable_random_interleaving=true",
           f"--benchmark_min_time={args.min_time}", f"--benchmark_filter={args.filter}", "--benchmark_format=json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    data = json.loads(out)

    # ns per item, per repetition, keyed by (op, impl)
    times = defaultdict(list)
    counted = defaultdict(lambda: defaultdict(list))  # (op, impl) -> counter -> values
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        op, impl = b["run_name"].removeprefix("BM_").split("/", 1)
        # items_per_second counts every item of the timed loop: 1e9 / it is ns per operation
        times[(op, impl)].append(1e9 / b["items_per_second"])
        for c in counters:
            if c in b:
                counted[(op, impl)][c].append(b[c])

    # Rows in the order the binary registers its benchmarks (the run itself is shuffled).
    listed = subprocess.run([args.binary, "--benchmark_list_tests=true", f"--benchmark_filter={args.filter}"],
                            check=True, capture_output=True, text=True).stdout.split()
    order = {name.removeprefix("BM_"): i for i, name in enumerate(listed)}
    ops = list(dict.fromkeys(n.split("/", 1)[0] for n in sorted(order, key=order.get)))
    print(f"Command: `{' '.join(cmd[:1] + cmd[1:-1])}` (ns per operation: median (min–max) of "
          f"{args.repetitions} interleaved repetitions; ratio to `{args.reference}` per repetition)\n")
    print(f"| operation | implementation | ns per op | ratio to {args.reference} |" + "".join(f" {c} |" for c in counters))
    print("|---|---|---:|---:|" + "---:|" * len(counters))
    for op in ops:
        ref = times.get((op, args.reference))
        for (o, impl), t in sorted(times.items(), key=lambda kv: order.get(f"{kv[0][0]}/{kv[0][1]}", 0)):
            if o != op:
                continue
            cell = f"{statistics.median(t):.2f} ({min(t):.2f}–{max(t):.2f})"
            if ref:
                r = [a / b for a, b in zip(t, ref)]
                ratio = f"{statistics.median(r):.2f} ({min(r):.2f}–{max(r):.2f})"
            else:
                ratio = "–"
            extra = "".join(f" {statistics.median(counted[(o, impl)][c]):.4g} |" if counted[(o, impl)][c] else " – |"
                            for c in counters)
            print(f"| {op} | {impl} | {cell} | {ratio} |" + extra)
    machine = data.get("context", {})
    # Google Benchmark's "library_build_type" is how Debian built libbenchmark
    # (debug), not how this project's benchmarks were built: said so, since
    # "library build debug" read as a debug build of the code being timed.
    print(f"\n{machine.get('num_cpus', '?')} CPUs at {machine.get('mhz_per_cpu', '?')} MHz, "
          f"date {machine.get('date', '?')}; the benchmarks are this project's build, linked to Debian's "
          f"Google Benchmark library (itself a {machine.get('library_build_type', '?')} build: it does the timing, "
          f"and is not timed).")
    return 0


if __name__ == "__main__":
    sys.exit(main())
