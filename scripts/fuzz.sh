#!/usr/bin/env bash
# Fuzzes the scene loader, the OBJ reader and the readers of results.json,
# baselines and sweep cells and manifests: builds the libFuzzer targets with clang, ASan and UBSan (the `fuzz`
# preset), seeds them with data/scenes, tests/core/data/meshes, fuzz/seeds and
# data/reference, and runs each for a fifth of the time given. Exit 0 when none
# finds a crash, a sanitizer report, an exception
# other than gacompare::Error, a hang (10 s per input) or a memory blow-up
# (2 GB); otherwise 1, with the input that did it in build/fuzz/crashes/.
#   bash scripts/fuzz.sh              # 60 s in all: the CI path (scripts/ci.sh)
#   bash scripts/fuzz.sh --seconds N  # N s in all
#   bash scripts/fuzz.sh --long       # an hour in all, for a release or after a loader change
# Prints each target's figures: runs, coverage (edges, features), corpus, crashes.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=60
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --long) seconds=3600; shift ;;
    *) echo "fuzz.sh: unknown argument $1 (expected --seconds N or --long)" >&2; exit 2 ;;
  esac
done
bash scripts/install-deps.sh
cmake --preset fuzz >&2
cmake --build --preset fuzz >&2
mkdir -p build/fuzz/corpus/scene build/fuzz/corpus/obj build/fuzz/corpus/results build/fuzz/corpus/baseline \
  build/fuzz/corpus/cell build/fuzz/crashes
share=$(( (seconds + 4) / 5 ))  # each target's share of the time
status=0
run() {  # target, dictionary, seed folders...
  local target="$1" dict="$2"; shift 2
  local log="build/fuzz/$target.log"
  local rc=0
  touch "$log.start"
  # The corpus kept between runs comes first: new finds go there, never into the seeds.
  build/fuzz/fuzz/"$target" -max_total_time="$share" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict="$dict" -artifact_prefix=build/fuzz/crashes/"$target"- \
    build/fuzz/corpus/"${target#fuzz_}" "$@" >"$log" 2>&1 || rc=$?
  local done_line runs cov ft corp crashes
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -1 || true)
  runs=$(grep -E '^stat::number_of_executed_units:' "$log" | awk '{print $2}' || true)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$done_line")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$done_line")
  corp=$(sed -nE 's/.* corp: ([0-9]+).*/\1/p' <<<"$done_line")
  crashes=$(find build/fuzz/crashes -name "$target-*" -newer "$log.start" 2>/dev/null | wc -l)
  echo "fuzz: $target: ${runs:-?} runs in ${share} s, coverage ${cov:-?} edges / ${ft:-?} features, corpus ${corp:-?}, crashes ${crashes} (exit ${rc}; log $log)"
  if [ "$rc" -ne 0 ] || [ "$crashes" -ne 0 ]; then
    grep -E 'ERROR|SUMMARY|==[0-9]+==|terminate|Test unit written' "$log" | head -20 >&2 || true
    status=1
  fi
}
run fuzz_scene fuzz/scene.dict data/scenes
run fuzz_obj fuzz/obj.dict tests/core/data/meshes
run fuzz_results fuzz/stored.dict fuzz/seeds/results
run fuzz_baseline fuzz/stored.dict data/reference
run fuzz_cell fuzz/stored.dict fuzz/seeds/cell
exit $status
