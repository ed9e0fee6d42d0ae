#!/usr/bin/env bash
# make demo: writes the small synthetic dataset the replay tests use, replays it with irlocd
# exactly as on a robot, and prints the result. (The physically grounded simulator replaces
# the synthetic dataset once it exists.)
set -euo pipefail
build=${1:-build}
out="$build/demo"
rm -rf "$out"
"$build/bin/irloc-sim" synth --out "$out/dataset" --frames 60 --drop 17
"$build/bin/irlocd" --config "$out/dataset/config.yaml" --camera "dir:$out/dataset" --serial none \
  --pose-csv "$out/pose.csv"
echo "demo: pose CSV in $out/pose.csv; first rows:"
head -n 6 "$out/pose.csv"
