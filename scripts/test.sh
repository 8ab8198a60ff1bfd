#!/usr/bin/env bash
# Installs the dependencies, builds lfcam (release preset) and runs the whole test suite.
# Usage: scripts/test.sh [--preset release|asan|debug] [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."

preset=release
if [ "${1:-}" = "--preset" ]; then
  preset=$2
  shift 2
fi

scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset" "$@"
