#!/usr/bin/env bash
# The main demo: simulate a few fresh urban scan pairs, then score the methods on
# the shipped test split. Run after building (scripts/setup.sh does both).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/apps

echo "== simulating 5 scan pairs with moving cars into build/demo_pairs"
rm -rf build/demo_pairs
"$bin/pcl_crf_simulate" -o build/demo_pairs --pairs 5 --seed 7 --scene mixed

methods=${PCL_CRF_DEMO_METHODS:-icp}
echo "== scoring [$methods] on the simulated pairs"
"$bin/pcl_crf_eval" build/demo_pairs --method "$methods" -q

echo "== scoring [$methods] on the shipped test split data/default/test"
"$bin/pcl_crf_eval" data/default/test --method "$methods" --models data/models
