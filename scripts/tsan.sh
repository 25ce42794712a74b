#!/usr/bin/env bash
# The threads' race check, run by hand: builds gacompare-state-hash with
# ThreadSanitizer (the tsan preset) and runs the determinism check's scenes
# on it (tests/scripts/determinism_test.sh with its small box, 300 bodies
# for 0.2 s, searched and not, and the mixed pile, in the three backends).
# Every run on two threads, and on two with every parallel loop split
# (--fine-grains), must finish without a race report: the first one stops
# the run and fails the script. Not in CI, which is near its time budget: the
# build takes some ten minutes on two cores and the runs a few more.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh tsan
TSAN_OPTIONS="halt_on_error=1 exitcode=66 ${TSAN_OPTIONS:-}" GACOMPARE_QUICK_TESTS=1 \
  bash tests/scripts/determinism_test.sh build/tsan/compare/gacompare-state-hash bench/scale/box_scene.py \
  data/scenes/mixed_pile.json
