#!/usr/bin/env bash
# Starts a camera array of real lfcam-node agents on this machine (loopback ports), one process
# per camera, and writes the array file and key that `lfcam capture` drives them with. For the
# capture demo (scripts/demo.sh --capture), the capture benchmark and trying the capture system
# without Raspberry Pis.
#
#   scripts/local-array.sh start DIR --grid 10x10 --sensor 648x486 --backend sim [--seed N]
#   scripts/local-array.sh start DIR --grid 10x10 --backend replay --replay FOLDER
#   scripts/local-array.sh stop DIR
#
# DIR gets array.json, array.key, node-RR-CC/ (each node's captures and log) and pids.
set -euo pipefail
cd "$(dirname "$0")/.."
node_bin=${LFCAM_NODE:-build/release/lfcam-node}

usage() { sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
action=$1 dir=$2
shift 2

stop() {
  [ -f "$dir/pids" ] || return 0
  while read -r pid; do kill "$pid" 2>/dev/null || true; done <"$dir/pids"
  while read -r pid; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done <"$dir/pids"
  rm -f "$dir/pids"
}

case $action in
  stop) stop; exit 0 ;;
  start) ;;
  *) usage ;;
esac

grid=10x10 sensor=648x486 backend=sim seed=1 replay="" base_port=0
while [ $# -gt 0 ]; do
  case $1 in
    --grid) grid=$2; shift 2 ;;
    --sensor) sensor=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --replay) replay=$(realpath "$2"); shift 2 ;;
    *) echo "local-array.sh: unknown flag $1" >&2; usage ;;
  esac
done
rows=${grid%x*} cols=${grid#*x}
[ -x "$node_bin" ] || { echo "local-array.sh: $node_bin is not built (cmake --build build/release)" >&2; exit 1; }
mkdir -p "$dir"
stop
[ -f "$dir/array.key" ] || "${LFCAM:-build/release/lfcam}" capture keygen --out "$dir/array.key" >/dev/null
: >"$dir/pids"
for ((r = 0; r < rows; r++)); do
  for ((c = 0; c < cols; c++)); do
    name=$(printf 'node-%02d-%02d' "$r" "$c")
    mkdir -p "$dir/$name"
    rm -f "$dir/$name/port"
    args=(--listen 127.0.0.1:0 --port-file "$dir/$name/port" --key-file "$dir/array.key"
          --captures "$dir/$name/captures" --name "$name" --quiet --threads 2 --backend "$backend")
    case $backend in
      sim) args+=(--sim-position "$r,$c" --sim-grid "$grid" --sim-seed "$seed") ;;
      replay) args+=(--replay "$replay") ;;
    esac
    "$node_bin" "${args[@]}" >"$dir/$name/log" 2>&1 &
    echo $! >>"$dir/pids"
  done
done
# The array file, once every node has said which port it took.
{
  echo '{"format": "lfcam-array", "version": 1,'
  echo "  \"rows\": $rows, \"cols\": $cols, \"pitch_mm\": 28.0, \"key_file\": \"array.key\","
  echo "  \"settings\": {\"width\": ${sensor%x*}, \"height\": ${sensor#*x}},"
  echo '  "boards": {"intrinsics": "10x7@30", "world": "11x10@50"},'
  echo '  "nodes": ['
  for ((r = 0; r < rows; r++)); do
    for ((c = 0; c < cols; c++)); do
      name=$(printf 'node-%02d-%02d' "$r" "$c")
      for _ in $(seq 100); do [ -s "$dir/$name/port" ] && break; sleep 0.05; done
      [ -s "$dir/$name/port" ] || { echo "local-array.sh: $name did not start: $(cat "$dir/$name/log")" >&2; stop; exit 1; }
      sep=$([ $r -eq $((rows - 1)) ] && [ $c -eq $((cols - 1)) ] && echo "" || echo ",")
      echo "    {\"row\": $r, \"col\": $c, \"address\": \"127.0.0.1:$(cat "$dir/$name/port")\"}$sep"
    done
  done
  echo '  ]}'
} >"$dir/array.json"
echo "local-array.sh: $((rows * cols)) $backend nodes up; array file $dir/array.json"
