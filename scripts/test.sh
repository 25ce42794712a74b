#!/usr/bin/env bash
# The test command: installs what is missing, builds (warnings are errors), runs
# every test, then the regression check of the bundled scenes against their
# stored baselines (data/reference). Extra arguments go to ctest, e.g. `-L algebra`.
#
# With --ci first (what CI runs, .ci/run): then also the determinism check
# against a clang build (the same state hashes as gcc's build gives), a 60 s fuzz run of the
# scene loader, the OBJ reader and the readers of results, baselines and sweep
# cells (scripts/fuzz.sh) and the whole suite again
# built with AddressSanitizer + UBSan (the asan preset).
set -euo pipefail
cd "$(dirname "$0")/.."
ci=0
if [ "${1:-}" = "--ci" ]; then
  ci=1
  shift
fi
bash scripts/build.sh ci
# In CI the Slurm test must run (it starts its own single-node Slurm); on a
# machine without Slurm or root it skips saying why.
GACOMPARE_REQUIRE_SLURM=$ci ctest --preset ci -j2 "$@"
build/ci/compare/gacompare check data/scenes/*.json --baseline data/reference --quiet
# Each CI phase prints the seconds elapsed when it ends (CI must stay well under its limit).
phase() { echo "ci: $1 done at ${SECONDS} s" >&2; }
if [ "$ci" = 1 ]; then
  phase "build, tests and check"
  bash scripts/build.sh clang
  bash tests/scripts/determinism_test.sh build/ci/compare/gacompare-state-hash bench/scale/box_scene.py \
    data/scenes/mixed_pile.json build/clang/compare/gacompare-state-hash
  phase "clang build and determinism check"
  bash scripts/fuzz.sh --seconds 60
  phase "fuzzing"
  bash scripts/build.sh asan
  phase "sanitized build"
  # Under the sanitizers the long physics runs (10 s stacks and columns of the
  # contact and stacking families) are left out: they run above, unsanitized,
  # and would take most of CI's time here for no memory error they could show.
  # The Slurm test ran above: the scheduler is not what the sanitizers check.
  GACOMPARE_QUICK_TESTS=1 ctest --preset asan -j2 -LE slurm "$@"
  phase "sanitized tests"
fi
