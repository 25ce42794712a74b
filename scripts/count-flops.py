#!/usr/bin/env python3
"""Counts the multiplies and adds the compiler emits for each operation of
scripts/flops/kernels.cpp: the point transform, the composition of two rigid
motions and the face test (a point's signed distance from a plane), in each
algebra side by side. Compiles that file with the given flags, disassembles it
(objdump, from binutils) and counts, per kernel and every function it calls:

  multiplies  mulsd 1, mulpd 2 (a packed instruction counts its lanes)
  adds        addsd subsd 1, addpd subpd 2 (an add or a subtract); x + x, the
              compiler's 2·x, is an add and is also shown as a doubling
  FMA         vfmadd… and kin: one multiply and one add per lane
  other       divisions, square roots, sign flips (xorpd with a mask) and
              abs (andpd), lane shuffles, calls out of the program, and loops
              (a backward branch: then the count is of instructions, not of
              the operations done, and --check refuses it)

  python3 scripts/count-flops.py                 # the table, in Markdown
  python3 scripts/count-flops.py --check         # exit 1 with a reason if a claim fails
  python3 scripts/count-flops.py --cxx clang++ --flags "-O3 -DNDEBUG"
  python3 scripts/count-flops.py --json counts.json   # the counts also as JSON

The flags default to the two optimisation levels the project builds with:
the RelWithDebInfo flags of the asan and fuzz presets (-O1 -g1 -DNDEBUG, the
table's main columns) and the Release build type of the release and ci
presets (-O3 -DNDEBUG, what the benchmarks run); no -march, so scalar and
two-lane packed SSE2. A count is of lanes computed: at -O3 GCC's SLP
vectoriser at times computes a packed add and a packed subtract and keeps one
lane of each, so a generic product can show more adds there than at -O1.
"""
import argparse
import json
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE = os.path.join("scripts", "flops", "kernels.cpp")
# The RelWithDebInfo flags of CMakePresets.json first (the table's main
# columns), then CMake's Release flags (the release and ci presets).
FLAGS = ["-O1 -g1 -DNDEBUG", "-O3 -DNDEBUG"]
SKIPPED = 77  # the exit status CTest is told means "skipped"

# (symbol in kernels.cpp, section, algebra, what it computes)
KERNELS = [
    ("point_quaternion", "point", "traditional", "Eigen::Quaterniond `q * x + t`"),
    ("point_matrix", "point", "traditional", "3×3 matrix `R * x + t`"),
    ("point_cga_motor", "point", "cga", "`cga::sandwich(T R, up(x))`, the motor on a conformal point"),
    ("point_cga_rotor", "point", "cga", "`cga::sandwich(Rotor5, up(x))`, rotation only"),
    ("point_cga_outermorphism", "point", "cga", "5×5 outermorphism matrix on a conformal point"),
    ("point_pga_apply", "point", "pga", "`pga::apply(Motor, Vec3)`, closed form"),
    ("point_pga_sandwich", "point", "pga", "`cga::sandwich(Motor, Point)`, the generic product"),
    ("compose_quaternion", "compose", "traditional", "quaternion × quaternion (rotation only)"),
    ("compose_quaternion_translation", "compose", "traditional", "(q, t) pairs: `qa qb`, `qa tb + ta`"),
    ("compose_matrix4", "compose", "traditional", "Eigen::Matrix4d product"),
    ("compose_isometry", "compose", "traditional", "Eigen::Isometry3d product"),
    ("compose_cga_rotor3", "compose", "cga", "Rotor3 × Rotor3 (rotation only)"),
    ("compose_cga_motor", "compose", "cga", "motor T R × motor T R (to Even5)"),
    ("compose_cga_even5", "compose", "cga", "Even5 × Even5, the whole even subalgebra"),
    ("compose_pga", "compose", "pga", "`pga::compose(Motor, Motor)`"),
    ("face_traditional", "face", "traditional", "`n.dot(x) - d`"),
    ("face_cga", "face", "cga", "`NarrowAlgebra::distance`: conformal point · dual plane"),
    ("face_pga", "face", "pga", "`pga::distance(Plane, Point)`: π ∧ X"),
]
SECTIONS = {"point": "point transform", "compose": "composition", "face": "face test"}

# The claims --check holds: (kernel, most multiplies, most adds, name). The
# point sandwich is 18 multiplies and 18 adds and subtracts, plus the doubling
# 2·(…) of its three coordinates, which the compiler emits as x + x: 3 more
# adds (counted as 3 multiplies, it reads 21 and 18).
CLAIMS = [
    ("point_pga_apply", 18, 21, "pga::apply"),
    ("compose_pga", 48, 40, "pga::compose"),
]

FUNC = re.compile(r"^([0-9a-f]+) <(.+)>:$")
INSN = re.compile(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$")
TARGET = re.compile(r"^([0-9a-f]+) <([^>+]+)(\+0x[0-9a-f]+)?>")
PREFIXES = {"bnd", "notrack", "rep", "repz", "repnz", "lock", "data16", "cs", "ds"}
SHUFFLES = {"unpcklpd", "unpckhpd", "shufpd", "movddup", "movhlps", "movlhps", "shufps", "unpcklps",
            "unpckhps", "pshufd", "permilpd", "permpd", "blendpd", "insertf128", "extractf128", "broadcastsd"}


def lanes(mnemonic, operands):
    if mnemonic.endswith(("sd", "ss")):
        return 1
    width = 8 if "%zmm" in operands else 4 if "%ymm" in operands else 2
    return width * 2 if mnemonic.endswith("ps") else width


class Count:
    FIELDS = ["mul", "add", "fma", "div", "sqrt", "sign", "shuffle", "doubling", "loop"]

    def __init__(self):
        for f in self.FIELDS:
            setattr(self, f, 0)
        self.calls = []

    def __iadd__(self, other):
        for f in self.FIELDS:
            setattr(self, f, getattr(self, f) + getattr(other, f))
        self.calls += other.calls
        return self


def classify(count, mnemonic, operands):
    m = mnemonic[1:] if mnemonic.startswith("v") and not mnemonic.startswith("vfm") \
        and not mnemonic.startswith("vfnm") else mnemonic
    regs = re.findall(r"%[xyz]mm\d+", operands)
    if re.fullmatch(r"vf(n?)m(add|sub|addsub|subadd)\d*(sd|pd|ss|ps)", m):
        n = lanes(m, operands)
        count.mul += n
        count.add += n
        count.fma += n
    elif re.fullmatch(r"mul(sd|pd|ss|ps)", m):
        count.mul += lanes(m, operands)
    elif re.fullmatch(r"(add|sub|hadd|hsub|addsub)(sd|pd|ss|ps)", m):
        count.add += lanes(m, operands)
        if len(regs) == 2 and regs[0] == regs[1] and "(" not in operands:
            count.doubling += lanes(m, operands)
    elif re.fullmatch(r"div(sd|pd|ss|ps)", m):
        count.div += lanes(m, operands)
    elif re.fullmatch(r"sqrt(sd|pd|ss|ps)", m):
        count.sqrt += lanes(m, operands)
    elif re.fullmatch(r"(xor|and|andn)(pd|ps)", m):
        # xorpd x, x zeroes a register: no arithmetic, no sign
        if not (len(regs) == 2 and regs[0] == regs[1] and "(" not in operands):
            count.sign += 1
    elif m in SHUFFLES:
        count.shuffle += 1


def disassemble(binary):
    """{function name: [(address, mnemonic, operands)]} of the linked program."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", binary], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, check=True).stdout
    functions, current = {}, None
    for line in out.splitlines():
        f = FUNC.match(line)
        if f:
            current = functions.setdefault(f.group(2), [])
            continue
        i = INSN.match(line)
        if i and current is not None:
            mnemonic, operands = i.group(2), i.group(3).split("#")[0].strip()
            if mnemonic in PREFIXES and operands:
                mnemonic, _, operands = operands.partition(" ")
                operands = operands.strip()
            current.append((int(i.group(1), 16), mnemonic, operands))
    return functions


def count_function(functions, name, memo, active=()):
    """The counts of function `name` and of every function of the program it
    calls or tail-calls, each callee counted once per call site."""
    if name in memo:
        return memo[name]
    if name in active:
        raise SystemExit(f"count-flops: {name} calls itself: no static count")
    total = Count()
    for address, mnemonic, operands in functions[name]:
        classify(total, mnemonic, operands)
        if not mnemonic.startswith(("j", "call")):
            continue
        t = TARGET.match(operands)
        if not t:
            if mnemonic.startswith(("call", "jmp")):
                total.calls.append("indirect")
            continue
        target, symbol, offset = int(t.group(1), 16), t.group(2), t.group(3)
        if symbol == name:
            if target <= address:
                total.loop += 1
        elif offset or symbol.endswith("@plt") or symbol not in functions:
            total.calls.append(symbol.split("@")[0])
        elif mnemonic.startswith(("call", "jmp")):
            total += count_function(functions, symbol, memo, active + (name,))
    memo[name] = total
    return total


def measure(cxx, flags, eigen="/usr/include/eigen3", keep=None):
    with tempfile.TemporaryDirectory(prefix="count-flops-") as scratch:
        binary = keep or os.path.join(scratch, "kernels")
        cmd = [cxx, "-std=c++20", *shlex.split(flags), "-I", ROOT, "-I", eigen,
               os.path.join(ROOT, SOURCE), "-o", binary]
        done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            tail = " ".join(done.stderr.strip().splitlines()[-3:])
            raise SystemExit(f"count-flops: {' '.join(cmd)} failed: {tail}")
        functions = disassemble(binary)
    memo, counts = {}, {}
    for symbol, *_ in KERNELS:
        if symbol not in functions:
            raise SystemExit(f"count-flops: no function {symbol} in the compiled {SOURCE}")
        counts[symbol] = count_function(functions, symbol, memo)
    return counts


# How "other" names each count: (field, label).
OTHER = [("fma", "{} FMA"), ("doubling", "{} of the adds are doublings (x + x)"), ("div", "{} div"),
         ("sqrt", "{} sqrt"), ("sign", "{} sign/abs masks"), ("shuffle", "{} shuffles")]


def other(c):
    parts = [label.format(getattr(c, field)) for field, label in OTHER if getattr(c, field)]
    if c.calls:
        parts.append("calls " + ", ".join(sorted(set(c.calls))))
    if c.loop:
        parts.append("a loop: counts are of the loop body, not of the work done")
    return "; ".join(parts) or "–"


def cell(c):
    """multiplies / adds, marked where a loop makes them a count of instructions."""
    return f"{c.mul} / {c.add}" + (" (loop)" if c.loop else "")


def table(results):
    """results: [(flags, counts)], the first shown in full (multiplies, adds,
    other), each further one as a "multiplies / adds" column of its own."""
    head = ["operation", "algebra", "what", "multiplies", "adds", "other"]
    head += [f"at `{flags}`: mul / add" for flags, _ in results[1:]]
    align = {"multiplies": "---:", "adds": "---:"}
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(align.get(h, "---") for h in head) + "|"]
    for symbol, section, algebra, what in KERNELS:
        c = results[0][1][symbol]
        mark = " (loop)" if c.loop else ""
        row = [SECTIONS[section], algebra, what, f"{c.mul}{mark}", f"{c.add}{mark}", other(c)]
        row += [cell(counts[symbol]) for _, counts in results[1:]]
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def check(results):
    """The first claim that fails, as one line, or None. Inlined and loop-free
    under every flag; the counts under the first flags (by default -O1,
    scalar code, where each instruction is one operation): at -O3 the SLP vectoriser may fill a packed
    instruction's second lane with work it throws away (pga::apply's scalar
    form reads 20 + 23 lanes there for its 18 + 21 operations)."""
    for flags, counts in results:
        for symbol, most_mul, most_add, name in CLAIMS:
            c = counts[symbol]
            where = f"{name} at {flags}"
            if c.loop:
                return f"{where}: a loop in the compiled code, so no static count"
            if c.calls:
                return f"{where}: calls {', '.join(sorted(set(c.calls)))} (not inlined)"
            if flags == results[0][0] and (c.mul > most_mul or c.add > most_add):
                return (f"{where}: {c.mul} multiplies and {c.add} adds, "
                        f"the claim is at most {most_mul} and {most_add}")
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cxx", default=os.environ.get("CXX", "c++"), help="the C++ compiler (default $CXX or c++)")
    ap.add_argument("--flags", action="append",
                    help="compile flags, repeatable (default: the two sets the project builds with)")
    ap.add_argument("--eigen", default="/usr/include/eigen3", help="Eigen's include folder")
    ap.add_argument("--check", action="store_true", help="exit 1 with a reason if a claim fails")
    ap.add_argument("--json", help="also write the counts here: {kernel: {flags: {field: n}}}")
    ap.add_argument("--keep", help="keep the compiled program here (with one --flags)")
    args = ap.parse_args()
    if platform.machine() not in ("x86_64", "AMD64"):
        print(f"count-flops: skipped: the counts read x86-64 SSE code, this is {platform.machine()}")
        return SKIPPED
    flag_sets = args.flags or FLAGS
    if args.keep and len(flag_sets) != 1:
        ap.error("--keep needs exactly one --flags")
    results = [(flags, measure(args.cxx, flags, args.eigen, args.keep)) for flags in flag_sets]
    if args.json:
        data = {symbol: {flags: {**{f: getattr(counts[symbol], f) for f in Count.FIELDS},
                                 "calls": sorted(set(counts[symbol].calls))} for flags, counts in results}
                for symbol, *_ in KERNELS}
        with open(args.json, "w") as f:
            json.dump(data, f, indent=1)
    if args.check:
        reason = check(results)
        if reason:
            print(f"count-flops: FAIL {reason}")
            return 1
        claims = "; ".join(f"{n} at most {m} multiplies and {a} adds" for _, m, a, n in CLAIMS)
        print(f"count-flops: pass: {claims} ({os.path.basename(args.cxx)}, "
              f"{' and '.join(f for f, _ in results)})")
        return 0
    print(f"`{SOURCE}` compiled by `{os.path.basename(args.cxx)} -std=c++20 {results[0][0]}` "
          "(no -march: SSE2, scalar and two-lane packed doubles); a packed instruction counts its lanes.\n")
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
