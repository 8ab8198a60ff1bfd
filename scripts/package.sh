#!/usr/bin/env bash
# Builds lfcam's Debian packages with CMake's CPack (docs/packaging.md): `lfcam` from the release
# build (and `python3-lfcam`, the Python module) and `lfcam-node` from a node-only build, for this machine and cross-built for the Pis
# (arm64, cmake/toolchains/aarch64-linux-gnu.cmake), into out/packages/; runs the arm64 agent under
# emulation as real nodes driven by this machine's `lfcam capture` (EmulatedArm64Node.*); and
# checks the packages with lintian (every warning fails, but those packaging/lintian-overrides
# explains).
# --install: then installs both with apt on this machine (as root: CI) and tries them.
# Usage: scripts/package.sh [--install]
set -euo pipefail
cd "$(dirname "$0")/.."

install=0
case "${1:-}" in
  --install) install=1 ;;
  "") ;;
  -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
  *) echo "package.sh: unknown argument '$1' (try --install)" >&2; exit 2 ;;
esac

LFCAM_PACKAGING_DEPS=1 LFCAM_ARM64_DEPS=1 scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target lfcam man-pages lfcam-changelog
rm -rf build/release/packages
(cd build/release && cpack -G DEB >/dev/null)
cmake -S . -B build/node -G Ninja -DLFCAM_NODE_ONLY=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/node --target lfcam-node man-pages lfcam-node-changelog
rm -rf build/node/packages
(cd build/node && cpack -G DEB >/dev/null)
cmake -S . -B build/node-arm64 -G Ninja -DLFCAM_NODE_ONLY=ON -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake --no-warn-unused-cli >/dev/null
cmake --build build/node-arm64 --target lfcam-node man-pages lfcam-node-changelog
rm -rf build/node-arm64/packages
(cd build/node-arm64 && cpack -G DEB >/dev/null)
echo "== the Pis' agent (arm64) under emulation, driven by this machine's lfcam capture"
cmake --build --preset release --target lfcam_tests
LFCAM_ARM64_NODE="$PWD/build/node-arm64/lfcam-node" LFCAM_REQUIRE_ARM64=1 \
  ctest --preset release -R '^EmulatedArm64Node$' --output-on-failure
rm -rf out/packages
mkdir -p out/packages
cp build/release/packages/*.deb build/node/packages/*.deb build/node-arm64/packages/*.deb \
  out/packages/
for deb in out/packages/*.deb; do
  echo "== $deb: $(dpkg-deb -f "$deb" Package) $(dpkg-deb -f "$deb" Version) $(dpkg-deb -f "$deb" Architecture), $(du -k "$deb" | cut -f1) KB"
  echo "   Depends: $(dpkg-deb -f "$deb" Depends)"
done
echo "== lintian"
lintian --fail-on error,warning --profile debian out/packages/*.deb
echo "lintian: clean (docs/packaging.md lists what it still says at info level)"

if [ $install -eq 1 ]; then
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "package.sh --install: needs root or sudo" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  arch=$(dpkg --print-architecture)
  echo "== installing with apt"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get install -y -qq ./out/packages/lfcam_*_"$arch".deb \
    ./out/packages/lfcam-node_*_"$arch".deb ./out/packages/python3-lfcam_*_"$arch".deb 2>&1 |
    grep -v '^debconf: ' || true
  dpkg -s lfcam lfcam-node >/dev/null
  [ "$(command -v lfcam)" = /usr/bin/lfcam ] || { echo "lfcam is not /usr/bin/lfcam" >&2; exit 1; }
  lfcam --version
  lfcam-node --version
  echo "== import lfcam, from the package (not the build tree), rendering what lfcam renders"
  try=$(mktemp -d)
  lfcam simulate lightfield --out "$try/small.lf" --grid 3x3 --st-res 64x56 --quiet >/dev/null
  lfcam render "$try/small.lf" --size 48 --aperture 20 --out "$try/cli.png" --quiet >/dev/null
  (cd "$try" && env -u PYTHONPATH /usr/bin/python3 -c "
import lfcam, numpy
assert lfcam.__file__.startswith('/usr/lib/python3/dist-packages/'), lfcam.__file__
image = lfcam.render(lfcam.open('small.lf'), size=48, aperture=20)
print('python3-lfcam', lfcam.__version__, 'rendered', image.shape, 'from', lfcam.__file__)")
  rm -rf "$try"
  for page in lfcam lfcam-node; do
    [ -s "/usr/share/man/man1/$page.1.gz" ] || { echo "no man page for $page" >&2; exit 1; }
  done
  if command -v systemd-analyze >/dev/null; then
    systemd-analyze verify /usr/lib/systemd/system/lfcam-node.service
  fi
  getent passwd lfcam >/dev/null || { echo "lfcam-node: no lfcam user" >&2; exit 1; }
  "${sudo_cmd[@]}" test -d /var/lib/lfcam-node/captures ||
    { echo "lfcam-node: no capture folder" >&2; exit 1; }
  [ ! -e /etc/lfcam/array.key ] && echo "lfcam-node: installed without a key, as expected: stopped"
  echo "== the rollout playbook for real on this machine (a local connection), twice"
  play=$(mktemp -d)
  lfcam capture keygen --out "$play/array.key" >/dev/null
  lfcam capture init --out "$play/array.json" --grid 1x1 --addresses 127.0.0.1:8470 >/dev/null
  lfcam capture inventory "$play/array.json" --package out/packages/lfcam-node_*_"$arch".deb \
    --out "$play/inventory.yml"
  for run in first second; do
    "${sudo_cmd[@]}" env ANSIBLE_HOME="$play" ANSIBLE_LOCAL_TEMP="$play" \
      ansible-playbook -i "$play/inventory.yml" -c local deploy/ansible/lfcam-node.yml \
      > "$play/$run.log" 2>&1 || { cat "$play/$run.log"; exit 1; }
    grep -E "^node-r00-c00 " "$play/$run.log" | sed "s/^/   $run run: /"
  done
  grep -qE "^node-r00-c00 +: ok=[0-9]+ +changed=0 +unreachable=0 +failed=0" "$play/second.log" ||
    { echo "the playbook's second run changed something (not idempotent)" >&2; exit 1; }
  "${sudo_cmd[@]}" test -f /etc/lfcam/array.key || { echo "the playbook left no key" >&2; exit 1; }
  [ "$("${sudo_cmd[@]}" stat -c '%U %a' /etc/lfcam/array.key)" = "lfcam 600" ] ||
    { echo "the key is not the lfcam user's, mode 600" >&2; exit 1; }
  rm -rf "$play"
  echo "== removing (captures stay) and purging (they go)"
  "${sudo_cmd[@]}" touch /var/lib/lfcam-node/captures/keep-me
  "${sudo_cmd[@]}" apt-get remove -y -qq lfcam-node >/dev/null
  "${sudo_cmd[@]}" test -e /var/lib/lfcam-node/captures/keep-me ||
    { echo "remove lost the captures" >&2; exit 1; }
  "${sudo_cmd[@]}" apt-get purge -y -qq lfcam-node >/dev/null
  [ ! -e /var/lib/lfcam-node ] || { echo "purge left the captures" >&2; exit 1; }
  "${sudo_cmd[@]}" apt-get purge -y -qq python3-lfcam lfcam >/dev/null
  echo "package.sh: installed, ran, removed and purged cleanly"
fi
