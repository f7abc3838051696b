#!/usr/bin/env python3
"""Writes a denser city than niendorf-urban for bench/compare.sh: `dense-city`.

150 rectangular building footprints (2.5 x niendorf-urban's 60) drawn with a fixed seed over
the same 2.6 km x 2.6 km around niendorf-urban's centre: long sides 50-140 m, short sides
35-100 m (niendorf-urban: 46-160 m and 41-156 m), any orientation, accepted only when its
circumscribed circle keeps 25 m from every earlier one (so no two footprints touch and every
gap between them is at least 25 m wide before the clearance). Vehicle and planner settings are
niendorf-urban's (turn radius 64 m, clearance 7 m, 50 m sample spacing); a start and a goal
with headings at free spots. The result is deterministic: the same file on every run.

Usage: python3 bench/make_dense_city.py OUT.geojson
"""
import json
import math
import random
import sys

SEED = 20240611
BUILDINGS = 150
HALF_SIDE_M = 1300.0
GAP_M = 25.0

lat0, lon0 = 48.0934, 11.6304  # niendorf-urban's centre
m_per_deg_lat = 111_132.0
m_per_deg_lon = 111_320.0 * math.cos(math.radians(lat0))


def geo(x, y):
    return [round(lon0 + x / m_per_deg_lon, 8), round(lat0 + y / m_per_deg_lat, 8)]


def buildings(rng):
    """Centres, half-diagonals and corner lists of the footprints, in metres."""
    placed = []
    while len(placed) < BUILDINGS:
        a, b = rng.uniform(50, 140), rng.uniform(35, 100)
        long_side, short_side = max(a, b), min(a, b)
        cx, cy = rng.uniform(-HALF_SIDE_M, HALF_SIDE_M), rng.uniform(-HALF_SIDE_M, HALF_SIDE_M)
        r = 0.5 * math.hypot(long_side, short_side)
        if any(math.hypot(cx - x, cy - y) < r + s + GAP_M for x, y, s, _ in placed):
            continue
        t = rng.uniform(0, math.pi)
        u, v = (math.cos(t), math.sin(t)), (-math.sin(t), math.cos(t))
        corners = [(cx + i * 0.5 * long_side * u[0] + j * 0.5 * short_side * v[0],
                    cy + i * 0.5 * long_side * u[1] + j * 0.5 * short_side * v[1])
                   for i, j in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        placed.append((cx, cy, r, corners))
    return placed


def free_spot(rng, placed, margin=60.0):
    """A point at least `margin` beyond every footprint's circumscribed circle."""
    while True:
        x, y = rng.uniform(-HALF_SIDE_M, HALF_SIDE_M), rng.uniform(-HALF_SIDE_M, HALF_SIDE_M)
        if all(math.hypot(x - cx, y - cy) > r + margin for cx, cy, r, _ in placed):
            return x, y


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[-1])
    rng = random.Random(SEED)
    placed = buildings(rng)
    features = []
    for k, (_, _, _, corners) in enumerate(placed):
        ring = [geo(x, y) for x, y in corners]
        ring.append(ring[0])
        features.append({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ring]},
                         "properties": {"kind": "no_fly", "name": f"B{k + 1}"}})
    for kind, name, heading in (("start", "P", 45.0), ("goal", "Q", 225.0)):
        x, y = free_spot(rng, placed)
        features.append({"type": "Feature", "geometry": {"type": "Point", "coordinates": geo(x, y)},
                         "properties": {"kind": kind, "name": name, "heading_deg": heading}})
    doc = {
        "type": "FeatureCollection",
        "name": "dense-city",
        "description": f"2.6 km x 2.6 km, {BUILDINGS} building footprints (seed {SEED}), "
                       "niendorf-urban's aircraft and planner settings: bench/make_dense_city.py",
        "vehicle": {"v_nominal_mps": 25.0, "v_min_mps": 20.0, "v_max_mps": 55.0,
                    "a_lat_max_mps2": 9.81, "a_long_min_mps2": -3.0, "a_long_max_mps2": 3.0,
                    "wingspan_m": 3.2},
        "planner": {"mode": "roadmap", "sample_spacing_m": 50.0, "neighbour_radius_m": 191.1,
                    "k_nearest_fallback": 8, "allow_ccc": True, "clearance_m": 7.0,
                    "arc_step_m": 40.0, "seed": 1},
        "features": features,
    }
    with open(sys.argv[1], "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
