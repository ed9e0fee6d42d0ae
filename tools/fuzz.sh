#!/usr/bin/env bash
# make fuzz: builds the libFuzzer targets (tests/fuzz/) with clang under ASan+UBSan in
# BUILD/fuzz, runs each for FUZZ_SECONDS (default 120) from a copy of its seed corpus, and prints
# a table: target, executions, executions per second, findings (crash, leak, timeout, out of
# memory: libFuzzer's artifacts in BUILD/fuzz/findings/). Exit status 1 when anything was found.
# Usage: tools/fuzz.sh BUILD [TARGET...]    (environment: FUZZ_SECONDS, FUZZ_JOBS)
set -euo pipefail
build=${1:?usage: tools/fuzz.sh BUILD [TARGET...]}
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(config calibration map board scenario frames_csv pgm localizer stargazer mavlink_rx drive_calibration survey)
seconds=${FUZZ_SECONDS:-120}
root=$(cd "$(dirname "$0")/.." && pwd)
out=$build/fuzz

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found: run tools/deps.sh fuzz" >&2; exit 2; }
CC=clang CXX=clang++ cmake -S "$root" -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIRLOC_FUZZ=ON \
  -DIRLOC_WERROR=OFF >/dev/null
cmake --build "$out" --target fuzz_targets

mkdir -p "$out/findings" "$out/corpus"
status=0
printf '%-12s %14s %10s %9s\n' target executions 'exec/s' findings
for target in "${targets[@]}"; do
  corpus=$out/corpus/$target
  mkdir -p "$corpus"
  cp -n "$root/tests/fuzz/corpus/$target/"* "$corpus/" 2>/dev/null || true
  log=$out/$target.log
  before=$(find "$out/findings" -name "$target-*" | wc -l)
  # -timeout: an input slower than 10 s is a hang; -rss_limit_mb: a runaway allocation.
  "$out/bin/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$out/findings/$target-" -print_final_stats=1 >"$log" 2>&1 || true
  after=$(find "$out/findings" -name "$target-*" | wc -l)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  found=$((after - before))
  [ "$found" -eq 0 ] || status=1
  printf '%-12s %14s %10s %9s\n' "$target" "${runs:-?}" "${rate:-?}" "$found"
done
[ "$status" -eq 0 ] || echo "fuzz: findings in $out/findings (logs: $out/*.log)" >&2
exit $status
