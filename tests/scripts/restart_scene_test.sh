#!/usr/bin/env bash
# bench/scale/restart_scene.py: a 27-body box run for 0.2 s and restarted
# from its sample at 0.1 s starts where that sample is (every body's
# position to the digit; its orientation, velocity and angular velocity to
# 1e-12, relative: the loader normalises the first and may hold the others
# as momenta, which rounds the last digit), runs the
# 0.1 s left, and a bad request (no such sample, several backends and none
# named, a body the sample lacks) ends with a one-line reason and no scene.
#   restart_scene_test.sh GACOMPARE BOX_SCENE_PY RESTART_SCENE_PY
set -euo pipefail
tool="$1" box_py="$2" restart_py="$3"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 "$box_py" --bodies 27 --seed 1 --duration 0.2 --every 0.1 >"$dir/box.json"
"$tool" -q run "$dir/box.json" --backend traditional --out "$dir/run" >/dev/null
python3 "$restart_py" "$dir/box.json" "$dir/run/trajectories.csv" --at 0.1 >"$dir/restarted.json"
"$tool" -q run "$dir/restarted.json" --backend traditional --out "$dir/again" >/dev/null
python3 - "$dir" <<'EOF'
import csv, json, sys
d = sys.argv[1]
def sample(path, t):
    return {r["name"]: r for r in csv.DictReader(open(path)) if abs(float(r["t"]) - t) < 1e-9}
before, after = sample(f"{d}/run/trajectories.csv", 0.1), sample(f"{d}/again/trajectories.csv", 0.0)
scene = json.load(open(f"{d}/restarted.json"))
assert abs(scene["duration"] - 0.1) < 1e-12, scene["duration"]
assert len(before) == 33 and set(before) == set(after), (len(before), len(after))
for name, b in before.items():
    a = after[name]
    for k in ("x", "y", "z"):
        assert float(a[k]) == float(b[k]), (name, k, a[k], b[k])
    for k in ("qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"):
        assert abs(float(a[k]) - float(b[k])) <= 1e-12 * max(1.0, abs(float(b[k]))), (name, k, a[k], b[k])
print("restarted at 0.1 s: every body where the sample put it")
EOF
# Bad requests: a reason on one line, a non-zero exit and nothing written.
expect_fail() {
  local want="$1"
  shift
  if python3 "$restart_py" "$@" >"$dir/out.json" 2>"$dir/err"; then
    echo "FAIL: restart_scene.py $* succeeded" >&2
    exit 1
  fi
  if ! grep -q "$want" "$dir/err" || [ "$(wc -l <"$dir/err")" -ne 1 ] || [ -s "$dir/out.json" ]; then
    echo "FAIL: restart_scene.py $*: expected one line with '$want', got:" >&2
    cat "$dir/err" >&2
    exit 1
  fi
}
expect_fail "no sample at t = 0.05" "$dir/box.json" "$dir/run/trajectories.csv" --at 0.05
"$tool" -q compare "$dir/box.json" --backends traditional,cga --repeat 1 --no-work-precision --out "$dir/both" >/dev/null
expect_fail "name one with --backend" "$dir/box.json" "$dir/both/trajectories.csv" --at 0.1
expect_fail "has no backend 'pga'" "$dir/box.json" "$dir/both/trajectories.csv" --at 0.1 --backend pga
grep -v ",b00003," "$dir/run/trajectories.csv" >"$dir/lacking.csv"
expect_fail "the sample has no body 'b00003'" "$dir/box.json" "$dir/lacking.csv" --at 0.1
expect_fail "nothing is left of the scene" "$dir/box.json" "$dir/run/trajectories.csv" --at 0.2
echo "bad requests: each refused with its reason"
