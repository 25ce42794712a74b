#!/usr/bin/env bash
# The test command: installs what is missing, builds (warnings are errors) and
# runs every test. Extra arguments go to ctest, e.g. `-L algebra`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh ci
ctest --preset ci -j2 "$@"
