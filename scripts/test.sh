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

# The asan preset compiles with clang (half GCC's time with the sanitizers; docs/robustness.md).
if [ "$preset" = asan ]; then export LFCAM_CLANG_DEPS=1; fi
scripts/install-deps.sh
# Mesa is installed above, so the GL tests must find a GL 4.3 context: fail rather than skip.
export LFCAM_REQUIRE_GL="${LFCAM_REQUIRE_GL:-1}"
# Chromium is installed above too: the web page's browser test must run, not skip.
export LFCAM_REQUIRE_BROWSER="${LFCAM_REQUIRE_BROWSER:-1}"
# And Ansible: the rollout's inventory and playbook must be checked, not skipped.
export LFCAM_REQUIRE_ANSIBLE="${LFCAM_REQUIRE_ANSIBLE:-1}"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
status=0
ctest --preset "$preset" "$@" || status=$?
# ctest runs a suite a process (cmake/TestSuites.cmake): the tests skipped inside suites that ran.
log=build/$preset/Testing/Temporary/LastTest.log
if [ -f "$log" ]; then
  skipped=$(sed -n 's/^\[  SKIPPED \] \([A-Za-z0-9_/]*\.[A-Za-z0-9_/]*\)$/\1/p' "$log" | sort -u)
  if [ -n "$skipped" ]; then
    echo "test.sh: $(echo "$skipped" | wc -l) tests skipped (their output says why):"
    echo "$skipped" | sed 's/^/  /'
  fi
fi
if [ $status -ne 0 ] && [ "$preset" = asan ]; then
  # LeakSanitizer's tracer now and then crashes at a test's exit on a loaded machine, after the
  # test itself passed ("LeakSanitizer has encountered a fatal error", "Tracer caught signal").
  # Such a test, and only such a test, runs once more; any other failure stands.
  temporary=build/asan/Testing/Temporary
  failed=$(sed 's/^[0-9]*://' "$temporary/LastTestsFailed.log" | sort)
  tracer=$(awk '/^[0-9]+\/[0-9]+ Testing: / { name = $3; passed = 0; crashed = 0 }
                /\[  PASSED  \]/ { passed = 1 }
                /LeakSanitizer has encountered a fatal error|Tracer caught signal/ { crashed = 1 }
                /^Test Failed/ { if (passed && crashed) print name }' \
                "$temporary/LastTest.log" | sort -u)
  if [ -n "$failed" ] && [ "$failed" = "$tracer" ]; then
    echo "test.sh: LeakSanitizer's tracer crashed after these passed; running them once more:"
    echo "$failed" | sed 's/^/  /'
    pattern=$(echo "$failed" | sed 's/[.[\*^$()+?{|]/\\&/g' | paste -sd'|')
    ctest --preset "$preset" -R "^($pattern)\$"
    exit $?
  fi
  exit $status
fi
exit $status
