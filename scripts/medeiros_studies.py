#!/usr/bin/env python3
"""Medeiros & da Silva's two turn radii (r_c 300 m and 2 000 m) at several flight altitudes on
the Jacksboro DEM, through the command line, printed as a Markdown table for docs/PAPERS.md.

Each variant is medeiros-jacksboro.geojson with only `terrain.altitude_m` and the vehicle's
lateral acceleration changed (the turn radius is v_nominal² / a_lat_max, so a_lat_max =
v_nominal² / r_c), written to a temporary folder with the DEM's absolute path, built with
`skyroute build` and planned P -> Q with `skyroute plan` (the paper's turn rule, the default).

    python3 scripts/medeiros_studies.py [--skyroute PATH]
"""

import argparse
import json
import os
import re
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIO = os.path.join(ROOT, "scenarios", "medeiros-jacksboro.geojson")
DEM = os.path.join(ROOT, "scenarios", "jacksboro-dem.asc")
RADII_M = [300.0, 2000.0]
ALTITUDES_M = [750.0, 850.0, 1000.0]


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    return r.returncode, (r.stdout + r.stderr).strip().splitlines()[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skyroute", default=os.path.join(ROOT, "target", "release", "skyroute"))
    sk = ap.parse_args().skyroute
    print("| turn radius | altitude | terrain graph | route P → Q | counted work |")
    print("|---:|---:|---|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for r_c in RADII_M:
            for alt in ALTITUDES_M:
                s = json.load(open(SCENARIO))
                v = s["vehicle"]["v_nominal_mps"]
                s["vehicle"]["a_lat_max_mps2"] = v * v / r_c
                s["terrain"]["altitude_m"] = alt
                s["terrain"]["dem"] = DEM
                sc = os.path.join(tmp, "jb.geojson")
                json.dump(s, open(sc, "w"))
                net, out = os.path.join(tmp, "jb.bin"), os.path.join(tmp, "r.json")
                code, line = run([sk, "build", sc, "-o", net])
                if code != 0:
                    print(f"| {r_c:.0f} m | {alt:.0f} m | not built: {line} | | |")
                    continue
                graph = re.search(r"(\d+) nodes, (\d+) edges", line)
                if not graph:
                    raise SystemExit(f"build at r_c {r_c} m, {alt} m: no graph in {line!r}")
                graph = f"{graph.group(1)} nodes, {graph.group(2)} edges"
                code, line = run([sk, "plan", net, "--scenario", sc, "-o", out])
                if code == 0:
                    route = json.load(open(out))
                    leg = route["legs"][0]
                    print(f"| {r_c:.0f} m | {alt:.0f} m | {graph} | {route['length_m']:.1f} m "
                          f"({leg['planned_length_m']:.1f} m before post-processing) | "
                          f"{route['work_all_queries']['total']} |")
                    os.remove(out)
                else:
                    why = re.search(r"no route.*", line)
                    why = why.group(0) if why else line
                    print(f"| {r_c:.0f} m | {alt:.0f} m | {graph} | {why[:120]} | |")


if __name__ == "__main__":
    main()
