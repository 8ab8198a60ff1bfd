#!/usr/bin/env bash
# Makes what a lent GPU machine (the `device` tool; docs/benchmarks.md, "Measuring on a lent
# GPU") needs to run lfcam there: .device/bundle.tar.xz (the release build's `lfcam` and
# `lfcam_tests`, stripped, with every shared library they load except glibc's and GL's; GDAL
# and GDCM replaced by stand-ins, which leaves out what they load too) and .device/gl/ (the
# GL vendor-neutral loaders as Debian packages, unpacked there over the driver's).
# Run from the repository root after `cmake --build --preset release`; carry `.device`.
set -euo pipefail
cd "$(dirname "$0")/../.."
for binary in lfcam lfcam_tests; do
  [ -x "build/release/$binary" ] ||
    { echo "bundle: build/release/$binary is missing (cmake --build --preset release)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/stand_ins" "$work/bundle/bin" "$work/bundle/lib" .device/gl
libs=/usr/lib/x86_64-linux-gnu
for name in libgdal.so.32 libgdcmMSFF.so.3.0 libgdcmDICT.so.3.0 libgdcmDSED.so.3.0; do
  [ -e "$libs/$name" ] || continue
  bench/device/stand_in.sh "$libs/$name" "$work/stand_ins" "$libs"/libopencv_*.so.4* "$libs"/libgdcm*.so.*
done
for binary in lfcam lfcam_tests; do
  cp "build/release/$binary" "$work/bundle/bin/"
  strip "$work/bundle/bin/$binary"
done
LD_LIBRARY_PATH="$work/stand_ins" ldd build/release/lfcam build/release/lfcam_tests |
  awk '/=> \//{print $3}' | sort -u | while read -r library; do
    case "$(basename "$library")" in
      libc.so* | libm.so* | libpthread* | libdl.so* | librt.so* | ld-linux* | libGL* | libEGL* | \
        libOpenGL* | libgbm* | libdrm* | libvulkan*) ;;  # libGL*: libGLX and libGLdispatch too
      *) cp -L "$library" "$work/bundle/lib/" ;;
    esac
  done
strip --strip-unneeded "$work/bundle/lib/"* 2>/dev/null || true
cp "$work/stand_ins/"* "$work/bundle/lib/" 2>/dev/null || true
# The bundle runs here too, as a check that nothing it needs was left out.
LD_LIBRARY_PATH="$work/bundle/lib" "$work/bundle/bin/lfcam_tests" --gtest_list_tests >/dev/null ||
  { echo "bundle: lfcam_tests does not start from the bundle" >&2; exit 1; }
tar -C "$work/bundle" -cf - . | xz -T0 -6 >.device/bundle.tar.xz
options=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists="$work/lists")
mkdir -p "$work/lists/partial"
apt-get "${options[@]}" update >/dev/null 2>&1
(cd .device/gl && apt-get "${options[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 \
  libglx0 libgles2 >/dev/null 2>&1)
echo "bundle: .device/bundle.tar.xz ($(du -h .device/bundle.tar.xz | cut -f1)), $(find .device/gl -name '*.deb' | wc -l) GL packages"
