#!/usr/bin/env python3
"""Generates babel-III-zigzag.geojson: Babel's scenario III as the paper tells it.

The paper's scenario III: at the nominal 12.5 km range the route flies long legs, and with every
rosette degraded to 70 % (8.75 km) it zig-zags through closer landmarks. The shared
babel-III.geojson cannot show this (no landmark is within 12.5 km of its start, and its random
landmarks leave no route at 70 %), so this file keeps babel-III's area, vehicle, planner, start,
goal, weathers and its 18 no-fly zones, and lays out its 50 landmarks so that both routes exist:

* M1 ... M8, the main row: about every 11.5 km along the start-goal line (M1 8 km from the
  start), each north or south of the line (0.25 km steps, at most 2.5 km): of the offsets that
  keep every straight leg of the row 0.6 km clear of every zone, those with the least total
  change of offset along the row.
  Consecutive main landmarks are 11.3-11.9 km apart: within 12.5 km, beyond 8.75 km.
* A1 ... A8, the alternates: one beside the middle of each main leg (and of M8 -> goal), 3 km to
  its north or south, alternating, with the side or the offset (2.5-3.5 km) changed where a
  zone is in the way. Each is within 8.75 km of both ends of its leg, so at 70 % the route can
  only go M, A, M, A, ...: the zig-zag.
* L1 ... L34: babel-III's landmarks L1-L34 where they are (its L35-L50 are dropped to keep 50).

Every landmark keeps babel-III's rosettes (1.0 in every heading; `degraded` 0.7) and d_max
12.5 km. Positions are computed in kilometres east (x) and north (y) of the start with a local
spherical approximation (a few metres over 100 km; the ground tool measures everything in its
own projection, so nothing depends on it).

Run: python3 scenarios/babel-III-zigzag.py > scenarios/babel-III-zigzag.geojson
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
R = 6371000.0
CLEAR_KM = 0.6
MAIN_SPACING_KM = 11.5
FIRST_MAIN_KM = 8.0
MAIN_COUNT = 8
ALT_OFFSET_KM = 3.0
DEGRADED_RANGE_KM = 8.75
NOMINAL_RANGE_KM = 12.5

shared = json.load(open(os.path.join(HERE, "babel-III.geojson")))
start = next(f for f in shared["features"] if f["properties"]["kind"] == "start")
goal = next(f for f in shared["features"] if f["properties"]["kind"] == "goal")
LON0, LAT0 = start["geometry"]["coordinates"]


def local(lon, lat):
    """Kilometres east and north of the start."""
    x = math.radians(lon - LON0) * R * math.cos(math.radians(LAT0)) / 1000.0
    y = math.radians(lat - LAT0) * R / 1000.0
    return x, y


def geo(x, y):
    lat = LAT0 + math.degrees(y * 1000.0 / R)
    lon = LON0 + math.degrees(x * 1000.0 / (R * math.cos(math.radians(LAT0))))
    return [round(lon, 8), round(lat, 8)]


zones = [[local(*c) for c in f["geometry"]["coordinates"][0]]
         for f in shared["features"] if f["properties"]["kind"] == "no_fly"]


def seg_dist(p, a, b):
    """Distance from point p to segment a b."""
    (px, py), (ax, ay), (bx, by) = p, a, b
    dx, dy = bx - ax, by - ay
    t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def inside(p, ring):
    x, y = p
    c = False
    for (x1, y1), (x2, y2) in zip(ring, ring[1:] + ring[:1]):
        if (y1 > y) != (y2 > y) and x < (x2 - x1) * (y - y1) / (y2 - y1) + x1:
            c = not c
    return c


def segments_cross(a, b, c, d):
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    return (orient(a, b, c) * orient(a, b, d) < 0) and (orient(c, d, a) * orient(c, d, b) < 0)


def leg_clear(a, b):
    """Whether the straight leg a b keeps CLEAR_KM from every zone."""
    for ring in zones:
        edges = list(zip(ring, ring[1:] + ring[:1]))
        if inside(a, ring) or inside(b, ring):
            return False
        if any(segments_cross(a, b, u, v) for u, v in edges):
            return False
        if min(min(seg_dist(u, a, b) for u, _ in edges),
               min(seg_dist(a, u, v) for u, v in edges),
               min(seg_dist(b, u, v) for u, v in edges)) < CLEAR_KM:
            return False
    return True


def offsets(limit_km, step_km):
    """0, +step, -step, +2 step, ... up to limit_km."""
    yield 0.0
    k = 1
    while k * step_km <= limit_km + 1e-9:
        yield k * step_km
        yield -k * step_km
        k += 1


goal_xy = local(*goal["geometry"]["coordinates"])
main_x = [FIRST_MAIN_KM + k * MAIN_SPACING_KM for k in range(MAIN_COUNT)]
ys = [k * 0.25 for k in range(-10, 11)]


def main_leg_ok(a, b):
    return a[0] == 0.0 or DEGRADED_RANGE_KM + 0.5 <= math.dist(a, b) <= NOMINAL_RANGE_KM - 0.5


# Dynamic programme over the main row's offsets: the least total change of offset along the row
# whose every leg is clear of the zones and of a length only the nominal range allows.
best = {0.0: (0.0, [])}
prev_x = 0.0
for x in main_x:
    nxt = {}
    for y in ys:
        options = [(cost + abs(y - py), row) for py, (cost, row) in best.items()
                   if main_leg_ok((prev_x, py), (x, y)) and leg_clear((prev_x, py), (x, y))]
        if options:
            cost, row = min(options)
            nxt[y] = (cost + abs(y) * 1e-3, row + [(x, y)])
    best, prev_x = nxt, x
if not best:
    raise SystemExit("no clear main row")
main = min(best.values())[1]

alternates = []
for k, (a, b) in enumerate(zip(main, main[1:] + [goal_xy])):
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    side = 1 if k % 2 == 0 else -1
    candidates = [(s * side, off) for s in (1, -1) for off in (ALT_OFFSET_KM, 2.5, 3.5)]
    for s, off in candidates:
        p = (mx, my + s * off)
        if (leg_clear(a, p) and leg_clear(p, b)
                and math.dist(a, p) <= DEGRADED_RANGE_KM - 0.5
                and math.dist(p, b) <= DEGRADED_RANGE_KM - 0.5):
            alternates.append(p)
            break
    else:
        raise SystemExit(f"no clear alternate beside the leg {a} -> {b}")

for a, b in zip(main, main[1:]):
    d = math.dist(a, b)
    assert DEGRADED_RANGE_KM < d <= NOMINAL_RANGE_KM - 0.5, (a, b, d)

kept = [f for f in shared["features"] if f["properties"]["kind"] == "landmark"][:34]
template = kept[0]["properties"]


def landmark(name, xy):
    return {"type": "Feature", "geometry": {"type": "Point", "coordinates": geo(*xy)},
            "properties": {"kind": "landmark", "name": name, "d_max_m": template["d_max_m"],
                           "quality": template["quality"]}}


features = [f for f in shared["features"] if f["properties"]["kind"] == "no_fly"]
features += [landmark(f"M{k + 1}", p) for k, p in enumerate(main)]
features += [landmark(f"A{k + 1}", p) for k, p in enumerate(alternates)]
features += kept + [start, goal]

doc = {k: v for k, v in shared.items() if k != "features"}
doc["name"] = "babel-III-zigzag"
doc["description"] = (
    "Babel's scenario III as the paper tells it: at 12.5 km the route flies long legs, at 70 % "
    "(8.75 km, weather 'degraded') it zig-zags through closer landmarks. babel-III's area, "
    "vehicle, planner, start, goal, weathers and zones; its 50 landmarks are a main row M1-M8 "
    "about every 11.5 km along the start-goal line (within 12.5 km of each other, beyond "
    "8.75 km), an alternate A1-A8 beside the middle of each main leg 2.5-3.5 km to alternating "
    "sides (within 8.75 km of both ends), and babel-III's L1-L34 where they are. Generated by "
    "babel-III-zigzag.py.")
doc["features"] = features
print(json.dumps(doc, indent=1))
