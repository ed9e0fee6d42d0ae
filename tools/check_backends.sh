#!/usr/bin/env bash
# Compile check of the libcamera and libgpiod backends against newer libraries than Debian 12's:
# bookworm-backports' libcamera-dev (0.3) and libgpiod-dev (2.1), downloaded with apt-get into a
# build-local apt state and unpacked into a build-local prefix (nothing is installed on the
# system). Each backend is compiled with the project's warning flags, -Werror.
# Usage: tools/check_backends.sh BUILD_DIR      (make check-backends)
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
work="$build/backends"
prefix="$work/prefix"
suite=bookworm-backports
mkdir -p "$work/apt/lists/partial" "$work/apt/cache/archives/partial" "$work/debs"
echo "deb http://deb.debian.org/debian $suite main" > "$work/apt/sources.list"
apt_options=(-o "Dir::Etc::SourceList=$work/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
             -o "Dir::State::Lists=$work/apt/lists" -o "Dir::Cache=$work/apt/cache" -o APT::Sandbox::User=root)
apt-get -qq "${apt_options[@]}" update
rm -rf "$prefix" "$work"/debs/*.deb
(cd "$work/debs" && apt-get -qq "${apt_options[@]}" download libcamera-dev libgpiod-dev)
for deb in "$work"/debs/*.deb; do dpkg-deb -x "$deb" "$prefix"; done

multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
export PKG_CONFIG_SYSROOT_DIR="$prefix" PKG_CONFIG_LIBDIR="$prefix/usr/lib/$multiarch/pkgconfig"
flags=(-std=c++20 -O2 -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Wmissing-declarations -Werror
       -I"$root" -I/usr/include/eigen3)

check() {
  local library=$1 source=$2
  shift 2
  local version
  version=$(pkg-config --modversion "$library")
  c++ "${flags[@]}" "$@" $(pkg-config --cflags "$library") -c "$root/$source" -o "$work/$(basename "$source" .cpp).o"
  echo "check-backends: $source compiles against $library $version ($suite)"
}
check libcamera hal/linux/libcamera_camera.cpp
check libgpiod hal/linux/gpiod_strobe.cpp -DIRLOC_GPIOD_V2
