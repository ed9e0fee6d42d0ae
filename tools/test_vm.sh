#!/usr/bin/env bash
# make test-vm: the libcamera backend capturing through a real libcamera. A Debian 13 (trixie) root
# file system with its kernel is made with debootstrap in BUILD/vm/rootfs; irlocd is built inside
# it (chroot) against trixie's libcamera 0.4, with the irloc-sim that renders a strobed dot drive
# there (one build of the libraries both link), which becomes JPEG frames for libcamera's virtual
# pipeline handler. A qemu VM (KVM where /dev/kvm works, else TCG) boots two disks: the root file
# system's image (made once per package list, never written: qemu's snapshot=on) and a small test
# disk (irlocd, the LED-line module, the drive, tools/vm/guest_test.sh) mounted at /irloc by
# tools/vm/guest_init.sh, the VM's init. The
# guest checks irlocd --camera libcamera against the same drive replayed with dir:, then captures
# from a UVC webcam emulated on the host (tools/vm/uvc_camera.c, plugged in by qemu's usb-redir
# on an xHCI controller), and powers off; its console (BUILD/vm/console.log) carries the verdict,
# and the UVC camera's log the controls the guest set (checked here).
# Cached between runs: the root file system and its image (remade when the package list or the
# init changes), the build (BUILD/vm/guest/build, incremental), the LED-line module and the UVC
# camera (rebuilt when their source changes), the drive (re-rendered when irloc-sim, the scenario
# or prepare_frames.sh changes). Every step prints its start time in seconds since the run's start.
# Usage: tools/test_vm.sh BUILD_DIR   (host packages: tools/deps.sh vm)
# IRLOC_VM_FRAMES (default 10000): frames captured; IRLOC_VM_DRIVE_FRAMES (default: the
# scenario's 199): frames rendered (fewer load faster: the virtual camera decodes every image).
set -euo pipefail
build=$(realpath -m "${1:?usage: $0 BUILD_DIR}")
root=$(cd "$(dirname "$0")/.." && pwd)
vm="$build/vm"
rootfs="$vm/rootfs"
# The guest's own tree, /irloc inside the chroot (a bind mount): sources, build, module, drive.
guest="$vm/guest"
mirror=${IRLOC_VM_MIRROR:-http://deb.debian.org/debian}
scenario=host_sim/scenarios/default_loop.yaml
started=$(date +%s)

step() { echo "test-vm: $(( $(date +%s) - started )) s: $*"; }
fail() { echo "test-vm: FAIL: $*" >&2; exit 1; }

# The guest's packages, in two sets installed one after the other: what building irlocd and the
# drive's frames needs (libcamera 0.4 with its virtual pipeline handler, the project's build
# dependencies without the test-only ones (IRLOC_TESTS=OFF), cjpeg), and the kernel with its
# initramfs and headers (tools/vm/irloc_vm_gpio.c, the LED line) and kmod, installed while irlocd
# builds.
build_packages=(libcamera0.4 libcamera-dev libjpeg-turbo-progs
                build-essential cmake ninja-build pkg-config libeigen3-dev libyaml-cpp-dev libcli11-dev
                nlohmann-json3-dev libgpiod-dev libcairo2-dev libcpp-httplib-dev libturbojpeg0-dev)
kernel_packages=(linux-image-amd64 linux-headers-amd64 initramfs-tools kmod)
packages="${build_packages[*]} ${kernel_packages[*]}"

# Runs a command in the root file system, /proc and /dev mounted, the guest's tree at /irloc and
# /tmp a tmpfs (the compiler's files stay out of the root file system's image), in a private
# mount namespace (gone with it).
chroot_dir=$rootfs
in_root() {
  local dir=$chroot_dir
  mkdir -p "$dir/irloc"
  unshare --mount --pid --fork --propagation private sh -c \
    'mount -t proc proc "$0/proc" && mount --rbind /dev "$0/dev" && mount --bind "$1" "$0/irloc" && mount -t tmpfs tmpfs "$0/tmp" && shift && exec chroot "$0" "$@"' \
    "$dir" "$guest" \
    /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive "$@"
}
apt_install() {  # apt_install PACKAGE...: into the root file system being made
  in_root apt-get -q install -y --no-install-recommends "$@" >> "$vm/apt.log" 2>&1 ||
    fail "installing the guest's packages failed (log: $vm/apt.log)"
}

[ "$(id -u)" = 0 ] || fail "needs root (debootstrap, chroot, mkfs.ext4 -d of a root file system)"
mkdir -p "$vm" "$guest"

# irlocd and irloc-sim, built inside the root file system (sources copied with their times, so
# ninja rebuilds only what changed); in the background, beside the kernel's packages on a first run.
build_programs() {
  mkdir -p "$guest/src"
  (cd "$root" && git ls-files -z --cached --others --exclude-standard | tar --null -T - -cf -) | tar -C "$guest/src" -xf -
  in_root sh -c 'cmake -S /irloc/src -B /irloc/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIRLOC_TESTS=OFF -DIRLOC_WERROR=ON > /dev/null &&
    nice -n 10 cmake --build /irloc/build --target irlocd irloc-sim -j2' > "$vm/build.log" 2>&1
}

# 1. The root file system, cached while the package list is the same.
if [ "$(cat "$rootfs/.irloc-packages" 2>/dev/null)" != "$packages" ]; then
  step "debootstrap trixie into $rootfs (first run: several minutes)"
  rm -rf "$rootfs" "$vm/rootfs.partial" "$guest/build" "$guest/gpio" "$vm/root.img"
  chroot_dir="$vm/rootfs.partial"
  debootstrap --variant=minbase trixie "$vm/rootfs.partial" "$mirror" > "$vm/debootstrap.log" 2>&1 ||
    fail "debootstrap trixie from $mirror failed (log: $vm/debootstrap.log)"
  echo "deb $mirror trixie main" > "$vm/rootfs.partial/etc/apt/sources.list"
  # The initramfs mounts a virtio disk holding ext4 and needs nothing else (small and quick to make).
  mkdir -p "$vm/rootfs.partial/etc/initramfs-tools/conf.d"
  printf '%s\n' virtio_pci virtio_blk ext4 > "$vm/rootfs.partial/etc/initramfs-tools/modules"
  echo MODULES=list > "$vm/rootfs.partial/etc/initramfs-tools/conf.d/irloc-vm"
  step "installing the guest's packages"
  in_root apt-get -q update > "$vm/apt.log" 2>&1 ||
    fail "apt-get update in the root file system failed (log: $vm/apt.log)"
  apt_install "${build_packages[@]}"
  step "building irlocd and irloc-sim in the root file system (libcamera 0.4; in the background) and installing the kernel"
  build_programs &
  guest_build=$!
  apt_install "${kernel_packages[@]}"
  in_root apt-get clean
  echo "$packages" > "$vm/rootfs.partial/.irloc-packages"
  mv "$vm/rootfs.partial" "$rootfs"
  chroot_dir=$rootfs
else
  step "building irlocd and irloc-sim in the root file system (libcamera 0.4; in the background)"
  build_programs &
  guest_build=$!
fi
in_root dpkg-query -W -f='test-vm: guest ${Package} ${Version}\n' libcamera0.4 linux-image-amd64

# The root file system's disk image, made once per package list and init; booted with
# snapshot=on, so that the guest's writes never reach it.
kernel=$(ls "$rootfs"/boot/vmlinuz-* | sort -V | tail -n 1)
kernel_version=${kernel##*/vmlinuz-}
initrd="$rootfs/boot/initrd.img-$kernel_version"
[ -f "$initrd" ] || fail "no initramfs beside $kernel"
root_stamp="$packages $(sha256sum < "$root/tools/vm/guest_init.sh")"
if [ "$(cat "$vm/root.img.stamp" 2>/dev/null)" != "$root_stamp" ]; then
  step "making the root file system's disk image"
  rm -f "$vm/root.img" "$vm/root.img.stamp"
  install -m 0755 "$root/tools/vm/guest_init.sh" "$rootfs/sbin/irloc-vm-init"
  # /irloc: the test disk's mount point, empty in the image.
  find "$rootfs/irloc" -mindepth 1 -delete
  size_mib=$(( $(du -sm "$rootfs" | cut -f1) * 5 / 4 + 256 ))
  mkfs.ext4 -q -F -L irloc-vm -d "$rootfs" "$vm/root.img" "${size_mib}M" || fail "mkfs.ext4 -d $rootfs failed"
  echo "$root_stamp" > "$vm/root.img.stamp"
fi

# 2. The LED line: a GPIO chip module built against the guest kernel (when its source changed).
mkdir -p "$guest/gpio"
if ! cmp -s "$root/tools/vm/irloc_vm_gpio.c" "$guest/gpio/irloc_vm_gpio.c" || [ ! -f "$guest/gpio/irloc_vm_gpio.ko" ]; then
  step "building the LED line's GPIO chip module"
  cp "$root/tools/vm/irloc_vm_gpio.c" "$guest/gpio/"
  echo 'obj-m := irloc_vm_gpio.o' > "$guest/gpio/Kbuild"
  in_root make -C "/usr/src/linux-headers-$kernel_version" M=/irloc/gpio modules > "$vm/gpio_module.log" 2>&1 ||
    fail "building the GPIO chip module failed (log: $vm/gpio_module.log)"
fi

# The UVC camera (tools/vm/uvc_camera.c), built on the host (when its source changed): it plugs
# into the guest through qemu's usb-redir.
if ! cmp -s "$root/tools/vm/uvc_camera.c" "$vm/uvc_camera.c" || [ ! -x "$vm/uvc_camera" ]; then
  step "building the UVC camera"
  cp "$root/tools/vm/uvc_camera.c" "$vm/"
  cc -std=c11 -D_GNU_SOURCE -O2 -Wall -Wextra -Werror -o "$vm/uvc_camera" "$vm/uvc_camera.c" -lusbredirparser \
    > "$vm/uvc_camera.log" 2>&1 || fail "building the UVC camera failed (log: $vm/uvc_camera.log)"
fi

step "waiting for the build"
wait "$guest_build" || fail "building irlocd and irloc-sim in the root file system failed (log: $vm/build.log)"

# 3. The dataset: rendered by irloc-sim, then the virtual camera's JPEG frames made
# (tools/vm/prepare_frames.sh), both in the root file system.
drive_frames=${IRLOC_VM_DRIVE_FRAMES:+--frames $IRLOC_VM_DRIVE_FRAMES}
stamp="$(sha256sum "$guest/build/bin/irloc-sim" "$root/$scenario" "$root/tools/vm/prepare_frames.sh" | sha256sum) $drive_frames"
if [ "$(cat "$guest/drive/.stamp" 2>/dev/null)" != "$stamp" ]; then
  step "rendering $scenario and its JPEG frames"
  rm -rf "$guest/drive"
  mkdir -p "$guest/drive"
  { in_root nice -n 5 /irloc/build/bin/irloc-sim render --scenario "/irloc/src/$scenario" $drive_frames --out /irloc/drive/dataset &&
    in_root sh -s /irloc/drive < "$root/tools/vm/prepare_frames.sh"; } > "$vm/render.log" 2>&1 ||
    fail "rendering the drive failed (log: $vm/render.log)"
  echo "$stamp" > "$guest/drive/.stamp"
fi

# 4. The test disk, mounted at /irloc in the guest: hard links to what the guest needs.
step "making the test disk"
rm -rf "$vm/test_disk" "$vm/test.img"
mkdir -p "$vm/test_disk/bin" "$vm/test_disk/gpio"
cp -l "$guest/build/bin/irlocd" "$vm/test_disk/bin/"
cp -l "$guest/gpio/irloc_vm_gpio.ko" "$vm/test_disk/gpio/"
cp -al "$guest/drive" "$vm/test_disk/drive"
install -m 0755 "$root/tools/vm/guest_test.sh" "$vm/test_disk/guest_test.sh"
size_mib=$(( $(du -sm "$vm/test_disk" | cut -f1) * 5 / 4 + 64 ))
mkfs.ext4 -q -F -L irloc-test -d "$vm/test_disk" "$vm/test.img" "${size_mib}M" || fail "mkfs.ext4 -d $vm/test_disk failed"
rm -rf "$vm/test_disk"

# 5. Boot: KVM where the host offers it, else TCG. Under nested virtualisation KVM may refuse the
# host CPU's model or fail to emulate an instruction of the guest kernel ("KVM internal error",
# then hanging): the boot is then done again with TCG. TCG emulates a Nehalem: with AVX2 (-cpu
# max) libjpeg-turbo and libyuv, which decode the virtual camera's images, take their AVX2 code,
# which TCG runs about 3 times slower than their SSE code (measured: 18 s against 6 s for the
# drive's images). The guest is a test machine: mitigations=off spares TCG the kernel's
# speculation barriers (retpolines).
# The UVC camera serves the drive's frames on a unix socket, which qemu's usb-redir device on
# its xHCI controller connects to (the guest then sees a USB webcam plugged in).
awk -F, -v dataset="$guest/drive/dataset" 'NR > 1 { print dataset "/" $4 }' "$guest/drive/dataset/frames.csv" > "$vm/uvc_frames.txt"
rm -f "$vm/uvc.sock"  # the last run's: qemu would find it before the camera listens
"$vm/uvc_camera" "$vm/uvc_frames.txt" "$vm/uvc_controls.log" "$vm/uvc.sock" 2> "$vm/uvc_camera.log" &
uvc_camera=$!
trap 'kill "$uvc_camera" 2>/dev/null' EXIT
for _ in $(seq 50); do [ -S "$vm/uvc.sock" ] && break; sleep 0.1; done
boot() {  # boot ACCEL CPU
  rm -f "$vm/console.log"
  timeout 1800 qemu-system-x86_64 -accel "$1" -cpu "$2" -m 1536 -smp 2 -nodefaults -display none -no-reboot \
    -kernel "$kernel" -initrd "$initrd" \
    -append "root=/dev/vda rw console=ttyS0 panic=1 mitigations=off init=/sbin/irloc-vm-init irloc_frames=${IRLOC_VM_FRAMES:-10000}" \
    -drive "file=$vm/root.img,format=raw,if=virtio,snapshot=on" -drive "file=$vm/test.img,format=raw,if=virtio" \
    -device qemu-xhci,id=xhci -chardev "socket,id=uvc,path=$vm/uvc.sock" -device usb-redir,chardev=uvc,bus=xhci.0 \
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
  boot tcg Nehalem || fail "qemu failed or timed out (console: $vm/console.log, qemu: $vm/qemu.log)"
fi
grep '^irloc-vm:' "$vm/console.log" || true
# The UVC camera's controls as the guest set them: manual exposure, the board's exposure (2000 us:
# 20 x 100 us) and gain (1.5: 150) when the camera started, then the --camera-settings file's
# (3000 us, gain 2.0) while streaming (tools/vm/guest_test.sh, part 6).
set_values() { awk -v name="$1" '$1 == name { printf "%s ", $2 }' "$vm/uvc_controls.log"; }
uvc_controls="auto-exposure mode $(set_values ae_mode)(1: manual), exposure $(set_values exposure_time_absolute)(x 100 us), gain $(set_values gain)"
if set_values ae_mode | grep -q '^1 ' && set_values exposure_time_absolute | grep -q '^20 .*30 $' &&
   set_values gain | grep -q '^150 .*200 $'; then
  echo "test-vm: ok uvc_controls: the UVC camera was set: $uvc_controls"
else
  echo "test-vm: FAIL uvc_controls: the UVC camera was set: $uvc_controls"
  uvc_failed=1
fi
step "done"
grep -qx 'irloc-vm: PASS' <(tr -d '\r' < "$vm/console.log") || fail "the guest's test did not pass (console: $vm/console.log)"
[ -z "${uvc_failed:-}" ] || fail "the UVC camera's controls were not set as asked (log: $vm/uvc_controls.log)"
echo "test-vm: PASS ($(( $(date +%s) - started )) s)"
