#!/usr/bin/env bash
# The main demo: simulate a few fresh urban scan pairs, then score ICP against the
# CRF estimators on them and on the shipped test split. Run after building
# (scripts/setup.sh --demo does both). PCL_CRF_DEMO_METHODS overrides the methods.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/apps
methods=${PCL_CRF_DEMO_METHODS:-icp,crf-matching,kmeans,cbd,crf-t,joint}

echo "== simulating 5 urban scan pairs with moving objects into build/demo_pairs"
rm -rf build/demo_pairs
"$bin/pcl_crf_simulate" -o build/demo_pairs --pairs 5 --seed 7 --scene mixed -q

echo "== scoring [$methods] on the simulated pairs (models from data/models)"
"$bin/pcl_crf_eval" build/demo_pairs --method "$methods" --models data/models -q

echo "== scoring [$methods] on the shipped test split data/default/test"
"$bin/pcl_crf_eval" data/default/test --method "$methods" --models data/models
