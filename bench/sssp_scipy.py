#!/usr/bin/env python3
"""Single-source shortest paths with SciPy on a network exported by `skyroute export`, checked
against skyroute's distances (`peers sssp`), for bench/compare.sh.

Usage:
    python3 bench/sssp_scipy.py EXPORT.json OURS.json OURS_DIST.bin OUT.json [--reps 5]

EXPORT.json is the `skyroute export` of the network; OURS.json and OURS_DIST.bin are what
`peers sssp` wrote for it (the source vertices, and the core's f32 distances, sources x
vertices, little-endian, infinity where unreachable). The graph is read from the export's
edges (`from`, `to`, `cost`) into a CSR matrix (the cheaper of any parallel edges kept, none
in the shared networks); `scipy.sparse.csgraph.dijkstra(directed=True, indices=source)` is timed
per source (median of --reps calls) and every distance compared with ours: equal when the
relative difference is at most 1e-5 (f32 against f64), and unreachable in both or neither.
"""

import argparse
import json
import statistics
import sys
import time

import numpy as np

try:
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra
    import scipy
except ImportError as e:  # pragma: no cover - environment problem, explained to the user
    sys.exit(f"{e}: pip install scipy numpy")

REL_TOL = 1e-5


def graph(export):
    """The export's edges as a CSR matrix (float64), parallel edges reduced to the cheapest."""
    n = len(export["vertices"])
    best = {}
    for e in export["edges"]:
        key = (e["from"], e["to"])
        best[key] = min(best.get(key, np.inf), float(e["cost"]))
    if any(c <= 0.0 for c in best.values()):
        # csgraph reads an explicit zero as "no edge"; no exported network has one.
        raise SystemExit("an edge of cost <= 0: csgraph would drop it")
    rows = np.fromiter((k[0] for k in best), dtype=np.int64, count=len(best))
    cols = np.fromiter((k[1] for k in best), dtype=np.int64, count=len(best))
    vals = np.fromiter(best.values(), dtype=np.float64, count=len(best))
    return csr_matrix((vals, (rows, cols)), shape=(n, n)), len(export["edges"]) - len(best)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("export")
    ap.add_argument("ours_json")
    ap.add_argument("ours_dist")
    ap.add_argument("out")
    ap.add_argument("--reps", type=int, default=5)
    a = ap.parse_args()
    with open(a.export) as f:
        export = json.load(f)
    with open(a.ours_json) as f:
        ours = json.load(f)
    g, parallel = graph(export)
    n = g.shape[0]
    sources = ours["sources"]
    dist = np.fromfile(a.ours_dist, dtype="<f4").astype(np.float64).reshape(len(sources), n)
    times, worst, mismatches = [], 0.0, 0
    for k, s in enumerate(sources):
        runs = []
        for _ in range(a.reps):
            t0 = time.perf_counter()
            d = dijkstra(g, directed=True, indices=s)
            runs.append(time.perf_counter() - t0)
        times.append(statistics.median(runs))
        mine = dist[k]
        both = np.isfinite(d) & np.isfinite(mine)
        mismatches += int(np.sum(np.isfinite(d) != np.isfinite(mine)))
        rel = np.abs(mine[both] - d[both]) / np.maximum(d[both], 1e-9)
        worst = max(worst, float(rel.max(initial=0.0)))
        mismatches += int(np.sum(rel > REL_TOL))
    times.sort()
    rank = lambda q: times[max(1, int(np.ceil(q * len(times)))) - 1]
    out = {
        "solver": f"scipy.sparse.csgraph.dijkstra (scipy {scipy.__version__}, float64)",
        "vertices": n,
        "edges": int(g.nnz),
        "parallel_edges_dropped": parallel,
        "sources": len(sources),
        "reps": a.reps,
        "scipy_s": {"median": rank(0.5), "p90": rank(0.9), "max": times[-1]},
        "max_rel_diff_vs_ours": worst,
        "mismatches_vs_ours": mismatches,
    }
    with open(a.out, "w") as f:
        json.dump(out, f, indent=1)
    print(f"scipy dijkstra: {len(sources)} sources on {n} vertices, median {rank(0.5) * 1e3:.3f} ms, "
          f"max rel diff vs ours {worst:.2e}, {mismatches} mismatches")


if __name__ == "__main__":
    main()
