#!/usr/bin/env bash
# Checks the Debian 12 packages a build needs and installs the missing ones.
# Usage: tools/deps.sh native|cross|fuzz|vm
#   native: host build, tests (OpenCV and AprilTag are test/bench-only oracles; systemd for
#           systemd-analyze, which checks the service unit; lintian checks the Debian package;
#           chromium, headless, loads irlocd's live view in its test; universal-ctags for
#           tools/code_size.sh) and benchmarks.
#   fuzz:   clang and libFuzzer, for make fuzz only.
#   cross:  aarch64 cross compiler, qemu and the arm64 multiarch -dev packages. libyaml-cpp-dev
#           is not multi-arch: the cross build uses its headers with the arm64 runtime library.
#   vm:     make test-vm's host tools: debootstrap (the Debian 13 guest), qemu (KVM or TCG),
#           e2fsprogs (mkfs.ext4 -d); the guest's own packages come from Debian 13 (tools/test_vm.sh).
# As root it runs apt-get; otherwise it prints the exact command and fails.
set -euo pipefail

native_packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libcamera-dev libgpiod-dev
  libgtest-dev libgmock-dev libbenchmark-dev valgrind
  libopencv-dev libapriltag-dev
  libcairo2-dev libcpp-httplib-dev libturbojpeg0-dev
  chromium
  nodejs
  systemd
  lintian
  universal-ctags
)
# node-mavlink, the independent MAVLink decoder of the tests, installs with npm; a Node.js
# package that bundles npm provides it, Debian's nodejs needs the separate npm package.
command -v npm >/dev/null || native_packages+=(npm)
# make fuzz: clang with libFuzzer and its sanitizer runtimes (not needed by make test).
fuzz_packages=(clang libclang-rt-14-dev)
vm_packages=(debootstrap qemu-system-x86 e2fsprogs git gcc libusbredirparser-dev)
cross_packages=(
  g++-aarch64-linux-gnu qemu-user
  libyaml-cpp0.7:arm64 libcamera-dev:arm64 libgpiod-dev:arm64
  libgtest-dev:arm64 libgmock-dev:arm64 libbenchmark-dev:arm64 libcairo2-dev:arm64
  libcpp-httplib-dev:arm64 libturbojpeg0-dev:arm64
)

case "${1:-}" in
  native) wanted=("${native_packages[@]}") ;;
  cross) wanted=("${native_packages[@]}" "${cross_packages[@]}") ;;
  fuzz) wanted=("${fuzz_packages[@]}") ;;
  vm) wanted=("${vm_packages[@]}") ;;
  *) echo "usage: $0 native|cross|fuzz|vm" >&2; exit 2 ;;
esac

native_arch=$(dpkg --print-architecture)

# A package given as NAME is wanted for this machine's architecture (or "all"); NAME:ARCH for ARCH.
is_installed() {
  local name=${1%%:*} arch=$native_arch
  case "$1" in *:*) arch=${1#*:} ;; esac
  dpkg-query -W -f='${Status} ${Architecture}\n' "$name" 2>/dev/null |
    grep -qE "^install ok installed ($arch|all)\$"
}

missing=()
for package in "${wanted[@]}"; do
  is_installed "$package" || missing+=("$package")
done
[ ${#missing[@]} -eq 0 ] && exit 0

needs_arm64=0
for package in "${missing[@]}"; do
  case "$package" in *:arm64) needs_arm64=1 ;; esac
done

commands=()
if [ "$needs_arm64" = 1 ] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
  commands+=("dpkg --add-architecture arm64")
fi
commands+=("apt-get update" "DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}")

if [ "$(id -u)" != 0 ]; then
  echo "irloc: missing Debian packages: ${missing[*]}" >&2
  echo "irloc: run as root:" >&2
  for command in "${commands[@]}"; do echo "  sudo $command" >&2; done
  exit 1
fi

echo "irloc: installing missing Debian packages: ${missing[*]}" >&2
for command in "${commands[@]}"; do
  echo "+ $command" >&2
  eval "$command" >&2
done
