#!/usr/bin/env bash
# The test command: installs what is missing, builds (warnings are errors), runs
# every test, then the regression check of the bundled scenes against their
# stored baselines (data/reference). Extra arguments go to ctest, e.g. `-L algebra`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh ci
ctest --preset ci -j2 "$@"
build/ci/compare/gacompare check data/scenes/*.json --baseline data/reference --quiet
