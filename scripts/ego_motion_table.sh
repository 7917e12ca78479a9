#!/usr/bin/env bash
# Ego-motion accuracy on the corrected CARMEN logs of ../shared/data/carmen:
# every method pcl_crf_run knows (plus the raw odometry it starts from) estimates
# the motion between consecutive scans; the table gives its translation and
# rotation error against the SLAM-corrected poses (mean and median per log, and
# pooled over all logs).
#
# Usage: scripts/ego_motion_table.sh            (after building into build/)
# Environment:
#   PCL_CRF_BIN   folder of the tools            (default: build/apps)
#   CARMEN_DIR    folder of *-corrected.log.gz   (default: ../shared/data/carmen)
#   METHODS       space-separated method names   (default: all of pcl_crf_run --list-methods)
#   MODELS        folder of learned models       (default: data/models)
#   STEP          pair scan k with k+STEP        (default: 1)
#   MAX_PAIRS     pairs per log, 0 = all         (default: 0)
#   OUT           keep the per-pair CSVs here    (default: a temporary folder)
set -euo pipefail
cd "$(dirname "$0")/.."

bin=${PCL_CRF_BIN:-build/apps}
carmen=${CARMEN_DIR:-../shared/data/carmen}
models=${MODELS:-data/models}
step=${STEP:-1}
max_pairs=${MAX_PAIRS:-0}
run="$bin/pcl_crf_run"

[ -x "$run" ] || { echo "error: $run not found: build first (cmake --build build)" >&2; exit 1; }
logs=$(ls "$carmen"/*-corrected.log.gz 2>/dev/null || true)
[ -n "$logs" ] || { echo "error: no *-corrected.log.gz in $carmen (set CARMEN_DIR)" >&2; exit 1; }
methods=${METHODS:-$("$run" --list-methods)}
out=${OUT:-$(mktemp -d)}
[ -n "${OUT:-}" ] || trap 'rm -rf "$out"' EXIT
mkdir -p "$out"

# summarize T_COL R_COL FILE... -> "pairs t_mean t_median r_mean r_median" over two CSV columns
summarize() {
  local t_col=$1 r_col=$2 values n mean_t mean_r median_t median_r
  shift 2
  values=$(awk -F, -v t="$t_col" -v r="$r_col" 'FNR > 1 && $t != "" { print $t, $r }' "$@")
  if [ -z "$values" ]; then echo "0 - - - -"; return; fi
  read -r n mean_t mean_r < <(echo "$values" | awk '{ st += $1; sr += $2 } END { printf "%d %.4f %.4f\n", NR, st / NR, sr / NR }')
  median_t=$(echo "$values" | cut -d' ' -f1 | median)
  median_r=$(echo "$values" | cut -d' ' -f2 | median)
  echo "$n $mean_t $median_t $mean_r $median_r"
}

median() {
  sort -g | awk '{ v[NR] = $1 } END { printf "%.4f", (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

row() {  # log method stats... seconds
  local log=$1 method=$2 pairs=$3 mt=$4 medt=$5 mr=$6 medr=$7 rate=$8
  printf "| %-20s | %-12s | %6s | %8s | %8s | %9s | %9s | %8s |\n" "$log" "$method" "$pairs" "$mt" "$medt" "$mr" "$medr" "$rate"
}

echo "Ego motion between scans k and k+$step of the corrected CARMEN logs vs the corrected poses"
echo "(translation error [m], rotation error [rad]; pcl_crf_run --step $step --max-pairs $max_pairs, 0 = all)"
echo
printf "| %-20s | %-12s | %6s | %8s | %8s | %9s | %9s | %8s |\n" log method pairs "t mean" "t median" "r mean" "r median" "pairs/s"
printf "|%s|%s|%s|%s|%s|%s|%s|%s|\n" "----------------------" "--------------" "--------" "----------" "----------" "-----------" "-----------" "----------"
for method in $methods; do
  for log in $logs; do
    name=$(basename "$log" -corrected.log.gz)
    csv="$out/$method-$name.csv"
    if ! "$run" "$log" --method "$method" --models "$models" --step "$step" --max-pairs "$max_pairs" -q \
        --csv "$csv" > "$out/$method-$name.txt" 2>&1; then
      echo "| $name | $method | failed: $(tail -n 1 "$out/$method-$name.txt") |"
      rm -f "$csv"
      continue
    fi
    rate=$(sed -n 's/.*(\([0-9.]*\) pairs\/s in the method.*/\1/p' "$out/$method-$name.txt")
    # shellcheck disable=SC2046
    row "$name" "$method" $(summarize 19 20 "$csv") "$rate"
  done
  csvs=$(ls "$out/$method"-*.csv 2>/dev/null || true)
  # shellcheck disable=SC2046,SC2086
  [ -z "$csvs" ] || row "ALL (pooled)" "$method" $(summarize 19 20 $csvs) ""
done
# the raw odometry the methods start from (the same for every method: take the first method's runs)
first=$(echo "$methods" | awk 'NF { print $1; exit }')
for log in $logs; do
  name=$(basename "$log" -corrected.log.gz)
  csv="$out/$first-$name.csv"
  # shellcheck disable=SC2046
  [ ! -f "$csv" ] || row "$name" "odometry" $(summarize 21 22 "$csv") ""
done
csvs=$(ls "$out/$first"-*.csv 2>/dev/null || true)
# shellcheck disable=SC2046,SC2086
[ -z "$csvs" ] || row "ALL (pooled)" "odometry" $(summarize 21 22 $csvs) ""
if [ -n "${OUT:-}" ]; then
  echo
  echo "per-pair CSVs (pcl_crf_run --csv) in $out"
fi
