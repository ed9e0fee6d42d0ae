#!/usr/bin/env bash
# The layering check notices each kind of wrong #include: one tree per case, each must fail.
set -u
check=$1
status=0
expect_refused() {
  local file=$1 include=$2 tree
  tree=$(mktemp -d)
  mkdir -p "$tree/algo" "$tree/io" "$tree/hal" "$tree/firmware" "$tree/host_sim" "$tree/$(dirname "$file")"
  echo "#include $include" > "$tree/$file"
  if "$check" "$tree" >/dev/null; then
    echo "not refused: $file including $include"
    status=1
  fi
  rm -rf "$tree"
}
expect_refused algo/bad.cpp '<unistd.h>'
expect_refused algo/kernels/bad.cpp '"algo/geometry/pose.hpp"'
expect_refused algo/markers/dot/bad.cpp '"algo/markers/square/square_detector.hpp"'
expect_refused algo/markers/dot/bad.cpp '"algo/pipeline/localizer.hpp"'
expect_refused algo/markers/outside_in/bad.cpp '"algo/markers/led/led_detector.hpp"'
expect_refused algo/source/bad.cpp '"algo/markers/dot/dot_pose.hpp"'
expect_refused algo/unlisted/bad.cpp '"algo/core/image.hpp"'
expect_refused hal/bad.cpp '"firmware/daemon.hpp"'
expect_refused hal/bad.hpp '"io/config/config_file.hpp"'
expect_refused io/config/bad.cpp '"hal/linux/termios_serial.hpp"'
expect_refused io/bad.cpp '"firmware/daemon.hpp"'
expect_refused hal/linux/bad.cpp '"host_sim/scenario.hpp"'
[ "$status" = 0 ] && echo "layering: every wrong #include of the cases is refused"
exit "$status"
