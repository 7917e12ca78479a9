#!/usr/bin/env python3
"""How often a dataset's scanner leaves a beam without a return inside a surface.

Counts, over both scans of every pair of a dataset folder (the dataset format of the
README: one folder per pair with pair.txt, source.pcd and target.pcd, ASCII PCD), the
beams without a return that lie between two returns on one surface: returns whose
ranges differ by less than 10 % and lie within 0.6 of the sensor's maximum range.
A simulated laser leaves 1-2 % of such beams empty, the real bags' scanners 18-24 %
(docs/EXPERIMENTS.md, "Directions without a return on the real bags"), which is what
the free-space steps' evidence from beams without a return rests on.

Usage: scripts/dropped_returns.py DATASET_FOLDER
"""
import math
import os
import sys

SAME_SURFACE = 0.1  # relative range difference of the returns bounding a run
NEAR = 0.6  # fraction of the maximum range the nearer bounding return lies within


def sensor_of(pair):
    with open(os.path.join(pair, "pair.txt")) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "sensor":
                return int(words[1]), float(words[2]), float(words[3]), float(words[4])
    raise ValueError(f"{pair}/pair.txt has no sensor line (beam count, first angle, step, max range)")


def points_of(path):
    with open(path) as f:
        lines = f.read().split("\n")
    data = [k for k, line in enumerate(lines) if line.startswith("DATA")]
    if not data or lines[data[0]].split()[1:] != ["ascii"]:
        raise ValueError(f"{path}: only ASCII PCD files are read here")
    return [tuple(map(float, line.split()[:2])) for line in lines[data[0] + 1:] if line.strip()]


def ranges_by_beam(points, beams, first, step):
    ranges = [None] * beams
    for x, y in points:
        beam = round((math.atan2(y, x) - first) / step) % beams
        ranges[beam] = math.hypot(x, y)
    return ranges


def count(ranges, max_range, runs):
    """Adds the runs of empty beams between two returns on one surface to runs
    (length -> how many); returns (beams with a return, empty beams in such runs)."""
    returned = sum(r is not None for r in ranges)
    empty = 0
    k = 0
    while k < len(ranges):
        if ranges[k] is not None:
            k += 1
            continue
        end = k
        while end < len(ranges) and ranges[end] is None:
            end += 1
        if k > 0 and end < len(ranges):
            a, b = ranges[k - 1], ranges[end]
            if abs(a - b) < SAME_SURFACE * min(a, b) and min(a, b) < NEAR * max_range:
                runs[end - k] = runs.get(end - k, 0) + 1
                empty += end - k
        k = end
    return returned, empty


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit(__doc__.strip().split("\n")[-1])
    folder = sys.argv[1]
    pairs = sorted(p for p in os.listdir(folder) if os.path.isfile(os.path.join(folder, p, "pair.txt")))
    if not pairs:
        sys.exit(f"{folder}: no pair folders (with pair.txt) in it")
    returned = empty = 0
    runs = {}
    for name in pairs:
        pair = os.path.join(folder, name)
        beams, first, step, max_range = sensor_of(pair)
        if beams <= 0 or step <= 0.0:
            sys.exit(f"{pair}: the sensor line does not describe its beams")
        for scan in ("source.pcd", "target.pcd"):
            r, e = count(ranges_by_beam(points_of(os.path.join(pair, scan)), beams, first, step), max_range, runs)
            returned += r
            empty += e
    print(f"pairs {len(pairs)}  beams with a return {returned}  empty beams inside surfaces {empty}"
          f"  rate {empty / max(1, returned + empty):.3f}")
    print("runs of 1 / 2 / 3 empty beams: " + " / ".join(str(runs.get(n, 0)) for n in (1, 2, 3)))


if __name__ == "__main__":
    main()
