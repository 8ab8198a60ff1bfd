#!/usr/bin/env bash
# The web page of a light field (`lfcam export --format web`) measured as issue 25 asks: its
# download size; its first picture's time from a local server (python3's http.server on
# loopback, headless Chromium on its software GPU, the page asking the server for a beacon once
# its first picture is drawn: navigation to beacon, wall-clock, median of N runs); and its
# screenshots against `lfcam render --integrator cameras` of the same view, same size (PSNR):
# a pinhole and a refocused view (docs/benchmarks.md, docs/fidelity.md).
# Usage: bench/web_page.sh [LIGHTFIELD.lf] [--runs N] [--size N]
#   default light field: the demo's (out/demo/paper.lf, 10x10 views of 624x576; scripts/demo.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

lf=out/demo/paper.lf; runs=5; size=1024
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    -*) echo "web_page.sh: unknown flag '$1'" >&2; exit 2 ;;
    *) lf=$1; shift ;;
  esac
done
[ -f "$lf" ] || { echo "web_page.sh: $lf: no such light field (run scripts/demo.sh)" >&2; exit 1; }
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target lfcam >/dev/null
lfcam=build/release/lfcam
work=$(mktemp -d)
server_pid=""
trap '[ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null; rm -rf "$work"' EXIT

$lfcam export "$lf" --format web --out "$work/page"
echo "download: $(du -cb "$work"/page/* | tail -1 | cut -f1) bytes ($(ls "$work/page" | tr '\n' ' '))"

chrome=(chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
        --no-first-run --disable-background-networking --disable-component-update --disable-sync
        --hide-scrollbars)

# The first picture, from a local server: the server notes when the page is asked for and when
# its beacon arrives.
cat > "$work/serve.py" <<'PY'
import http.server, sys, time
asked = {}
class Handler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args): pass
    def do_GET(self):
        if self.path.startswith('/index.html'):
            asked['t'] = time.time()
        if self.path.startswith('/first-picture'):
            print(f"{1000 * (time.time() - asked['t']):.0f}", flush=True)
            self.send_response(204); self.end_headers(); return
        super().do_GET()
http.server.ThreadingHTTPServer(('127.0.0.1', int(sys.argv[2])), lambda *a: Handler(*a, directory=sys.argv[1])).serve_forever()
PY
port=$((20000 + RANDOM % 20000))
python3 "$work/serve.py" "$work/page" "$port" > "$work/times.txt" &
server_pid=$!
sleep 0.5
for i in $(seq "$runs"); do
  rm -rf "$work/profile"
  timeout 20 "${chrome[@]}" --user-data-dir="$work/profile" --remote-debugging-port=0 \
    --window-size="$size,$size" \
    "http://127.0.0.1:$port/index.html?ui=0&size=${size}x${size}&beacon=/first-picture" \
    >/dev/null 2>&1 || true
done
echo "first picture from a local server (ms, $runs runs): $(sort -n "$work/times.txt" | tr '\n' ' ')"
echo "  median: $(sort -n "$work/times.txt" | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}') ms"

# The screenshots against the renderer, once the page says its first picture is drawn.
compare_view() {
  local name=$1 query=$2; shift 2
  node bench/page_screenshot.js "file://$work/page/index.html?ui=0&size=${size}x${size}&$query" \
    --size "${size}x${size}" --png "$work/$name.png"
  $lfcam render "$lf" --integrator cameras --size "$size" "$@" --out "$work/${name}_render.png" \
    --quiet >/dev/null
  echo "$name ($query): $($lfcam compare "$work/$name.png" "$work/${name}_render.png")"
}
compare_view pinhole "f=500&focus=4000&aperture=0" --focal-length 500 --focus-distance 4000
compare_view refocused "f=500&focus=3400&aperture=192" --focal-length 500 --focus-distance 3400 \
  --aperture 192
