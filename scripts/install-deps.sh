#!/usr/bin/env bash
# Installs lfcam's build and test dependencies from Debian 12's packages (nothing else).
# Used by scripts/demo.sh and scripts/test.sh; safe to run again.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libtbb-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libzstd-dev libxxhash-dev zlib1g-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-calib3d-dev
  libopencv-video-dev
  # ChArUco boards (the aruco module); Debian's package also brings VTK and Open MPI along.
  libopencv-contrib-dev
  libceres-dev libjpeg62-turbo-dev libpng-dev
  # The vectorised CPU renderer (Google Highway: portable SIMD, dispatched at run time).
  libhwy-dev
  # The GL renderer: OpenGL 4.3+ compute through EGL, headless (libepoxy loads the entry points);
  # Mesa's llvmpipe runs it where there is no GPU (CI).
  libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri
  # The viewer: a GLFW window with Dear ImGui (its GLFW and OpenGL backends' sources come with
  # libimgui-dev); Xvfb gives it a screen in the tests.
  libglfw3-dev libimgui-dev xvfb xauth
  # The capture system: the node agent's HTTP API (cpp-httplib) and its signatures (OpenSSL).
  libcpp-httplib-dev libssl-dev
  # Video files (`render --video`, quilt videos): H.264 in MP4 through FFmpeg's libraries.
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libgtest-dev libgmock-dev
  # bench/hci_score.py (the depth benchmark's metrics) and bench/heldout_regions.py (OpenCV's
  # Python module reads the images), run by tests; and `import lfcam` (the Python module:
  # pybind11 over Debian's python3, its tests under pytest).
  python3-numpy python3-opencv python3-dev pybind11-dev python3-pytest
  # The web page `export --format web` writes: its logic's unit tests (node's test runner) and
  # the page itself rendered in headless Chromium.
  nodejs chromium
  # The rollout to the array's nodes (deploy/ansible): its inventory and playbook are checked.
  ansible-core
)
# bench/peer.sh: the NumPy + OpenCV peer renderer.
if [ "${LFCAM_PEER_DEPS:-0}" = 1 ]; then
  packages+=(python3-numpy python3-opencv)
fi
# scripts/package.sh: the Debian packages' tools (man pages from the help, lintian).
if [ "${LFCAM_PACKAGING_DEPS:-0}" = 1 ]; then
  packages+=(help2man lintian dpkg-dev fakeroot file)
fi
# scripts/package.sh: the Pis' lfcam-node cross-built for arm64 (Debian's cross toolchain and
# multiarch :arm64 libraries) and run here under user-mode emulation.
if [ "${LFCAM_ARM64_DEPS:-0}" = 1 ]; then
  packages+=(g++-aarch64-linux-gnu qemu-user-static
             libfmt-dev:arm64 libssl-dev:arm64 libjpeg62-turbo-dev:arm64 libcpp-httplib-dev:arm64)
fi
# scripts/fuzz.sh and the asan preset (scripts/test.sh --preset asan): clang, its sanitizer and
# libFuzzer runtimes, and LLVM's linker (a fifth of the default linker's time on those trees).
if [ "${LFCAM_FUZZ_DEPS:-0}" = 1 ] || [ "${LFCAM_CLANG_DEPS:-0}" = 1 ]; then
  packages+=(clang-14 libclang-rt-14-dev lld-14)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if [[ " ${missing[*]}" == *":arm64"* ]] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
  "${sudo_cmd[@]}" dpkg --add-architecture arm64
fi
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
