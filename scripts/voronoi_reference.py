#!/usr/bin/env python3
"""Independent reference Voronoi vertices of site sets, computed by SciPy (Qhull).

Writes a CSV with the columns set,kind,x,y (metres): for each site set, its sites (kind
`site`) then the finite Voronoi vertices `scipy.spatial.Voronoi` finds for them (kind
`vertex`). `host-tests/tests/core/voronoi.rs` inserts the sites into `skyroute`'s
`geometry::voronoi::Delaunay` and compares its Voronoi vertices with these.

Every site lies on the core's 1/16 m grid (an integer number of sixteenths, |x| <= 1000 m), so
the core's quantisation does not move it and both sides see exactly the same input. Families:
uniform random sites, random subsets of a small integer lattice (many cocircular and collinear
quadruples), integer points on a circle (one Voronoi vertex for the whole set) with a few
random sites added, and clusters of nearby sites. Qhull works in double precision and merges
nearly-cocircular facets, so the test compares vertex sets within a tolerance, not counts.

Usage: python3 scripts/voronoi_reference.py [OUT_CSV] [SETS] [--seed N]
Defaults: target/reference/scipy_voronoi.csv (relative to the repository root), 400 sets.
Needs the PyPI packages `scipy` and `numpy`.
"""

import argparse
import os
import sys

import numpy as np

try:
    from scipy.spatial import Voronoi
except ImportError:  # pragma: no cover - environment problem, explained to the user
    sys.exit("the PyPI package `scipy` is needed: pip install scipy")

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(REPO_ROOT, "target", "reference", "scipy_voronoi.csv")
DEFAULT_SETS = 400
UNITS = 16  # grid units per metre


def uniform(rng):
    n = int(rng.integers(5, 41))
    return rng.integers(-1000 * UNITS, 1000 * UNITS + 1, size=(n, 2))


def lattice(rng):
    """A random subset of a k x k integer lattice with spacing s metres."""
    k = int(rng.integers(3, 8))
    s = int(rng.integers(1, 200)) * UNITS // int(rng.choice([1, 2, 4, 8, 16]))
    pts = np.array([(i, j) for i in range(k) for j in range(k)]) * max(s, 1)
    take = int(rng.integers(5, min(40, len(pts)) + 1))
    return pts[rng.choice(len(pts), size=take, replace=False)]


def circle(rng):
    """The integer points of the circle of radius 25 or 65 (scaled), plus a few random sites."""
    r = int(rng.choice([25, 65]))
    pts = [(x, y) for x in range(-r, r + 1) for y in range(-r, r + 1) if x * x + y * y == r * r]
    pts = np.array(pts) * int(rng.integers(1, 8))
    extra = rng.integers(-3 * r, 3 * r + 1, size=(int(rng.integers(0, 4)), 2))
    return np.vstack([pts, extra])


def clusters(rng):
    """Two to four clusters of sites within a few metres of each other."""
    out = []
    for _ in range(int(rng.integers(2, 5))):
        c = rng.integers(-900 * UNITS, 900 * UNITS + 1, size=2)
        m = int(rng.integers(2, 10))
        out.append(c + rng.integers(-5 * UNITS, 5 * UNITS + 1, size=(m, 2)))
    return np.vstack(out)


FAMILIES = [uniform, lattice, circle, clusters]


def site_set(rng, i):
    """Distinct grid sites, not all collinear (Qhull needs a full-dimensional input)."""
    while True:
        pts = np.unique(FAMILIES[i % len(FAMILIES)](rng), axis=0)
        if len(pts) >= 3 and np.linalg.matrix_rank(pts[1:] - pts[0]) == 2:
            return pts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default=DEFAULT_OUT, help="output CSV path")
    ap.add_argument("sets", nargs="?", type=int, default=DEFAULT_SETS, help="number of site sets")
    ap.add_argument("--seed", type=int, default=20240917, help="numpy seed")
    args = ap.parse_args()
    if args.sets < 1:
        sys.exit("SETS must be positive")
    rng = np.random.default_rng(args.seed)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    tmp = args.out + ".tmp"
    with open(tmp, "w") as f:
        f.write("set,kind,x,y\n")
        for i in range(args.sets):
            units = site_set(rng, i)
            sites = units.astype(np.float64) / UNITS  # exact: sixteenths of small integers
            vor = Voronoi(sites)
            for x, y in sites.tolist():
                f.write(f"{i},site,{x!r},{y!r}\n")
            for x, y in vor.vertices.tolist():
                f.write(f"{i},vertex,{x!r},{y!r}\n")
    os.replace(tmp, args.out)
    print(f"wrote {args.sets} site sets to {args.out}")


if __name__ == "__main__":
    main()
