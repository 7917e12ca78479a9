#!/usr/bin/env bash
# Regenerates the shipped default dataset data/default/{train,test} with
# pcl_crf_simulate. The output is byte-identical on every run (see SIMULATOR.md).
#
# Usage: data/generate_default.sh [SIMULATE_BINARY] [OUTPUT_DIR]
#   SIMULATE_BINARY  the pcl_crf_simulate program (default: build/apps/pcl_crf_simulate
#                    under the source root)
#   OUTPUT_DIR       where the splits are written (default: data/default); their
#                    sub-folders are replaced.
# Environment:
#   SPLITS           space-separated NAME:SEED splits (default: "train:1001 test:2002",
#                    the shipped ones); other seeds give fresh splits of the same
#                    distribution (scripts/heldout_table.sh).
#   BEAMS, FOV       beams per scan and field of view [deg] (default 361 and 180, the
#                    shipped SICK-like scans; BEAMS=1081 FOV=270 gives Hokuyo-like
#                    scans of the same kind of street, to test the 361-beam models
#                    on a sensor they were not trained on).
#   NOISE, DROPOUT   range noise std [m] and fraction of beams without a return
#                    (default 0.01 and 0.01, as shipped)
#   ODOM_NOISE       odometry noise std as X,Y,YAW [m, m, rad] (default 0.1,0.05,0.02)
#   YAW_RATE         the sensor's turn rate [rad/s] (default 0: driving straight)
#   NO_RETURN_POINTS 1: beams without a return written as points at the maximum
#                    range (pcl_crf_simulate --no-return-points; default 0: left out)
#                    These five give harder splits of the same streets
#                    (scripts/robustness_table.sh).
#   SCENE            the street's traffic (pcl_crf_simulate --scene: mixed, crossing,
#                    opposite, overtaking, outline, pedestrians, static; default mixed,
#                    as shipped): one kind of mover at a time (scripts/robustness_table.sh).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
simulate="${1:-$root/build/apps/pcl_crf_simulate}"
out="${2:-$here/default}"

if [ ! -x "$simulate" ]; then
  echo "generate_default.sh: '$simulate' is not an executable pcl_crf_simulate (build it first)" >&2
  exit 1
fi

beams=${BEAMS:-361}
fov=${FOV:-180}
for value in "$beams" "$fov"; do
  [[ "$value" =~ ^[1-9][0-9]*$ ]] || { echo "generate_default.sh: BEAMS and FOV must be positive integers, got '$value'" >&2; exit 1; }
done
noise=${NOISE:-0.01}
dropout=${DROPOUT:-0.01}
odom_noise=${ODOM_NOISE:-0.1,0.05,0.02}
yaw_rate=${YAW_RATE:-0}
number='[0-9]+([.][0-9]+)?'
for value in "$noise" "$dropout" "$yaw_rate"; do
  [[ "$value" =~ ^-?$number$ ]] || { echo "generate_default.sh: NOISE, DROPOUT and YAW_RATE must be decimal numbers, got '$value'" >&2; exit 1; }
done
[[ "$odom_noise" =~ ^$number,$number,$number$ ]] || { echo "generate_default.sh: ODOM_NOISE must be X,Y,YAW (three non-negative numbers), got '$odom_noise'" >&2; exit 1; }
scene=${SCENE:-mixed}
[[ "$scene" =~ ^[a-z]+$ ]] || { echo "generate_default.sh: SCENE must be a scene name (see pcl_crf_simulate -h), got '$scene'" >&2; exit 1; }
extra=()
case "${NO_RETURN_POINTS:-0}" in
  0) ;;
  1) extra=(--no-return-points) ;;
  *) echo "generate_default.sh: NO_RETURN_POINTS must be 0 or 1, got '${NO_RETURN_POINTS}'" >&2; exit 1 ;;
esac

# Every setting spelled out, so a change of a default does not change the dataset.
common=(--pairs 30 --beams "$beams" --fov "$fov" --range 30 --noise "$noise" --dropout "$dropout"
        --speed 10 --yaw-rate "$yaw_rate" --scene "$scene" --moving -1 --object-speed -1
        --spacing travel --travel 2,4 --odom-noise "$odom_noise" --legs 0.5
        --name-prefix pair_ "${extra[@]}")

for split in ${SPLITS:-train:1001 test:2002}; do
  name=${split%%:*}
  seed=${split#*:}
  if [ -z "$name" ] || [ "$name" = "$split" ] || ! [[ "$seed" =~ ^[0-9]+$ ]]; then
    echo "generate_default.sh: split '$split' is not NAME:SEED (SEED a non-negative integer)" >&2
    exit 1
  fi
  rm -rf "${out:?}/$name"
  "$simulate" -o "$out/$name" --seed "$seed" "${common[@]}"
done
