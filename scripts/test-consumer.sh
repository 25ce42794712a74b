#!/usr/bin/env bash
# Installs the build in $1 into a scratch prefix and builds tests/consumer, a
# separate project, against it with find_package(gacompare); runs it. Used by
# ctest (tests/CMakeLists.txt, label install). Leaves nothing behind.
set -euo pipefail
build="$1"
here="$(cd "$(dirname "$0")/.." && pwd)"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/gacompare-consumer.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$here/tests/consumer" -B "$scratch/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
test -x "$scratch/prefix/bin/gacompare"
