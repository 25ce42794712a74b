"""What every results page shares: where things are, running a tool, the
provenance header, and filling a page's generated blocks.

A page under docs/results/ is markdown written by people, with generated
blocks between marker comments:

    <!-- generated: NAME -->
    ...replaced on every run...
    <!-- end: NAME -->

The script fills every block a page declares and refuses a page that lacks
one (so prose and tables cannot drift apart silently). The block `provenance`
opens every page: machine, load, commit, date and the command that wrote it.
"""
import datetime
import os
import platform
import re
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESULTS = os.path.join(ROOT, "docs", "results")


class Context:
    """One generation: the build to use, quick or full, a scratch folder."""

    def __init__(self, build, quick, scratch):
        self.build = build          # e.g. build/ci, relative to ROOT
        self.quick = quick
        self.scratch = scratch      # a temporary folder for report folders
        self.commands = []          # the tool commands run for the current page

    def tool(self, *parts):
        """Path of a built binary, relative to ROOT (as the page quotes it)."""
        return os.path.join(self.build, *parts)

    @property
    def gacompare(self):
        return self.tool("compare", "gacompare")

    def run(self, cmd, quote=None):
        """Runs cmd (a list) from ROOT and returns its stdout. `quote` is how the
        page shows the command (scratch paths replaced by a readable name)."""
        shown = quote or " ".join(shlex.quote(c) for c in cmd)
        self.commands.append(shown)
        print(f"results: {shown}", file=sys.stderr, flush=True)
        done = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            tail = "\n".join(done.stderr.strip().splitlines()[-5:])
            raise SystemExit(f"results: `{shown}` exited {done.returncode}:\n{tail}")
        return done.stdout

    def scratch_dir(self, name):
        path = os.path.join(self.scratch, name)
        os.makedirs(path, exist_ok=True)
        return path


def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                          text=True).stdout.strip()


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def usable_cpus():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count()


class Provenance:
    """Taken when a page starts, finished when its tools are done."""

    def __init__(self):
        self.started = datetime.datetime.now(datetime.timezone.utc)
        self.load_start = os.getloadavg()
        self.commit = git("rev-parse", "HEAD") or "unknown"
        # The generated files themselves do not make the tree dirty.
        changed = git("status", "--porcelain", "--", ".", ":!docs/results", ":!README.md")
        self.dirty = bool(changed)

    def block(self, page_command, quick, full_command, tool_commands):
        load_end = os.getloadavg()
        seconds = (datetime.datetime.now(datetime.timezone.utc) - self.started).total_seconds()
        fmt = lambda l: ", ".join(f"{x:.2f}" for x in l)
        lines = [
            f"- **Written by** `{page_command}` in {seconds:.0f} s, "
            f"{self.started.strftime('%Y-%m-%d %H:%M')} UTC.",
            f"- **Machine:** {cpu_model()}, {usable_cpus()} usable of {os.cpu_count()} logical CPUs; "
            f"load average (1, 5, 15 min) {fmt(self.load_start)} at the start, {fmt(load_end)} at the end "
            "(a load above the CPU count means other work shared the machine: compare ratios, not absolute times).",
            f"- **Commit:** `{self.commit}`" + (" with uncommitted changes" if self.dirty else "") + ".",
        ]
        if quick:
            lines.append(f"- **Quick run**: fewer repeats or smaller sizes than the page's full form, so the "
                         f"spreads are wider and some rows are missing. The full form: `{full_command}`.")
        lines.append("- **Tools run**, in order:")
        lines += [f"  - `{c}`" for c in tool_commands]
        return "\n".join(lines)


BLOCK = re.compile(r"<!-- generated: ([a-z0-9_-]+) -->\n.*?<!-- end: \1 -->", re.S)


def fill(text, blocks, where):
    """Replaces each named block's body; every block given must be in text."""
    found = set(BLOCK.findall(text))
    missing = sorted(set(blocks) - found)
    if missing:
        raise SystemExit(f"results: {where}: no block {', '.join(missing)} "
                         f"(add <!-- generated: NAME --> ... <!-- end: NAME --> where it belongs)")

    def body(m):
        name = m.group(1)
        if name not in blocks:
            return m.group(0)
        return f"<!-- generated: {name} -->\n{blocks[name].rstrip()}\n<!-- end: {name} -->"

    return BLOCK.sub(body, text)


def write_page(name, blocks):
    path = os.path.join(RESULTS, name + ".md")
    with open(path) as f:
        text = f.read()
    new = fill(text, blocks, os.path.relpath(path, ROOT))
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, path)


def table_rows(markdown):
    """The rows of the first markdown table in `markdown`, as lists of cells
    (header first, the |---| line dropped)."""
    rows = []
    for line in markdown.splitlines():
        line = line.strip()
        if not line.startswith("|"):
            if rows:
                break
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if all(re.fullmatch(r":?-+:?", c) for c in cells if c):
            continue
        rows.append(cells)
    return rows


def tables(markdown):
    """Every markdown table in `markdown`: a list of row lists (as table_rows)."""
    out, current = [], []
    for line in markdown.splitlines() + [""]:
        s = line.strip()
        if s.startswith("|"):
            cells = [c.strip() for c in s.strip("|").split("|")]
            if not all(re.fullmatch(r":?-+:?", c) for c in cells if c):
                current.append(cells)
        elif current:
            out.append(current)
            current = []
    return out


def strip_command_line(markdown):
    """Drops a tool's own leading "Command: `...`" line: the provenance block
    lists every command with this repository's paths."""
    lines = markdown.strip().splitlines()
    while lines and (lines[0].startswith("Command: ") or not lines[0].strip()):
        lines.pop(0)
    return "\n".join(lines)


def first_number(cell):
    m = re.search(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", cell)
    return float(m.group(0)) if m else None


def ratios(ctx, binary, reference, repetitions, quick_repetitions, filter_=None, counters=None):
    reps = str(quick_repetitions if ctx.quick else repetitions)
    cmd = ["python3", "scripts/bench-ratios.py", ctx.tool("bench", binary), "--reference", reference,
           "--repetitions", reps]
    if filter_:
        cmd += ["--filter", filter_]
    if counters:
        cmd += ["--counters", counters]
    quoted = " ".join(c if not any(ch in c for ch in " |()") else f'"{c}"' for c in cmd)
    text = ctx.run(cmd, quote=quoted)
    # Keep the table; the machine line is in the page's provenance.
    body = strip_command_line(text)
    return "\n".join(l for l in body.splitlines() if l.startswith("|"))


def ratio_of(markdown, op, impl):
    """The median ratio cell of (op, impl) in a bench-ratios table."""
    for t in tables(markdown):
        for row in t[1:]:
            if len(row) >= 4 and row[0] == op and row[1] == impl:
                return row[3]
    return None
