#!/usr/bin/env bash
# The soak: FRAMES frames through the whole daemon on the simulated camera and LEDs, unpaced,
# with resident memory, open file descriptors and heap allocations measured when start-up is done
# and after the last frame. Pass: no allocation after start-up, the same descriptors at the end,
# resident memory grown by at most 1 MiB (first touches of buffers sized at start-up), and every
# frame processed.
# Usage: tools/soak.sh BUILD_DIR FRAMES     (make soak: 1e6 frames; ctest soak_short: a few thousand)
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR FRAMES}
frames=${2:?usage: $0 BUILD_DIR FRAMES}
irlocd="$build/bin/irlocd-soak"
sim="$build/bin/irloc-sim"
for binary in "$irlocd" "$sim"; do [ -x "$binary" ] || { echo "soak: $binary not built" >&2; exit 1; }; done
rss_growth_limit_kib=1024

work=$(mktemp -d "${TMPDIR:-/tmp}/irloc-soak.XXXXXX")
pid=
cleanup() {
  [ -n "$pid" ] && kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
"$sim" synth --out "$work/config" --frames 2 >/dev/null

start=$(date +%s.%N)
"$irlocd" --config "$work/config/config.yaml" --camera "sim:$frames:unpaced" --serial none \
  --stats "$work/stats.json" 2>"$work/stderr" &
pid=$!
echo "soak: $frames frames through irlocd-soak (pid $pid) on the simulated camera, unpaced"

# Progress every 10 s (every second for short runs), from the status line and /proc.
interval=10
[ "$frames" -le 100000 ] && interval=1
rss_min= rss_max=0 fds_max=0
while kill -0 "$pid" 2>/dev/null; do
  sleep "$interval"
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  fds=$(ls "/proc/$pid/fd" 2>/dev/null | wc -l || true)
  [ -n "$rss" ] || break
  [ -z "$rss_min" ] || [ "$rss" -lt "$rss_min" ] && rss_min=$rss
  [ "$rss" -gt "$rss_max" ] && rss_max=$rss
  [ "$fds" -gt "$fds_max" ] && fds_max=$fds
  fps=$( (grep -o '^irlocd: [0-9.]* fps' "$work/stderr" || true) | tail -1 | awk '{print $2}')
  elapsed=$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN {printf "%.0f", n - s}')
  echo "soak: ${elapsed} s, ${fps:-?} fps, RSS ${rss} KiB, ${fds} fds"
done
status=0
wait "$pid" || status=$?
pid=
wall=$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN {printf "%.1f", n - s}')
if [ "$status" != 0 ] || [ ! -f "$work/stats.json" ]; then
  echo "soak: FAIL: irlocd-soak exited with status $status:" >&2
  tail -5 "$work/stderr" >&2
  exit 1
fi

# The stats file is nlohmann's indented JSON: one "key": value per line.
field() { grep -A3 "\"$1\"" "$work/stats.json" | grep -m1 "\"$2\"" | sed -E 's/.*: ([0-9]+).*/\1/'; }
top() { sed -nE "s/^  \"$1\": ([0-9]+),?$/\1/p" "$work/stats.json"; }
done_frames=$(top frames)
attempts=$(top pose_attempts)
poses=$(top poses_ok)
allocations=$(top allocations_after_startup)
rss_start=$(field resources_at_start resident_kib)
rss_end=$(field resources_at_end resident_kib)
fds_start=$(field resources_at_start open_fds)
fds_end=$(field resources_at_end open_fds)
rate=$(awk -v f="$done_frames" -v w="$wall" 'BEGIN {printf "%.0f", f / w}')

echo "soak: frames $done_frames, pose attempts $attempts, poses ok $poses"
echo "soak: resident memory at start $rss_start KiB, at end $rss_end KiB (sampled while running: $rss_min..$rss_max KiB)"
echo "soak: open descriptors at start $fds_start, at end $fds_end (sampled while running: at most $fds_max)"
echo "soak: heap allocations after start-up: $allocations"
echo "soak: wall time $wall s ($rate frames/s)"
failures=()
[ "$done_frames" = "$frames" ] || failures+=("$done_frames frames of $frames")
[ "$allocations" = 0 ] || failures+=("$allocations allocations after start-up")
[ "$fds_end" = "$fds_start" ] || failures+=("open descriptors $fds_start -> $fds_end")
[ $((rss_end - rss_start)) -le $rss_growth_limit_kib ] ||
  failures+=("resident memory grew $((rss_end - rss_start)) KiB (limit $rss_growth_limit_kib)")
if [ ${#failures[@]} -gt 0 ]; then
  printf 'soak: FAIL: %s\n' "${failures[@]}"
  exit 1
fi
echo "soak: PASS"
