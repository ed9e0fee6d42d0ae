#!/usr/bin/env bash
# Measures irlocd --calibrate (docs/calibration.md) on a rendered drive: renders
# host_sim/scenarios/calibration_drive.yaml, replays it with the true, a perturbed and a
# data-sheet calibration (host_sim/scenarios/calibration_drive/), calibrates from each wrong one
# with --calibrate, replays the same drive with the refined config, and prints the pose errors
# against the rendered truth; OUT/CASE/residuals.png pictures the residuals.
#   tools/calibration_drive.sh [OUT (build/calibration_drive)] [FRAMES (the scenario's)]
set -euo pipefail
out=${1:-build/calibration_drive}
frames=${2:-}
bin=build/bin
scenarios=host_sim/scenarios
dataset=$out/dataset

"$bin/irloc-sim" render --scenario "$scenarios/calibration_drive.yaml" --out "$dataset" ${frames:+--frames "$frames"}
cp "$scenarios"/calibration_drive/*.yaml "$dataset/"

# Errors of a pose CSV against truth.csv: ok poses / attempts, position RMS and max (mm), yaw RMS
# and max (deg).
errors() {
  awk -F, 'NR == FNR { if (FNR > 1) { x[$1] = $3; y[$1] = $4; yaw[$1] = $8 } next }
    FNR > 1 { attempts++ }
    FNR > 1 && $3 == "ok" && ($1 in x) {
      ok++
      d2 = ($4 - x[$1]) ^ 2 + ($5 - y[$1]) ^ 2; p += d2; if (d2 > pmax) pmax = d2
      a = $9 - yaw[$1]; while (a > 3.14159265358979) a -= 6.28318530717959; while (a < -3.14159265358979) a += 6.28318530717959
      y2 = a * a; w += y2; if (y2 > wmax) wmax = y2
    }
    END { if (ok == 0) { printf "0/%d poses ok\n", attempts; exit }
          printf "%d/%d poses ok, position RMS %.2f mm (max %.2f), yaw RMS %.4f deg (max %.4f)\n",
          ok, attempts, 1000 * sqrt(p / ok), 1000 * sqrt(pmax), 57.2957795 * sqrt(w / ok), 57.2957795 * sqrt(wmax) }' \
    "$dataset/truth.csv" "$1"
}

replay() {  # CONFIG POSE_CSV [--calibrate DIR]
  local config=$1 poses=$2
  shift 2
  "$bin/irlocd" --config "$config" --camera "dir:$dataset" --serial none --pose-csv "$poses" "$@" 2>"$poses.log" ||
    { cat "$poses.log" >&2; exit 1; }
}

replay "$dataset/config.yaml" "$out/true.csv"
echo "true calibration:       $(errors "$out/true.csv")"
for case in perturbed data_sheet; do
  replay "$dataset/${case}_config.yaml" "$out/$case.csv" --calibrate "$out/$case"
  echo "$case calibration: $(errors "$out/$case.csv")"
  replay "$out/$case/config.yaml" "$out/${case}_calibrated.csv"
  echo "  after --calibrate:    $(errors "$out/${case}_calibrated.csv")"
  grep -A30 "^reprojection" "$out/$case/calibration_report.txt" | sed 's/^/    /'
  "$bin/irloc-sim" plot-residuals --calibration "$out/$case" | sed 's/^/    /'
done
