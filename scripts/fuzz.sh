#!/usr/bin/env bash
# Builds lfcam's libFuzzer targets (the fuzz preset: clang, AddressSanitizer, UBSan) and runs
# each of them, starting from the seed corpus in fuzz/corpus/TARGET/.
#
#   scripts/fuzz.sh [SECONDS]          each target for SECONDS (default 30): CI's smoke run
#   scripts/fuzz.sh --runs N [TARGET]  each target (or one) for N executions: the long run
#
# New inputs libFuzzer finds go to build/fuzz/corpus/TARGET (not into the tree); a crash is
# saved as build/fuzz/artifacts/TARGET/crash-* and fails the run. Every crash found becomes a
# regression test (docs/robustness.md). The last line is "fuzz: N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=30
runs=""
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    [0-9]*) seconds=$1; shift ;;
    *) only=$1; shift ;;
  esac
done

LFCAM_FUZZ_DEPS=1 scripts/install-deps.sh
cmake --preset fuzz >/dev/null
targets=()
for source in $(find src/lfcam -name '*_fuzz.cpp' | sort); do
  name=$(basename "$source" .cpp)
  if [ -z "$only" ] || [ "$only" = "$name" ]; then targets+=("$name"); fi
done
[ ${#targets[@]} -gt 0 ] || { echo "fuzz: no target named '$only'" >&2; exit 2; }
cmake --build --preset fuzz --target "${targets[@]}"

passed=0
failed=0
for name in "${targets[@]}"; do
  corpus=build/fuzz/corpus/$name
  artifacts=build/fuzz/artifacts/$name
  mkdir -p "$corpus" "$artifacts"
  limit=(-max_total_time="$seconds")
  [ -n "$runs" ] && limit=(-runs="$runs")
  log=build/fuzz/$name.log
  if [ -n "$runs" ]; then echo "fuzz: $name ($runs runs)"; else echo "fuzz: $name ($seconds s)"; fi
  if build/fuzz/"$name" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$artifacts/" "$corpus" "fuzz/corpus/$name" >"$log" 2>&1; then
    passed=$((passed + 1))
    executions=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    echo "fuzz: $name passed: ${executions:-?} executions, no crash, no sanitizer report"
  else
    failed=$((failed + 1))
    echo "fuzz: $name FAILED; the end of its log ($log):"
    tail -40 "$log"
  fi
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
