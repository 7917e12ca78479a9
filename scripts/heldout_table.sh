#!/usr/bin/env bash
# Scores the shipped models on fresh simulated splits that no model, parameter or
# design decision has seen: data/generate_default.sh with new seeds (the default
# dataset's distribution), then pcl_crf_eval on every split and on all of them
# pooled (one seed: its split is the pool, OUT/pooled.csv a copy). The shipped test
# split is one draw of 30 pairs and per-pair V is close to all-or-nothing, so
# differences of a few hundredths there are within its noise;
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

# One seed: its split is the pool (scored once).
scored=("${names[@]}")
[ ${#names[@]} -eq 1 ] || scored+=(pooled)
for split in "${scored[@]}"; do
  echo "## $split ($(find -L "$out/$split/" -mindepth 2 -maxdepth 2 -name pair.txt | wc -l) pairs)"
  "$bin/pcl_crf_eval" "$out/$split" --method "$methods" --models "$models" -q --format csv \
      --output "$out/$split.csv"
  awk -v header=1 -f scripts/score_table.awk "$out/$split.csv"
  echo
done
[ ${#names[@]} -gt 1 ] || cp "$out/${names[0]}.csv" "$out/pooled.csv"
