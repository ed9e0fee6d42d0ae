#!/bin/sh
# Runs inside make test-vm's root file system (tools/test_vm.sh): turns the drive irloc-sim
# rendered into OUT/dataset into what libcamera's virtual camera plays, OUT/frames/N.jpg.
# libcamera 0.4's virtual pipeline handler shows each image for 4 frames in a row, so the
# per-frame strobe cannot be played frame by frame: each LED-off/LED-on pair of the drive becomes
# two consecutive images (2j, 2j+1), and the camera's LED-on frame 8j+4 (the first frame of image
# 2j+1) pairs with frame 8j+3 (the last of image 2j) exactly as on a robot; the other pairs are
# the same image twice (no contrast) or the LED-on image before the next LED-off one (swapped).
# OUT/pairs.csv maps each LED-on image to the dataset's frame, for scoring (guest_test.sh).
# OUT/decoded is the dataset with each of those frames replaced by its JPEG image decoded as the
# virtual camera decodes it (libyuv: libjpeg-turbo's fast integer IDCT, djpeg -dct fast): the
# frames libcamera plays, to be replayed with dir:.
# Also writes the virtual camera's configuration (OUT/virtual.yaml) and a board file for it.
# Usage: prepare_frames.sh OUT
set -eu
out=$1
mkdir -p "$out/frames"
# JPEG at quality 100, grey: the virtual camera's NV12 luma is this image's, up to the encoding.
awk -F, 'NR > 1 {
    if ($3 == 1 && previous_led == 0 && $1 == previous_seq + 1) print previous_file, $4, $1
    previous_seq = $1; previous_led = $3; previous_file = $4
  }' "$out/dataset/frames.csv" > "$out/pairs.txt"
echo "image,seq" > "$out/pairs.csv"
rm -rf "$out/decoded"
cp -r "$out/dataset" "$out/decoded"
image=0
while read -r off on seq; do
  cjpeg -quality 100 -grayscale "$out/dataset/$off" > "$out/frames/$image.jpg"
  cjpeg -quality 100 -grayscale "$out/dataset/$on" > "$out/frames/$((image + 1)).jpg"
  djpeg -dct fast -pnm "$out/frames/$image.jpg" > "$out/decoded/$off"
  djpeg -dct fast -pnm "$out/frames/$((image + 1)).jpg" > "$out/decoded/$on"
  echo "$((image + 1)),$seq" >> "$out/pairs.csv"
  image=$((image + 2))
done < "$out/pairs.txt"
rm "$out/pairs.txt"
[ "$image" -gt 0 ] || { echo "prepare_frames: $out/dataset: no LED-off/LED-on pair" >&2; exit 1; }

size=$(sed -n 's/^image_\(width\|height\): *//p' "$out/dataset/calib.yaml" | tr '\n' ' ')
set -- $size
cat > "$out/virtual.yaml" <<EOF
# libcamera's virtual pipeline handler: one camera playing the rendered drive.
"Virtual0":
  supported_formats:
    - width: $1
      height: $2
      frame_rates: [30]
  frames:
    path: $out/frames/
  model: "irloc rendered drive"
EOF
cat > "$out/board.yaml" <<EOF
# libcamera's virtual camera in make test-vm's guest; the LED line is irloc_vm_gpio's (nothing lit).
name: vm-virtual
description: libcamera virtual camera (NV12 $1x$2), LED line on irloc_vm_gpio, pose stream on ttyS1
camera:
  driver: libcamera
  formats: [NV12]
  frame_duration_us: 33333
  exposure_us: 2000
  analogue_gain: 1.0
  buffers: 6
  calibration: dataset/calib.yaml
strobe:
  chip: irloc-vm-leds
  line: 0
  active_low: false
  latency_frames: 0
  noise_level: 12
  min_contrast_ratio: 3
serial:
  device: /dev/ttyS1
  baud: 921600
  protocol: mavlink
EOF
echo "prepare_frames: $((image / 2)) pairs as $image JPEG frames of $1x$2"
