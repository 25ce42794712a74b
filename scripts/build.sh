#!/usr/bin/env bash
# Installs what is missing, configures and builds gacompare with the given CMake
# preset (default: release). Two jobs: the machines here have two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
bash scripts/install-deps.sh
cmake --preset "$preset" >&2
cmake --build --preset "$preset" >&2
