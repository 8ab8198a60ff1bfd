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
# Mesa is installed above, so the GL tests must find a GL 4.3 context: fail rather than skip.
export LFCAM_REQUIRE_GL="${LFCAM_REQUIRE_GL:-1}"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset" "$@"
