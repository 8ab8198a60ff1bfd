#!/usr/bin/env bash
# The main job, the way a user with an array runs it: build lfcam; take a raw capture with the
# simulated 10x10 array of Raspberry Pi camera modules (board shots and the Fig. 11 scene);
# calibrate the array; build the light field; and render Fig. 11 (a)-(e) from it with the
# paper's parameters into out/demo/ (one PNG per frame and one contact sheet per sequence, and
# each sequence as an MP4); then share it: a web page anyone opens in a browser (out/demo/web)
# and a Looking Glass quilt (out/demo/quilt).
# Usage: scripts/demo.sh [--quick] [--capture]
#   default: modules of 1296x972 (binned, half the Pi v1.3's size), a 1248x1152 light field,
#            1024x1024 frames
#   --quick: modules of 648x486, a 624x576 light field and 512x512 frames
#   --capture: take the raw capture the way a real array does: 100 lfcam-node agents (one
#            process per camera, on loopback, playing simulated modules) driven by
#            `lfcam capture` (configure, 14 board poses, world board, scene), instead of
#            `lfcam simulate capture` writing the session directly (docs/hardware.md)
#   --video: light field video instead (scripts/demo-video.sh: 100 nodes record the moving
#            scene, the host aligns the frames, lfcam builds and renders the video)
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0 capture=0
for arg in "$@"; do
  case "$arg" in
    --video) shift; exec scripts/demo-video.sh "$@" ;;
    --quick) quick=1 ;;
    --capture) capture=1 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "demo.sh: unknown argument '$arg' (try --quick, --capture or --video)" >&2; exit 2 ;;
  esac
done

start=$(date +%s)
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target lfcam lfcam-node
lfcam=build/release/lfcam

out=out/demo
mkdir -p "$out"
if [ $quick -eq 1 ]; then
  sensor=648x486; st_res=624x576; size=512
else
  sensor=1296x972; st_res=1248x1152; size=1024
fi
session="$out/capture"
lf="$out/paper.lf"
rm -rf "$session"
if [ $capture -eq 1 ]; then
  nodes="$out/nodes"
  trap 'scripts/local-array.sh stop "$nodes" >/dev/null 2>&1 || true' EXIT
  echo "== starting 100 lfcam-node agents (simulated Pi camera modules of $sensor) on loopback"
  scripts/local-array.sh start "$nodes" --grid 10x10 --sensor "$sensor" --backend sim
  array="$nodes/array.json"
  echo "== locking the same settings on every node"
  $lfcam capture configure "$array" | tail -n 1
  for k in $(seq -w 0 13); do
    echo "== shooting board pose $k (every node at one trigger time, then fetched and verified)"
    $lfcam capture shoot "$array" --session "$session" --kind intrinsics --quiet
  done
  echo "== shooting the world board, then the scene"
  $lfcam capture shoot "$array" --session "$session" --kind world --quiet
  $lfcam capture shoot "$array" --session "$session" --kind scene --quiet
  scripts/local-array.sh stop "$nodes"
else
  echo "== capturing: 10x10 simulated Pi camera modules of $sensor (14 board poses, world board, scene)"
  $lfcam simulate capture --scene paper --grid 10x10 --sensor "$sensor" --out "$session"
fi
echo "== calibrating the array"
$lfcam calibrate "$session" --out "$out/calibration.json"
echo "== building the light field: 10x10 views of $st_res st samples"
$lfcam build "$session" --calibration "$out/calibration.json" --st-res "$st_res" --out "$lf"
$lfcam info "$lf"

# render NAME FLAGS...: one frame of a sequence, through the limit of the paper's own estimator
# (its smooth out-of-focus blur, without its lens-sample noise; docs/fidelity.md says why).
render() {
  local name=$1; shift
  $lfcam render "$lf" --out "$out/$name.png" --size "$size" --integrator cameras-quadrilinear "$@"
}
# sheet SEQ TITLE LABELS FILES...: the contact sheet of a sequence.
sheet() {
  local seq=$1 title=$2 labels=$3; shift 3
  $lfcam montage "$@" --out "$out/fig11${seq}_sheet.png" --title "$title" --labels "$labels" \
    --tile-width 256 >/dev/null
  echo "   sheet: $out/fig11${seq}_sheet.png"
}

# movie NAME FLAGS...: a sequence as an H.264 video (60 frames, 2 s), the swept parameter A:B.
movie() {
  local name=$1; shift
  $lfcam render "$lf" --video "$out/$name.mp4" --size "$size" --integrator cameras-quadrilinear \
    --frames 60 --quiet "$@" | sed 's/^/   /'
}

focus=(3400 3700 3900 4300 4700 5200)
echo "== Fig. 11 (a): refocus with breathing, f = 500, d_l = 192, d_o = 3400 -> 5200"
files=(); labels=""
for d in "${focus[@]}"; do
  render "fig11a_do$d" --focal-length 500 --aperture 192 --focus-distance "$d"
  files+=("$out/fig11a_do$d.png"); labels+="d_o $d;"
done
sheet a "(a) refocus with focus breathing, f 500, d_l 192" "$labels" "${files[@]}"
movie fig11a --focal-length 500 --aperture 192 --focus-distance 3400:5200

echo "== Fig. 11 (b): refocus without breathing"
files=(); labels=""
for d in "${focus[@]}"; do
  render "fig11b_do$d" --focal-length 500 --aperture 192 --focus-distance "$d" --no-breathing
  files+=("$out/fig11b_do$d.png"); labels+="d_o $d;"
done
sheet b "(b) refocus without breathing, f 500, d_l 192" "$labels" "${files[@]}"
movie fig11b --focal-length 500 --aperture 192 --focus-distance 3400:5200 --no-breathing

echo "== Fig. 11 (c): depth of field, f = 444, d_o = 3900, d_l = 64 -> 512"
files=(); labels=""
for a in 64 96 128 256 512; do
  render "fig11c_dl$a" --focal-length 444 --focus-distance 3900 --aperture "$a"
  files+=("$out/fig11c_dl$a.png"); labels+="d_l $a;"
done
sheet c "(c) depth of field, f 444, d_o 3900" "$labels" "${files[@]}"
movie fig11c --focal-length 444 --focus-distance 3900 --aperture 64:512

echo "== Fig. 11 (d): zoom, d_o = 3900, d_l = 192, f = 500 -> 1000"
files=(); labels=""
for f in 500 600 700 800 900 1000; do
  render "fig11d_f$f" --focal-length "$f" --focus-distance 3900 --aperture 192
  files+=("$out/fig11d_f$f.png"); labels+="f $f;"
done
sheet d "(d) zoom, d_o 3900, d_l 192" "$labels" "${files[@]}"
movie fig11d --focal-length 500:1000 --focus-distance 3900 --aperture 192

echo "== Fig. 11 (e): moving camera, d_o = 4300, f = 700, d_l = 64"
# The eye slides across the array, always looking at the centre of the plane of focus (4.3 m
# away): what lies on it stays put, nearer objects move against the eye, farther ones with it.
files=(); labels=""
for x in -100 -60 -20 20 60 100; do
  render "fig11e_x$x" --focal-length 700 --focus-distance 4300 --aperture 64 \
    --eye "$((300 + x)),275,3600" --look-at "300,275,-700"
  files+=("$out/fig11e_x$x.png"); labels+="eye x $x mm;"
done
sheet e "(e) moving camera, f 700, d_o 4300, d_l 64" "$labels" "${files[@]}"
movie fig11e --focal-length 700 --focus-distance 4300 --aperture 64 \
  --eye 200,275,3600:400,275,3600 --look-at 300,275,-700

echo "== sharing: a web page anyone opens in a browser, and a Looking Glass quilt"
rm -rf "$out/web" "$out/quilt"
$lfcam export "$lf" --format web --out "$out/web" --focal-length 400 --focus-distance 4300 \
  --aperture 64
$lfcam export "$lf" --format quilt --out "$out/quilt" --focal-length 520 --focus-distance 4300 \
  --quiet

echo
echo "Done in $(( $(date +%s) - start )) s. Frames, contact sheets and videos are in $out/:"
ls "$out"/*_sheet.png "$out"/*.mp4
echo "Open the light field in a browser: $out/web/index.html (any static server shares it)"
echo "Explore the light field interactively (F1 lists the keys; docs/viewer.md):"
echo "  $lfcam view $lf"
