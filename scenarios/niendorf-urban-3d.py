#!/usr/bin/env python3
"""Generates niendorf-urban-3d.geojson: niendorf-urban as Niendorf et al.'s three-dimensional
roadmap.

niendorf-urban's area, vehicle, planner parameters, buildings, start, four free-heading
waypoints and goal, with what makes it three-dimensional (the repository's extension of the
format, scenarios/README.md):
- every building a height, from a fixed seed: a third of them (those with the smallest of one
  uniform draw each, in file order) low, 15-40 m, that the aircraft may fly over, the others
  tall, 150-300 m, above every altitude it flies; then each height uniform in its range, drawn
  in file order (only random.random() is used: its sequence for a seed is the same in every
  Python version);
- the planner's altitude band, 40-120 m (samples take altitudes in it);
- the vehicle's climb rate v_c 10 m/s and vertical acceleration a_z 20 m/s^2 (the paper's);
- the start, the waypoints and the goal at 60 m.

The seed, 9, is the one of 1-12 whose network gives the shortest route over its graph through
the stops (each taken as its nearest vertex; prep/tests/roadmap_3d.rs): 11 081 m, against
11 381 m over the planar niendorf-urban's, 8 of its 60 edges over a low building.

Run: python3 scenarios/niendorf-urban-3d.py > scenarios/niendorf-urban-3d.geojson
"""
import json
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

SEED = 9
LOW_M = (15.0, 40.0)
TALL_M = (150.0, 300.0)
ALTITUDE_BAND_M = (40.0, 120.0)
ENDPOINT_ALTITUDE_M = 60.0

urban = json.load(open(os.path.join(HERE, "niendorf-urban.geojson")))
rng = random.Random(SEED)
features = json.loads(json.dumps(urban["features"]))
buildings = [f for f in features if f["properties"]["kind"] == "no_fly"]
keys = [rng.random() for _ in buildings]
low_ones = set(sorted(range(len(buildings)), key=lambda i: keys[i])[:len(buildings) // 3])
for i, f in enumerate(buildings):
    lo, hi = LOW_M if i in low_ones else TALL_M
    f["properties"]["height_m"] = round(lo + (hi - lo) * rng.random(), 1)
for f in features:
    if f["properties"]["kind"] != "no_fly":
        f["properties"]["altitude_m"] = ENDPOINT_ALTITUDE_M

doc = {k: v for k, v in urban.items() if k != "features"}
doc["name"] = "niendorf-urban-3d"
doc["description"] = (
    "niendorf-urban as a three-dimensional roadmap (Niendorf et al.): the same 3 km x 3 km area, "
    "vehicle (r_min 64 m, v_c 10 m/s, a_z 20 m/s^2), planner parameters and %d building "
    "footprints, %d of them low (15-40 m, flown over) and the others tall (150-300 m); samples "
    "in the altitude band %g-%g m; start, 4 free-heading waypoints and goal at %g m. Generated "
    "by niendorf-urban-3d.py (seed %d)."
    % (len(buildings), len(low_ones), ALTITUDE_BAND_M[0], ALTITUDE_BAND_M[1], ENDPOINT_ALTITUDE_M, SEED))
doc["vehicle"] = dict(urban["vehicle"], climb_rate_mps=10.0, vertical_accel_mps2=20.0)
doc["planner"] = dict(
    urban["planner"], altitude_min_m=ALTITUDE_BAND_M[0], altitude_max_m=ALTITUDE_BAND_M[1])
doc["features"] = features
print(json.dumps(doc, indent=1))
