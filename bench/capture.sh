#!/usr/bin/env bash
# The capture system at full scale on one machine (docs/benchmarks.md, "Capture"): 100 lfcam-node
# agents on loopback with the replay backend, each serving a 2.7 MB JPEG (the size of a Pi
# camera v1.3 still at 2592x1944), driven by `lfcam capture shoot`. Prints, per shot, the
# trigger skew across nodes (latest minus earliest actual trigger time) and the time from the
# command's start to the last image verified on disk, and their medians.
#
# Then the floor under the skew on this machine: the same number of bare processes woken at one
# time (bench/wake_floor.cpp).
#
#   bench/capture.sh [SHOTS (default 7)] [GRID (default 10x10)]
set -euo pipefail
cd "$(dirname "$0")/.."
shots=${1:-7} grid=${2:-10x10}
LFCAM_PEER_DEPS=1 scripts/install-deps.sh  # python3-opencv, for the test image
cmake --preset release >/dev/null
cmake --build build/release --target lfcam lfcam-node lfcam_wake_floor >/dev/null
work=$(mktemp -d /tmp/lfcam-bench-capture.XXXXXX)
trap 'scripts/local-array.sh stop "$work/array" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
mkdir -p "$work/replay"
# Blurred noise at JPEG quality 95: about 2.7 MB, and as hard to compress as a real photograph.
/usr/bin/python3 - "$work/replay/scene.jpg" <<'PY'
import sys, cv2, numpy as np
noise = np.random.default_rng(1).random((1944, 2592, 3)).astype(np.float32) * 255
image = cv2.GaussianBlur(noise, (0, 0), 1.1).astype(np.uint8)
cv2.imwrite(sys.argv[1], image, [cv2.IMWRITE_JPEG_QUALITY, 95])
PY
size=$(stat -c %s "$work/replay/scene.jpg")
scripts/local-array.sh start "$work/array" --grid "$grid" --sensor 2592x1944 --backend replay \
  --replay "$work/replay" >/dev/null
build/release/lfcam capture configure "$work/array/array.json" --json >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "nodes: $grid replay agents on loopback, image $(awk "BEGIN{printf \"%.2f\", $size/1e6}") MB"
results=()
for ((k = 0; k < shots; k++)); do
  start=$(date +%s.%N)
  build/release/lfcam capture shoot "$work/array/array.json" --session "$work/s$k" --quiet --json \
    >"$work/r$k.json"
  end=$(date +%s.%N)
  line=$(/usr/bin/python3 - "$work/r$k.json" "$start" "$end" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["complete"] and r["images_ok"] == r["cameras"], r["problems"][:3]
print(f'{r["skew_ms"]:.3f} {float(sys.argv[3]) - float(sys.argv[2]):.3f} {r["bytes"] / 1e6:.0f} {r["fetch_s"]:.3f}')
PY
)
  read -r skew total mb fetch <<<"$line"
  echo "shot $k: skew ${skew} ms, shoot + fetch ${total} s end to end (${mb} MB fetched in ${fetch} s, checksums verified)"
  results+=("$skew $total")
  rm -rf "$work/s$k"
done
nodes=$(( ${grid%x*} * ${grid#*x} ))
echo "floor, the same machine now: $(build/release/lfcam_wake_floor "$nodes")"
printf '%s\n' "${results[@]}" | /usr/bin/python3 -c "
import sys, statistics as s
rows = [tuple(map(float, l.split())) for l in sys.stdin if l.strip()]
print(f'median of {len(rows)}: skew {s.median(r[0] for r in rows):.3f} ms, shoot + fetch {s.median(r[1] for r in rows):.2f} s'
      ' (the paper: two groups 0.5 s apart, under a minute)')"
