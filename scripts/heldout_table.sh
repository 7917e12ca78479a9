#!/usr/bin/env bash
# Scores the shipped models on fresh simulated splits that no model, parameter or
# design decision has seen: data/generate_default.sh with new seeds (the default
# dataset's distribution), then pcl_crf_eval on every split and on all of them
# pooled. The shipped test split is one draw of 30 pairs and per-pair V is close to
# all-or-nothing, so differences of a few hundredths there are within its noise;
# this table tells them apart.
#
# Usage: scripts/heldout_table.sh            (after building into build/)
# Environment:
#   PCL_CRF_BIN   folder of the tools                      (default: build/apps)
#   SEEDS         space-separated simulator seeds          (default: "3003 4004")
#   METHODS       comma-separated methods                  (default: the joint paper's comparison)
#   MODELS        folder of learned models                 (default: data/models)
#   OUT           keep the splits and CSVs here            (default: a temporary folder)
#   BEAMS, FOV    scan resolution of the fresh splits      (default: 361 beams over 180°,
#                 as shipped; BEAMS=1081 FOV=270 for Hokuyo-like scans, see
#                 data/generate_default.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

bin=${PCL_CRF_BIN:-build/apps}
seeds=${SEEDS:-3003 4004}
methods=${METHODS:-crf-matching,icp+kmeans,crf-matching+kmeans,crf-m,joint}
models=${MODELS:-data/models}
for tool in pcl_crf_simulate pcl_crf_eval; do
  [ -x "$bin/$tool" ] || { echo "error: $bin/$tool not found: build first (cmake --build build)" >&2; exit 1; }
done
out=${OUT:-$(mktemp -d)}
[ -n "${OUT:-}" ] || trap 'rm -rf "$out"' EXIT
mkdir -p "$out/pooled"

names=()
splits=""
for seed in $seeds; do
  [[ "$seed" =~ ^[0-9]+$ ]] || { echo "error: seed '$seed' is not a non-negative integer" >&2; exit 1; }
  names+=("seed_$seed")
  splits="$splits seed_$seed:$seed"
done
[ ${#names[@]} -gt 0 ] || { echo "error: SEEDS is empty" >&2; exit 1; }
SPLITS="$splits" data/generate_default.sh "$bin/pcl_crf_simulate" "$out" >&2

# Pool the splits' pairs into one dataset (links, renamed per split).
for name in "${names[@]}"; do
  for pair in "$out/$name"/*/; do
    ln -s "$(cd "$pair" && pwd)" "$out/pooled/${name}_$(basename "$pair")"
  done
done

for split in "${names[@]}" pooled; do
  echo "## $split ($(find -L "$out/$split/" -mindepth 2 -maxdepth 2 -name pair.txt | wc -l) pairs)"
  "$bin/pcl_crf_eval" "$out/$split" --method "$methods" --models "$models" -q --format csv \
      --output "$out/$split.csv"
  awk -F, '
    NR == 1 { next }
    $2 == "association_accuracy" || $2 == "cluster_accuracy" || $2 == "v_measure" ||
    $2 == "ego_translation_error" || $2 == "moving_translation_error" {
      if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
      value[$1, $2] = $4
    }
    END {
      printf "| method | association accuracy | motion-detection accuracy | V | ego motion [m] | moving objects [m] |\n"
      printf "|---|---|---|---|---|---|\n"
      for (k = 1; k <= n; ++k) {
        m = order[k]
        printf "| %s | %s | %s | %s | %s | %s |\n", m, fmt(value[m, "association_accuracy"]),
               fmt(value[m, "cluster_accuracy"]), fmt(value[m, "v_measure"]),
               fmt(value[m, "ego_translation_error"]), fmt(value[m, "moving_translation_error"])
      }
    }
    function fmt(v) { return v == "" ? "-" : sprintf("%.3f", v) }' "$out/$split.csv"
  echo
done
