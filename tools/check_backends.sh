#!/usr/bin/env bash
# Compile check of the libcamera and libgpiod backends and of the live view's HTTP server against
# newer libraries than Debian 12's: the libcamera-dev and libgpiod-dev of bookworm-backports
# (libcamera 0.3, libgpiod 2.1; it has no newer cpp-httplib) and those and libcpp-httplib-dev of
# Debian 13 (trixie: libcamera 0.4, libgpiod 2.2, cpp-httplib 0.18), each downloaded with apt-get into a build-local apt state and unpacked into a
# build-local prefix (nothing is installed on the system). Each backend is compiled with the
# project's warning flags, -Werror, against each suite's headers. A mirror it cannot reach is not a
# failure of the backends: it says so and exits 77 (ctest's skip) before compiling anything.
# Usage: tools/check_backends.sh BUILD_DIR [SUITE...]   (make check-backends: both suites; ctest
# check_backends: bookworm-backports)
set -euo pipefail
build=$(realpath -m "${1:?usage: $0 BUILD_DIR [SUITE...]}")
shift
suites=("$@")
[ ${#suites[@]} -gt 0 ] || suites=(bookworm-backports trixie)
root=$(cd "$(dirname "$0")/.." && pwd)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
flags=(-std=c++20 -O2 -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Wmissing-declarations -Werror
       -I"$root" -I/usr/include/eigen3)

# Unpacks SUITE's development packages into $build/backends/SUITE/prefix and compiles what uses them.
check_suite() {
  local suite=$1
  local work="$build/backends/$suite"
  local prefix="$work/prefix"
  mkdir -p "$work/apt/lists/partial" "$work/apt/cache/archives/partial" "$work/debs"
  echo "deb http://deb.debian.org/debian $suite main" > "$work/apt/sources.list"
  local apt_options=(-o "Dir::Etc::SourceList=$work/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
                     -o "Dir::State::Lists=$work/apt/lists" -o "Dir::Cache=$work/apt/cache" -o APT::Sandbox::User=root)
  apt_options+=(-o Acquire::Retries=2 -o Acquire::http::Timeout=30)
  local packages=(libcamera-dev libgpiod-dev)
  [ "$suite" = bookworm-backports ] || packages+=(libcpp-httplib-dev)
  rm -rf "$prefix" "$work"/debs/*.deb
  if ! apt-get -qq "${apt_options[@]}" update ||
     ! (cd "$work/debs" && apt-get -qq "${apt_options[@]}" download "${packages[@]/%//$suite}"); then
    echo "check-backends: deb.debian.org ($suite) cannot be reached: nothing checked" >&2
    exit 77
  fi
  for deb in "$work"/debs/*.deb; do dpkg-deb -x "$deb" "$prefix"; done
  (
    # The suite's own .pc files first; what they require (openssl for cpp-httplib) from the system's.
    export PKG_CONFIG_SYSROOT_DIR="$prefix"
    export PKG_CONFIG_LIBDIR="$prefix/usr/lib/$multiarch/pkgconfig:$prefix/usr/share/pkgconfig:/usr/lib/$multiarch/pkgconfig:/usr/share/pkgconfig"
    check "$suite" "$work" libcamera hal/linux/libcamera_camera.cpp
    check "$suite" "$work" libgpiod hal/linux/gpiod_strobe.cpp -DIRLOC_GPIOD_V2
    [ ! -f "$prefix/usr/include/httplib.h" ] || check "$suite" "$work" cpp-httplib firmware/live/live_server.cpp
  )
}

check() {
  local suite=$1 work=$2 library=$3 source=$4
  shift 4
  local version
  version=$(pkg-config --modversion "$library")
  c++ "${flags[@]}" "$@" $(pkg-config --cflags "$library") -c "$root/$source" -o "$work/$(basename "$source" .cpp).o"
  echo "check-backends: $source compiles against $library $version ($suite)"
}

for suite in "${suites[@]}"; do check_suite "$suite"; done
