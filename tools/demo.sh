#!/usr/bin/env bash
# make demo: renders the simulator's embedded default scenario (a robot driving a loop under dot
# markers and a square tape marker), replays it through irlocd exactly as on a robot, and prints
# the metrics against ground truth. Pictures and metrics.json land in build/demo/.
set -euo pipefail
build=${1:-build}
out="$build/demo"
rm -rf "$out"
"$build/bin/irloc-sim" run --out "$out"
echo "demo: metrics in $out/metrics.json; plots $out/trajectory.png $out/errors.png; debug frames $out/debug_frame_*.png"
