#!/usr/bin/env bash
# The main job: installs what is missing, builds, runs every bundled scene
# through both backends and writes one report folder, whose path it prints.
# Extra arguments go to `gacompare compare` (e.g. --repeat 9, --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh release
exec build/release/compare/gacompare compare data/scenes/*.json "$@"
