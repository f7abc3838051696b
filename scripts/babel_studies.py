#!/usr/bin/env python3
"""Babel's landmark experiments on our scenarios, through the command line, each printed as a
Markdown table for docs/PAPERS.md:

1. Scenario I, two landmarks degraded to half their range (3.5 km): every pair of babel-I-bridged's
   ten landmarks halved in turn (45 weathers in one scenario, one network), planned start -> goal.
2. Scenario III, every rosette scaled down (the paper's 70 %, and the levels between): one
   weather per level on babel-III-reach and on babel-III-zigzag (the repo's layout of the
   paper's scenario III: a main row of landmarks 11.3-11.9 km apart and closer alternates).
3. Landmark density: 30, 40 and 50 of babel-III-reach's landmarks (a fixed-seed choice of the
   others dropped), nominal and at 90 %: the stored edges, the share pruned onboard and the route.
4. The two readings of the network: `build --landmark-ranges ground` (our default: chains out of
   range dropped on the ground) against `onboard` (Babel's: every chain stored, navigability
   pruned onboard), on babel-II-N and babel-III-reach in each weather: stored edges, image, the
   share pruned onboard, the route and the counted work.

Each variant is written to a temporary folder as a scenario (the shared file with only its
`weather` and the landmarks' `quality` or the landmark list changed), built with
`skyroute build --hull-repair` and planned with `skyroute plan --weather W`.

    python3 scripts/babel_studies.py [--skyroute PATH] [--only 1,2,3,4]
"""

import argparse
import itertools
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIO_I = os.path.join(ROOT, "scenarios", "babel-I-bridged.geojson")
SCENARIO_III = os.path.join(ROOT, "scenarios", "babel-III-reach.geojson")
SCENARIO_III_ZIGZAG = os.path.join(ROOT, "scenarios", "babel-III-zigzag.geojson")
LEVELS = [1.0, 0.9, 0.85, 0.8, 0.75, 0.7]
PLANNED = re.compile(r"planned .* in weather (\S+): ([0-9.]+) km over (\d+) overflights.*work (\d+) "
                     r"\((\d+) of (\d+) edges leaving overflights not navigable\)")


def landmarks(s):
    return [f for f in s["features"] if f["properties"]["kind"] == "landmark"]


def build(skyroute, scenario, out, *extra):
    t = time.monotonic()
    r = subprocess.run([skyroute, "build", scenario, "--hull-repair", "-o", out, *extra],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"build {scenario}: {r.stderr.strip()}")
    m = re.search(r"(\d+) edges between them", r.stdout)
    if not m:
        sys.exit(f"build {scenario}: no edge count in its summary: {r.stdout.strip()}")
    return int(m.group(1)), time.monotonic() - t


def plan(skyroute, network, scenario, weather, out):
    """(length km, overflights, pruned, edges leaving overflights, route file) or the refusal."""
    r = subprocess.run([skyroute, "plan", network, "--hull-repair", "--scenario", scenario,
                        "--weather", weather, "-o", out], capture_output=True, text=True)
    m = PLANNED.search(r.stdout + r.stderr)
    if r.returncode != 0 or not m:
        why = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "no output"
        reach = re.search(r"straight legs within range reach only (.*?) from the start", why)
        if reach:
            n = reach.group(1).count("(range")
            why = f"none can exist: straight legs within range reach only {n} landmarks from the start"
        return None, why
    return (float(m.group(2)), int(m.group(3)), int(m.group(5)), int(m.group(6)),
            int(m.group(4))), out


def pruned_share(pruned, leaving):
    """The edges pruned onboard out of those leaving overflights, with their share."""
    return f"{pruned} of {leaving} ({100 * pruned / leaving:.0f} %)"


def heading_changes(route_file):
    """The overflight headings' mean absolute change between consecutive overflights, degrees:
    how much the route zig-zags."""
    with open(route_file) as f:
        route = json.load(f)
    hs = [o["heading_deg"] for o in route.get("overflights", []) if "heading_deg" in o]
    if len(hs) < 2:
        return float("nan")
    d = [abs((b - a + 180.0) % 360.0 - 180.0) for a, b in zip(hs, hs[1:])]
    return sum(d) / len(d)


def study_pairs(skyroute, tmp):
    s = json.load(open(SCENARIO_I))
    lms = landmarks(s)
    names = [f["properties"]["name"] for f in lms]
    pairs = list(itertools.combinations(range(len(lms)), 2))
    weathers = ["nominal"] + [f"half_{names[i]}_{names[j]}" for i, j in pairs]
    for k, f in enumerate(lms):
        nominal = f["properties"]["quality"]["nominal"]
        q = {"nominal": nominal}
        for (i, j), w in zip(pairs, weathers[1:]):
            q[w] = [v * 0.5 for v in nominal] if k in (i, j) else nominal
        f["properties"]["quality"] = q
    s["weather"] = weathers
    path = os.path.join(tmp, "babel-I-pairs.geojson")
    json.dump(s, open(path, "w"))
    net = os.path.join(tmp, "babel-I-pairs.bin")
    build(skyroute, path, net)
    base, why = plan(skyroute, net, path, "nominal", os.path.join(tmp, "I-nominal.json"))
    if not base:
        sys.exit(f"{SCENARIO_I} in nominal weather: {why}")
    routed, refused = [], 0
    for w in weathers[1:]:
        got, why = plan(skyroute, net, path, w, os.path.join(tmp, f"I-{w}.json"))
        if got:
            routed.append((w, got[0]))
        elif "no navigable route" in why or "none can exist" in why:
            refused += 1
        else:
            sys.exit(f"weather {w}: {why}")
    print("\n### Scenario I: two landmarks at half range\n")
    print(f"babel-I-bridged, nominal: {base[0]:.1f} km over {base[1]} overflights.\n")
    print("| pairs halved | routed | refused (no navigable route) | routed pairs: route (km) |")
    print("|---:|---:|---:|---|")
    print(f"| {len(pairs)} | {len(routed)} | {refused} | "
          + ", ".join(f"{w[5:].replace('_', '+')} {km:.1f}" for w, km in routed) + " |")


def scaled_weathers(s, levels):
    names = [f"q{round(l * 100)}" for l in levels]
    for f in landmarks(s):
        nominal = f["properties"]["quality"]["nominal"]
        f["properties"]["quality"] = {n: [v * l for v in nominal] for n, l in zip(names, levels)}
    s["weather"] = names
    return names


def study_degradation(skyroute, tmp):
    for scenario in (SCENARIO_III, SCENARIO_III_ZIGZAG):
        degrade(skyroute, tmp, scenario)


def degrade(skyroute, tmp, scenario):
    s = json.load(open(scenario))
    name = s["name"]
    names = scaled_weathers(s, LEVELS)
    path = os.path.join(tmp, f"{name}-levels.geojson")
    json.dump(s, open(path, "w"))
    net = os.path.join(tmp, f"{name}-levels.bin")
    edges, secs = build(skyroute, path, net)
    print(f"\n### Scenario III: every rosette scaled ({name})\n")
    print(f"{name}, {edges} stored edges (built in {secs:.0f} s).\n")
    print("| rosettes at | range | route (km) | overflights | mean heading change between overflights (°) | edges pruned onboard |")
    print("|---:|---:|---:|---:|---:|---:|")
    for n, l in zip(names, LEVELS):
        got, why = plan(skyroute, net, path, n, os.path.join(tmp, f"{name}-{n}.json"))
        if got:
            km, over, pruned, leaving, _ = got
            print(f"| {l:.0%} | {12.5 * l:.2f} km | {km:.1f} | {over} | {heading_changes(why):.0f} | "
                  f"{pruned_share(pruned, leaving)} |")
        else:
            print(f"| {l:.0%} | {12.5 * l:.2f} km | no route | | | {why[:140]} |")


def study_density(skyroute, tmp):
    print("\n### Landmark density (babel-III-reach's map)\n")
    print("| landmarks | stored edges | build (s) | weather | route (km) | overflights | edges pruned onboard |")
    print("|---:|---:|---:|---|---:|---:|---:|")
    full = json.load(open(SCENARIO_III))
    order = [f["properties"]["name"] for f in landmarks(full)]
    random.Random(7).shuffle(order)
    for count in (30, 40, 50):
        s = json.load(open(SCENARIO_III))
        keep = set(order[:count])
        s["features"] = [f for f in s["features"] if f["properties"]["kind"] != "landmark"
                         or f["properties"]["name"] in keep]
        names = scaled_weathers(s, [1.0, 0.9])
        path = os.path.join(tmp, f"babel-III-{count}.geojson")
        json.dump(s, open(path, "w"))
        net = os.path.join(tmp, f"babel-III-{count}.bin")
        edges, secs = build(skyroute, path, net)
        for n in names:
            got, why = plan(skyroute, net, path, n, os.path.join(tmp, f"D{count}-{n}.json"))
            if got:
                km, over, pruned, leaving, _ = got
                print(f"| {count} | {edges} | {secs:.0f} | {n} | {km:.1f} | {over} | "
                      f"{pruned_share(pruned, leaving)} |")
            else:
                print(f"| {count} | {edges} | {secs:.0f} | {n} | no route | | {why[:140]} |")


def study_readings(skyroute, tmp):
    print("\n### The two readings: chains dropped on the ground, or all stored and pruned onboard\n")
    print("| scenario | reading | stored edges | image (bytes) | weather | route (km) | edges pruned onboard | counted work |")
    print("|---|---|---:|---:|---|---:|---:|---:|")
    for name in ("babel-II-N", "babel-III-reach"):
        path = os.path.join(ROOT, "scenarios", name + ".geojson")
        weathers = json.load(open(path)).get("weather", ["nominal"])
        for reading in ("ground", "onboard"):
            net = os.path.join(tmp, f"{name}-{reading}.bin")
            edges, _ = build(skyroute, path, net, "--landmark-ranges", reading)
            size = os.path.getsize(net)
            for w in weathers:
                got, why = plan(skyroute, net, path, w, os.path.join(tmp, f"R-{name}-{w}.json"))
                if got:
                    km, _, pruned, leaving, work = got
                    print(f"| {name} | {reading} | {edges} | {size} | {w} | {km:.1f} | "
                          f"{pruned_share(pruned, leaving)} | {work} |")
                else:
                    print(f"| {name} | {reading} | {edges} | {size} | {w} | no route | {why[:140]} | |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skyroute", default=os.path.join(ROOT, "target", "release", "skyroute"))
    ap.add_argument("--only", default="1,2,3,4")
    a = ap.parse_args()
    only = {int(x) for x in a.only.split(",")}
    with tempfile.TemporaryDirectory() as tmp:
        if 1 in only:
            study_pairs(a.skyroute, tmp)
        if 2 in only:
            study_degradation(a.skyroute, tmp)
        if 3 in only:
            study_density(a.skyroute, tmp)
        if 4 in only:
            study_readings(a.skyroute, tmp)


if __name__ == "__main__":
    main()
