#!/usr/bin/env python3
"""Checks what readers read (ctest -L docs):

- README.md is at most 400 lines;
- no tracking words (issue numbers, commit hashes in prose) in README.md,
  docs/, the scene files, or the sources of cga/ traditional/ compare/ tests/
  bench/ scripts/ (git log keeps them);
- every relative link and image in README.md and docs/ resolves to a file in
  the repository, and every #anchor to a heading of that file; every
  repository path named in backticks (`core/scene.hpp`) exists, so a file
  that moves cannot leave a page pointing at its old place;
- a scene's description says what happens in the scene: it names no file
  of the repository (where it is tested, what implements it), which belongs
  in the code, not in a page a reader sees in the report and the replay;
- every page under docs/results/ and the README's headline table have been
  generated (scripts/results.py fills them).

Prints one line per problem, naming the file and line; exit 1 if any.
"""
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_README_LINES = 400
# Folders whose every text file is checked for tracking words. core/ joins
# once its comments are rewritten.
SOURCE_FOLDERS = ["cga", "traditional", "compare", "tests", "bench", "scripts"]
TEXT = (".cpp", ".hpp", ".h", ".py", ".sh", ".txt", ".cmake", ".md", ".json", ".in")
TRACKING = re.compile(r"issue #?[0-9]+|\(#[0-9]+\)", re.I)
# A commit hash in prose: 7 to 40 hex digits with a letter and a digit, not
# part of a longer word or path; the provenance line of a results page is the
# one place a commit belongs.
HASH = re.compile(r"(?<![\w/.-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![\w-])")
LINK = re.compile(r"!?\[([^\]]*)\]\(([^)\s]+)\)")
# A path into the repository in backticks; patterns (*, {a,b}, <N>) are not paths.
# A repository file named in a scene's description.
SOURCE_PATH = re.compile(r"(?:core|cga|pga|traditional|compare|tests|bench|scripts|answers)/[\w/.-]+|\b\w+\.(?:hpp|cpp|py)\b")
NAMED_PATH = re.compile(r"`((?:core|cga|traditional|compare|tests|bench|scripts|data|docs|fuzz)/[^`\s*{<]+)`")


def markdown_files():
    yield "README.md"
    for folder, _, files in os.walk(os.path.join(ROOT, "docs")):
        for f in sorted(files):
            if f.endswith(".md"):
                yield os.path.relpath(os.path.join(folder, f), ROOT)


def source_files():
    for top in SOURCE_FOLDERS:
        for folder, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [d for d in dirs if not d.startswith(".")]
            for f in sorted(files):
                if f.endswith(TEXT):
                    yield os.path.relpath(os.path.join(folder, f), ROOT)
    scenes = os.path.join(ROOT, "data", "scenes")
    for f in sorted(os.listdir(scenes)):
        yield os.path.join("data", "scenes", f)


def read(rel):
    with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
        return f.read()


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = LINK.sub(lambda m: m.group(1), heading)
    return re.sub(r"[^\w\- ]", "", text.strip().lower()).replace(" ", "-")


def anchors(text):
    seen, out = {}, set()
    fence = False
    for line in text.splitlines():
        if line.startswith("```"):
            fence = not fence
        if fence:
            continue
        m = re.match(r"#{1,6} (.*)", line)
        if m:
            s = slug(m.group(1))
            n = seen.get(s, 0)
            seen[s] = n + 1
            out.add(s if n == 0 else f"{s}-{n}")
    return out


def check_links(rel, text, problems):
    base = os.path.dirname(os.path.join(ROOT, rel))
    fence = False
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("```"):
            fence = not fence
        if fence:
            continue
        for m in LINK.finditer(line):
            target = m.group(2)
            if re.match(r"[a-z]+:", target):
                continue  # http:, https:, mailto:: outside the repository by intent
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(base, path)) if path else os.path.join(ROOT, rel)
            if not full.startswith(ROOT + os.sep) and full != ROOT:
                problems.append(f"{rel}:{number}: link '{target}' leaves the repository")
                continue
            if not os.path.exists(full):
                problems.append(f"{rel}:{number}: link '{target}' does not resolve")
                continue
            if anchor and full.endswith(".md") and anchor not in anchors(read(os.path.relpath(full, ROOT))):
                problems.append(f"{rel}:{number}: link '{target}': no heading '#{anchor}' there")
        for m in NAMED_PATH.finditer(line):
            path = m.group(1).split(":")[0]
            if not os.path.exists(os.path.join(ROOT, path)):
                problems.append(f"{rel}:{number}: `{m.group(1)}` names no file of the repository")


def main():
    problems = []
    readme = read("README.md")
    lines = readme.count("\n")
    if lines > MAX_README_LINES:
        problems.append(f"README.md: {lines} lines, at most {MAX_README_LINES}: measurements belong in docs/results/")
    for rel in markdown_files():
        text = read(rel)
        check_links(rel, text, problems)
        for number, line in enumerate(text.splitlines(), 1):
            if TRACKING.search(line):
                problems.append(f"{rel}:{number}: an issue number: {TRACKING.search(line).group(0)}")
            if "**Commit:**" not in line and HASH.search(line):
                problems.append(f"{rel}:{number}: what looks like a commit hash: {HASH.search(line).group(0)}")
    for rel in source_files():
        for number, line in enumerate(read(rel).splitlines(), 1):
            m = TRACKING.search(line)
            if m:
                problems.append(f"{rel}:{number}: an issue number: {m.group(0)}")
    for rel in sorted(r for r in source_files() if r.startswith(os.path.join("data", "scenes"))):
        try:
            description = json.loads(read(rel)).get("description", "")
        except ValueError as e:
            problems.append(f"{rel}: not JSON ({e})")
            continue
        m = SOURCE_PATH.search(description)
        if m:
            problems.append(f"{rel}: the description names a source file ({m.group(0)}): say what happens in the scene")
    results = os.path.join(ROOT, "docs", "results")
    for f in sorted(os.listdir(results)):
        if f.endswith(".md") and "**Commit:**" not in read(os.path.join("docs", "results", f)):
            problems.append(f"docs/results/{f}: not generated (python3 scripts/results.py --list names the page that writes it)")
    table = re.search(r"<!-- generated: headline -->\n(.*?)<!-- end: headline -->", readme, re.S)
    if not table or "|" not in table.group(1):
        problems.append("README.md: the headline table is empty (run python3 scripts/results.py --only readme)")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
