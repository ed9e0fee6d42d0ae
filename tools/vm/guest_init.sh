#!/bin/sh
# make test-vm's init (PID 1; tools/test_vm.sh installs it as /sbin/irloc-vm-init in the root file
# system's image): mounts the test disk (the VM's second disk: irlocd, the LED-line module, the
# drive, guest_test.sh) at /irloc and runs the test there. The initramfs has moved its devtmpfs
# to /dev, so the disk's node exists; without the disk the VM powers off with the reason.
if ! mount -t ext4 /dev/vdb /irloc; then
  echo "irloc-vm: FAIL: no test disk at /dev/vdb"
  mount -t proc proc /proc
  echo o > /proc/sysrq-trigger
fi
exec /irloc/guest_test.sh
