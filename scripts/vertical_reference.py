#!/usr/bin/env python3
"""Independent reference for the vertical profile of Niendorf et al.'s aircraft, by linear
programming (SciPy's HiGHS).

The aircraft's vertical motion is a double integrator: climb rate |z'| <= v_c, vertical
acceleration |z''| <= a_z, at rest (z' = 0) at both ends of an edge flown in T = L / v seconds.
The time is cut into N steps of dt = T / N with a constant acceleration a_k in each:

    w_{k+1} = w_k + a_k dt,    z_{k+1} = z_k + w_k dt + a_k dt^2 / 2

which is exact for piecewise-constant acceleration, and since w is linear within a step the
rate bound at the step ends holds throughout. Every LP solution is therefore a flyable
continuous move, and the LP optimum is at most the continuous optimum; it approaches it as N
grows (the gap is O(v_c dt)).

For each random case (v, v_c, a_z, L) the script writes:
  * `max_climb`: the largest z_N - z_0 (rest to rest);
  * for a climb of `climb` metres (a random fraction of the largest), at three times
    t_j = j T / 4 (j = 1, 2, 3), the highest altitude z_j above the start that any monotone
    move (w >= 0, z never above the end altitude) reaches at t_j and still ends at rest at
    exactly `climb`.

`host-tests/tests/core/vertical_profile.rs` checks `VerticalLimits::max_climb` and
`VerticalProfile::altitude_at` against these: ours must be at least the LP's (the LP's moves
are flyable, so a lower value would mean ours is not the highest), and within the
discretisation gap above it.

Usage: python3 scripts/vertical_reference.py [OUT_CSV] [CASES] [--seed N] [--steps N]
Defaults: target/reference/vertical_lp.csv (relative to the repository root), 120 cases,
200 steps. Needs the PyPI packages `scipy` and `numpy`.
"""

import argparse
import os
import sys

import numpy as np

try:
    from scipy.optimize import linprog
except ImportError:  # pragma: no cover - environment problem, explained to the user
    sys.exit("the PyPI package `scipy` is needed: pip install scipy")

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(REPO_ROOT, "target", "reference", "vertical_lp.csv")


def solve(n, dt, vc, az, climb=None, at=None):
    """Variables: z_0..z_n, w_0..w_n, a_0..a_{n-1}. Maximises z_n (climb None) or z_at."""
    nz, nw, na = n + 1, n + 1, n
    size = nz + nw + na
    iz = lambda k: k  # noqa: E731
    iw = lambda k: nz + k  # noqa: E731
    ia = lambda k: nz + nw + k  # noqa: E731
    rows, rhs = [], []
    for k in range(n):
        r = np.zeros(size)  # w_{k+1} - w_k - a_k dt = 0
        r[iw(k + 1)], r[iw(k)], r[ia(k)] = 1.0, -1.0, -dt
        rows.append(r)
        rhs.append(0.0)
        r = np.zeros(size)  # z_{k+1} - z_k - w_k dt - a_k dt^2/2 = 0
        r[iz(k + 1)], r[iz(k)], r[iw(k)], r[ia(k)] = 1.0, -1.0, -dt, -0.5 * dt * dt
        rows.append(r)
        rhs.append(0.0)
    for fixed in (iz(0), iw(0), iw(n)):
        r = np.zeros(size)
        r[fixed] = 1.0
        rows.append(r)
        rhs.append(0.0)
    bounds = [(None, None)] * nz + [(-vc, vc)] * nw + [(-az, az)] * na
    cost = np.zeros(size)
    if climb is None:
        cost[iz(n)] = -1.0
    else:
        r = np.zeros(size)
        r[iz(n)] = 1.0
        rows.append(r)
        rhs.append(climb)
        # Monotone and never above the end: 0 <= w, z_k <= climb.
        bounds = [(None, climb)] * nz + [(0.0, vc)] * nw + [(-az, az)] * na
        cost[iz(at)] = -1.0
    res = linprog(cost, A_eq=np.array(rows), b_eq=np.array(rhs), bounds=bounds, method="highs")
    if res.status != 0:
        raise RuntimeError(f"LP failed: {res.message}")
    return -res.fun


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", default=DEFAULT_OUT)
    parser.add_argument("cases", nargs="?", type=int, default=120)
    parser.add_argument("--seed", type=int, default=20261203)
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    n = args.steps
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as out:
        out.write("v,vc,az,length,steps,max_climb,climb,z1,z2,z3\n")
        for _ in range(args.cases):
            # f32-exact inputs: the Rust side reads the same numbers.
            v = float(np.float32(rng.uniform(10.0, 60.0)))
            vc = float(np.float32(rng.uniform(1.0, 15.0)))
            az = float(np.float32(rng.uniform(1.0, 30.0)))
            length = float(np.float32(np.exp(rng.uniform(np.log(5.0), np.log(3000.0)))))
            dt = length / v / n
            best = solve(n, dt, vc, az)
            climb = float(np.float32(best * rng.uniform(0.05, 0.95)))
            highs = [solve(n, dt, vc, az, climb=climb, at=j * n // 4) for j in (1, 2, 3)]
            out.write(
                f"{v!r},{vc!r},{az!r},{length!r},{n},{best!r},{climb!r},"
                + ",".join(repr(h) for h in highs)
                + "\n"
            )
    print(f"wrote {args.cases} cases to {args.out}")


if __name__ == "__main__":
    main()
