#!/usr/bin/env python3
"""How much of a dataset's association accuracy its rule for the true matches decides.

A dataset's `match` field names, per source point, "the corresponding target point"
(data/README.md), and the simulators define it two ways:
  * pcl_crf_simulate (data/SIMULATOR.md): the target return nearest to the *stored*
    source point moved by its object's true motion (range noise included);
  * scripts/parking_lot/simulate.py: the return nearest to the *noise-free* surface
    point, moved the same way.
This script scores two oracles that know every object's true motion (the `object`
lines of pair.txt) on the truly matched source points of a dataset:
  nearest return   the target point of the same object nearest to the stored source
                   point moved by its object's motion (what the estimators do with
                   their estimated motions);
  nearest surface  the same with every point of both scans first moved along its own
                   beam onto the line through it and its neighbours (up to 2 beams
                   either side, each within 0.3 m per beam apart): range noise moves a
                   return along its beam only, so the intersection of the beam with the
                   local surface estimates the noise-free point. Points whose line meets
                   the beam at a grazing angle (cosine below 0.2), or which it would move
                   by more than 0.1 m, stay where they are.
A dataset whose rule uses the noise-free points caps the first oracle below 1; one
whose rule uses the stored points caps the second.

With --errors, it instead sorts a method's associations (pcl_crf_eval
--save-predictions D, then D/<method>) against the dataset's true matches: correct, a
match where there is none, none where there is one, another target point within 0.1 m
of the true one, another one farther.

Usage: scripts/truth_rule_oracle.py DATASET_FOLDER [DATASET_FOLDER ...]
       scripts/truth_rule_oracle.py --errors DATASET_FOLDER PREDICTIONS_FOLDER
(ASCII PCD files, as both simulators write them and pcl_crf_eval saves predictions)
"""
import math
import os
import sys

NEIGHBOURS = 2  # beams either side
GAP_PER_BEAM = 0.3  # [m] farthest neighbour per beam of separation
GRAZING_COSINE = 0.2
LARGEST_CORRECTION = 0.1  # [m]


def read_fields(path):
    """The points of an ASCII PCD file as dicts of their fields."""
    with open(path) as f:
        lines = f.read().split("\n")
    fields, data = None, None
    for k, line in enumerate(lines):
        words = line.split()
        if words and words[0] == "FIELDS":
            fields = words[1:]
        if words and words[0] == "DATA":
            if words[1:] != ["ascii"]:
                raise ValueError(f"{path}: only ASCII PCD files are read here")
            data = k + 1
            break
    if fields is None or data is None:
        raise ValueError(f"{path}: no FIELDS or DATA line")
    return [dict(zip(fields, map(float, line.split()))) for line in lines[data:] if line.strip()]


def object_motions(pair):
    motions = {}
    with open(os.path.join(pair, "pair.txt")) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "object":
                motions[int(words[1])] = tuple(map(float, words[3:6]))
    return motions


def moved(motion, point):
    x, y, theta = motion
    c, s = math.cos(theta), math.sin(theta)
    return (c * point[0] - s * point[1] + x, s * point[0] + c * point[1] + y)


def on_local_surface(points, i):
    """Point i moved along its beam onto the line through it and its neighbours."""
    x, y = points[i]
    near = [(x, y)]
    for step in range(1, NEIGHBOURS + 1):
        for j in (i - step, i + step):
            if 0 <= j < len(points) and math.dist(points[j], (x, y)) < GAP_PER_BEAM * step:
                near.append(points[j])
    if len(near) < 3:
        return x, y
    mx = sum(p[0] for p in near) / len(near)
    my = sum(p[1] for p in near) / len(near)
    sxx = sum((p[0] - mx) ** 2 for p in near)
    syy = sum((p[1] - my) ** 2 for p in near)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in near)
    direction = 0.5 * math.atan2(2.0 * sxy, sxx - syy)  # total least squares line
    nx, ny = -math.sin(direction), math.cos(direction)
    r = math.hypot(x, y)
    if r == 0.0:
        return x, y
    ux, uy = x / r, y / r
    cosine = ux * nx + uy * ny
    if abs(cosine) < GRAZING_COSINE:
        return x, y
    t = (mx * nx + my * ny) / cosine
    if abs(t - r) > LARGEST_CORRECTION:
        return x, y
    return t * ux, t * uy


def score(folder):
    pairs = pair_folders(folder)
    hits = {"nearest return": 0, "nearest surface": 0}
    matched = 0
    for name in pairs:
        pair = os.path.join(folder, name)
        motions = object_motions(pair)
        source = read_fields(os.path.join(pair, "source.pcd"))
        target = read_fields(os.path.join(pair, "target.pcd"))
        of_object = {}
        for j, t in enumerate(target):
            of_object.setdefault(int(t["label"]), []).append(j)
        raw_source = [(p["x"], p["y"]) for p in source]
        raw_target = [(p["x"], p["y"]) for p in target]
        views = {"nearest return": (raw_source, raw_target),
                 "nearest surface": ([on_local_surface(raw_source, i) for i in range(len(raw_source))],
                                     [on_local_surface(raw_target, j) for j in range(len(raw_target))])}
        for i, p in enumerate(source):
            truth = int(p["match"])
            if truth < 0:
                continue
            matched += 1
            candidates = of_object.get(int(p["label"]), [])
            for oracle, (s, t) in views.items():
                q = moved(motions[int(p["label"])], s[i])
                if candidates and min(candidates, key=lambda j: math.dist(t[j], q)) == truth:
                    hits[oracle] += 1
    return len(pairs), matched, hits


def pair_folders(folder):
    pairs = sorted(p for p in os.listdir(folder) if os.path.isfile(os.path.join(folder, p, "pair.txt")))
    if not pairs:
        sys.exit(f"{folder}: no pair folders (with pair.txt) in it")
    return pairs


def association_errors(folder, predictions):
    """Every source point's predicted match sorted against its true one."""
    kinds = {"correct": 0, "matched, truly none": 0, "none, truly matched": 0,
             "another within 0.1 m": 0, "another farther": 0}
    for name in pair_folders(folder):
        source = read_fields(os.path.join(folder, name, "source.pcd"))
        target = read_fields(os.path.join(folder, name, "target.pcd"))
        predicted = read_fields(os.path.join(predictions, name, "prediction.pcd"))
        if len(predicted) != len(source):
            sys.exit(f"{predictions}/{name}: {len(predicted)} predicted points for {len(source)} source points")
        for p, q in zip(source, predicted):
            truth, match = int(p["match"]), int(q["match"])
            if truth == match:
                kinds["correct"] += 1
            elif truth < 0:
                kinds["matched, truly none"] += 1
            elif match < 0:
                kinds["none, truly matched"] += 1
            else:
                apart = math.dist((target[truth]["x"], target[truth]["y"]), (target[match]["x"], target[match]["y"]))
                kinds["another within 0.1 m" if apart < 0.1 else "another farther"] += 1
    total = max(1, sum(kinds.values()))
    print("| " + " | ".join(["dataset"] + list(kinds)) + " |")
    print("|" + "---|" * (len(kinds) + 1))
    print("| " + " | ".join([folder] + [f"{n / total:.3f}" for n in kinds.values()]) + " |")


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--errors" and all(os.path.isdir(d) for d in sys.argv[2:]):
        association_errors(sys.argv[2], sys.argv[3])
        return
    if len(sys.argv) < 2 or not all(os.path.isdir(d) for d in sys.argv[1:]):
        sys.exit("\n".join(__doc__.strip().split("\n")[-3:-1]))
    print("| dataset | pairs | truly matched source points | nearest return | nearest surface |")
    print("|---|---|---|---|---|")
    for folder in sys.argv[1:]:
        pairs, matched, hits = score(folder)
        print(f"| {folder} | {pairs} | {matched} | {hits['nearest return'] / max(1, matched):.3f} "
              f"| {hits['nearest surface'] / max(1, matched):.3f} |")


if __name__ == "__main__":
    main()
