#!/usr/bin/env python3
"""Writes scenarios/voronoi-dense.geojson: a Voronoi-mode scenario denser than ruz-popups.

30 radar threats drawn with a fixed seed over 60 km x 30 km (the ruz-popups area), two
no-fly polygons, start and goal on the west and east edges. Reference distances 2-4 km as
in ruz-popups. Run from the repository root; the output is committed, so this only documents
how it was made (and remakes it identically).
"""
import json
import math
import random

rng = random.Random(12)
lat0, lon0 = 48.21489805, 12.0138
m_per_deg_lat = 111_132.0
m_per_deg_lon = 111_320.0 * math.cos(math.radians(lat0))


def geo(x, y):
    return [round(lon0 + x / m_per_deg_lon, 8), round(lat0 + y / m_per_deg_lat, 8)]


features = []
sites = []
while len(sites) < 30:
    x, y = rng.uniform(-26_000, 26_000), rng.uniform(-13_000, 13_000)
    if all(math.hypot(x - a, y - b) > 3_000 for a, b in sites):
        sites.append((x, y))
for i, (x, y) in enumerate(sites):
    features.append({"type": "Feature", "geometry": {"type": "Point", "coordinates": geo(x, y)},
                     "properties": {"kind": "threat", "name": f"R{i + 1}",
                                    "radius_m": round(rng.uniform(2000, 4000), 1)}})
for name, (cx, cy, w, h) in {"Z1": (-8_000, 9_000, 3_000, 2_000),
                             "Z2": (10_000, -8_000, 2_500, 3_500)}.items():
    ring = [geo(cx - w, cy - h), geo(cx + w, cy - h), geo(cx + w, cy + h), geo(cx - w, cy + h)]
    ring.append(ring[0])
    features.append({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ring]},
                     "properties": {"kind": "no_fly", "name": name}})
features.append({"type": "Feature", "geometry": {"type": "Point", "coordinates": geo(-30_000, 0)},
                 "properties": {"kind": "start", "name": "P", "heading_deg": 90.0}})
features.append({"type": "Feature", "geometry": {"type": "Point", "coordinates": geo(30_000, 0)},
                 "properties": {"kind": "goal", "name": "Q"}})
doc = {
    "type": "FeatureCollection",
    "name": "voronoi-dense",
    "description": "60 km x 30 km, 30 radar threats (seed 12), 2 no-fly zones: a dense "
                   "Voronoi-mode scenario (Judd & McLain) beside ruz-popups",
    "vehicle": {"v_nominal_mps": 50.0, "v_min_mps": 40.0, "v_max_mps": 60.0,
                "a_lat_max_mps2": 15.0, "a_long_min_mps2": -4.0, "a_long_max_mps2": 4.0,
                "wingspan_m": 5.0},
    "planner": {"mode": "voronoi", "clearance_m": 50.0, "threat_weight": 0.5},
    "features": features,
}
with open("scenarios/voronoi-dense.geojson", "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
