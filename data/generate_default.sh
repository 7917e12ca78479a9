#!/usr/bin/env bash
# Regenerates the shipped default dataset data/default/{train,test} with
# pcl_crf_simulate. The output is byte-identical on every run (see SIMULATOR.md).
#
# Usage: data/generate_default.sh [SIMULATE_BINARY] [OUTPUT_DIR]
#   SIMULATE_BINARY  the pcl_crf_simulate program (default: build/apps/pcl_crf_simulate
#                    under the source root)
#   OUTPUT_DIR       where train/ and test/ are written (default: data/default);
#                    the two sub-folders are replaced.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
simulate="${1:-$root/build/apps/pcl_crf_simulate}"
out="${2:-$here/default}"

if [ ! -x "$simulate" ]; then
  echo "generate_default.sh: '$simulate' is not an executable pcl_crf_simulate (build it first)" >&2
  exit 1
fi

# Every setting spelled out, so a change of a default does not change the dataset.
common=(--pairs 30 --beams 361 --fov 180 --range 30 --noise 0.01 --dropout 0.01
        --speed 10 --yaw-rate 0 --scene mixed --moving -1 --object-speed -1
        --spacing travel --travel 2,4 --odom-noise 0.1,0.05,0.02 --legs 0.5
        --name-prefix pair_)

rm -rf "$out/train" "$out/test"
"$simulate" -o "$out/train" --seed 1001 "${common[@]}"
"$simulate" -o "$out/test" --seed 2002 "${common[@]}"
