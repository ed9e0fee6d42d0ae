#!/bin/sh
# The rolling-shutter evaluation (issue 29; docs/dot_markers.md and docs/square_markers.md,
# "Rolling shutter"): a family of drives drawn from a seed, each rendered twice by irloc-sim run,
# with a rolling shutter and with a global shutter (the same drive and frame times), and replayed
# through irlocd. A family is a base scenario whose robot drives a circle, with the circle's centre,
# radius, speed (at most 90 deg/s of turn) and sense drawn per scene:
#   dot     host_sim/scenarios/dot_rolling_board.yaml: the default board's mode (820x616, 37.8 us
#           a row), dots every 1.8 m; radius 0.64-1.6 m, 0.5-1 m/s, at most 90 deg/s.
#   square  host_sim/scenarios/square_rolling_fisheye.yaml: 1280x1024 fisheye, 18 us a row, a 2 m
#           square; centre within 0.3 m of the square's, radius 0.5-0.9 m, 0.4-0.8 m/s, at most
#           60 deg/s (issue 29's square drives).
#   led     host_sim/scenarios/led_ceiling_up.yaml: 640x480 fisheye under seven ceiling LEDs, the
#           default board's readout time (23.3 ms: 48.5 us a row); radius 0.6-1 m, 0.4-1 m/s, at
#           most 90 deg/s.
# Prints one line per scene and shutter, then the pooled figures against the family's goals (dot:
# position RMS <= 0.5 mm, yaw RMS <= 0.03 deg, no gross error; square: position RMS <= 1 mm; every
# family: a pose rate as the global shutter's and within 2x of its RMS); a missed goal is
# reported, and the status is 1.
#
#   tools/rolling_eval.sh BUILD_DIR [SCENES] [SEED] [FRAMES] [FAMILY]    (make eval-rolling)
set -eu
build=$1
scenes=${2:-6}
seed=${3:-29}
frames=${4:-200}
family=${5:-dot}
root=$(cd "$(dirname "$0")/.." && pwd)
sim="$build/bin/irloc-sim"
# Per family: base scenario, line time (ns), the circle's centre (x, y) and its spread (+-), radius
# and speed ranges (min, span), the fastest turn (rad/s: the speed is cut to radius x turn), the
# goals (position RMS m, yaw RMS rad, no gross error: 1/0; 0 for no absolute goal), the source's
# pose stage (irlocd's stage times).
case "$family" in
  dot) base=dot_rolling_board.yaml line=37800 cx=0 cy=0 spread=0.9 r0=0.64 rs=0.96 v0=0.5 vs=0.5 turn=1.5708
       goal_pos=0.0005 goal_yaw=0.000523599 goal_gross=1 stage=pose ;;
  square) base=square_rolling_fisheye.yaml line=18000 cx=0 cy=0 spread=0.3 r0=0.5 rs=0.4 v0=0.4 vs=0.4 turn=1.0472
          goal_pos=0.001 goal_yaw=0 goal_gross=0 stage=square ;;
  led) base=led_ceiling_up.yaml line=48500 cx=3 cy=2.5 spread=0.4 r0=0.6 rs=0.4 v0=0.4 vs=0.6 turn=1.5708
       goal_pos=0 goal_yaw=0 goal_gross=0 stage="led pose" ;;
  *) echo "rolling_eval.sh: FAMILY must be dot, square or led, not '$family'" >&2; exit 2 ;;
esac
base="$root/host_sim/scenarios/$base"
out="$build/eval-rolling/$family"
rm -rf "$out"
mkdir -p "$out"

# KEY's number in metrics.json FILE (the first match; for error stats, FIELD of its object).
stat() { sed -n "s/.*\"$2\": {\"count\": \([0-9]*\), \"rmse\": \([-0-9.e+]*\), \"max\": \([-0-9.e+]*\)}.*/\1 \2 \3/p" "$1"; }
number() { sed -n "s/.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1; }
# The mean time per pose attempt of irlocd's stage KEY in metrics.json FILE, ms.
stage_ms() { sed -n "s/.*\"stages_ms\": {.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1"; }

scene=0
while [ "$scene" -lt "$scenes" ]; do
  # The scene's drive, drawn from (seed, scene).
  drive=$(awk -v s=$((seed * 1000 + scene)) -v cx="$cx" -v cy="$cy" -v spread="$spread" -v r0="$r0" -v rs="$rs" \
              -v v0="$v0" -v vs="$vs" -v turn="$turn" 'BEGIN { srand(s);
    r = r0 + rs * rand(); v = v0 + vs * rand(); if (v > turn * r) v = turn * r;
    printf "%.3f %.3f %.3f %.3f %s", cx - spread + 2 * spread * rand(), cy - spread + 2 * spread * rand(), r, v,
           rand() < 0.5 ? "true" : "false" }')
  set -- $drive
  for shutter in rolling global; do
    line_time=$line
    [ "$shutter" = global ] && line_time=0
    dir="$out/scene_$scene/$shutter"
    mkdir -p "$dir"
    sed -e "s|^seed: .*|seed: $((seed * 1000 + scene))|" -e "s|^frames: .*|frames: $frames|" \
        -e "s|calibration_file: \.\./\.\./|calibration_file: $root/|" -e "/^  line_time_ns: /d" -e "/^  clockwise: /d" \
        -e "s|^camera:\$|camera:\n  line_time_ns: $line_time|" \
        -e "s|^  centre: .*|  centre: [$1, $2]|" -e "s|^  radius: .*|  radius: $3|" \
        -e "s|^  speed: .*|  speed: $4\n  clockwise: $5|" "$base" > "$dir/scenario.yaml"
    nice -n 10 "$sim" run --scenario "$dir/scenario.yaml" --out "$dir" > "$dir/run.log"
    m="$dir/metrics.json"
    set -- $drive
    echo "scene $scene $shutter: circle r $3 m at $4 m/s: posed $(number "$m" detection_rate)," \
         "position (n rmse max) $(stat "$m" position_error_m), yaw $(stat "$m" yaw_error_rad)," \
         "gross $(number "$m" gross_errors), $stage stage ms $(stage_ms "$m" "$stage")"
  done
  scene=$((scene + 1))
done

# Pooled over the scenes, from each run's pose CSV against its truth.csv (the pose at t_ns): the
# pose rate, position and yaw RMS and max, gross errors (5 cm, 1 deg), per shutter; and the same
# without each drive's first pose (no track yet).
pool() {
  for run in "$out"/scene_*/"$1"; do
    awk -F, -v skip="$2" 'NR == FNR { if (FNR > 1) { x[$1] = $3; y[$1] = $4; z[$1] = $5; yaw[$1] = $8 } next }
      FNR == 1 { next }
      { attempts++ }
      $3 == "ok" { ok++; if (ok <= skip) next;
        dp = sqrt(($4 - x[$1])^2 + ($5 - y[$1])^2 + ($6 - z[$1])^2);
        dy = $9 - yaw[$1]; while (dy > 3.14159265358979) dy -= 6.28318530717959; while (dy < -3.14159265358979) dy += 6.28318530717959;
        printf "pose %.9f %.9f\n", dp, (dy < 0 ? -dy : dy) }
      END { printf "attempts %d %d\n", attempts, ok }' "$run/dataset/truth.csv" "$run/pose.csv"
  done | awk '$1 == "attempts" { a += $2; ok += $3; next }
    { n++; p2 += $2 * $2; if ($2 > pm) pm = $2; y2 += $3 * $3; if ($3 > ym) ym = $3; if ($2 > 0.05 || $3 > 0.01745) g++ }
    END { if (n == 0) n = 1; printf "%.4f %.6f %.6f %.6f %.6f %d\n", ok / a, sqrt(p2 / n), pm, sqrt(y2 / n), ym, g }'
}

# Each drive's first pose (no track: the motion from the frame alone where it decides it, else
# the plain fit, its covariance inflated for the unknown motion), position error in mm, per
# shutter: what the every-pose figures carry that the others do not.
first_poses() {
  for run in "$out"/scene_*/"$1"; do
    awk -F, 'NR == FNR { if (FNR > 1) { x[$1] = $3; y[$1] = $4; z[$1] = $5 } next }
      FNR > 1 && $3 == "ok" { printf " %.2f", 1e3 * sqrt(($4 - x[$1])^2 + ($5 - y[$1])^2 + ($6 - z[$1])^2); exit }' \
        "$run/dataset/truth.csv" "$run/pose.csv"
  done
}
echo "$family, each drive's first pose, position error mm: rolling$(first_poses rolling); global$(first_poses global)"

verdict=0
for skip in 0 1; do
  set -- $(pool rolling $skip)
  r_rate=$1 r_pos=$2 r_pos_max=$3 r_yaw=$4 r_yaw_max=$5 r_gross=$6
  set -- $(pool global $skip)
  g_rate=$1 g_pos=$2 g_pos_max=$3 g_yaw=$4 g_yaw_max=$5 g_gross=$6
  awk -v rr="$r_rate" -v rp="$r_pos" -v rpm="$r_pos_max" -v ry="$r_yaw" -v rym="$r_yaw_max" -v rg="$r_gross" \
      -v gr="$g_rate" -v gp="$g_pos" -v gpm="$g_pos_max" -v gy="$g_yaw" -v gym="$g_yaw_max" -v gg="$g_gross" \
      -v n="$scenes" -v skip="$skip" -v family="$family" -v goal_pos="$goal_pos" -v goal_yaw="$goal_yaw" \
      -v goal_gross="$goal_gross" 'BEGIN {
    d = 180 / 3.14159265358979;
    printf "%s, pooled over %d scenes%s:\n", family, n, skip ? ", without each drive'"'"'s first pose" : ", every pose";
    printf "  rolling shutter: posed %.1f %%, position RMS %.3f mm (max %.2f), yaw RMS %.4f deg (max %.3f), gross %d\n", 100 * rr, 1e3 * rp, 1e3 * rpm, d * ry, d * rym, rg;
    printf "  global shutter:  posed %.1f %%, position RMS %.3f mm (max %.2f), yaw RMS %.4f deg (max %.3f), gross %d\n", 100 * gr, 1e3 * gp, 1e3 * gpm, d * gy, d * gym, gg;
    fail = 0; met = "pose rate as global, within 2x global";
    if (rr < gr) { print "  MISSED: pose rate below the global shutter'"'"'s"; fail = 1 }
    if (goal_gross && rg > 0) { print "  MISSED: gross errors"; fail = 1 }
    if (goal_gross) met = "no gross error, " met;
    if (goal_pos > 0 && rp > goal_pos) { printf "  MISSED: position RMS above %g mm\n", 1e3 * goal_pos; fail = 1 }
    if (goal_pos > 0) met = sprintf("position RMS <= %g mm, ", 1e3 * goal_pos) met;
    if (goal_yaw > 0 && ry > goal_yaw) { printf "  MISSED: yaw RMS above %g deg\n", d * goal_yaw; fail = 1 }
    if (goal_yaw > 0) met = sprintf("yaw RMS <= %.2f deg, ", d * goal_yaw) met;
    if (rp > 2 * gp || ry > 2 * gy) { print "  MISSED: more than 2x the global shutter'"'"'s RMS"; fail = 1 }
    if (!fail) print "  goals met: " met;
    exit fail }' || verdict=1
done
exit $verdict
