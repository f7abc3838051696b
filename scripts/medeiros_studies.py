#!/usr/bin/env python3
"""Medeiros & da Silva's parameters on the Jacksboro DEM, through the command line, each printed as
a Markdown table for docs/PAPERS.md:

1. The paper's two turn radii (r_c 300 m and 2 000 m) at several flight altitudes.
2. The paper's safety height a_s 300 m (ours: 100 m) with its safety distance d_s 100 m (our
   `clearance_m`, already 100 m), r_c 300 m, at several flight altitudes.
3. A grid like the paper's (30 m): the DEM resampled from 3 to 1 arc-second (bilinear, so the
   terrain is the same surface sampled three times finer) against the DEM as it is: the elevation
   grid's cells, the cells blocked, the terrain graph, build and plan time, the route, and the
   cells each turn-arc check visits (the paper's Table 4 counts these for its grid search).
4. The visibility graph's longest edge: every pair of nodes (the paper's graph, our default)
   against `build --max-edge` 10 km and 5 km.
5. Post-processing: the greedy shortcut pass (`plan --shortcuts greedy`) against the best chain of
   shortcuts (the default), each followed by heading smoothing, at several flight altitudes, on
   the graph of every pair and on the 10 km one.

Each variant is medeiros-jacksboro.geojson with only the fields named changed (the turn radius is
v_nominal² / a_lat_max, so a_lat_max = v_nominal² / r_c), written to a temporary folder with the
DEM's absolute path, built with `skyroute build` and planned P -> Q with `skyroute plan` (the
paper's turn rule, the default, unless a row says otherwise).

    python3 scripts/medeiros_studies.py [--skyroute PATH] [--only 1,2,3,4,5]
"""

import argparse
import json
import os
import re
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIO = os.path.join(ROOT, "scenarios", "medeiros-jacksboro.geojson")
DEM = os.path.join(ROOT, "scenarios", "jacksboro-dem.asc")
RADII_M = [300.0, 2000.0]
ALTITUDES_M = [750.0, 850.0, 1000.0]
PAPER_SAFETY_HEIGHT_M = 300.0
SAFETY_ALTITUDES_M = [750.0, 850.0, 1000.0, 1100.0]
BUILT = re.compile(r"terrain graph (\d+) nodes, (\d+) edges \((\d+) corners, (\d+) pairs tested\), "
                   r"elevation grid (\d+) x (\d+) of ([0-9.]+) m, (\d+) blocked")


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    return r.returncode, (r.stdout + r.stderr).strip().splitlines()[-1]


def variant(tmp, radius_m=300.0, altitude_m=750.0, safety_height_m=None, dem=DEM):
    """medeiros-jacksboro with the given turn radius, altitude, safety height and DEM."""
    s = json.load(open(SCENARIO))
    v = s["vehicle"]["v_nominal_mps"]
    s["vehicle"]["a_lat_max_mps2"] = v * v / radius_m
    s["terrain"]["altitude_m"] = altitude_m
    if safety_height_m is not None:
        s["terrain"]["safety_height_m"] = safety_height_m
    s["terrain"]["dem"] = dem
    path = os.path.join(tmp, "jb.geojson")
    json.dump(s, open(path, "w"))
    return path


def build(sk, scenario, net, *extra):
    """(summary match, seconds) or (None, the refusal)."""
    t = time.monotonic()
    code, line = run([sk, "build", scenario, "-o", net, *extra])
    if code != 0:
        return None, line
    m = BUILT.search(line)
    if not m:
        raise SystemExit(f"build {scenario}: no graph in {line!r}")
    return m, time.monotonic() - t


ARCS = re.compile(r"(\d+) turn arcs checked against the elevation grid: (\d+) cells, "
                  r"([0-9.]+) per arc, at most (\d+) \(bound (\d+)\)")


def plan(sk, scenario, net, out, *extra):
    """(route length, length before post-processing, counted work, seconds, turn-arc check
    match) or (None, the refusal)."""
    t = time.monotonic()
    r = subprocess.run([sk, "plan", net, "--scenario", scenario, "-o", out, *extra],
                       capture_output=True, text=True)
    secs = time.monotonic() - t
    if r.returncode != 0:
        line = (r.stdout + r.stderr).strip().splitlines()[-1]
        why = re.search(r"no route.*", line)
        return None, (why.group(0) if why else line)
    route = json.load(open(out))
    os.remove(out)
    leg = route["legs"][0]
    return (route["length_m"], leg["planned_length_m"], route["work_all_queries"]["total"],
            secs, ARCS.search(r.stdout)), None


def route_cell(got, why):
    if got is None:
        return why[:120]
    return f"{got[0]:.1f} m ({got[1]:.1f} m before post-processing)"


def study_radii(sk, tmp):
    print("\n### The paper's turn radii\n")
    print("| turn radius | altitude | terrain graph | route P → Q | counted work |")
    print("|---:|---:|---|---:|---:|")
    for r_c in RADII_M:
        for alt in ALTITUDES_M:
            sc = variant(tmp, radius_m=r_c, altitude_m=alt)
            net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
            m, why = build(sk, sc, net)
            if m is None:
                print(f"| {r_c:.0f} m | {alt:.0f} m | not built: {why} | | |")
                continue
            got, why = plan(sk, sc, net, out)
            work = got[2] if got else ""
            print(f"| {r_c:.0f} m | {alt:.0f} m | {m.group(1)} nodes, {m.group(2)} edges | "
                  f"{route_cell(got, why)} | {work} |")


def study_safety_height(sk, tmp):
    print(f"\n### The paper's safety height a_s {PAPER_SAFETY_HEIGHT_M:.0f} m (d_s 100 m, r_c 300 m)\n")
    print("| altitude | cells blocked (at or above altitude − a_s) | terrain graph | route P → Q | counted work |")
    print("|---:|---:|---|---:|---:|")
    for alt in SAFETY_ALTITUDES_M:
        sc = variant(tmp, altitude_m=alt, safety_height_m=PAPER_SAFETY_HEIGHT_M)
        net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
        m, why = build(sk, sc, net)
        if m is None:
            print(f"| {alt:.0f} m | | not built: {why[:140]} | | |")
            continue
        cells = int(m.group(5)) * int(m.group(6))
        got, why = plan(sk, sc, net, out)
        work = got[2] if got else ""
        print(f"| {alt:.0f} m | {int(m.group(8))} of {cells} | {m.group(1)} nodes, {m.group(2)} edges | "
              f"{route_cell(got, why)} | {work} |")


def resample_dem(src, dst, factor):
    """Writes `src` (an ESRI ASCII grid without NODATA cells) resampled `factor` times finer by
    bilinear interpolation between the cell centres: the same corners and surface."""
    import numpy as np
    from scipy.ndimage import map_coordinates

    header = {}
    with open(src) as f:
        for _ in range(6):
            k, v = f.readline().split()
            header[k.lower()] = float(v)
    z = np.loadtxt(src, skiprows=6)
    if (z == header["nodata_value"]).any():
        raise SystemExit(f"{src}: NODATA cells; this resampler interpolates complete grids only")
    rows, cols = z.shape
    # A fine cell's centre in coarse-cell index units (coarse cell i's centre is at i).
    r = (np.arange(rows * factor) + 0.5) / factor - 0.5
    c = (np.arange(cols * factor) + 0.5) / factor - 0.5
    rr, cc = np.meshgrid(r, c, indexing="ij")
    fine = map_coordinates(z, [rr, cc], order=1, mode="nearest")
    with open(dst, "w") as f:
        f.write(f"ncols {cols * factor}\nnrows {rows * factor}\n"
                f"xllcorner {header['xllcorner']:.8f}\nyllcorner {header['yllcorner']:.8f}\n"
                f"cellsize {header['cellsize'] / factor:.10f}\nNODATA_value -9999\n")
        np.savetxt(f, fine, fmt="%.1f")


def study_grid(sk, tmp):
    fine = os.path.join(tmp, "jacksboro-1s.asc")
    resample_dem(DEM, fine, 3)
    print("\n### A grid like the paper's (30 m)\n")
    print("| DEM | elevation grid | cells blocked at 750 m − 100 m | terrain graph | image | build | "
          "route P → Q, paper's turn rule | route P → Q, equal split (counted work, plan time) | "
          "cells per turn-arc check, equal split: mean, most (bound) |")
    print("|---|---:|---:|---|---:|---:|---|---|---|")
    for label, dem in [("3″ (as shared)", DEM), ("1″ (resampled ×3)", fine)]:
        sc = variant(tmp, dem=dem)
        net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
        m, secs = build(sk, sc, net)
        if m is None:
            print(f"| {label} | not built: {secs} | | | | | | |")
            continue
        size = os.path.getsize(net)
        paper, why_paper = plan(sk, sc, net, out)
        split, why_split = plan(sk, sc, net, out, "--turn-rule", "shared-equally")
        split_cell, arcs_cell = route_cell(split, why_split), ""
        if split:
            split_cell += f" ({split[2]}, {split[3]:.1f} s)"
            a = split[4]
            arcs_cell = f"{a.group(3)}, {a.group(4)} ({a.group(5)}) over {a.group(1)} arcs"
        print(f"| {label} | {m.group(5)} × {m.group(6)} of {float(m.group(7)):.1f} m | {m.group(8)} | "
              f"{m.group(1)} nodes ({m.group(3)} corners), {m.group(2)} edges, {m.group(4)} pairs tested | "
              f"{size / 1e6:.2f} MB | {secs:.1f} s | {route_cell(paper, why_paper)} | {split_cell} | "
              f"{arcs_cell} |")


def study_max_edge(sk, tmp):
    print("\n### The visibility graph's longest edge (750 m, r_c 300 m)\n")
    print("| edges tried | terrain graph | route P → Q | counted work |")
    print("|---|---|---:|---:|")
    for label, extra in [("every pair (default)", []), ("`--max-edge 10000`", ["--max-edge", "10000"]),
                         ("`--max-edge 5000`", ["--max-edge", "5000"])]:
        sc = variant(tmp)
        net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
        m, why = build(sk, sc, net, *extra)
        if m is None:
            print(f"| {label} | not built: {why} | | |")
            continue
        got, why = plan(sk, sc, net, out)
        work = got[2] if got else ""
        print(f"| {label} | {m.group(1)} nodes, {m.group(2)} edges ({m.group(4)} pairs tested) | "
              f"{route_cell(got, why)} | {work} |")


def study_shortcuts(sk, tmp):
    print("\n### Post-processing: the greedy shortcut pass against the best chain (r_c 300 m)\n")
    print("| altitude | edges tried | route P → Q as searched | greedy shortcuts, then smoothing "
          "(plan time) | best chain, then smoothing (plan time) |")
    print("|---:|---|---:|---:|---:|")
    for alt in ALTITUDES_M:
        for label, extra in [("every pair", []), ("`--max-edge 10000`", ["--max-edge", "10000"])]:
            sc = variant(tmp, altitude_m=alt)
            net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
            m, why = build(sk, sc, net, *extra)
            if m is None:
                print(f"| {alt:.0f} m | {label}: not built: {why} | | | |")
                continue
            greedy, why_g = plan(sk, sc, net, out, "--shortcuts", "greedy")
            best, why_b = plan(sk, sc, net, out, "--shortcuts", "best")
            if greedy is None or best is None:
                print(f"| {alt:.0f} m | {label} | {why_g or why_b} | | |")
                continue
            print(f"| {alt:.0f} m | {label} | {best[1]:.1f} m | {greedy[0]:.1f} m ({greedy[3]:.1f} s) | "
                  f"{best[0]:.1f} m ({best[3]:.1f} s) |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skyroute", default=os.path.join(ROOT, "target", "release", "skyroute"))
    ap.add_argument("--only", default="1,2,3,4,5")
    a = ap.parse_args()
    only = {int(x) for x in a.only.split(",")}
    with tempfile.TemporaryDirectory() as tmp:
        if 1 in only:
            study_radii(a.skyroute, tmp)
        if 2 in only:
            study_safety_height(a.skyroute, tmp)
        if 3 in only:
            study_grid(a.skyroute, tmp)
        if 4 in only:
            study_max_edge(a.skyroute, tmp)
        if 5 in only:
            study_shortcuts(a.skyroute, tmp)


if __name__ == "__main__":
    main()
