#!/usr/bin/env bash
# Builds lfcam's libFuzzer targets and runs each of them (one a core at a time), starting from
# the seed corpus in fuzz/corpus/TARGET/.
#
#   scripts/fuzz.sh [SECONDS]          each target for SECONDS (default 30)
#   scripts/fuzz.sh --runs N [TARGET]  each target (or one) for N executions: the long run
#   --preset fuzz (the default)        the fuzz preset: clang, ASan, UBSan, the library
#                                      instrumented for coverage (coverage-guided fuzzing)
#   --preset asan                      the targets of the asan preset's tree, over its library
#                                      without coverage feedback (no build of their own where
#                                      scripts/test.sh --preset asan has built that tree)
#
# CI's smoke run (.ci/run) is `scripts/fuzz.sh --preset fuzz 3`.
#
# New inputs libFuzzer finds go to build/PRESET/corpus/TARGET (not into the tree); a crash is
# saved as build/PRESET/artifacts/TARGET/crash-* and fails the run. Every crash found becomes a
# regression test (docs/robustness.md). The last line is "fuzz: N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=30
runs=""
only=""
preset=fuzz
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    [0-9]*) seconds=$1; shift ;;
    *) only=$1; shift ;;
  esac
done

case "$preset" in
  fuzz|asan) ;;
  *) echo "fuzz: no preset '$preset' (fuzz or asan)" >&2; exit 2 ;;
esac
tree=build/$preset
LFCAM_FUZZ_DEPS=1 scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
targets=()
for source in $(find src/lfcam -name '*_fuzz.cpp' | sort); do
  name=$(basename "$source" .cpp)
  if [ -z "$only" ] || [ "$only" = "$name" ]; then targets+=("$name"); fi
done
[ ${#targets[@]} -gt 0 ] || { echo "fuzz: no target named '$only'" >&2; exit 2; }
cmake --build --preset "$preset" --target "${targets[@]}"

# One target a core at a time (each is one process on one core); the report in the targets' order.
run_target() {
  local name=$1
  local corpus=$tree/corpus/$name artifacts=$tree/artifacts/$name
  mkdir -p "$corpus" "$artifacts"
  local limit=(-max_total_time="$seconds")
  [ -n "$runs" ] && limit=(-runs="$runs")
  local status=0
  "$tree/$name" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "$corpus" "fuzz/corpus/$name" >"$tree/$name.log" 2>&1 ||
    status=$?
  echo "$status" >"$tree/$name.status"
}
jobs_at_once=$(nproc)
if [ -n "$runs" ]; then echo "fuzz: ${#targets[@]} targets, $runs runs each, $jobs_at_once at a time"
else echo "fuzz: ${#targets[@]} targets, $seconds s each, $jobs_at_once at a time"; fi
for name in "${targets[@]}"; do
  rm -f "$tree/$name.status"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_at_once" ]; do wait -n || true; done
  run_target "$name" &
done
wait
passed=0
failed=0
for name in "${targets[@]}"; do
  log=$tree/$name.log
  if [ "$(cat "$tree/$name.status" 2>/dev/null)" = 0 ]; then
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
