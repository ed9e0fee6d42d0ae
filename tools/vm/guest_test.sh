#!/bin/sh
# make test-vm's guest (tools/test_vm.sh boots it as the VM's init, PID 1): irlocd on libcamera's
# virtual camera playing the rendered drive of tools/vm/prepare_frames.sh, checked against the
# same drive replayed with dir:. Every check prints one line `irloc-vm: ok|FAIL NAME: detail` on
# the console (ttyS0); the last line is `irloc-vm: PASS` or `irloc-vm: FAIL`; then it powers off.
PATH=/usr/sbin:/usr/bin:/sbin:/bin
export PATH
drive=/irloc/drive
results=/irloc/results
irlocd=/irloc/build/bin/irlocd
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
finish() {
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
mkdir -p /usr/share/libcamera/pipeline/virtual
cp "$drive/virtual.yaml" /usr/share/libcamera/pipeline/virtual/virtual.yaml
cd "$drive" || finish

# 1. The drive replayed from its PGM files: the reference.
"$irlocd" --config dataset/config.yaml --camera dir:dataset --serial none --pose-csv "$results/replay.csv" \
  2> "$results/replay.log"
check replay "$(tail -n 1 "$results/replay.log")" test $? = 0

# 2. The same drive captured through libcamera: 10,000 frames, the camera lost at frame 5000 and
# reopened (a new camera manager, acquired, configured, started) after 0.5 s.
uptime_ns() { awk '{ printf "%d\n", $1 * 1e9 }' /proc/uptime; }
start_ns=$(uptime_ns)
LIBCAMERA_LOG_LEVELS='*:WARN,Camera:INFO' timeout 900 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera \
  --frames "$frames" --inject-faults "lost@$((frames / 2))+500" --pose-csv "$results/live.csv" --stats "$results/live.json" \
  2> "$results/live.log"
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
check no_lost_buffers "$dropped frames dropped (sequence gaps); the only camera loss the injected one" \
  sh -c "[ '$dropped' = 0 ] && [ \$(grep -c 'no pose until it is back' '$results/live.log') = 1 ]"
check reopen "$(grep -m 1 'camera back after' "$results/live.log")" grep -q 'camera back after' "$results/live.log"
fds_start=$(json_number open_fds "$results/live.json" resources_at_start)
fds_end=$(json_number open_fds "$results/live.json" resources_at_end)
check flat_descriptors "$fds_start open at start, $fds_end at the end" test "$fds_start" = "$fds_end"
rss_start=$(json_number resident_kib "$results/live.json" resources_at_start)
rss_end=$(json_number resident_kib "$results/live.json" resources_at_end)
check flat_memory "resident $rss_start KiB at start, $rss_end KiB at the end (at most 2 MiB more)" \
  test "$rss_end" -le $((rss_start + 2048))
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
set -- $(score "$results/live.csv" 1)
live_poses=$1 live_rmse=$2 live_max=$3 live_unmapped=$4
say "replay (dir:): $replay_poses poses, position RMSE $replay_rmse m, max $replay_max m"
say "libcamera: $live_poses poses, position RMSE $live_rmse m, max $live_max m"
check poses "libcamera gave $live_poses poses, every one from a rendered LED-on image ($live_unmapped not)" \
  sh -c "[ '$live_poses' -ge $((frames / 8 * 3 / 4)) ] && [ '$live_unmapped' = 0 ]"
check accuracy "libcamera RMSE $live_rmse m within 2x the replay's $replay_rmse m" \
  awk -v poses="$live_poses" -v live="$live_rmse" -v replay="$replay_rmse" 'BEGIN { exit !(poses > 0 && replay > 0 && live <= 2 * replay) }'

# 4. Controls: the virtual camera lists none of exposure, gain, frame duration as irlocd reads
# them; asking for one is a clean start-up error naming the file and the key.
printf 'exposure_us: 3000\n' > "$results/camera.yaml"
timeout 300 "$irlocd" --board board.yaml --config dataset/config.yaml --camera libcamera --frames 10 \
  --camera-settings "$results/camera.yaml" 2> "$results/controls.log"
status=$?
check unsupported_control "exit $status: $(tail -n 1 "$results/controls.log")" \
  sh -c "[ $status = 1 ] && grep -q 'camera.yaml.*exposure_us' '$results/controls.log'"
finish
