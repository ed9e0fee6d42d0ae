#!/usr/bin/env bash
# The Debian package as `make deb` builds it on this machine: its Depends names exactly the
# packages that provide the libraries irlocd links (found here independently: the binary's NEEDED
# entries, resolved by the dynamic linker's cache, owned per dpkg -S), plus adduser; lintian finds
# no error; the contents are the ones docs/hardware.md lists.
# Usage: deb_package_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=${1:?usage: $0 SOURCE_DIR BUILD_DIR}
build=${2:?usage: $0 SOURCE_DIR BUILD_DIR}
work=$(mktemp -d "${TMPDIR:-/tmp}/irloc-deb.XXXXXX")
trap 'rm -rf "$work"' EXIT
failed=0
arch=$(dpkg --print-architecture)

"$source_dir/tools/make_deb.sh" "$build" "$arch" "$work" > "$work/make_deb.txt"
deb=$(ls "$work"/irlocd_*_"$arch".deb)

# Depends, one package name a line, without versions.
dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -E 's/^ *//; s/ *\(.*//; s/ *$//' | sort -u > "$work/depends.txt"
# The oracle: each NEEDED soname's file, as the dynamic linker finds it, and the package owning it
# (dpkg knows a file by the path its package ships, /lib or /usr/lib on a merged-/usr system).
owner() {
  local path=$1
  for candidate in "$path" "/usr$path" "${path#/usr}" "$(readlink -f "$path")"; do
    dpkg -S "$candidate" 2>/dev/null && return 0
  done
  echo "FAIL: no package owns $path" >&2
  return 1
}
objdump -p "$build/bin/irlocd" | awk '/NEEDED/ {print $2}' > "$work/needed.txt"
while read -r soname; do
  path=$(ldconfig -p | awk -v so="$soname" '$1 == so && /x86-64|AArch64/ && !found {print $NF; found = 1}')
  [ -n "$path" ] || { echo "FAIL: $soname: not in the linker cache"; exit 1; }
  owner "$path" || exit 1
done < "$work/needed.txt" | cut -d: -f1 | sort -u > "$work/linked.txt"
echo adduser >> "$work/linked.txt"
sort -u -o "$work/linked.txt" "$work/linked.txt"
if ! diff -u "$work/linked.txt" "$work/depends.txt" > "$work/diff.txt"; then
  echo "FAIL: Depends differs from the packages of the linked libraries (- linked, + Depends):"; cat "$work/diff.txt"
  failed=1
fi

if ! lintian --fail-on error --tag-display-limit 0 "$deb" > "$work/lintian.txt" 2>&1; then
  echo "FAIL: lintian reports errors:"; grep '^E:' "$work/lintian.txt" || cat "$work/lintian.txt"
  failed=1
fi

dpkg-deb -c "$deb" | awk '{print $NF}' > "$work/contents.txt"
for file in ./usr/bin/irlocd ./lib/systemd/system/irlocd.service ./etc/irloc/config.yaml ./etc/default/irlocd \
            ./usr/share/irloc/boards/rpi4-noir.yaml ./usr/share/doc/irlocd/copyright ./usr/share/doc/irlocd/changelog.gz; do
  grep -qxF "$file" "$work/contents.txt" || { echo "FAIL: $deb has no $file"; failed=1; }
done

if [ "$failed" = 0 ]; then
  echo "$(basename "$deb"): Depends = $(paste -sd' ' "$work/depends.txt"); lintian: $(grep -c '^[EW]:' "$work/lintian.txt" || true) warnings, 0 errors"
fi
exit "$failed"
