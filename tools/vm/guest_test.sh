#!/bin/sh
# make test-vm's guest (PID 1, from tools/vm/guest_init.sh, the VM's init): irlocd on libcamera's
# virtual camera playing the rendered drive of tools/vm/prepare_frames.sh, checked against the
# same drive replayed with dir:, then on the UVC camera tools/test_vm.sh plugs in (part 6). Every check prints one line `irloc-vm: ok|FAIL NAME: detail` on
# the console (ttyS0); the last line is `irloc-vm: PASS` or `irloc-vm: FAIL`; then it powers off.
# Each part's start is a line `irloc-vm: at T s: PART` (T: seconds since the guest's boot).
PATH=/usr/sbin:/usr/bin:/sbin:/bin
export PATH
drive=/irloc/drive
results=/irloc/results
irlocd=/irloc/bin/irlocd
# irloc_frames=N on the kernel command line (IRLOC_VM_FRAMES of tools/test_vm.sh) reaches init
# as an environment variable; the camera is lost and reopened halfway.
frames=${irloc_frames:-10000}
failed=0

say() { echo "irloc-vm: $*"; }
check() {  # check NAME DETAIL CONDITION...
  name=$1 detail=$2
  shift 2
  if "$@"; then say "ok $name: $detail"; else say "FAIL $name: $detail"; failed=1; fi
}
part() { say "at $(cut -d ' ' -f 1 /proc/uptime) s: $*"; }
finish() {
  part "powering off"
  if [ "$failed" = 0 ]; then say PASS; else say FAIL; fi
  sync
  mount -o remount,ro / 2>/dev/null
  echo o > /proc/sysrq-trigger
  sleep 10
}
# The number after "KEY": in a JSON file irlocd wrote (pretty-printed, one key a line); with
# OBJECT, inside that object.
json_number() {
  awk -v key="\"$1\":" -v object="\"$3\":" '
    $1 == object { inside = 1 }
    (inside || object == "\"\":") && $1 == key { gsub(/[,}]/, "", $2); print $2; exit }' "$2"
}

mountpoint -q /proc || mount -t proc proc /proc
mountpoint -q /sys || mount -t sysfs sysfs /sys
mountpoint -q /dev || mount -t devtmpfs devtmpfs /dev
mount -o remount,rw /
mkdir -p "$results"
say "kernel $(uname -r), $(nproc) CPUs, $(awk '/MemTotal/ { print $2 " kB" }' /proc/meminfo)"

# libcamera's virtual camera allocates its buffers from a DMA heap or udmabuf.
check dma_buffers "$(ls -d /dev/dma_heap/* /dev/udmabuf 2>/dev/null | tr '\n' ' ')" \
  sh -c '[ -e /dev/udmabuf ] || [ -n "$(ls /dev/dma_heap 2>/dev/null)" ]'
# The board's LED line: a GPIO chip without hardware behind it (tools/vm/irloc_vm_gpio.c).
insmod /irloc/gpio/irloc_vm_gpio.ko
check gpio_chip "$(ls /dev/gpiochip* 2>/dev/null | tr '\n' ' ')labelled $(cat /sys/class/gpio/gpiochip*/label 2>/dev/null)" \
  sh -c 'cat /sys/class/gpio/gpiochip*/label | grep -qx irloc-vm-leds'
# Transparent huge pages off: khugepaged would fold the virtual camera's image store (386 MB on
# the heap of irlocd's process) into 2 MiB pages at times of its own, each fold adding up to 2 MiB
# of resident memory that is not the program's (measured: three such steps in one run, all
# anonymous), and the flat-memory check is about the program.
echo never > /sys/kernel/mm/transparent_hugepage/enabled
say "transparent huge pages: $(cat /sys/kernel/mm/transparent_hugepage/enabled)"
mkdir -p /usr/share/libcamera/pipeline/virtual
cp "$drive/virtual.yaml" /usr/share/libcamera/pipeline/virtual/virtual.yaml
cd "$drive" || finish

# 1. The drive replayed from its PGM files: the reference.
part "replays with dir:"
"$irlocd" --config dataset/config.yaml --camera dir:dataset --serial none --pose-csv "$results/replay.csv" \
  2> "$results/replay.log"
check replay "$(tail -n 1 "$results/replay.log")" test $? = 0

# The frames the virtual camera plays (the JPEG images decoded), replayed: the reference for the
# capture's accuracy (the images' encoding costs accuracy that is not the backend's).
"$irlocd" --config decoded/config.yaml --camera dir:decoded --serial none --pose-csv "$results/decoded.csv" \
  2> "$results/decoded.log"
check replay_decoded "$(tail -n 1 "$results/decoded.log")" test $? = 0

# The pixels: the first frames captured through libcamera, recorded by irlocd, are the first two
# images decoded (each image is shown for 4 frames) as libyuv decodes them (libjpeg's fast
# integer IDCT), byte for byte: the luma plane read with its stride, at the negotiated size.
part "the first frames through libcamera"
timeout 300 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera --frames 8 \
  --record "$results/recorded" 2> "$results/recorded.log"
pixels_differing() {  # IMAGE RECORDED_FRAME: how many pixel bytes differ (headers aside)
  bytes=$(( $(sed -n 's/^image_width: *//p' dataset/calib.yaml) * $(sed -n 's/^image_height: *//p' dataset/calib.yaml) ))
  djpeg -dct fast -pnm "frames/$1.jpg" | tail -c "$bytes" > "$results/image.raw"
  tail -c "$bytes" "$results/recorded/$2" > "$results/frame.raw"
  cmp -l "$results/image.raw" "$results/frame.raw" | wc -l
}
differing_0=$(pixels_differing 0 frame_000000.pgm)
differing_1=$(pixels_differing 1 frame_000004.pgm)
check pixels "frames 0 and 4 against images 0 and 1: $differing_0 and $differing_1 pixels differ" \
  test "$differing_0" = 0 -a "$differing_1" = 0

# 2. The same drive captured through libcamera: 10,000 frames, every buffer back and requeued.
uptime_ns() { awk '{ printf "%d\n", $1 * 1e9 }' /proc/uptime; }
part "$frames frames through libcamera"
start_ns=$(uptime_ns)
# libcamera takes the first pattern a category matches.
LIBCAMERA_LOG_LEVELS='Camera:INFO,*:WARN' timeout 900 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera \
  --frames "$frames" --pose-csv "$results/live.csv" --stats "$results/live.json" 2> "$results/live.log" &
runner=$!
# irlocd's resident memory every 2 s while it runs (KiB, one a line), and its parts (anonymous,
# file, shared memory: the frame buffers) beside it.
sleep 1
irlocd_pid=$(pgrep -P "$runner" -x irlocd)
while kill -0 "$irlocd_pid" 2>/dev/null; do
  awk '/^VmRSS:/ { print $2 > "/dev/stdout" } /^Rss(Anon|File|Shmem):/ { printf "%s %s ", $1, $2 > "/dev/stderr" }
       END { print "" > "/dev/stderr" }' "/proc/$irlocd_pid/status" 2>> "$results/live_rss_parts.txt"
  sleep 2
done > "$results/live_rss.txt"
wait "$runner"
status=$?
end_ns=$(uptime_ns)
check capture "exit $status: $(tail -n 1 "$results/live.log")" test "$status" = 0
[ "$status" = 0 ] || tail -n 30 "$results/live.log" | sed 's/^/irloc-vm: log: /'
say "libcamera: $(grep -m 1 'configuring streams' "$results/live.log" | sed 's/.*configuring streams: //')"
check format "NV12 at the calibration's size, stride = width (the virtual camera pads no row)" \
  grep -q "configuring streams: (0) $(sed -n 's/^image_width: *//p' dataset/calib.yaml)x$(sed -n 's/^image_height: *//p' dataset/calib.yaml)-NV12" "$results/live.log"
got_frames=$(json_number frames "$results/live.json")
check frames "$got_frames of $frames frames" test "$got_frames" = "$frames"
dropped=$(json_number dropped_frames "$results/live.json")
check no_lost_buffers "$dropped frames dropped (sequence gaps), no camera loss" \
  sh -c "[ '$dropped' = 0 ] && ! grep -q 'no pose until it is back' '$results/live.log'"
fds_start=$(json_number open_fds "$results/live.json" resources_at_start)
fds_end=$(json_number open_fds "$results/live.json" resources_at_end)
check flat_descriptors "$fds_start open at start, $fds_end at the end" test "$fds_start" = "$fds_end"
# Flat memory: from the end of a warm-up (the first fifth of the run: every buffer mapped and
# touched, every scratch area used) to the end, resident memory grows by at most 1 MiB.
rss_start=$(json_number resident_kib "$results/live.json" resources_at_start)
rss_end=$(json_number resident_kib "$results/live.json" resources_at_end)
samples=$(wc -l < "$results/live_rss.txt")
rss_warm=$(sed -n "$((samples / 5 + 1))p" "$results/live_rss.txt")
say "resident memory (KiB) every 2 s: $(tr '\n' ' ' < "$results/live_rss.txt")"
say "its parts at the warm-up's end: $(sed -n "$((samples / 5 + 1))p" "$results/live_rss_parts.txt"); 2 s before the end: $(sed -n "$((samples - 1))p" "$results/live_rss_parts.txt")"
check flat_memory "resident $rss_start KiB at start-up, $rss_warm KiB after the warm-up, $rss_end KiB at the end (at most 1 MiB more)" \
  sh -c "[ '$samples' -ge 5 ] && [ '$rss_end' -le $((${rss_warm:-0} + 1024)) ]"
say "strobe verdicts: verified $(json_number verified "$results/live.json") swapped $(json_number swapped "$results/live.json") no_contrast $(json_number no_contrast "$results/live.json")"

# Timestamps (conventions.md): t_ns on CLOCK_MONOTONIC, the middle of the exposure: inside the
# run, increasing within each camera session, and the capture-to-write latency positive.
check timestamps "t_ns within the run ($start_ns..$end_ns ns after boot) and increasing" \
  awk -F, -v from="$start_ns" -v to="$end_ns" 'NR > 1 {
      if ($2 < from - 1e9 || $2 > to) exit 1
      if (NR > 2 && $1 > previous_seq && $2 <= previous_t) exit 1
      previous_seq = $1; previous_t = $2 }' "$results/live.csv"
latency=$(json_number median "$results/live.json" capture_to_write_ms)
check latency "capture to serial write median $latency ms" awk -v ms="$latency" 'BEGIN { exit !(ms > 1 && ms < 100) }'

# 3. Poses scored against the truth: the live ones through pairs.csv (camera frame -> image ->
# dataset frame, tools/vm/prepare_frames.sh), the replayed ones directly.
images=$(ls frames | wc -l)
score() {  # score POSE_CSV MAPPED(0|1): "poses rmse_m max_m unmapped"
  awk -F, -v mapped="$2" -v images="$images" '
    FILENAME ~ /truth/ && FNR > 1 { x[$1] = $3; y[$1] = $4; z[$1] = $5; next }
    FILENAME ~ /pairs/ && FNR > 1 { seq_of_image[$1] = $2; next }
    FNR > 1 && $3 == "ok" {
      seq = $1
      if (mapped) {
        image = int(seq / 4) % images
        if (seq % 4 != 0 || !(image in seq_of_image)) { unmapped++; next }
        seq = seq_of_image[image]
      }
      e = sqrt(($4 - x[seq])^2 + ($5 - y[seq])^2 + ($6 - z[seq])^2)
      n++; sum += e * e; if (e > max) max = e
    }
    END { printf "%d %.6f %.6f %d\n", n, n ? sqrt(sum / n) : 0, max, unmapped }' dataset/truth.csv pairs.csv "$1"
}
set -- $(score "$results/replay.csv" 0)
replay_poses=$1 replay_rmse=$2 replay_max=$3
set -- $(score "$results/decoded.csv" 0)
decoded_poses=$1 decoded_rmse=$2 decoded_max=$3
set -- $(score "$results/live.csv" 1)
live_poses=$1 live_rmse=$2 live_max=$3 live_unmapped=$4
say "replay of the rendered frames (dir:): $replay_poses poses, position RMSE $replay_rmse m, max $replay_max m"
say "replay of the decoded images (dir:): $decoded_poses poses, position RMSE $decoded_rmse m, max $decoded_max m"
say "libcamera: $live_poses poses, position RMSE $live_rmse m, max $live_max m"
check poses "libcamera gave $live_poses poses, every one from a rendered LED-on image ($live_unmapped not)" \
  sh -c "[ '$live_poses' -ge $((frames / 8 * 3 / 4)) ] && [ '$live_unmapped' = 0 ]"
check accuracy "libcamera RMSE $live_rmse m within 2x the decoded images' replay's $decoded_rmse m" \
  awk -v poses="$live_poses" -v live="$live_rmse" -v replay="$decoded_rmse" 'BEGIN { exit !(poses > 0 && replay > 0 && live <= 2 * replay) }'

# 4. The camera lost at frame 300 and reopened after 0.5 s (a new camera manager, acquired,
# configured, started), as irlocd does when a robot's camera drops off its bus: poses again after
# it, nothing dropped but the loss, descriptors as at start. The reopen is start-up work: the
# virtual camera decodes all its images again in this process, so memory may settle a little
# higher (at most 8 MiB), once per reopen, not per frame.
part "the reopen"
timeout 600 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera --frames 600 \
  --inject-faults lost@300+500 --pose-csv "$results/reopen.csv" --stats "$results/reopen.json" 2> "$results/reopen.log"
status=$?
check reopen "exit $status: $(grep -m 1 'camera back after' "$results/reopen.log")" \
  sh -c "[ $status = 0 ] && [ \$(grep -c 'no pose until it is back' '$results/reopen.log') = 1 ] && grep -q 'camera back after' '$results/reopen.log'"
# The reopen shows in the pose rows as a gap in t_ns of at least the 0.5 s the camera was away.
poses_after=$(awk -F, 'NR > 2 && $2 - previous_t > 4e8 { reopened = 1 } NR > 1 { previous_t = $2 } reopened && $3 == "ok" { n++ } END { print n + 0 }' "$results/reopen.csv")
check poses_after_reopen "$poses_after poses after the reopen" test "$poses_after" -ge 20
fds_start=$(json_number open_fds "$results/reopen.json" resources_at_start)
fds_end=$(json_number open_fds "$results/reopen.json" resources_at_end)
rss_start=$(json_number resident_kib "$results/reopen.json" resources_at_start)
rss_end=$(json_number resident_kib "$results/reopen.json" resources_at_end)
check reopen_resources "$fds_start descriptors at start, $fds_end at the end; resident $rss_start KiB, then $rss_end KiB" \
  sh -c "[ '$fds_start' = '$fds_end' ] && [ '$rss_end' -le $((rss_start + 8192)) ]"

# 5. Controls: the virtual camera lists none of exposure, gain, frame duration as irlocd reads
# them; asking for one is a clean start-up error naming the file and the key.
part "an unsupported control"
printf 'exposure_us: 3000\n' > "$results/camera.yaml"
timeout 300 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera --frames 10 \
  --camera-settings "$results/camera.yaml" 2> "$results/controls.log"
status=$?
check unsupported_control "exit $status: $(tail -n 1 "$results/controls.log")" \
  sh -c "[ $status = 1 ] && grep -q 'camera.yaml.*exposure_us' '$results/controls.log'"

# 6. A camera with exposure and gain: tools/vm/uvc_camera.c, a UVC webcam emulated on the host and
# plugged in through qemu's usb-redir on its xHCI controller, playing the drive's frames in order
# as YUYV (luma = the rendered image). libcamera's uvcvideo handler maps AeEnable, ExposureTime
# and AnalogueGain to its controls; the camera logs each value set, which tools/test_vm.sh checks
# after the guest: the board's at start (gain 1.5 here), the settings file's while streaming.
part "a UVC camera"
rm -f /usr/share/libcamera/pipeline/virtual/virtual.yaml
modprobe xhci_pci && modprobe uvcvideo
# uvcvideo registers the media device after the video nodes.
for _ in $(seq 200); do [ -e /dev/media0 ] && break; sleep 0.1; done
# libcamera lists only devices udev has initialised (a udev database entry each), and no udev
# daemon runs here: the entries are made by hand.
mkdir -p /run/udev/data
for device in /sys/class/video4linux/* /sys/bus/media/devices/*; do
  [ -e "$device/dev" ] && : > "/run/udev/data/c$(cat "$device/dev")"
done
sed -e 's/^  formats: .*/  formats: [YUYV]/' -e 's/^  analogue_gain: .*/  analogue_gain: 1.5/' board.yaml > uvc_board.yaml
printf 'exposure_us: 3000\nanalogue_gain: 2.0\n' > "$results/uvc_settings.yaml"
LIBCAMERA_LOG_LEVELS='Camera:INFO,*:WARN' timeout 300 "$irlocd" --board uvc_board.yaml --config dataset/config.yaml --camera libcamera --frames 60 \
  --camera-settings "$results/uvc_settings.yaml" --record "$results/uvc_recorded" --stats "$results/uvc.json" 2> "$results/uvc.log"
status=$?
check uvc_capture "exit $status: $(tail -n 1 "$results/uvc.log")" test "$status" = 0
[ "$status" = 0 ] || { tail -n 20 "$results/uvc.log"; dmesg | tail -n 20; } | sed 's/^/irloc-vm: log: /'
say "UVC camera: $(grep -m 1 'configuring streams' "$results/uvc.log" | sed 's/.*configuring streams: //')"
# The pixels: every recorded frame (YUYV, rows of 2 x width bytes) is one of the drive's frames,
# byte for byte (irlocd and irloc-sim write the same PGM header).
sums() { md5sum "$@" 2>/dev/null | cut -d ' ' -f 1 | sort -u; }
sums $(awk -F, 'NR > 1 { print "dataset/" $4 }' dataset/frames.csv) > "$results/uvc_frame_sums.txt"
recorded=$(ls "$results"/uvc_recorded/*.pgm 2>/dev/null | wc -l)
foreign=$(sums "$results"/uvc_recorded/*.pgm | comm -23 - "$results/uvc_frame_sums.txt" | wc -l)
check uvc_pixels "$recorded frames recorded through YUYV, $foreign not a drive frame byte for byte" \
  test "$recorded" = 60 -a "$foreign" = 0
finish
