#!/usr/bin/env python3
"""Independent reference points of skyroute's local frame, computed by PROJ (pyproj).

For the frame origin of every shipped scenario (scenarios/*.geojson: the centre of the
bounding box of its points and no-fly outer rings, as the ground tool's
`Scenario::local_frame` takes it), PROJ's

    +proj=tmerc +lat_0=LAT0 +lon_0=LON0 +k=1 +x_0=0 +y_0=0 +ellps=WGS84

gives, at POINTS local positions within +-50 km east and north of the origin (an 11 x 11 grid
with 10 km spacing, corners included, and random points), the longitude and latitude
(inverse), the projected x, y of that longitude and latitude (forward), the meridian
convergence (degrees, as PROJ's `get_factors` reports it) and the point scale.
`host-tests/tests/core/geo.rs` compares `skyroute::geo::LocalFrame` with these and reports the
largest differences; it also checks that the origins here are the shipped scenarios' origins.

Writes a CSV with the columns
    scenarios,origin_lat,origin_lon,lon,lat,x,y,convergence_deg,scale
(`scenarios`: the names of the scenarios sharing that origin, joined by `;`), floats written
with Python's repr (shortest exact round trip).

Usage: python3 scripts/pyproj_tmerc_reference.py [OUT_CSV] [--seed N] [--random N]
Default OUT_CSV: host-tests/data/pyproj_tmerc.csv (the committed reference).
Needs the PyPI package `pyproj`.
"""

import argparse
import glob
import json
import os
import random
import sys

try:
    import pyproj
except ImportError:  # pragma: no cover - environment problem, explained to the user
    sys.exit("the PyPI package `pyproj` is needed: pip install pyproj")

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(REPO_ROOT, "host-tests", "data", "pyproj_tmerc.csv")
HALF_EXTENT_M = 50_000.0
GRID_STEP_M = 10_000.0


def scenario_points(path):
    """Every (lon, lat) the ground tool puts in a scenario's extent: Point features and the
    outer ring of Polygon features."""
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    for feature in doc["features"]:
        geom = feature["geometry"]
        if geom["type"] == "Point":
            yield tuple(geom["coordinates"][:2])
        elif geom["type"] == "Polygon":
            for c in geom["coordinates"][0]:
                yield tuple(c[:2])
        else:
            sys.exit(f"{path}: geometry {geom['type']} not handled")


def origin(path):
    """The centre of the bounding box, (lat, lon): 0.5 * (min + max) as the ground tool takes
    it (no shipped scenario crosses the antimeridian)."""
    pts = list(scenario_points(path))
    lons = [p[0] for p in pts]
    lats = [p[1] for p in pts]
    if max(lons) - min(lons) > 180.0:
        sys.exit(f"{path}: crosses the antimeridian; not handled here")
    return 0.5 * (min(lats) + max(lats)), 0.5 * (min(lons) + max(lons))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default=DEFAULT_OUT)
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--random", type=int, default=29, help="random points per origin")
    args = ap.parse_args()
    rng = random.Random(args.seed)

    origins = {}
    for path in sorted(glob.glob(os.path.join(REPO_ROOT, "scenarios", "*.geojson"))):
        name = os.path.basename(path)[: -len(".geojson")]
        origins.setdefault(origin(path), []).append(name)

    n = int(round(HALF_EXTENT_M / GRID_STEP_M))
    grid = [i * GRID_STEP_M for i in range(-n, n + 1)]
    rows = []
    for (lat0, lon0), names in origins.items():
        proj = pyproj.Proj(
            f"+proj=tmerc +lat_0={lat0!r} +lon_0={lon0!r} +k=1 +x_0=0 +y_0=0 +ellps=WGS84"
        )
        local = [(x, y) for x in grid for y in grid]
        local += [
            (rng.uniform(-HALF_EXTENT_M, HALF_EXTENT_M), rng.uniform(-HALF_EXTENT_M, HALF_EXTENT_M))
            for _ in range(args.random)
        ]
        for x0, y0 in local:
            lon, lat = proj(x0, y0, inverse=True)
            x, y = proj(lon, lat)
            factors = proj.get_factors(lon, lat)
            rows.append(
                (
                    ";".join(names),
                    lat0,
                    lon0,
                    lon,
                    lat,
                    x,
                    y,
                    factors.meridian_convergence,
                    factors.meridional_scale,
                )
            )

    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(
            f"# PROJ {pyproj.proj_version_str} (pyproj {pyproj.__version__}): "
            "python3 scripts/pyproj_tmerc_reference.py\n"
        )
        f.write("scenarios,origin_lat,origin_lon,lon,lat,x,y,convergence_deg,scale\n")
        for r in rows:
            f.write(",".join([r[0]] + [repr(float(v)) for v in r[1:]]) + "\n")
    print(f"{len(rows)} points around {len(origins)} origins -> {args.out}")


if __name__ == "__main__":
    main()
