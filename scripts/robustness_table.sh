#!/usr/bin/env bash
# Scores the shipped models on harder versions of the default dataset's streets, one
# condition changed at a time: more range noise, more beams without a return, worse
# odometry, a turning sensor, a dataset that kept its beams without a return as
# points at the maximum range (which the methods leave out), and streets with one kind
# of traffic only (crossing, oncoming, overtaking, cars along their own outline,
# pedestrians) or none. Each condition is a fresh split (data/generate_default.sh
# with the condition's setting, seeds no model has seen), scored with pcl_crf_eval;
# one Markdown table, a row per condition and method.
#
# Usage: scripts/robustness_table.sh          (after building into build/)
# Environment:
#   PCL_CRF_BIN   folder of the tools                  (default: build/apps)
#   SEEDS         space-separated simulator seeds      (default: "7007"; 30 pairs each)
#   METHODS       comma-separated methods              (default: icp+kmeans,crf-m,joint)
#   MODELS        folder of learned models             (default: data/models)
#   OUT           keep the splits and CSVs here        (default: a temporary folder)
set -euo pipefail
cd "$(dirname "$0")/.."

out=${OUT:-$(mktemp -d)}
[ -n "${OUT:-}" ] || trap 'rm -rf "$out"' EXIT

# label|environment of data/generate_default.sh (the shipped values where not named)
conditions=(
  "as shipped|"
  "range noise 3 cm|NOISE=0.03"
  "10 % of beams without a return|DROPOUT=0.1"
  "odometry noise ×3|ODOM_NOISE=0.3,0.15,0.06"
  "turning at 0.3 rad/s|YAW_RATE=0.3"
  "beams without a return kept as points at the maximum range|NO_RETURN_POINTS=1"
  "crossing traffic only|SCENE=crossing"
  "oncoming traffic only|SCENE=opposite"
  "overtaking traffic only|SCENE=overtaking"
  "cars along their own outline only|SCENE=outline"
  "pedestrians only|SCENE=pedestrians"
  "no mover|SCENE=static"
)

header=1
for k in "${!conditions[@]}"; do
  label=${conditions[$k]%%|*}
  setting=${conditions[$k]#*|}
  echo "condition $((k + 1))/${#conditions[@]}: $label" >&2
  if ! env $setting SEEDS="${SEEDS:-7007}" METHODS="${METHODS:-icp+kmeans,crf-m,joint}" OUT="$out/condition_$k" \
      scripts/heldout_table.sh > /dev/null 2> "$out/condition_$k.log"; then
    cat "$out/condition_$k.log" >&2
    exit 1
  fi
  awk -v header=$header -v label="$label" -f scripts/score_table.awk "$out/condition_$k/pooled.csv"
  header=0
done
