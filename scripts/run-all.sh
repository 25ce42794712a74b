#!/usr/bin/env bash
# The main job: installs what is missing, builds the gacompare command alone
# (not the tests and benchmarks: scripts/test.sh builds those), runs every
# bundled scene through both backends and writes one report folder, whose path
# it prints. Extra arguments go to `gacompare compare` (e.g. --repeat 9, --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >&2
cmake --build --preset release --target gacompare >&2
exec build/release/compare/gacompare compare data/scenes/*.json "$@"
