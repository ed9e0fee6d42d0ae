#!/usr/bin/env bash
# Builds the irlocd Debian package from a finished build tree.
# Usage: tools/make_deb.sh BUILD_DIR ARCH   (ARCH: amd64, or arm64 for the cross build)
# Writes BUILD_DIR/irlocd_VERSION_ARCH.deb: /usr/bin/irlocd, the boards and lens calibrations
# under /usr/share/irloc/boards, a default config under /etc/irloc, /etc/default/irlocd and the
# systemd unit. The dependencies are Debian 12's runtime packages of the libraries irlocd links.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR ARCH}
arch=${2:?usage: $0 BUILD_DIR ARCH}
root=$(cd "$(dirname "$0")/.." && pwd)
version=$(sed -nE 's/^project\(irloc VERSION ([0-9.]+).*/\1/p' "$root/CMakeLists.txt")
binary="$build/bin/irlocd"
[ -x "$binary" ] || { echo "make_deb: $binary not built" >&2; exit 1; }
case "$arch" in
  amd64) strip=strip ;;
  arm64) strip=aarch64-linux-gnu-strip ;;
  *) echo "make_deb: unknown architecture $arch" >&2; exit 1 ;;
esac

stage="$build/deb/irlocd_${version}_${arch}"
rm -rf "$stage"
install -d "$stage/DEBIAN" "$stage/usr/bin" "$stage/usr/share/irloc/boards/lenses" "$stage/etc/irloc" \
  "$stage/etc/default" "$stage/lib/systemd/system" "$stage/usr/share/doc/irlocd"
install -m 755 "$binary" "$stage/usr/bin/irlocd"
"$strip" --strip-unneeded "$stage/usr/bin/irlocd"
install -m 644 "$root"/boards/*.yaml "$stage/usr/share/irloc/boards/"
install -m 644 "$root"/boards/lenses/*.yaml "$stage/usr/share/irloc/boards/lenses/"
install -m 644 "$root/tools/deb/config.yaml" "$root/tools/deb/map.yaml" "$stage/etc/irloc/"
install -m 644 "$root/tools/deb/default.irlocd" "$stage/etc/default/irlocd"
install -m 644 "$root/tools/deb/irlocd.service" "$stage/lib/systemd/system/irlocd.service"
install -m 644 "$root/docs/hardware.md" "$stage/usr/share/doc/irlocd/hardware.md"
install -m 755 "$root/tools/deb/postinst" "$root/tools/deb/prerm" "$stage/DEBIAN/"
printf '%s\n' /etc/irloc/config.yaml /etc/irloc/map.yaml /etc/default/irlocd > "$stage/DEBIAN/conffiles"
size=$(du -sk --exclude=DEBIAN "$stage" | cut -f1)
cat > "$stage/DEBIAN/control" <<CONTROL
Package: irlocd
Version: $version
Architecture: $arch
Maintainer: irloc project <irloc@localhost>
Installed-Size: $size
Depends: libc6 (>= 2.36), libstdc++6 (>= 12), libgcc-s1, libcamera0.0.3, libgpiod2 (>= 1.6), libyaml-cpp0.7, libcairo2, libcpp-httplib0.11, libturbojpeg0, adduser
Section: misc
Priority: optional
Description: robot pose from ceiling markers
 irlocd finds retro-reflective ceiling markers with an upward camera and a strobed
 ring of IR LEDs, computes the robot's pose and streams it over a serial port as
 MAVLink v2 VISION_POSITION_ESTIMATE or StarGazer-compatible ASCII.
CONTROL
(cd "$stage" && find . -type f ! -path './DEBIAN/*' -printf '%P\0' | xargs -0 md5sum > DEBIAN/md5sums)
out="$build/irlocd_${version}_${arch}.deb"
dpkg-deb --root-owner-group --build "$stage" "$out" >/dev/null
echo "make_deb: $out"
