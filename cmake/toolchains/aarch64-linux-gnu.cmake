# Cross-building lfcam-node for the Raspberry Pis (Raspberry Pi OS bookworm = Debian 12 arm64)
# on a Debian 12 amd64 machine, with Debian's cross toolchain and multiarch :arm64 packages
# (scripts/package.sh --arm64; docs/packaging.md):
#   dpkg --add-architecture arm64 && apt-get update
#   apt-get install g++-aarch64-linux-gnu qemu-user-static libfmt-dev:arm64 libssl-dev:arm64 \
#     libjpeg62-turbo-dev:arm64 libcpp-httplib-dev:arm64
#   cmake -S . -B build/node-arm64 -G Ninja -DLFCAM_NODE_ONLY=ON \
#     -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# The arm64 libraries live beside the host's in the multiarch folders (/usr/lib/aarch64-linux-gnu,
# /usr/include/aarch64-linux-gnu); the architecture-independent headers (JSON, CLI11, Eigen) and
# CMake package files under /usr/share serve both. Programs found are the host's own.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
# pkg-config answers for arm64 only (cpp-httplib's .pc).
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")
# The built programs run here under user-mode emulation (the man page from `--help`, the tests).
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/bin/qemu-aarch64-static)
# dpkg-shlibdeps and CPack: the package is for arm64.
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
