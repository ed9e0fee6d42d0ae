#!/usr/bin/env bash
# Builds the irlocd Debian package from a finished build tree, on the machine that will run it
# (`make deb` on a Raspberry Pi) or for arm64 after `make cross`.
# Usage: tools/make_deb.sh BUILD_DIR ARCH [OUT_DIR]   (ARCH: the build's, amd64 or arm64)
# Writes OUT_DIR (default BUILD_DIR)/irlocd_VERSION_ARCH.deb: /usr/bin/irlocd, the boards and lens
# calibrations under /usr/share/irloc/boards, a default config under /etc/irloc,
# /etc/default/irlocd and the systemd unit. Depends is computed by dpkg-shlibdeps from the
# libraries the binary links, as this system's packages provide them (libcamera0.0.3 on Debian 12,
# libcamera0.3 or newer on Raspberry Pi OS), plus adduser for the maintainer scripts.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR ARCH [OUT_DIR]}
arch=${2:?usage: $0 BUILD_DIR ARCH [OUT_DIR]}
[ -d "$build" ] || { echo "make_deb: $build: no such build folder" >&2; exit 1; }
build=$(cd "$build" && pwd)
out_dir=${3:-$build}
root=$(cd "$(dirname "$0")/.." && pwd)
version=$(sed -nE 's/^project\(irloc VERSION ([0-9.]+).*/\1/p' "$root/CMakeLists.txt")
binary="$build/bin/irlocd"
[ -x "$binary" ] || { echo "make_deb: $binary not built" >&2; exit 1; }
native_arch=$(dpkg --print-architecture)
case "$arch" in
  "$native_arch") strip=strip ;;
  arm64) strip=aarch64-linux-gnu-strip ;;
  *) echo "make_deb: cannot package $arch on $native_arch (expected $native_arch, or arm64 after make cross)" >&2; exit 1 ;;
esac

stage="$build/deb/irlocd_${version}_${arch}"
rm -rf "$stage"
install -d "$stage/DEBIAN" "$stage/usr/bin" "$stage/usr/share/irloc/boards/lenses" "$stage/etc/irloc" \
  "$stage/etc/default" "$stage/lib/systemd/system" "$stage/usr/share/doc/irlocd"
install -m 755 "$binary" "$stage/usr/bin/irlocd"
"$strip" --strip-unneeded --remove-section=.comment --remove-section=.note "$stage/usr/bin/irlocd"
install -m 644 "$root"/boards/*.yaml "$stage/usr/share/irloc/boards/"
install -m 644 "$root"/boards/lenses/*.yaml "$stage/usr/share/irloc/boards/lenses/"
install -m 644 "$root/tools/deb/config.yaml" "$root/tools/deb/map.yaml" "$stage/etc/irloc/"
install -m 644 "$root/tools/deb/default.irlocd" "$stage/etc/default/irlocd"
install -m 644 "$root/tools/deb/irlocd.service" "$stage/lib/systemd/system/irlocd.service"
install -m 644 "$root/docs/hardware.md" "$stage/usr/share/doc/irlocd/hardware.md"
install -m 644 "$root/tools/deb/copyright" "$stage/usr/share/doc/irlocd/copyright"
gzip -9n < "$root/tools/deb/changelog" > "$stage/usr/share/doc/irlocd/changelog.gz"
chmod 644 "$stage/usr/share/doc/irlocd/changelog.gz"
install -m 755 "$root/tools/deb/postinst" "$root/tools/deb/prerm" "$stage/DEBIAN/"
printf '%s\n' /etc/irloc/config.yaml /etc/irloc/map.yaml /etc/default/irlocd > "$stage/DEBIAN/conffiles"

# dpkg-shlibdeps reads a debian/control; a minimal one beside the staged tree is enough. For
# arm64 it looks the libraries up in the arm64 multiarch packages (tools/deps.sh cross).
shlibs="$build/deb/shlibdeps"
rm -rf "$shlibs"
install -d "$shlibs/debian"
printf 'Source: irlocd\n\nPackage: irlocd\nArchitecture: any\n' > "$shlibs/debian/control"
if ! shlibs_output=$(cd "$shlibs" && dpkg-architecture -a"$arch" -c dpkg-shlibdeps -O -e"$stage/usr/bin/irlocd" 2>"$shlibs/errors.txt"); then
  echo "make_deb: dpkg-shlibdeps failed on $binary:" >&2
  cat "$shlibs/errors.txt" >&2
  exit 1
fi
shlib_depends=$(sed -n 's/^shlibs:Depends=//p' <<< "$shlibs_output")
[ -n "$shlib_depends" ] || { echo "make_deb: dpkg-shlibdeps found no dependencies of $binary" >&2; exit 1; }

size=$(du -sk --exclude=DEBIAN "$stage" | cut -f1)
cat > "$stage/DEBIAN/control" <<CONTROL
Package: irlocd
Version: $version
Architecture: $arch
Maintainer: irloc project <irloc@example.org>
Installed-Size: $size
Depends: $shlib_depends, adduser
Section: misc
Priority: optional
Description: robot pose from ceiling markers
 irlocd finds retro-reflective ceiling markers with an upward camera and a
 strobed ring of IR LEDs, computes the robot's pose and streams it over a
 serial port as MAVLink v2 VISION_POSITION_ESTIMATE or StarGazer-compatible
 ASCII.
CONTROL
(cd "$stage" && find . -type f ! -path './DEBIAN/*' -printf '%P\0' | sort -z | xargs -0 md5sum > DEBIAN/md5sums)
chmod 644 "$stage/DEBIAN/md5sums" "$stage/DEBIAN/control" "$stage/DEBIAN/conffiles"
mkdir -p "$out_dir"
out="$out_dir/irlocd_${version}_${arch}.deb"
dpkg-deb --root-owner-group -Zxz --build "$stage" "$out" >/dev/null
echo "make_deb: $out (Depends: $shlib_depends, adduser)"
