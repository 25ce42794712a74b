#!/usr/bin/env bash
# bench/scale/settings.py: a 27-body box under a 2 x 2 grid of collision
# steps and tolerances gives one row per setting, each with its time, its
# counters and both depth rules read from the run's report; the scene of
# each setting carries that step, RK4 at half of it, and that tolerance; the
# runs' folders are gone once the table is written; a bad grid ends with a
# one-line reason and no table.
#   settings_test.sh GACOMPARE SETTINGS_PY
set -euo pipefail
tool="$1" settings_py="$2"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/tmp"
TMPDIR="$dir/tmp" python3 "$settings_py" --binary "$tool" --sizes 27 --repeat 2 --duration 0.05 --steps 1,2 \
  --tolerances 1e-4,1e-3 >"$dir/table.md" 2>"$dir/err"
python3 - "$dir/table.md" "$settings_py" <<'EOF'
import importlib.util, sys
rows = [[c.strip() for c in line.strip().strip("|").split("|")] for line in open(sys.argv[1])
        if line.startswith("| 27 |")]
assert [(r[1], r[2]) for r in rows] == [("1", "0.0001"), ("1", "0.001"), ("2", "0.0001"), ("2", "0.001")], rows
for r in rows:
    assert len(r) == 9, r
    float(r[3].split(" ")[0])  # the median time
    for depth in r[7:]:
        assert depth != "–", ("a depth rule missing from the report", r)
        float(depth.split(" ")[0])
spec = importlib.util.spec_from_file_location("settings", sys.argv[2])
settings = importlib.util.module_from_spec(spec)
spec.loader.exec_module(settings)
class Args: seed, duration, every = 1, 0.05, 0.05
scene = settings.scene_with(27, Args, 4, 5e-3)
collisions = [e for e in scene["effects"] if e["type"] == "collisions"]
assert len(collisions) == 1 and collisions[0]["step"] == 0.004 and collisions[0]["penetration_tolerance"] == 5e-3
assert collisions[0]["time_of_impact"] == "none" and scene["solver"]["dt"] == 0.002, scene["solver"]
EOF
if [ -n "$(ls -A "$dir/tmp")" ]; then
  echo "FAIL: settings.py left its scratch behind: $(ls "$dir/tmp")" >&2
  exit 1
fi
for bad in "--steps 1,x" "--tolerances 0" "--steps ,"; do
  if python3 "$settings_py" --binary "$tool" --sizes 27 $bad >"$dir/out" 2>"$dir/err"; then
    echo "FAIL: settings.py accepted $bad" >&2
    exit 1
  fi
  if [ -s "$dir/out" ] || [ "$(wc -l <"$dir/err")" -ne 1 ] || ! grep -q "settings.py: --" "$dir/err"; then
    echo "FAIL: $bad: expected no table and a one-line reason, got:" >&2
    cat "$dir/out" "$dir/err" >&2
    exit 1
  fi
done
echo "settings.py: 4 rows with every cell, scenes as asked, no scratch left, bad grids refused"
