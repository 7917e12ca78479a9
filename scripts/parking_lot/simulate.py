#!/usr/bin/env python3
"""A second 2D laser scan-pair simulator: parking lots and campus paths.

This simulator was written without reading the source of pcl_crf's own
simulator (src/simulation, apps/pcl_crf_simulate.cpp), and it draws a
different world, so its datasets score the methods on scenes that no model,
parameter or design decision was tuned to.  It needs the Python 3 standard
library only and writes datasets in the format of data/README.md:
DIR/pair_NNNN/ holding pair.txt, source.pcd and target.pcd (ascii).

World (a new random scene for every pair):
  * static world: irregular star-shaped buildings, walls and fences
    (polylines), rows of parked cars with empty bays, poles and trees, and
    people standing still, all kept 2 m clear of the sensor's path;
  * movers, each a rigid outline on a unicycle path (some turning): cars
    (3.8-5 m x 1.6-2 m, 2-15 m/s), pedestrians (round or elliptic,
    radius 0.2-0.35 m, 0.8-1.8 m/s) and cyclists (1.7 m x 0.5 m, 3-7 m/s);
  * sensor: a unicycle with random speed, acceleration, yaw rate and yaw
    acceleration, integrated numerically; the odometry is its true motion
    with Gaussian noise;
  * laser: an instantaneous scan cast against every outline, with Gaussian
    range noise, random beams without a return and a maximum range.

Association rule (the `match` field of source.pcd): a source return's
noise-free surface point is moved with its object's true motion into the
target frame.  It is matched to the nearest noise-free target return of the
same object when (a) the target sensor sees it (within the field of view and
0.99999 of the maximum range, and the target ray along its bearing first
hits the same object no nearer than 3 cm in front of it) and (b) that return
lies within 2 beam spacings at its range + 2 cm; otherwise `match` is -1.

Presets:
  sick         361 beams over 180 deg (the shipped dataset's resolution),
               30 m range, the sensor travels 2-4 m between the scans
  consecutive  the same laser, consecutive scans 0.1 s apart
  lidar360     720 beams over 360 deg, 25 m, scans 0.1 s apart, more people
  clockwise    the scenes of sick, each scan's points stored in reverse
               (clockwise) beam order

The same arguments write byte-identical files (each pair draws from its own
random stream, seeded with SEED * 100003 + pair index), given the same
platform's maths library: the last bit of a sine may differ elsewhere.

Usage: scripts/parking_lot/simulate.py --preset sick -o DIR [--pairs N]
           [--seed S] [--force] [--check] [--quiet]
"""
import argparse
import math
import os
import random
import re
import shutil
import sys
from dataclasses import dataclass

MAX_PAIRS = 10000  # pair folders are named pair_0000 ... pair_9999
PAIR_FOLDER = re.compile(r'pair_\d{4}')

BASE = dict(
    beams=361, a0=-math.pi / 2, da=math.pi / 360, rmax=30.0, sigma=0.02,
    dropout=0.01, ego_speed=(5.0, 12.0), ego_vmax=14.0, ego_yaw=0.35,
    travel=(2.0, 4.0), interval=None, movers=(1, 4), corridor=2.0,
    buildings=(4, 9), walls=(2, 5), parked_rows=(1, 3), poles=(5, 15),
    kind_weights=[('car', 0.45), ('pedestrian', 0.3), ('cyclist', 0.25)],
    place_half_angle=math.radians(80), odom_sigma=(0.08, 0.04, 0.015),
    world_id=0, mover_id_base=1, mover_id_step=1, standing=1,
    reverse=False, seed=4501)
PRESETS = {
    'sick': dict(BASE),
    'consecutive': dict(
        BASE, travel=None, interval=0.1, ego_speed=(0.0, 12.0),
        odom_sigma=(0.02, 0.01, 0.005), seed=4502),
    'lidar360': dict(
        BASE, beams=720, a0=-math.pi, da=2 * math.pi / 720, rmax=25.0,
        sigma=0.015, travel=None, interval=0.1, ego_speed=(1.0, 8.0),
        movers=(1, 6), place_half_angle=math.pi,
        kind_weights=[('car', 0.25), ('pedestrian', 0.55),
                      ('cyclist', 0.2)],
        odom_sigma=(0.03, 0.02, 0.008), mover_id_base=10, mover_id_step=7,
        standing=2, seed=4503),
    # The seed of sick: the same scenes, the points stored clockwise.
    'clockwise': dict(BASE, reverse=True),
}


# ------------------------------------------------------------- 2D poses
def wrap(angle):
    """The angle wrapped into [-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def compose(a, b):
    """The pose a * b of poses (x, y, theta)."""
    ca, sa = math.cos(a[2]), math.sin(a[2])
    return (a[0] + ca * b[0] - sa * b[1], a[1] + sa * b[0] + ca * b[1],
            wrap(a[2] + b[2]))


def inverse(a):
    """The inverse of pose a."""
    ca, sa = math.cos(a[2]), math.sin(a[2])
    return (-(ca * a[0] + sa * a[1]), -(-sa * a[0] + ca * a[1]), wrap(-a[2]))


def apply(a, p):
    """Point p mapped by pose a."""
    ca, sa = math.cos(a[2]), math.sin(a[2])
    return (a[0] + ca * p[0] - sa * p[1], a[1] + sa * p[0] + ca * p[1])


# ------------------------------------------------------------- geometry
def orientation(a, b, c):
    """Twice the signed area of triangle abc (> 0: counter-clockwise)."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def segments_cross(p1, p2, q1, q2):
    """Whether segments p1p2 and q1q2 cross (touching does not count)."""
    return (orientation(q1, q2, p1) * orientation(q1, q2, p2) < 0
            and orientation(p1, p2, q1) * orientation(p1, p2, q2) < 0)


def point_in_polygon(p, polygon):
    """Whether p lies inside the closed polygon (even-odd rule)."""
    x, y = p
    inside = False
    n = len(polygon)
    for i in range(n):
        x1, y1 = polygon[i]
        x2, y2 = polygon[(i + 1) % n]
        if (y1 > y) != (y2 > y):
            if x1 + (y - y1) * (x2 - x1) / (y2 - y1) > x:
                inside = not inside
    return inside


def point_segment_distance(p, a, b):
    """Distance from point p to segment ab."""
    ex, ey = b[0] - a[0], b[1] - a[1]
    length2 = ex * ex + ey * ey
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, (
        (p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / length2))
    return math.hypot(a[0] + t * ex - p[0], a[1] + t * ey - p[1])


class Shape:
    """A closed polygon or an open polyline (a wall) in world coordinates."""

    def __init__(self, points, closed=True):
        self.points = points
        self.closed = closed
        n = len(points)
        self.edges = [(points[i], points[(i + 1) % n])
                      for i in range(n if closed else n - 1)]
        cx = sum(p[0] for p in points) / n
        cy = sum(p[1] for p in points) / n
        self.centre = (cx, cy)
        self.radius = max(math.hypot(p[0] - cx, p[1] - cy)
                          for p in points) + 1e-6

    def distance_to(self, p):
        """Distance from p to the outline (0 inside a closed shape)."""
        d = min(point_segment_distance(p, a, b) for a, b in self.edges)
        if self.closed and point_in_polygon(p, self.points):
            return 0.0
        return d

    def overlaps(self, other, margin=0.0):
        """Whether the shapes intersect or come closer than margin."""
        if math.hypot(self.centre[0] - other.centre[0],
                      self.centre[1] - other.centre[1]) > \
                self.radius + other.radius + margin:
            return False
        if any(segments_cross(a, b, c, d)
               for a, b in self.edges for c, d in other.edges):
            return True
        if self.closed and point_in_polygon(other.points[0], self.points):
            return True
        if other.closed and point_in_polygon(self.points[0], other.points):
            return True
        return margin > 0 and (
            any(other.distance_to(p) < margin for p in self.points)
            or any(self.distance_to(p) < margin for p in other.points))


def segment_shape_distance(a, b, shape):
    """Distance from segment ab to a shape, sampled every 0.25 m."""
    for e0, e1 in shape.edges:
        if segments_cross(a, b, e0, e1):
            return 0.0
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    n = max(2, int(length / 0.25) + 1)
    best = 1e18
    for i in range(n + 1):
        t = i / n
        p = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
        if math.hypot(p[0] - shape.centre[0], p[1] - shape.centre[1]) \
                - shape.radius > best:
            continue
        best = min(best, shape.distance_to(p))
    return best


def cast(origin, angle, shapes, rmax):
    """(range, shape index) of a ray's first hit, or (None, None)."""
    ox, oy = origin
    dx, dy = math.cos(angle), math.sin(angle)
    best = rmax
    who = None
    for k, shape in enumerate(shapes):
        cx, cy = shape.centre[0] - ox, shape.centre[1] - oy
        along = cx * dx + cy * dy
        if abs(cx * dy - cy * dx) > shape.radius or \
                along + shape.radius < 0 or along - shape.radius > best:
            continue
        for (ax, ay), (bx, by) in shape.edges:
            ex, ey = bx - ax, by - ay
            den = dx * ey - dy * ex
            if abs(den) < 1e-14:
                continue
            wx, wy = ax - ox, ay - oy
            t = (wx * ey - wy * ex) / den
            if t <= 1e-9 or t >= best:
                continue
            u = (wx * dy - wy * dx) / den
            if 0.0 <= u <= 1.0:
                best = t
                who = k
    if who is None:
        return None, None
    return best, who


# ------------------------------------------------------------- outlines
def rectangle(length, width):
    """A length x width rectangle centred on the origin, along x."""
    return [(length / 2, width / 2), (-length / 2, width / 2),
            (-length / 2, -width / 2), (length / 2, -width / 2)]


def ellipse(rx, ry, n, phase=0.0):
    """An n-gon on the ellipse of semi-axes rx (along x) and ry."""
    return [(rx * math.cos(phase + 2 * math.pi * i / n),
             ry * math.sin(phase + 2 * math.pi * i / n)) for i in range(n)]


def place(outline, pose):
    """Outline points mapped by pose."""
    return [apply(pose, p) for p in outline]


class Mover:
    """A rigid outline moving at constant speed and yaw rate."""

    def __init__(self, kind, outline, pose0, speed, yaw_rate):
        self.kind = kind
        self.outline = outline
        self.pose0 = pose0
        self.speed = speed
        self.yaw_rate = yaw_rate

    def pose(self, t):
        """The pose at time t after the source scan."""
        x, y, h = self.pose0
        v, w = self.speed, self.yaw_rate
        if abs(w) < 1e-9:
            return (x + v * t * math.cos(h), y + v * t * math.sin(h), h)
        h1 = h + w * t
        return (x + v / w * (math.sin(h1) - math.sin(h)),
                y - v / w * (math.cos(h1) - math.cos(h)), wrap(h1))

    def shape(self, t):
        """The outline in world coordinates at time t."""
        return Shape(place(self.outline, self.pose(t)))


# ------------------------------------------------------------- sensor path
def ego_path(pose0, motion, duration, vmax, steps=400):
    """The sensor's poses over duration (steps + 1 of them).

    motion is (speed, acceleration, yaw rate, yaw acceleration) at time 0.
    """
    v0, acc, w0, wacc = motion
    poses = [pose0]
    x, y, h = pose0
    dt = duration / steps
    for i in range(steps):
        t = (i + 0.5) * dt
        v = min(vmax, max(0.0, v0 + acc * t))
        w = w0 + wacc * t
        x += v * dt * math.cos(h + w * dt / 2)
        y += v * dt * math.sin(h + w * dt / 2)
        h += w * dt
        poses.append((x, y, wrap(h)))
    return poses


def path_length(poses):
    """Length of the polyline through the poses."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1])
               for a, b in zip(poses, poses[1:]))


def duration_for_length(pose0, motion, vmax, length):
    """The time (to 0.1 ms) in which the sensor travels length metres."""
    lo, hi = 0.0, 5.0
    for _ in range(40):
        mid = (lo + hi) / 2
        travelled = path_length(ego_path(pose0, motion, mid, vmax, 100))
        lo, hi = (mid, hi) if travelled < length else (lo, mid)
    return round((lo + hi) / 2, 4)


def draw_sensor_path(rng, cfg):
    """A random sensor path from the source to the target scan.

    Returns its poses and its duration [s].
    """
    pose0 = (rng.uniform(-50, 50), rng.uniform(-50, 50),
             rng.uniform(-math.pi, math.pi))
    motion = (rng.uniform(*cfg['ego_speed']), rng.uniform(-1.5, 1.5),
              rng.uniform(-cfg['ego_yaw'], cfg['ego_yaw']),
              rng.uniform(-0.3, 0.3))
    if cfg['travel']:
        length = rng.uniform(*cfg['travel'])
        duration = duration_for_length(pose0, motion, cfg['ego_vmax'], length)
    else:
        duration = cfg['interval']
    return ego_path(pose0, motion, duration, cfg['ego_vmax']), duration


# ------------------------------------------------------------- static world
def corridor_segments(path):
    """Segments along the sensor's path, and 3 m on past its end."""
    segments = [(path[i][:2], path[min(i + 40, len(path) - 1)][:2])
                for i in range(0, len(path) - 1, 40)]
    x, y, h = path[-1]
    segments.append(((x, y), (x + 3 * math.cos(h), y + 3 * math.sin(h))))
    return segments


def clear_of_corridor(shape, corridor, clearance):
    """Whether shape keeps clearance metres from every corridor segment."""
    for a, b in corridor:
        if math.hypot((a[0] + b[0]) / 2 - shape.centre[0],
                      (a[1] + b[1]) / 2 - shape.centre[1]) > \
                shape.radius + clearance + 5:
            continue
        if segment_shape_distance(a, b, shape) < clearance:
            return False
    return True


def random_position(rng, centre, rmin, rmax):
    """A point at a uniform bearing and distance rmin..rmax from centre."""
    a = rng.uniform(-math.pi, math.pi)
    r = rng.uniform(rmin, rmax)
    return (centre[0] + r * math.cos(a), centre[1] + r * math.sin(a))


def draw_building(rng, origin):
    """A star-shaped polygon of 5-9 corners, 8-38 m from origin."""
    c = random_position(rng, origin, 8, 38)
    n = rng.randint(5, 9)
    base = rng.uniform(3, 10)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
    return [Shape([(c[0] + base * rng.uniform(0.6, 1.3) * math.cos(a),
                    c[1] + base * rng.uniform(0.6, 1.3) * math.sin(a))
                   for a in angles])]


def draw_wall(rng, origin):
    """A wall or fence of 1-3 straight runs, starting 5-30 m from origin."""
    p = random_position(rng, origin, 5, 30)
    h = rng.uniform(-math.pi, math.pi)
    points = [p]
    for _ in range(rng.randint(1, 3)):
        length = rng.uniform(3, 15)
        h += rng.choice([0.0, math.pi / 2, -math.pi / 2, rng.uniform(-1, 1)])
        p = (p[0] + length * math.cos(h), p[1] + length * math.sin(h))
        points.append(p)
    return [Shape(points, closed=False)]


def draw_parked_row(rng, origin):
    """A row of 3-10 parking bays, a quarter of them empty."""
    p = random_position(rng, origin, 4, 25)
    h = rng.uniform(-math.pi, math.pi)
    row = []
    for k in range(rng.randint(3, 10)):
        if rng.random() < 0.25:
            continue
        length, width = rng.uniform(3.8, 5.0), rng.uniform(1.6, 2.0)
        offset = k * 2.6
        pose = (p[0] + offset * math.cos(h), p[1] + offset * math.sin(h),
                wrap(h + math.pi / 2 + rng.uniform(-0.08, 0.08)))
        row.append(Shape(place(rectangle(length, width), pose)))
    return row


def draw_pole(rng, origin):
    """A pole (radius 5-12 cm) or a tree (15-45 cm), 2.5-30 m away."""
    x, y = random_position(rng, origin, 2.5, 30)
    r = rng.choice([rng.uniform(0.05, 0.12), rng.uniform(0.15, 0.45)])
    return [Shape(place(ellipse(r, r, 10, phase=rng.uniform(0, 1)),
                        (x, y, 0.0)))]


def make_static(rng, path, cfg):
    """The static world's shapes, clear of a corridor around the path."""
    corridor = corridor_segments(path)
    shapes = []
    for draw, count in ((draw_building, cfg['buildings']),
                        (draw_wall, cfg['walls']),
                        (draw_parked_row, cfg['parked_rows']),
                        (draw_pole, cfg['poles'])):
        for _ in range(rng.randint(*count)):
            for _attempt in range(20):
                group = draw(rng, path[0])
                if group and all(clear_of_corridor(s, corridor,
                                                   cfg['corridor'])
                                 for s in group):
                    shapes.extend(group)
                    break
    return shapes


# ------------------------------------------------------------- movers
def draw_mover(rng, cfg, pose0):
    """A random car, pedestrian or cyclist in front of the sensor."""
    kinds, weights = zip(*cfg['kind_weights'])
    kind = rng.choices(kinds, weights)[0]
    if kind == 'car':
        outline = rectangle(rng.uniform(3.8, 5.0), rng.uniform(1.6, 2.0))
        speed = rng.uniform(2, 15)
        yaw_rate = rng.uniform(-0.5, 0.5) if rng.random() < 0.4 else 0.0
    elif kind == 'pedestrian':
        r = rng.uniform(0.2, 0.35)
        rx = r if rng.random() < 0.5 else r * rng.uniform(0.55, 0.8)
        outline = ellipse(rx, r, 12)
        speed = rng.uniform(0.8, 1.8)
        yaw_rate = rng.uniform(-0.4, 0.4) if rng.random() < 0.3 else 0.0
    else:
        outline = rectangle(1.7, 0.5)
        speed = rng.uniform(3, 7)
        yaw_rate = rng.uniform(-0.3, 0.3) if rng.random() < 0.3 else 0.0
    half = cfg['place_half_angle']
    a = pose0[2] + rng.uniform(-half, half)
    r = rng.uniform(3, cfg['rmax'] * 0.7)
    start = (pose0[0] + r * math.cos(a), pose0[1] + r * math.sin(a),
             rng.uniform(-math.pi, math.pi))
    return Mover(kind, outline, start, speed, yaw_rate)


def mover_fits(mover, duration, static, movers, sensor_points):
    """Whether a mover keeps clear of the sensor, the world and the others.

    At both scan times: 1.5 m from the sensor, 0.1 m from the static world
    and 0.2 m from the movers placed before it.
    """
    start, end = mover.shape(0.0), mover.shape(duration)
    for shape in (start, end):
        if any(shape.distance_to(e) < 1.5 for e in sensor_points):
            return False
        if any(shape.overlaps(s, 0.1) for s in static):
            return False
    return not any(start.overlaps(o.shape(0.0), 0.2)
                   or end.overlaps(o.shape(duration), 0.2) for o in movers)


def make_movers(rng, cfg, static, pose0, pose1, duration):
    """The movers of a scene (each dropped after 200 failed placements)."""
    count = rng.randint(*cfg['movers'])
    movers = []
    for _ in range(count):
        for _attempt in range(200):
            mover = draw_mover(rng, cfg, pose0)
            if mover_fits(mover, duration, static, movers,
                          (pose0[:2], pose1[:2])):
                movers.append(mover)
                break
    return movers


def add_standing_people(rng, cfg, scene):
    """Adds people standing still, each with probability 1/2, to the world.

    They move with the static world, so they carry its label.
    """
    half = cfg['place_half_angle']
    pose0, pose1 = scene.pose0, scene.pose1
    for _ in range(cfg['standing']):
        if rng.random() >= 0.5:
            continue
        a = pose0[2] + rng.uniform(-half, half)
        r = rng.uniform(3, 15)
        radius = rng.uniform(0.2, 0.3)
        person = Shape(place(ellipse(radius, radius, 12),
                             (pose0[0] + r * math.cos(a),
                              pose0[1] + r * math.sin(a), 0)))
        if not any(person.overlaps(s, 0.1) for s in scene.static) and \
                all(person.distance_to(e[:2]) > 1.5
                    for e in (pose0, pose1)) and \
                not any(person.overlaps(m.shape(0), 0.2)
                        or person.overlaps(m.shape(scene.duration), 0.2)
                        for m in scene.movers):
            scene.static.append(person)


# ------------------------------------------------------------- scene
@dataclass
class Scene:
    """The world and the sensor's poses at the two scan times."""

    pose0: tuple
    pose1: tuple
    duration: float
    static: list
    movers: list
    world_id: int
    mover_ids: list

    def shapes(self, t):
        """Every shape at time t (0: source scan, duration: target)."""
        return self.static + [m.shape(t) for m in self.movers]

    def labels(self):
        """The object id of every shape, in the order of shapes()."""
        return [self.world_id] * len(self.static) + self.mover_ids

    def motions(self):
        """The true T_target_source of the world and of every mover."""
        inv1 = inverse(self.pose1)
        motions = {self.world_id: compose(inv1, self.pose0)}
        for mover, oid in zip(self.movers, self.mover_ids):
            motions[oid] = compose(compose(compose(
                inv1, mover.pose(self.duration)), inverse(mover.pose(0.0))),
                self.pose0)
        return motions


def draw_scene(rng, cfg):
    """A random scene: sensor path, static world, movers."""
    path, duration = draw_sensor_path(rng, cfg)
    pose0, pose1 = path[0], path[-1]
    static = make_static(rng, path, cfg)
    movers = make_movers(rng, cfg, static, pose0, pose1, duration)
    mover_ids = [cfg['mover_id_base'] + k * cfg['mover_id_step']
                 for k in range(len(movers))]
    scene = Scene(pose0, pose1, duration, static, movers, cfg['world_id'],
                  mover_ids)
    add_standing_people(rng, cfg, scene)
    return scene


# ------------------------------------------------------------- laser
@dataclass
class Return:
    """One laser return: its object id, noise-free and measured point."""

    label: int
    true_point: tuple
    point: tuple


def scan(rng, pose, shapes, labels, cfg):
    """The returns of a scan from pose, in beam order."""
    returns = []
    rmax = cfg['rmax']
    for b in range(cfg['beams']):
        angle = cfg['a0'] + b * cfg['da']
        r, k = cast(pose[:2], pose[2] + angle, shapes, rmax)
        # Every beam draws its noise and dropout, hit or not.
        noise = rng.gauss(0.0, cfg['sigma'])
        dropped = rng.random() < cfg['dropout']
        if r is None or dropped:
            continue
        measured = r + noise
        if measured >= 0.99999 * rmax or r >= 0.99999 * rmax or \
                measured <= 0.05:
            continue
        c, s = math.cos(angle), math.sin(angle)
        returns.append(Return(labels[k], (r * c, r * s),
                              (measured * c, measured * s)))
    return returns


def visible(q, label, pose1, shapes, labels, cfg):
    """Whether the target sensor sees target-frame point q of object label."""
    rq = math.hypot(q[0], q[1])
    if rq >= cfg['rmax'] * 0.99999:
        return False
    bearing = math.atan2(q[1], q[0])
    da = cfg['da']
    rel = (bearing - cfg['a0']) % (2 * math.pi)
    if rel > (cfg['beams'] - 1) * da + 0.5 * da and \
            not (2 * math.pi - rel) < 0.5 * da:
        return False
    r, k = cast(pose1[:2], pose1[2] + bearing, shapes, cfg['rmax'])
    return r is not None and labels[k] == label and r >= rq - 0.03


def associate(scene, source, target, cfg):
    """The true match (target index or -1) of every source return."""
    motions = scene.motions()
    shapes1 = scene.shapes(scene.duration)
    labels = scene.labels()
    by_label = {}
    for j, t in enumerate(target):
        by_label.setdefault(t.label, []).append(j)
    matches = []
    for s in source:
        q = apply(motions[s.label], s.true_point)
        best, nearest = 1e18, -1
        for j in by_label.get(s.label, []):
            t = target[j].true_point
            d = math.hypot(t[0] - q[0], t[1] - q[1])
            if d < best:
                best, nearest = d, j
        tolerance = 2.0 * math.hypot(q[0], q[1]) * cfg['da'] + 0.02
        if nearest >= 0 and best <= tolerance and \
                visible(q, s.label, scene.pose1, shapes1, labels, cfg):
            matches.append(nearest)
        else:
            matches.append(-1)
    return matches


# ------------------------------------------------------------- pairs
@dataclass
class Pair:
    """A simulated pair as written, and the truth the check needs."""

    lines: list          # pair.txt
    source_rows: list    # (x, y, label, match) in stored order
    target_rows: list    # (x, y, label) in stored order
    motions: dict        # T_target_source by object id
    kinds: list          # what each listed mover is
    surfaces: dict       # noise-free target-frame edges by object id


def number(value):
    """A float as pair.txt stores it (shortest exact decimal)."""
    return repr(float(value))


def draw_scans(rng, cfg):
    """A scene and its two scans, drawn again until both have a return."""
    while True:
        scene = draw_scene(rng, cfg)
        labels = scene.labels()
        source = scan(rng, scene.pose0, scene.shapes(0.0), labels, cfg)
        target = scan(rng, scene.pose1, scene.shapes(scene.duration),
                      labels, cfg)
        if source and target:
            return scene, source, target


def draw_odometry(rng, scene, cfg):
    """The true T_source_target of the sensor with Gaussian noise."""
    sx, sy, st = cfg['odom_sigma']
    noise = (rng.gauss(0, sx), rng.gauss(0, sy), rng.gauss(0, st))
    return compose(compose(inverse(scene.pose0), scene.pose1), noise)


def target_surfaces(scene):
    """Every object's noise-free edges in the target sensor frame."""
    inv1 = inverse(scene.pose1)
    surfaces = {}
    for shape, label in zip(scene.shapes(scene.duration), scene.labels()):
        surfaces.setdefault(label, []).extend(
            (apply(inv1, a), apply(inv1, b)) for a, b in shape.edges)
    return surfaces


def pair_lines(cfg, header, odometry, scene, listed):
    """The lines of pair.txt; listed: the movers' (id, kind) to write."""
    sx, sy, st = cfg['odom_sigma']
    motions = scene.motions()
    world = motions[scene.world_id]
    lines = ['pcl_crf_pair 1', header,
             'sensor %d %s %s %s' % (cfg['beams'], number(cfg['a0']),
                                     number(cfg['da']), number(cfg['rmax'])),
             'odometry %s %s %s' % tuple(number(v) for v in odometry),
             'odometry_covariance %s 0 0 0 %s 0 0 0 %s' % (
                 number(sx * sx), number(sy * sy), number(st * st)),
             'interval %s' % number(scene.duration),
             'object %d static %s %s %s world' % (
                 scene.world_id, number(world[0]), number(world[1]),
                 number(world[2]))]
    for oid, kind in listed:
        m = motions[oid]
        lines.append('object %d moving %s %s %s %s' % (
            oid, number(m[0]), number(m[1]), number(m[2]), kind))
    return lines


def simulate_pair(rng, cfg, header):
    """One random pair of the preset cfg; header: pair.txt's comment."""
    scene, source, target = draw_scans(rng, cfg)
    matches = associate(scene, source, target, cfg)
    odometry = draw_odometry(rng, scene, cfg)
    seen = {r.label for r in source} | {r.label for r in target}
    listed = [(oid, m.kind) for m, oid in zip(scene.movers, scene.mover_ids)
              if oid in seen]
    order = list(range(len(source)))
    target_order = list(range(len(target)))
    if cfg['reverse']:
        order.reverse()
        target_order.reverse()
    stored_index = {j: k for k, j in enumerate(target_order)}
    source_rows = [(source[i].point[0], source[i].point[1], source[i].label,
                    stored_index[matches[i]] if matches[i] >= 0 else -1)
                   for i in order]
    target_rows = [(target[j].point[0], target[j].point[1], target[j].label)
                   for j in target_order]
    lines = pair_lines(cfg, header, odometry, scene, listed)
    motions = {oid: tuple(float(number(v)) for v in m)
               for oid, m in scene.motions().items()}
    return Pair(lines, source_rows, target_rows, motions,
                [kind for _, kind in listed], target_surfaces(scene))


# ------------------------------------------------------------- output
def write_pcd(path, rows, with_match):
    """An ascii PCD of x y z label [match] rows (z written as 0)."""
    if with_match:
        fields = ('FIELDS x y z label match\nSIZE 4 4 4 4 4\n'
                  'TYPE F F F U I\nCOUNT 1 1 1 1 1\n')
        row_format = '%.6f %.6f 0 %d %d\n'
    else:
        fields = ('FIELDS x y z label\nSIZE 4 4 4 4\n'
                  'TYPE F F F U\nCOUNT 1 1 1 1\n')
        row_format = '%.6f %.6f 0 %d\n'
    n = len(rows)
    with open(path, 'w', encoding='ascii', newline='\n') as f:
        f.write('# .PCD v0.7 - Point Cloud Data file format\n'
                'VERSION 0.7\n')
        f.write(fields)
        f.write('WIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n'
                'POINTS %d\nDATA ascii\n' % (n, n))
        f.writelines(row_format % row for row in rows)


def write_pair(folder, pair):
    """Writes pair.txt, source.pcd and target.pcd into folder."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, 'pair.txt'), 'w', encoding='ascii',
              newline='\n') as f:
        f.write('\n'.join(pair.lines) + '\n')
    write_pcd(os.path.join(folder, 'source.pcd'), pair.source_rows, True)
    write_pcd(os.path.join(folder, 'target.pcd'), pair.target_rows, False)


# ------------------------------------------------------------- check
def percentile(values, q):
    """The q-quantile of values (nearest rank below)."""
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


class TruthCheck:
    """Residuals of the true matches, accumulated over the pairs.

    For every matched source point p: |T_o p - t_match| (T_o its object's
    T_target_source as written in pair.txt, t_match the target point it
    is matched to) and the distance of T_o p to object o's noise-free
    outline at the target time, both of the points before their rounding
    to 1 um in the PCD files.  Both hold the range noise; the first also
    the spacing of the beams.
    """

    def __init__(self):
        self.points = 0
        self.match_residuals = []
        self.surface_residuals = []

    def add(self, pair):
        """Adds a pair's matched points."""
        for x, y, label, match in pair.source_rows:
            self.points += 1
            if match < 0:
                continue
            q = apply(pair.motions[label], (x, y))
            t = pair.target_rows[match]
            self.match_residuals.append(math.hypot(q[0] - t[0], q[1] - t[1]))
            self.surface_residuals.append(min(
                point_segment_distance(q, a, b)
                for a, b in pair.surfaces[label]))

    def report(self, name):
        """The summary lines."""
        matched = len(self.match_residuals)
        lines = ['%s: %d source points, %d matched (%.1f %%)' % (
            name, self.points, matched, 100.0 * matched / self.points)]
        for what, values in (
                ('|T_object p_source - p_target[match]|',
                 self.match_residuals),
                ('distance of T_object p_source to the true outline',
                 self.surface_residuals)):
            if values:
                lines.append('  %s [m]: median %.4f  p95 %.4f  max %.4f' % (
                    what, percentile(values, 0.5), percentile(values, 0.95),
                    max(values)))
        return lines


# ------------------------------------------------------------- command line
def parse_arguments(argv):
    """The checked command-line arguments."""
    parser = argparse.ArgumentParser(
        description=__doc__.split('\nUsage:')[0],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--preset', required=True, choices=list(PRESETS),
                        help='sensor and scene setting')
    parser.add_argument('--pairs', type=int, default=30,
                        help='number of pairs (default: 30)')
    parser.add_argument('--seed', type=int,
                        help='random seed (default: the preset\'s own: %s)'
                        % ', '.join('%s %d' % (name, cfg['seed'])
                                    for name, cfg in PRESETS.items()))
    parser.add_argument('-o', '--out', required=True, metavar='DIR',
                        help='dataset folder to write (created if missing)')
    parser.add_argument('--force', action='store_true',
                        help='write into a non-empty DIR, replacing its '
                        'pair_NNNN folders (other contents are kept)')
    parser.add_argument('--check', action='store_true',
                        help='print the residuals of the true matches')
    parser.add_argument('-q', '--quiet', action='store_true',
                        help='no progress line per pair')
    args = parser.parse_args(argv)
    if not 1 <= args.pairs <= MAX_PAIRS:
        parser.error('--pairs must be between 1 and %d, got %d'
                     % (MAX_PAIRS, args.pairs))
    if args.seed is not None and args.seed < 0:
        parser.error('--seed must be a non-negative integer, got %d'
                     % args.seed)
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        parser.error('output %s exists and is not a folder' % args.out)
    if os.path.isdir(args.out) and os.listdir(args.out) and not args.force:
        parser.error('output folder %s is not empty (--force replaces its '
                     'pair_NNNN folders)' % args.out)
    return args


def prepare_output(folder):
    """Creates folder and removes the pair_NNNN folders in it."""
    os.makedirs(folder, exist_ok=True)
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if PAIR_FOLDER.fullmatch(name) and os.path.isdir(path) and \
                not os.path.islink(path):
            shutil.rmtree(path)


def main(argv=None):
    """Writes the dataset; returns the exit status."""
    args = parse_arguments(argv)
    cfg = PRESETS[args.preset]
    seed = cfg['seed'] if args.seed is None else args.seed
    check = TruthCheck()
    try:
        prepare_output(args.out)
        for i in range(args.pairs):
            header = ('# scripts/parking_lot/simulate.py --preset %s '
                      '--seed %d, pair %d' % (args.preset, seed, i))
            pair = simulate_pair(random.Random(seed * 100003 + i), cfg,
                                 header)
            write_pair(os.path.join(args.out, 'pair_%04d' % i), pair)
            check.add(pair)
            if not args.quiet:
                print('%s pair %d: %d source, %d target points, movers: %s'
                      % (args.preset, i, len(pair.source_rows),
                         len(pair.target_rows),
                         ', '.join(pair.kinds) or 'none'), file=sys.stderr)
    except OSError as error:
        print('error: cannot write the dataset: %s' % error, file=sys.stderr)
        return 1
    if args.check:
        print('\n'.join(check.report('%s (seed %d)' % (args.preset, seed))))
    return 0


if __name__ == '__main__':
    sys.exit(main())
