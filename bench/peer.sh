#!/usr/bin/env bash
# Times the NumPy + OpenCV peer (bench/peer.py: shift-and-add of every view with cv2.warpAffine)
# and `lfcam render --integrator cameras` on the same light field, the same 1024^2 frame and a
# full aperture (d_l = 256 mm, f = 444 mm, d_o = 4000 mm), then the peer's pinhole (the four
# views around the eye) and lfcam's (--aperture 0), one after the other in one run, and prints
# the medians and the ratios (docs/benchmarks.md); last, the floor under any pinhole frame on this
# machine (bench/frame_floor.cpp: the bytes a frame reads and writes, moved with no arithmetic).
# Usage: bench/peer.sh [LIGHTFIELD.lf] [--runs N]
#   default light field: the paper's 10x10x1248x1152, simulated once into out/bench/paper.lf
set -euo pipefail
cd "$(dirname "$0")/.."

lf=""; runs=9
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    -*) echo "peer.sh: unknown flag '$1'" >&2; exit 2 ;;
    *) lf=$1; shift ;;
  esac
done

LFCAM_PEER_DEPS=1 scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target lfcam lfcam_frame_floor >/dev/null
lfcam=build/release/lfcam
if [ -z "$lf" ]; then
  lf=out/bench/paper.lf
  if [ ! -f "$lf" ]; then
    mkdir -p out/bench
    echo "== simulating the paper's light field (10x10 views of 1248x1152) into $lf"
    $lfcam simulate lightfield --out "$lf" --st-domain=-1.2,-1.2,1.2,1.2 --supersampling 1 --quiet
  fi
fi
out=out/bench
mkdir -p "$out"
frame=(--size 1024 --focal-length 444 --focus-distance 4000)

# One comparison: the peer with its flags, lfcam with its flags, both medians and the ratio.
compare() {
  local name=$1 peer_flags=$2 lfcam_flags=$3 tag=$4
  local peer_line lfcam_line peer_ms lfcam_ms
  # shellcheck disable=SC2086  # the flags are words
  peer_line=$(/usr/bin/python3 bench/peer.py "$lf" "${frame[@]}" $peer_flags --runs "$runs" \
    --out "$out/peer_$tag.png")
  echo "$peer_line"
  # shellcheck disable=SC2086
  lfcam_line=$($lfcam render "$lf" "${frame[@]}" $lfcam_flags --repeat "$runs" --quiet \
    --out "$out/lfcam_$tag.png")
  echo "lfcam: $lfcam_line"
  peer_ms=$(sed -n 's/.*median \([0-9.]*\) ms.*/\1/p' <<<"$peer_line")
  lfcam_ms=$(sed -n 's/.*; \([0-9.]*\) ms (median.*/\1/p' <<<"$lfcam_line")
  awk -v n="$name" -v p="$peer_ms" -v l="$lfcam_ms" 'BEGIN {
    printf "%s: peer %.1f ms, lfcam %.2f ms: lfcam is %.1fx faster\n", n, p, l, p / l }'
  echo "frames: $out/peer_$tag.png, $out/lfcam_$tag.png"
}

compare "d_l 256 (every view: lfcam --integrator cameras)" "" \
  "--aperture 256 --integrator cameras" cameras
compare "pinhole (the four views around the eye, the focal-plane lookup)" "--pinhole" \
  "--aperture 0 --interpolation focal-plane" pinhole
build/release/lfcam_frame_floor 2
