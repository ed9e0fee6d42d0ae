#!/usr/bin/env bash
# make test-vm: the libcamera backend capturing through a real libcamera. A Debian 13 (trixie) root
# file system with its kernel is made with debootstrap in BUILD/vm/rootfs; irlocd is built inside
# it (chroot) against trixie's libcamera 0.4; the host's irloc-sim (BUILD/bin) renders a strobed dot
# drive that becomes JPEG frames for libcamera's virtual pipeline handler; the root file system becomes
# a disk image (mkfs.ext4 -d) that a qemu VM (KVM where /dev/kvm works, else TCG) boots with
# tools/vm/guest_test.sh as its init. The guest checks irlocd --camera libcamera against the same
# drive replayed with dir: and powers off; its console (BUILD/vm/console.log) carries the verdict.
# Cached between runs: the root file system (rebuilt when the package list changes), the build
# (incremental), the dataset (re-rendered when irloc-sim or the scenario changes).
# Usage: tools/test_vm.sh BUILD_DIR   (host packages: tools/deps.sh vm)
# IRLOC_VM_FRAMES (default 10000): frames captured; IRLOC_VM_DRIVE_FRAMES (default: the
# scenario's 199): frames rendered (fewer load faster: the virtual camera decodes every image).
set -euo pipefail
build=$(realpath -m "${1:?usage: $0 BUILD_DIR}")
root=$(cd "$(dirname "$0")/.." && pwd)
vm="$build/vm"
rootfs="$vm/rootfs"
mirror=${IRLOC_VM_MIRROR:-http://deb.debian.org/debian}
scenario=host_sim/scenarios/default_loop.yaml
started=$(date +%s)

step() { echo "test-vm: $(( $(date +%s) - started )) s: $*"; }
fail() { echo "test-vm: FAIL: $*" >&2; exit 1; }

# The guest's packages: libcamera 0.4 with its virtual pipeline handler, the project's build
# dependencies without the test-only ones (IRLOC_TESTS=OFF), the kernel with its initramfs and
# headers (tools/vm/irloc_vm_gpio.c, the LED line), kmod, cjpeg for the virtual camera's frames.
packages=(linux-image-amd64 linux-headers-amd64 initramfs-tools kmod libcamera0.4 libcamera-dev libjpeg-turbo-progs
          build-essential cmake ninja-build pkg-config libeigen3-dev libyaml-cpp-dev libcli11-dev
          nlohmann-json3-dev libgpiod-dev libcairo2-dev libcpp-httplib-dev libturbojpeg0-dev)

# Runs a command in ROOT with /proc and /dev mounted in a private mount namespace (gone with it).
in_root() {
  local dir=$1
  shift
  unshare --mount --pid --fork --propagation private sh -c \
    'mount -t proc proc "$0/proc" && mount --rbind /dev "$0/dev" && exec chroot "$0" "$@"' "$dir" \
    /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive "$@"
}

[ "$(id -u)" = 0 ] || fail "needs root (debootstrap, chroot, mkfs.ext4 -d of a root file system)"
mkdir -p "$vm"

# The host's irloc-sim (step 3) builds while the root file system is fetched and unpacked, which
# waits mostly on the network and the disk.
step "building irloc-sim on the host (in the background)"
nice -n 5 cmake --build "$build" --target irloc-sim > "$vm/host_build.log" 2>&1 &
host_build=$!

# 1. The root file system, cached while the package list is the same.
if [ "$(cat "$rootfs/.irloc-packages" 2>/dev/null)" != "${packages[*]}" ]; then
  step "debootstrap trixie into $rootfs (first run: several minutes)"
  rm -rf "$rootfs" "$vm/rootfs.partial"
  debootstrap --variant=minbase trixie "$vm/rootfs.partial" "$mirror" > "$vm/debootstrap.log" 2>&1 ||
    fail "debootstrap trixie from $mirror failed (log: $vm/debootstrap.log)"
  echo "deb $mirror trixie main" > "$vm/rootfs.partial/etc/apt/sources.list"
  # The initramfs mounts a virtio disk holding ext4 and needs nothing else (small and quick to make).
  mkdir -p "$vm/rootfs.partial/etc/initramfs-tools/conf.d"
  printf '%s\n' virtio_pci virtio_blk ext4 > "$vm/rootfs.partial/etc/initramfs-tools/modules"
  echo MODULES=list > "$vm/rootfs.partial/etc/initramfs-tools/conf.d/irloc-vm"
  in_root "$vm/rootfs.partial" apt-get -q update > "$vm/apt.log" 2>&1 ||
    fail "apt-get update in the root file system failed (log: $vm/apt.log)"
  in_root "$vm/rootfs.partial" apt-get -q install -y --no-install-recommends "${packages[@]}" >> "$vm/apt.log" 2>&1 ||
    fail "installing the guest's packages failed (log: $vm/apt.log)"
  in_root "$vm/rootfs.partial" apt-get clean
  echo "${packages[*]}" > "$vm/rootfs.partial/.irloc-packages"
  mv "$vm/rootfs.partial" "$rootfs"
fi
in_root "$rootfs" dpkg-query -W -f='test-vm: guest ${Package} ${Version}\n' libcamera0.4 linux-image-amd64

# 2. irlocd built inside it (sources copied with their times, so ninja rebuilds only what changed).
step "building irlocd in the root file system (libcamera 0.4)"
mkdir -p "$rootfs/irloc/src"
(cd "$root" && git ls-files -z --cached --others --exclude-standard | tar --null -T - -cf -) | tar -C "$rootfs/irloc/src" -xf -
in_root "$rootfs" sh -c 'cmake -S /irloc/src -B /irloc/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIRLOC_TESTS=OFF -DIRLOC_WERROR=ON > /dev/null &&
  nice -n 10 cmake --build /irloc/build --target irlocd -j2' > "$vm/build.log" 2>&1 ||
  fail "building irlocd in the root file system failed (log: $vm/build.log)"

# The LED line: a GPIO chip module built against the guest kernel.
kernel=$(ls "$rootfs"/boot/vmlinuz-* | sort -V | tail -n 1)
kernel_version=${kernel##*/vmlinuz-}
mkdir -p "$rootfs/irloc/gpio"
cp -p "$root/tools/vm/irloc_vm_gpio.c" "$rootfs/irloc/gpio/"
echo 'obj-m := irloc_vm_gpio.o' > "$rootfs/irloc/gpio/Kbuild"
in_root "$rootfs" make -C "/usr/src/linux-headers-$kernel_version" M=/irloc/gpio modules > "$vm/gpio_module.log" 2>&1 ||
  fail "building the GPIO chip module failed (log: $vm/gpio_module.log)"

# 3. The dataset: rendered by the host's irloc-sim, then the virtual camera's JPEG frames made in
# the guest's file system (tools/vm/prepare_frames.sh).
wait "$host_build" || fail "building irloc-sim failed (log: $vm/host_build.log)"
drive_frames=${IRLOC_VM_DRIVE_FRAMES:+--frames $IRLOC_VM_DRIVE_FRAMES}
stamp="$(sha256sum "$build/bin/irloc-sim" "$root/$scenario" "$root/tools/vm/prepare_frames.sh" | sha256sum) $drive_frames"
if [ "$(cat "$rootfs/irloc/drive/.stamp" 2>/dev/null)" != "$stamp" ]; then
  step "rendering $scenario and its JPEG frames"
  rm -rf "$rootfs/irloc/drive"
  mkdir -p "$rootfs/irloc/drive"
  { nice -n 5 "$build/bin/irloc-sim" render --scenario "$root/$scenario" $drive_frames --out "$rootfs/irloc/drive/dataset" &&
    in_root "$rootfs" sh /irloc/src/tools/vm/prepare_frames.sh /irloc/drive; } > "$vm/render.log" 2>&1 ||
    fail "rendering the drive failed (log: $vm/render.log)"
  echo "$stamp" > "$rootfs/irloc/drive/.stamp"
fi

# 4. The guest's test, its boot files and the disk image.
install -m 0755 "$root/tools/vm/guest_test.sh" "$rootfs/irloc/guest_test.sh"
rm -rf "$rootfs/irloc/results"
initrd="$rootfs/boot/initrd.img-$kernel_version"
[ -f "$initrd" ] || fail "no initramfs beside $kernel"
step "making the disk image"
rm -f "$vm/disk.img"
size_mib=$(( $(du -sm "$rootfs" | cut -f1) * 5 / 4 + 512 ))
mkfs.ext4 -q -F -L irloc-vm -d "$rootfs" "$vm/disk.img" "${size_mib}M" || fail "mkfs.ext4 -d $rootfs failed"

# 5. Boot: KVM where the host offers it, else TCG. Under nested virtualisation KVM may refuse the
# host CPU's model or fail to emulate an instruction of the guest kernel ("KVM internal error",
# then hanging): the boot is then done again with TCG.
boot() {  # boot ACCEL CPU
  rm -f "$vm/console.log"
  timeout 1800 qemu-system-x86_64 -accel "$1" -cpu "$2" -m 1536 -smp 2 -nodefaults -display none -no-reboot \
    -kernel "$kernel" -initrd "$initrd" \
    -append "root=/dev/vda rw console=ttyS0 panic=1 init=/irloc/guest_test.sh irloc_frames=${IRLOC_VM_FRAMES:-10000}" \
    -drive "file=$vm/disk.img,format=raw,if=virtio" \
    -serial "file:$vm/console.log" -serial null 2> "$vm/qemu.log" &
  local qemu=$!
  while kill -0 "$qemu" 2>/dev/null; do
    if grep -q 'KVM internal error' "$vm/qemu.log"; then
      kill "$qemu"
      wait "$qemu" 2>/dev/null
      return 1
    fi
    sleep 1
  done
  wait "$qemu"
}
status=1
if [ -w /dev/kvm ]; then
  step "booting the guest (KVM)"
  boot kvm host && status=0 || echo "test-vm: KVM failed ($(head -n 1 "$vm/qemu.log")): TCG instead"
fi
if [ "$status" != 0 ]; then
  step "booting the guest (TCG)"
  boot tcg max || fail "qemu failed or timed out (console: $vm/console.log, qemu: $vm/qemu.log)"
fi
grep '^irloc-vm:' "$vm/console.log" || true
step "done"
grep -qx 'irloc-vm: PASS' <(tr -d '\r' < "$vm/console.log") || fail "the guest's test did not pass (console: $vm/console.log)"
echo "test-vm: PASS ($(( $(date +%s) - started )) s)"
