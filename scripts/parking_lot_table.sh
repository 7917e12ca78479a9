#!/usr/bin/env bash
# Scores the shipped models on datasets of a second simulator, written without reading
# pcl_crf_simulate's source and drawing another world: parking lots and campus paths
# (scripts/parking_lot/simulate.py; its docstring gives the world, the presets and the
# rule of its true associations). Each preset is generated with its fixed seed, so the
# tables are the same run to run, then scored with pcl_crf_eval: one Markdown table per
# preset, and the V a method that sees every mover of 3 or more source points allows
# (pcl_crf_eval --v-ceiling, N = 3).
#
# Usage: scripts/parking_lot_table.sh        (after building into build/; needs python3)
# Environment:
#   PCL_CRF_BIN   folder of the tools                      (default: build/apps)
#   PRESETS       space-separated simulator presets        (default: "sick consecutive lidar360";
#                 also clockwise: the scenes of sick listed clockwise)
#   PAIRS         pairs per preset                         (default: 30)
#   METHODS       comma-separated methods                  (default: the joint paper's comparison)
#   MODELS        folder of learned models                 (default: data/models)
#   OUT           keep the datasets and CSVs here          (default: a temporary folder;
#                 the pair folders of a kept OUT/PRESET are replaced)
set -euo pipefail
# A relative OUT names a folder of the caller's, not of the source tree.
[ -z "${OUT:-}" ] || OUT=$(mkdir -p "$OUT" && cd "$OUT" && pwd)
cd "$(dirname "$0")/.."

bin=${PCL_CRF_BIN:-build/apps}
presets=${PRESETS:-sick consecutive lidar360}
pairs=${PAIRS:-30}
methods=${METHODS:-crf-matching,icp+kmeans,crf-matching+kmeans,crf-m,joint}
models=${MODELS:-data/models}
command -v python3 >/dev/null ||
  { echo "error: python3 not found: scripts/parking_lot/simulate.py needs it (standard library only)" >&2; exit 1; }
[ -x "$bin/pcl_crf_eval" ] || { echo "error: $bin/pcl_crf_eval not found: build first (cmake --build build)" >&2; exit 1; }
[ -n "${presets// /}" ] || { echo "error: PRESETS is empty" >&2; exit 1; }
out=${OUT:-$(mktemp -d)}
[ -n "${OUT:-}" ] || trap 'rm -rf "$out"' EXIT
mkdir -p "$out"

for preset in $presets; do
  # pcl_crf_eval scores every pair folder: a kept OUT/PRESET must hold the simulator's alone.
  if [ -d "$out/$preset" ] && find "$out/$preset" -mindepth 1 -maxdepth 1 ! -name 'pair_[0-9][0-9][0-9][0-9]' | grep -q .; then
    echo "error: $out/$preset holds files other than the simulator's pair folders: give an empty OUT" >&2
    exit 1
  fi
  python3 scripts/parking_lot/simulate.py --preset "$preset" --pairs "$pairs" -o "$out/$preset" --force -q
  echo "## $preset ($pairs pairs)"
  "$bin/pcl_crf_eval" "$out/$preset" --method "$methods" --models "$models" -q --format csv \
      --output "$out/$preset.csv"
  awk -v header=1 -f scripts/score_table.awk "$out/$preset.csv"
  echo
  "$bin/pcl_crf_eval" "$out/$preset" --v-ceiling -q |
    awk '/pairs with V >= 0.95/ { total = $NF; sub(/\)$/, "", total) }
         $1 == 3 { found = 1
                   printf "V ceiling (every mover of >= 3 source points found exactly, smaller ones missed): %s, %s of %s pairs with V >= 0.95\n", $2, $3, total }
         END { if (!found) { print "error: no N = 3 row in pcl_crf_eval --v-ceiling" > "/dev/stderr"; exit 1 } }'
  echo
done
