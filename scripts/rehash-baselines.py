#!/usr/bin/env python3
"""Stores a scene's new sha256 in its baseline (data/reference/NAME.json) when
the scene changed in its description alone.

A baseline keeps the sha256 of the scene file it was stored from, and
`gacompare check` refuses a baseline whose scene changed. A description is
text for readers, not physics, so rerunning and storing everything
(`check --update`) would be more than the change asks for. For each scene
whose file no longer matches its baseline's sha256, this finds in the git
history the version that does, and if the two differ only in "description"
rewrites the sha256 line of the baseline and nothing else. Any other change
is refused (exit 1) with the key that changed: such a scene needs
`gacompare check --update`, which reruns it. Run `gacompare check` afterwards
(the test command does): the stored states still have to hold.

  python3 scripts/rehash-baselines.py                 # every bundled scene
  python3 scripts/rehash-baselines.py data/scenes/contact_row.json
"""
import glob
import hashlib
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def sha256(data):
    return hashlib.sha256(data).hexdigest()


def history(rel):
    """Every committed version of rel, newest first, as bytes."""
    commits = subprocess.run(["git", "rev-list", "HEAD", "--", rel], cwd=ROOT, capture_output=True,
                             text=True, check=True).stdout.split()
    for c in commits:
        shown = subprocess.run(["git", "show", f"{c}:{rel}"], cwd=ROOT, capture_output=True)
        if shown.returncode == 0:
            yield shown.stdout


def differing_keys(a, b):
    return sorted(k for k in set(a) | set(b) if k != "description" and a.get(k) != b.get(k))


def rehash(scene_path):
    rel = os.path.relpath(os.path.abspath(scene_path), ROOT)
    with open(os.path.join(ROOT, rel), "rb") as f:
        now = f.read()
    scene = json.loads(now)
    baseline = os.path.join(ROOT, "data", "reference", scene["name"] + ".json")
    if not os.path.exists(baseline):
        return f"{rel}: no baseline data/reference/{scene['name']}.json", False
    with open(baseline) as f:
        text = f.read()
    stored = json.loads(text)["sha256"]
    if sha256(now) == stored:
        return None, True
    old = next((v for v in history(rel) if sha256(v) == stored), None)
    if old is None:
        return f"{rel}: no committed version matches its baseline's sha256; run gacompare check --update", False
    keys = differing_keys(json.loads(old), scene)
    if keys:
        return (f"{rel}: changed beyond its description ({', '.join(keys)}); "
                "run gacompare check --update to rerun it"), False
    new_text, n = re.subn(r'("sha256": ")' + stored + '"', r"\g<1>" + sha256(now) + '"', text, count=1)
    if n != 1:
        return f"{os.path.relpath(baseline, ROOT)}: no sha256 line to rewrite", False
    with open(baseline + ".tmp", "w") as f:
        f.write(new_text)
    os.replace(baseline + ".tmp", baseline)
    return f"{os.path.relpath(baseline, ROOT)}: sha256 of the new description stored", True


def main():
    scenes = sys.argv[1:] or sorted(glob.glob(os.path.join(ROOT, "data", "scenes", "*.json")))
    ok = True
    for s in scenes:
        line, fine = rehash(s)
        if line:
            print(line, file=sys.stdout if fine else sys.stderr)
        ok = ok and fine
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
