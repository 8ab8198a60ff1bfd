#!/usr/bin/env bash
# Light field video, the way a user with an array records it (issue 24; docs/hardware.md): build
# lfcam; start 100 lfcam-node agents on loopback playing the simulated 10x10 array of Pi camera
# modules; shoot the calibration boards through them; record the moving `paper` scene (a ball
# crossing it, a bead whirling, the fan turning) with libcamera's sync; say how well the array
# kept in step; calibrate; build the light field video; and render a short sequence from it
# into out/video/ (one PNG per frame, a contact sheet, and the sync report's picture).
# Usage: scripts/demo-video.sh [--seconds S] [--fps F]     (also: scripts/demo.sh --video)
#   default: 2 s at 30 fps, modules of 648x486; a few minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=2 fps=30
while [ $# -gt 0 ]; do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --fps) fps=$2; shift 2 ;;
    --video) shift ;;  # from scripts/demo.sh --video
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "demo-video.sh: unknown argument '$1' (try --seconds S or --fps F)" >&2; exit 2 ;;
  esac
done

start=$(date +%s)
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target lfcam lfcam-node
lfcam=build/release/lfcam

out=out/video
session="$out/capture"
nodes="$out/nodes"
video="$out/paper.lfv"
sensor=648x486
mkdir -p "$out"
rm -rf "$session" "$video"
trap 'scripts/local-array.sh stop "$nodes" >/dev/null 2>&1 || true' EXIT
echo "== starting 100 lfcam-node agents (simulated Pi camera modules of $sensor) on loopback"
scripts/local-array.sh start "$nodes" --grid 10x10 --sensor "$sensor" --backend sim
array="$nodes/array.json"
echo "== locking the same settings on every node"
$lfcam capture configure "$array" | tail -n 1
echo "== shooting the calibration boards: 14 poses of the intrinsics board, the world board"
for k in $(seq -w 0 13); do
  $lfcam capture shoot "$array" --session "$session" --kind intrinsics --quiet >/dev/null
done
$lfcam capture shoot "$array" --session "$session" --kind world --quiet >/dev/null
echo "== recording the moving scene: $seconds s at $fps fps, $sensor, libcamera's sync"
$lfcam capture record "$array" --session "$session" --seconds "$seconds" --fps "$fps" \
  --size "$sensor" --quiet
scripts/local-array.sh stop "$nodes"
$lfcam capture report --session "$session" --out "$out/sync.png" >/dev/null
echo "   the sync report's picture: $out/sync.png"

echo "== calibrating the array from the board shots"
$lfcam calibrate "$session" --out "$out/calibration.json" | tail -n 3
echo "== building the light field video"
$lfcam build "$session" --calibration "$out/calibration.json" --shot rec_00 --out "$video" --quiet
$lfcam info "$video" | head -n 4

# Every fifth frame (1/6 s at 30 fps): the fan (2 turns a second, 5 blades) and the bead
# (5 turns a second) do not come back to where they were.
echo "== rendering every fifth frame: focused on the ball's plane (4.3 m), f 500, d_l 96"
frames=$(awk -v s="$seconds" -v f="$fps" 'BEGIN { print int(s * f + 0.5) }')
files=(); labels=""
for ((k = 0; k < frames; k += 5)); do
  name=$(printf 'frame_%03d' "$k")
  $lfcam render "$video" --frame "$k" --out "$out/$name.png" --size 512 \
    --integrator cameras-quadrilinear --focal-length 500 --focus-distance 4300 --aperture 96 \
    >/dev/null
  files+=("$out/$name.png")
  labels+="t = $(awk -v k="$k" -v f="$fps" 'BEGIN { printf "%.2f s", k / f }');"
done
$lfcam montage "${files[@]}" --out "$out/sequence_sheet.png" --labels "$labels" \
  --title "light field video: every fifth frame, f 500, d_o 4300, d_l 96" --tile-width 256 \
  >/dev/null
echo "   sheet: $out/sequence_sheet.png"
echo "== done in $(( $(date +%s) - start )) s; frames and sheets in $out/"
echo "   look around one frame: $lfcam view $video   (frame 0)"
