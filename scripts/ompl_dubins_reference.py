#!/usr/bin/env python3
"""Independent reference lengths of Dubins shortest paths, computed by OMPL.

Writes a CSV with the columns x0,y0,h0,x1,y1,h1,r,ompl_length (metres, radians counter-clockwise
from east; OMPL's yaw uses the same convention) that `host-tests/tests/core/dubins.rs` compares with
`skyroute::DubinsPath::shortest`.

Every input is rounded to f32 *before* OMPL sees it, so the Rust test (which works in f32)
evaluates exactly the same poses: the Dubins distance is discontinuous in the goal pose, and a
reference computed for slightly different inputs could differ by a full loop.

OMPL's `DubinsStateSpace(r, isSymmetric=False)` is used: its `distance(a, b)` is the length of
the shortest forward path from `a` to `b` (the symmetric variant would take the minimum over
both directions, which is not what an aircraft can fly).

Usage: python3 scripts/ompl_dubins_reference.py [OUT_CSV] [ROWS] [--seed N]
Defaults: target/reference/ompl_dubins.csv (relative to the repository root), 120000 rows.
Needs the PyPI wheels `ompl` and `numpy`.
"""

import argparse
import math
import os
import sys

import numpy as np

try:
    from ompl import base as ob
except ImportError:  # pragma: no cover - environment problem, explained to the user
    sys.exit("the PyPI package `ompl` is needed: pip install ompl")

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(REPO_ROOT, "target", "reference", "ompl_dubins.csv")
DEFAULT_ROWS = 120_000
TAU = 2.0 * math.pi

# Share of the rows per family (the random family takes the remainder).
FAMILIES = {
    "coincident": 0.02,
    "nearly_coincident": 0.06,
    "on_turning_circle": 0.08,
    "heading_wrap": 0.06,
    "centres_near_2r": 0.06,
    "centres_near_4r": 0.06,
    "large_coordinates": 0.10,
}


def radii(rng, n):
    """Turn radii, log-uniform over 10..500 m."""
    return np.exp(rng.uniform(math.log(10.0), math.log(500.0), n))


def headings(rng, n):
    """Headings in assorted representations: (-pi, pi], [0, 2pi) and a few beyond +-2pi."""
    h = rng.uniform(-math.pi, math.pi, n)
    kind = rng.integers(0, 10, n)
    h = np.where(kind == 7, np.mod(h, TAU), h)  # [0, 2pi)
    h = np.where(kind == 8, h + TAU * rng.integers(-3, 4, n), h)  # several turns off
    return h


def signed_log_uniform(rng, lo, hi, n):
    return rng.choice([-1.0, 1.0], n) * np.exp(rng.uniform(math.log(lo), math.log(hi), n))


def random_pairs(rng, n, offset_lo=0.0, offset_hi=0.0):
    """Goal at a distance log-uniform over 0.01r..20r in a uniform direction."""
    r = radii(rng, n)
    dist = r * np.exp(rng.uniform(math.log(0.01), math.log(20.0), n))
    ang = rng.uniform(-math.pi, math.pi, n)
    x0 = rng.uniform(-500.0, 500.0, n)
    y0 = rng.uniform(-500.0, 500.0, n)
    if offset_hi > 0.0:
        x0 = x0 + signed_log_uniform(rng, offset_lo, offset_hi, n)
        y0 = y0 + signed_log_uniform(rng, offset_lo, offset_hi, n)
    x1 = x0 + dist * np.cos(ang)
    y1 = y0 + dist * np.sin(ang)
    return x0, y0, headings(rng, n), x1, y1, headings(rng, n), r


def coincident(rng, n):
    """The same position; the same heading, or (a third of them) a turn in place."""
    r = radii(rng, n)
    x0 = rng.uniform(-3000.0, 3000.0, n)
    y0 = rng.uniform(-3000.0, 3000.0, n)
    h0 = headings(rng, n)
    h1 = np.where(rng.integers(0, 3, n) == 0, headings(rng, n), h0)
    return x0, y0, h0, x0.copy(), y0.copy(), h1, r


def nearly_coincident(rng, n):
    """Positions 1e-4..1e-2 m apart; headings equal, a hair apart, or unrelated."""
    r = radii(rng, n)
    x0 = rng.uniform(-500.0, 500.0, n)
    y0 = rng.uniform(-500.0, 500.0, n)
    dist = np.exp(rng.uniform(math.log(1e-4), math.log(1e-2), n))
    ang = rng.uniform(-math.pi, math.pi, n)
    h0 = headings(rng, n)
    kind = rng.integers(0, 3, n)
    h1 = np.where(
        kind == 0,
        h0,
        np.where(kind == 1, h0 + signed_log_uniform(rng, 1e-6, 1e-2, n), headings(rng, n)),
    )
    return x0, y0, h0, x0 + dist * np.cos(ang), y0 + dist * np.sin(ang), h1, r


def on_turning_circle(rng, n):
    """Goal on the start's left or right turning circle, heading tangent (same turn sense).

    The turn angle is uniform over (0, 2pi) for half of them, tiny (1e-5..1e-2 rad) or within
    1e-5..1e-2 rad of a full turn for the rest.
    """
    r = radii(rng, n)
    x0 = rng.uniform(-500.0, 500.0, n)
    y0 = rng.uniform(-500.0, 500.0, n)
    h0 = rng.uniform(-math.pi, math.pi, n)
    sign = rng.choice([-1.0, 1.0], n)  # +1 left, -1 right
    kind = rng.integers(0, 4, n)
    small = np.exp(rng.uniform(math.log(1e-5), math.log(1e-2), n))
    theta = np.where(kind <= 1, rng.uniform(0.0, TAU, n), np.where(kind == 2, small, TAU - small))
    # Centre = position + r * sign * left normal; the goal is the start rotated about it.
    cx = x0 - sign * r * np.sin(h0)
    cy = y0 + sign * r * np.cos(h0)
    h1 = h0 + sign * theta
    x1 = cx + sign * r * np.sin(h1)
    y1 = cy - sign * r * np.cos(h1)
    return x0, y0, h0, x1, y1, h1, r


def heading_wrap(rng, n):
    """Headings straddling the wrap: 359.9 deg vs 0.1 deg, pi - e vs -pi + e, 2pi - e vs e."""
    r = radii(rng, n)
    x0 = rng.uniform(-500.0, 500.0, n)
    y0 = rng.uniform(-500.0, 500.0, n)
    dist = r * np.exp(rng.uniform(math.log(0.01), math.log(20.0), n))
    ang = rng.uniform(-math.pi, math.pi, n)
    x1 = x0 + dist * np.cos(ang)
    y1 = y0 + dist * np.sin(ang)
    eps = np.exp(rng.uniform(math.log(1e-7), math.log(1e-2), n))
    eps2 = np.exp(rng.uniform(math.log(1e-7), math.log(1e-2), n))
    kind = rng.integers(0, 6, n)
    h0 = np.select(
        [kind == 0, kind == 1, kind == 2, kind == 3, kind == 4],
        [np.full(n, math.radians(359.9)), math.pi - eps, TAU - eps, -eps, -math.pi + eps],
        math.pi,
    )
    h1 = np.select(
        [kind == 0, kind == 1, kind == 2, kind == 3, kind == 4],
        [np.full(n, math.radians(0.1)), -math.pi + eps2, eps2, TAU - eps2, math.pi - eps2],
        -math.pi,
    )
    swap = rng.integers(0, 2, n) == 1
    h0, h1 = np.where(swap, h1, h0), np.where(swap, h0, h1)
    # A quarter of them straight ahead or straight behind along the start heading.
    along = rng.integers(0, 4, n) == 0
    x1 = np.where(along, x0 + np.sign(ang) * dist * np.cos(h0), x1)
    y1 = np.where(along, y0 + np.sign(ang) * dist * np.sin(h0), y1)
    return x0, y0, h0, x1, y1, h1, r


def centres_near(rng, n, multiple):
    """A start circle and a goal circle (either turn each) whose centres are `multiple`*r apart,
    exactly or up to a relative 1e-7..1e-2 either way: where CSC inner tangents (2r) and CCC
    words (4r) appear or vanish."""
    r = radii(rng, n)
    x0 = rng.uniform(-500.0, 500.0, n)
    y0 = rng.uniform(-500.0, 500.0, n)
    h0 = headings(rng, n)
    s0 = rng.choice([-1.0, 1.0], n)
    s1 = rng.choice([-1.0, 1.0], n)
    rel = np.where(
        rng.integers(0, 4, n) == 0, 0.0, signed_log_uniform(rng, 1e-7, 1e-2, n)
    )
    dist = multiple * r * (1.0 + rel)
    ang = rng.uniform(-math.pi, math.pi, n)
    c0x = x0 - s0 * r * np.sin(h0)
    c0y = y0 + s0 * r * np.cos(h0)
    c1x = c0x + dist * np.cos(ang)
    c1y = c0y + dist * np.sin(ang)
    h1 = headings(rng, n)
    x1 = c1x + s1 * r * np.sin(h1)
    y1 = c1y - s1 * r * np.cos(h1)
    return x0, y0, h0, x1, y1, h1, r


def large_coordinates(rng, n):
    """The random family, both poses offset by 2000..5000 m on each axis."""
    return random_pairs(rng, n, offset_lo=2000.0, offset_hi=5000.0)


GENERATORS = {
    "coincident": coincident,
    "nearly_coincident": nearly_coincident,
    "on_turning_circle": on_turning_circle,
    "heading_wrap": heading_wrap,
    "centres_near_2r": lambda rng, n: centres_near(rng, n, 2.0),
    "centres_near_4r": lambda rng, n: centres_near(rng, n, 4.0),
    "large_coordinates": large_coordinates,
}


def generate(rows, seed):
    rng = np.random.default_rng(seed)
    parts = []
    used = 0
    for name, share in FAMILIES.items():
        n = int(rows * share)
        parts.append(np.column_stack(GENERATORS[name](rng, n)))
        used += n
    parts.append(np.column_stack(random_pairs(rng, rows - used)))
    data = np.vstack(parts)
    # Round every input to f32: the test then evaluates exactly these poses.
    return data.astype(np.float32)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default=DEFAULT_OUT, help="output CSV path")
    ap.add_argument("rows", nargs="?", type=int, default=DEFAULT_ROWS, help="number of rows")
    ap.add_argument("--seed", type=int, default=20240611, help="numpy seed")
    args = ap.parse_args()
    if args.rows < 1:
        sys.exit("ROWS must be positive")

    data = generate(args.rows, args.seed)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)

    last_r, space, a, b = None, None, None, None
    tmp = args.out + ".tmp"
    with open(tmp, "w") as f:
        f.write("x0,y0,h0,x1,y1,h1,r,ompl_length\n")
        for row in data:
            x0, y0, h0, x1, y1, h1, r = (float(v) for v in row)  # exact f32 values
            if r != last_r:
                space = ob.DubinsStateSpace(r, False)  # isSymmetric = False: forward paths
                a, b = space.allocState(), space.allocState()
                last_r = r
            a.setX(x0)
            a.setY(y0)
            a.setYaw(h0)
            b.setX(x1)
            b.setY(y1)
            b.setYaw(h1)
            length = space.distance(a, b)
            # str(np.float32) is the shortest decimal that reads back as the same f32.
            f.write(",".join(str(v) for v in row) + "," + repr(length) + "\n")
    os.replace(tmp, args.out)
    print(f"wrote {len(data)} rows to {args.out}")


if __name__ == "__main__":
    main()
