#!/usr/bin/env bash
# Compares two builds of lfcam on the CPU renderer's main cells, alternated in the same minutes
# (this machine's speed moves by a factor of two from day to day, so only builds run side by side
# can be compared; docs/benchmarks.md, "The cameras integrator's counting off the blend's common
# path"): the pinhole, the cameras integrator at d_l 256, the quadrilinear limit at d_l 128 and
# the paper's lens samples at d_l 256 gamma 1 and d_l 64 gamma 4, 1024^2 frames (f 444 mm,
# d_o 4000 mm). Prints each round's medians, the median over the rounds, new / old, and whether
# the two builds' frames are the same bytes.
# Usage: bench/ab.sh OLD_LFCAM NEW_LFCAM [LIGHTFIELD.lf] [--rounds N] [--repeat N]
#   default light field: the bench's, simulated once into out/bench/paper.lf (as bench/peer.sh)
# An old build to compare against: `git worktree add /tmp/old COMMIT && cd /tmp/old &&
# cmake --preset release && cmake --build --preset release --target lfcam`.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,12p' "$0"; exit 2; }
old="" new="" lf="" rounds=3 repeat=15
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=${2:?--rounds N}; shift 2 ;;
    --repeat) repeat=${2:?--repeat N}; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "ab.sh: unknown flag '$1'" >&2; exit 2 ;;
    *)
      if [ -z "$old" ]; then old=$1
      elif [ -z "$new" ]; then new=$1
      elif [ -z "$lf" ]; then lf=$1
      else echo "ab.sh: one light field at most ('$1')" >&2; exit 2
      fi
      shift ;;
  esac
done
if [ -z "$old" ] || [ -z "$new" ]; then usage; fi
for binary in "$old" "$new"; do
  [ -x "$binary" ] || { echo "ab.sh: '$binary' is not an executable lfcam" >&2; exit 2; }
done
case "$rounds$repeat" in *[!0-9]*) echo "ab.sh: --rounds and --repeat take whole numbers" >&2; exit 2 ;; esac
if [ -z "$lf" ]; then
  lf=out/bench/paper.lf
  if [ ! -f "$lf" ]; then
    mkdir -p out/bench
    echo "== simulating the bench's light field (10x10 views of 1248x1152) into $lf"
    "$new" simulate lightfield --out "$lf" --st-domain=-1.2,-1.2,1.2,1.2 --supersampling 1 --quiet
  fi
fi
[ -f "$lf" ] || { echo "ab.sh: no light field at '$lf'" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cells=("pinhole|--aperture 0"
       "cameras d_l 256|--integrator cameras --aperture 256"
       "quadrilinear limit d_l 128|--integrator cameras-quadrilinear --aperture 128"
       "lens samples d_l 256 gamma 1|--aperture 256 --lens-rate 1"
       "lens samples d_l 64 gamma 4|--aperture 64 --lens-rate 4")

# One frame's median (ms) from `lfcam render --repeat`, its frame written to $3.
median_ms() {
  local binary=$1 flags=$2 out=$3 line
  # shellcheck disable=SC2086  # the cell's flags are words
  line=$("$binary" render "$lf" $flags --size 1024 --focal-length 444 --focus-distance 4000 \
    --repeat "$repeat" --out "$out" 2>&1 | tail -n 1)
  sed -n 's/.*; \([0-9.]*\) ms (median.*/\1/p' <<<"$line" | grep . ||
    { echo "ab.sh: no time in '$line'" >&2; return 1; }
}

middle() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "light field: $lf; $rounds rounds of $repeat frames a cell, old and new alternated"
printf '%-30s %-28s %-28s %8s %8s %6s  %s\n' cell "old, each round (ms)" "new, each round (ms)" old new new/old frames
for cell in "${cells[@]}"; do
  name=${cell%%|*} flags=${cell#*|}
  old_times=() new_times=()
  for ((round = 0; round < rounds; ++round)); do
    old_times+=("$(median_ms "$old" "$flags" "$work/old.png")")
    new_times+=("$(median_ms "$new" "$flags" "$work/new.png")")
  done
  old_mid=$(printf '%s\n' "${old_times[@]}" | middle)
  new_mid=$(printf '%s\n' "${new_times[@]}" | middle)
  if cmp -s "$work/old.png" "$work/new.png"; then same="the same bytes"
  else same=$("$new" compare "$work/old.png" "$work/new.png" 2>&1 | tail -n 1); fi
  printf '%-30s %-28s %-28s %8s %8s %6s  %s\n' "$name" "${old_times[*]}" "${new_times[*]}" \
    "$old_mid" "$new_mid" "$(awk -v a="$old_mid" -v b="$new_mid" 'BEGIN {printf "%.2f", b / a}')" "$same"
done
