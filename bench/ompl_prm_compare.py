#!/usr/bin/env python3
"""skyroute's roadmap next to OMPL's PRM* over a Dubins state space, on the same map.

What it does (see bench/README.md for how to run it and what the numbers mean):

1. Reads a network exported by `skyroute export` (obstacles in the network's local metric frame,
   turn radius, clearance, vertices) and the scenario it was built from (for the sampled area: the
   bounding box of every position in the scenario, exactly as `skyroute build` takes it).
2. Sets up OMPL: `DubinsStateSpace(turn_radius)` (forward-only, asymmetric distance) over that
   area, a state validity checker that rejects a pose whose position is within `clearance_m` of an
   obstacle (distance <= clearance, polygons with their interiors, as skyroute's sample filter),
   and OMPL's discrete motion validator with one state checked every `--resolution-m` metres
   along each Dubins path (default 1 m).
3. Grows a PRM* roadmap (`growRoadmap`) until it has as many milestones as skyroute's network has
   vertices, and records the wall time, the milestone and edge counts, and the validity checks.
4. Draws `--queries` start/goal pose pairs with a fixed seed (free positions at least
   `--min-free-m` beyond the clearance from every obstacle, at least `--min-separation-m` apart,
   fixed uniformly drawn headings), writes each as a scenario (a copy of the original scenario
   with its start, goal and waypoints replaced: start and goal both with a heading, no
   waypoints), plans it with `skyroute plan` (timed as a whole process: start-up, network load,
   planning, post-processing, writing the route), and solves the same pair with the grown PRM*
   (`solve` with a time cap, `clearQuery` between queries).
5. Compares lengths pair by pair, re-checks every OMPL solution in its direction of flight
   (PRM's roadmap is an undirected graph: an edge is only checked in the direction it was added),
   measures the closest approach to the obstacles of both routes by dense sampling, and writes a
   JSON report with every number (`--report`).

Usage:
    python3 bench/ompl_prm_compare.py /tmp/n.json --network /tmp/n.bin \
        --scenario scenarios/niendorf-urban.geojson --skyroute target/release/skyroute \
        --report /tmp/ompl_compare.json

Needs the PyPI wheels `ompl` (2.x, nanobind bindings), `shapely` (2.x), `pyproj` and `numpy`.
"""

import argparse
import copy
import json
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np

try:
    import shapely
    from shapely.geometry import Point, Polygon
    from shapely.ops import unary_union
    from pyproj import Geod, Transformer
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou
except ImportError as e:  # pragma: no cover - environment problem, explained to the user
    sys.exit(f"{e}: pip install ompl shapely pyproj numpy")

TAU = 2.0 * math.pi


# --------------------------------------------------------------------------------------------
# The map
# --------------------------------------------------------------------------------------------


class Obstacles:
    """The network's obstacles and the clearance, with an exact point test.

    `blocked(x, y)` is True when the point lies inside a polygon or within `clearance` of one
    (GEOS `dwithin`: distance <= clearance), or within `radius + clearance` of a circle's centre.
    A grid of `cell`-metre cells speeds it up without changing a single answer: the distance to
    the obstacles is 1-Lipschitz, so a cell whose centre is farther than `clearance + h` (h the
    half-diagonal) is free throughout, one whose centre is within `clearance - h` is blocked
    throughout, and only points in the remaining cells (a band about 2h wide along the clearance
    contour), or outside the grid, are tested exactly.
    """

    def __init__(self, network, bounds, cell=4.0, margin=400.0):
        self.clearance = float(network["clearance_m"])
        polys, self.circles = [], []
        for o in network["obstacles"]:
            if o["kind"] == "polygon":
                polys.append(Polygon(o["points"]))
            else:
                self.circles.append((o["centre"][0], o["centre"][1], o["radius"]))
        self.union = unary_union(polys) if polys else None
        if self.union is not None:
            shapely.prepare(self.union)
        (x0, y0, x1, y1) = bounds
        self.x0, self.y0, self.cell = x0 - margin, y0 - margin, cell
        self.nx = int(math.ceil((x1 - x0 + 2 * margin) / cell))
        self.ny = int(math.ceil((y1 - y0 + 2 * margin) / cell))
        xs = self.x0 + (np.arange(self.nx) + 0.5) * cell
        ys = self.y0 + (np.arange(self.ny) + 0.5) * cell
        gx, gy = np.meshgrid(xs, ys)
        d = self.distance_many(gx.ravel(), gy.ravel()).reshape(gy.shape)
        h = cell * math.sqrt(0.5)
        self.grid = np.full(gy.shape, 2, dtype=np.uint8)  # 2: test exactly
        self.grid[d > self.clearance + h] = 0  # free throughout
        self.grid[d < self.clearance - h] = 1  # blocked throughout
        self.grid_list = self.grid.tolist()  # list indexing is faster than numpy's from Python
        self.exact_tests = 0

    def distance_many(self, xs, ys):
        """Distance from each point to the nearest obstacle (0 inside a polygon)."""
        d = np.full(len(xs), np.inf)
        if self.union is not None:
            d = shapely.distance(self.union, shapely.points(xs, ys))
        for cx, cy, r in self.circles:
            d = np.minimum(d, np.maximum(np.hypot(xs - cx, ys - cy) - r, 0.0))
        return d

    def blocked_exact(self, x, y):
        self.exact_tests += 1
        if self.union is not None and shapely.dwithin(self.union, Point(x, y), self.clearance):
            return True
        return any(math.hypot(x - cx, y - cy) <= r + self.clearance for cx, cy, r in self.circles)

    def blocked(self, x, y):
        i = int((x - self.x0) // self.cell)
        j = int((y - self.y0) // self.cell)
        if 0 <= i < self.nx and 0 <= j < self.ny:
            g = self.grid_list[j][i]
            if g != 2:
                return g == 1
        return self.blocked_exact(x, y)

    def self_test(self, bounds, n=20000, seed=12345):
        """The grid never changes an answer: compares with the exact test on random points."""
        rng = np.random.default_rng(seed)
        (x0, y0, x1, y1) = bounds
        pts = np.column_stack([rng.uniform(x0, x1, n), rng.uniform(y0, y1, n)])
        # Half of them near the obstacles' clearance contour, where mistakes would show.
        if self.union is not None:
            ring = self.union.buffer(self.clearance, quad_segs=16).boundary
            t = rng.uniform(0, ring.length, n // 2)
            near = shapely.get_coordinates(shapely.line_interpolate_point(ring, t))
            pts[: n // 2] = near + rng.normal(0, 1.5, (n // 2, 2))
        bad = sum(self.blocked(x, y) != self.blocked_exact(x, y) for x, y in pts)
        if bad:
            raise AssertionError(f"the grid changed {bad} of {n} answers")
        return n

    def min_distance_along(self, points):
        """Smallest obstacle distance over a polyline's sample points (array of shape (n, 2))."""
        if len(points) == 0:
            return math.inf
        return float(np.min(self.distance_many(points[:, 0], points[:, 1])))


def scenario_bounds(scenario, to_local):
    """Bounding box of every position of the scenario in the local frame (`skyroute build`'s area)."""
    pts = []

    def walk(c):
        if isinstance(c[0], (int, float)):
            pts.append(c)
        else:
            for x in c:
                walk(x)

    for f in scenario["features"]:
        walk(f["geometry"]["coordinates"])
    xy = np.array([to_local(lon, lat) for lon, lat in pts])
    return (float(xy[:, 0].min()), float(xy[:, 1].min()), float(xy[:, 0].max()), float(xy[:, 1].max()))


class Frame:
    """The network's local frame (transverse Mercator on WGS-84 centred on the origin, k0 = 1),
    and compass headings, through PROJ."""

    def __init__(self, lat0, lon0):
        proj = f"+proj=tmerc +lat_0={lat0!r} +lon_0={lon0!r} +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m"
        self.fwd = Transformer.from_crs("EPSG:4326", proj, always_xy=True)
        self.inv = Transformer.from_crs(proj, "EPSG:4326", always_xy=True)
        self.geod = Geod(ellps="WGS84")

    def to_local(self, lon, lat):
        return self.fwd.transform(lon, lat)

    def to_geo(self, x, y):
        return self.inv.transform(x, y)

    def compass_deg(self, x, y, heading_rad):
        """A local heading (radians counter-clockwise from +x) as a compass heading at (x, y):
        the geodesic azimuth of a 1 m step in that grid direction (includes the meridian
        convergence, which `skyroute` takes out again when it reads the scenario)."""
        lon1, lat1 = self.to_geo(x, y)
        lon2, lat2 = self.to_geo(x + math.cos(heading_rad), y + math.sin(heading_rad))
        az, _, _ = self.geod.inv(lon1, lat1, lon2, lat2)
        return az % 360.0


# --------------------------------------------------------------------------------------------
# Queries
# --------------------------------------------------------------------------------------------


def draw_queries(obstacles, bounds, n, seed, min_free, min_sep, edge_margin):
    """`n` deterministic (start, goal) pose pairs: positions at least `min_free` beyond the
    clearance from every obstacle and `edge_margin` inside the area, at least `min_sep` apart,
    headings uniform."""
    rng = np.random.default_rng(seed)
    (x0, y0, x1, y1) = bounds

    def free_position():
        while True:
            x = rng.uniform(x0 + edge_margin, x1 - edge_margin)
            y = rng.uniform(y0 + edge_margin, y1 - edge_margin)
            d = obstacles.distance_many(np.array([x]), np.array([y]))[0]
            if d >= obstacles.clearance + min_free:
                return x, y

    out = []
    while len(out) < n:
        a, b = free_position(), free_position()
        if math.hypot(b[0] - a[0], b[1] - a[1]) < min_sep:
            continue
        ha = rng.uniform(-math.pi, math.pi)
        hb = rng.uniform(-math.pi, math.pi)
        # Rounded to f32, the precision the onboard core works in.
        f32 = lambda v: float(np.float32(v))
        out.append({"start": [f32(a[0]), f32(a[1]), f32(ha)], "goal": [f32(b[0]), f32(b[1]), f32(hb)]})
    return out


def query_scenario(base, q, frame, name):
    """A copy of the scenario with its start, goal and waypoints replaced by the query's poses."""
    s = copy.deepcopy(base)
    s["name"] = name
    s["description"] = f"{base.get('name', '')} with start and goal from bench/ompl_prm_compare.py"
    s["features"] = [
        f for f in s["features"] if f["properties"].get("kind") not in ("start", "goal", "waypoint")
    ]
    for kind, label, (x, y, h) in (("start", "S", q["start"]), ("goal", "G", q["goal"])):
        lon, lat = frame.to_geo(x, y)
        s["features"].append(
            {
                "type": "Feature",
                "geometry": {"type": "Point", "coordinates": [lon, lat]},
                "properties": {"kind": kind, "name": label, "heading_deg": frame.compass_deg(x, y, h)},
            }
        )
    return s


def sample_primitives(prims, step=0.5):
    """Points every `step` metres along skyroute route primitives (lines and arcs)."""
    pts = []
    for p in prims:
        if p["type"] == "line":
            (ax, ay), (bx, by) = p["start"], p["end"]
            n = max(1, int(math.ceil(math.hypot(bx - ax, by - ay) / step)))
            t = np.linspace(0.0, 1.0, n + 1)
            pts.append(np.column_stack([ax + (bx - ax) * t, ay + (by - ay) * t]))
        else:
            (cx, cy), r, a0, sw = p["centre"], p["radius"], p["start_angle"], p["sweep"]
            n = max(1, int(math.ceil(abs(sw) * r / step)))
            a = a0 + sw * np.linspace(0.0, 1.0, n + 1)
            pts.append(np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)]))
    return np.vstack(pts) if pts else np.zeros((0, 2))


def run_skyroute(exe, network, scenario_path, route_path, repeat):
    """Runs `skyroute plan` `repeat` times; returns (route JSON or None, wall times, stderr)."""
    cmd = [exe, "plan", network, "--scenario", scenario_path, "-o", route_path]
    times, proc = [], None
    for _ in range(repeat):
        if os.path.exists(route_path):
            os.remove(route_path)
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        times.append(time.perf_counter() - t0)
        if proc.returncode != 0:
            return None, times, proc.stderr.strip()
    with open(route_path) as f:
        return json.load(f), times, ""


# --------------------------------------------------------------------------------------------
# OMPL
# --------------------------------------------------------------------------------------------


def setup_ompl(network, bounds, obstacles, resolution_m):
    space = ob.DubinsStateSpace(float(network["turn_radius_m"]), False)
    b = ob.RealVectorBounds(2)
    b.setLow(0, bounds[0])
    b.setHigh(0, bounds[2])
    b.setLow(1, bounds[1])
    b.setHigh(1, bounds[3])
    space.setBounds(b)
    si = ob.SpaceInformation(space)
    calls = [0]
    blocked = obstacles.blocked

    def valid(s):
        calls[0] += 1
        return not blocked(s.getX(), s.getY())

    si.setStateValidityChecker(valid)
    # The resolution is a fraction of the space's maximum extent; OMPL's Dubins space cuts a
    # motion into ceil(dubins_length / (fraction * extent)) segments and checks every state.
    extent = space.getMaximumExtent()
    si.setStateValidityCheckingResolution(resolution_m / extent)
    si.setup()
    return space, si, calls


def set_pose(state, pose):
    state.setXY(pose[0], pose[1])
    state.setYaw(pose[2])


def path_points(space, path, step=0.5):
    """Points every `step` metres along the Dubins curves joining the path's states in order."""
    tmp = space.allocState()
    pts = []
    for i in range(path.getStateCount() - 1):
        a, b = path.getState(i), path.getState(i + 1)
        n = max(1, int(math.ceil(space.distance(a, b) / step)))
        for k in range(n + 1):
            space.interpolate(a, b, k / n, tmp)
            pts.append((tmp.getX(), tmp.getY()))
    return np.array(pts)


def forward_motions_valid(si, path):
    """Whether every motion of the path, flown from state i to state i+1, passes OMPL's own
    (discrete) motion check."""
    return all(si.checkMotion(path.getState(i), path.getState(i + 1)) for i in range(path.getStateCount() - 1))


# --------------------------------------------------------------------------------------------


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("network_json", help="network exported by `skyroute export`")
    ap.add_argument("--network", required=True, help="the network image (`skyroute build -o`)")
    ap.add_argument("--scenario", required=True, help="the scenario the network was built from")
    ap.add_argument("--skyroute", default="target/release/skyroute", help="the ground tool binary")
    ap.add_argument("--work-dir", default="/tmp/ompl_prm_compare", help="query scenarios and routes")
    ap.add_argument("--report", default="/tmp/ompl_compare.json", help="JSON report")
    ap.add_argument("--queries", type=int, default=30)
    ap.add_argument("--seed", type=int, default=20240611, help="seed of the query poses")
    ap.add_argument("--ompl-seed", type=int, default=1, help="seed of OMPL's RNG")
    ap.add_argument("--min-separation-m", type=float, default=1000.0)
    ap.add_argument("--min-free-m", type=float, default=20.0, help="free margin beyond the clearance")
    ap.add_argument("--edge-margin-m", type=float, default=50.0, help="keep poses this far inside the area")
    ap.add_argument("--resolution-m", type=float, default=1.0, help="OMPL motion-check step along a path")
    ap.add_argument("--solve-time", type=float, default=1.0, help="OMPL time cap per query, seconds")
    ap.add_argument("--simplify-time", type=float, default=1.0, help="OMPL PathSimplifier cap, seconds")
    ap.add_argument("--repeat", type=int, default=5, help="`skyroute plan` runs per query (timing)")
    ap.add_argument("--target", type=int, default=None, help="milestones (default: the network's vertices)")
    args = ap.parse_args()

    with open(args.network_json) as f:
        net = json.load(f)
    with open(args.scenario) as f:
        scenario = json.load(f)
    fr = net["frame"]
    frame = Frame(fr["origin_lat_deg"], fr["origin_lon_deg"])
    bounds = scenario_bounds(scenario, frame.to_local)
    target = args.target or len(net["vertices"])
    print(f"area {bounds[0]:.1f}..{bounds[2]:.1f} x {bounds[1]:.1f}..{bounds[3]:.1f} m, "
          f"r = {net['turn_radius_m']:.3f} m, clearance {net['clearance_m']} m, "
          f"{len(net['obstacles'])} obstacles; skyroute: {len(net['vertices'])} vertices, {len(net['edges'])} edges")

    t0 = time.perf_counter()
    obstacles = Obstacles(net, bounds)
    checker_setup_s = time.perf_counter() - t0
    tested = obstacles.self_test(bounds)
    print(f"validity checker: grid {obstacles.nx}x{obstacles.ny} cells of {obstacles.cell} m, "
          f"{checker_setup_s:.2f} s to set up, agrees with the exact test on {tested} points")

    # Our vertices must be valid states for OMPL too (the same clearance rule).
    ours_invalid = sum(obstacles.blocked(v["x"], v["y"]) for v in net["vertices"])

    ou.setLogLevel(ou.LOG_WARN)
    ou.RNG.setSeed(args.ompl_seed)
    space, si, calls = setup_ompl(net, bounds, obstacles, args.resolution_m)
    planner = og.PRMstar(si)
    pdef = ob.ProblemDefinition(si)
    s0, g0 = space.allocState(), space.allocState()
    set_pose(s0, (0.0, 0.0, 0.0))
    set_pose(g0, (1.0, 0.0, 0.0))
    pdef.setStartAndGoalStates(s0, g0)
    planner.setProblemDefinition(pdef)
    planner.setup()
    print(f"OMPL: DubinsStateSpace extent {space.getMaximumExtent():.1f}, resolution "
          f"{si.getStateValidityCheckingResolution():.3e} of it = {space.getLongestValidSegmentLength():.3f} m")

    # Grow to exactly `target` milestones: the termination condition is evaluated before every
    # sample, so the roadmap stops at the count.
    ptc = ob.PlannerTerminationCondition(lambda: planner.milestoneCount() >= target)
    calls[0], obstacles.exact_tests = 0, 0
    t0 = time.perf_counter()
    planner.growRoadmapPtc(ptc) if hasattr(planner, "growRoadmapPtc") else planner.growRoadmap(ptc)
    build_s = time.perf_counter() - t0
    build = {
        "seconds": build_s,
        "milestones": planner.milestoneCount(),
        "edges": planner.edgeCount(),
        "validity_checks": calls[0],
        "exact_point_tests": obstacles.exact_tests,
    }
    print(f"OMPL PRM*: {build['milestones']} milestones, {build['edges']} edges, {build_s:.2f} s, "
          f"{calls[0]} state validity checks")

    # Cost of one validity callback as OMPL sees it (C++ -> Python -> grid/GEOS), measured on a
    # separate batch of random states through si.isValid.
    rng = np.random.default_rng(7)
    st = space.allocState()
    n_cal = 50000
    xs = rng.uniform(bounds[0], bounds[2], n_cal)
    ys = rng.uniform(bounds[1], bounds[3], n_cal)
    t0 = time.perf_counter()
    for x, y in zip(xs, ys):
        st.setXY(x, y)
        si.isValid(st)
    per_check_s = (time.perf_counter() - t0) / n_cal
    build["per_check_us_estimate"] = per_check_s * 1e6

    # Queries
    os.makedirs(args.work_dir, exist_ok=True)
    queries = draw_queries(obstacles, bounds, args.queries, args.seed, args.min_free_m,
                           args.min_separation_m, args.edge_margin_m)
    simplifier = og.PathSimplifier(si)
    results = []
    milestones_before = planner.milestoneCount()
    for i, q in enumerate(queries):
        name = f"q{i:02d}"
        spath = os.path.join(args.work_dir, f"{name}.geojson")
        rpath = os.path.join(args.work_dir, f"{name}.route.json")
        with open(spath, "w") as f:
            json.dump(query_scenario(scenario, q, frame, name), f, indent=1)
        route, times, err = run_skyroute(args.skyroute, args.network, spath, rpath, args.repeat)
        r = {"name": name, "start": q["start"], "goal": q["goal"],
             "euclidean_m": math.hypot(q["goal"][0] - q["start"][0], q["goal"][1] - q["start"][1])}
        if route is not None:
            prims = [p for leg in route["legs"] for p in leg["primitives"]]
            pts = sample_primitives(prims)
            first = pts[0] if len(pts) else (math.nan, math.nan)
            r["ours"] = {
                "solved": True,
                "length_m": route["length_m"],
                "planned_length_m": sum(l["planned_length_m"] for l in route["legs"]),
                "network_edges": sum(l["network_edges"] for l in route["legs"]),
                "core_queries": route["queries"],
                "wall_s": times,
                "wall_median_s": median(times),
                "min_obstacle_distance_m": obstacles.min_distance_along(pts),
                "start_offset_m": math.hypot(first[0] - q["start"][0], first[1] - q["start"][1]),
            }
        else:
            r["ours"] = {"solved": False, "error": err, "wall_s": times, "wall_median_s": median(times)}

        # OMPL: the same poses on the grown roadmap.
        s, g = space.allocState(), space.allocState()
        set_pose(s, q["start"])
        set_pose(g, q["goal"])
        pd = ob.ProblemDefinition(si)
        pd.setStartAndGoalStates(s, g)
        planner.setProblemDefinition(pd)  # also clears the previous query
        m0 = planner.milestoneCount()
        t0 = time.perf_counter()
        status = planner.solve(ob.timedPlannerTerminationCondition(args.solve_time))
        solve_s = time.perf_counter() - t0
        o = {"status": str(status), "solve_s": solve_s, "milestones_added": planner.milestoneCount() - m0,
             "solved": bool(pd.hasExactSolution())}
        if o["solved"]:
            path = pd.getSolutionPath()
            raw = og.PathGeometric(path)
            o["raw_states"] = raw.getStateCount()
            o["raw_length_m"] = raw.length()
            o["raw_forward_valid"] = forward_motions_valid(si, raw)
            o["raw_min_obstacle_distance_m"] = obstacles.min_distance_along(path_points(space, raw))
            simp = og.PathGeometric(raw)
            t1 = time.perf_counter()
            simplifier.simplify(simp, args.simplify_time)
            o["simplify_s"] = time.perf_counter() - t1
            o["simplified_states"] = simp.getStateCount()
            o["simplified_length_m"] = simp.length()
            o["simplified_forward_valid"] = forward_motions_valid(si, simp)
            o["simplified_min_obstacle_distance_m"] = obstacles.min_distance_along(path_points(space, simp))
        r["ompl"] = o
        results.append(r)
        ours = r["ours"]
        print(f"{name}: {r['euclidean_m']:6.0f} m apart | ours "
              + (f"{ours['length_m']:7.1f} m (planned {ours['planned_length_m']:7.1f}) {ours['wall_median_s']*1e3:5.0f} ms"
                 if ours["solved"] else f"FAILED ({ours['error']})")
              + f" | OMPL {o['status']}, {solve_s*1e3:6.1f} ms"
              + (f", raw {o['raw_length_m']:7.1f} m (flyable as checked: {o['raw_forward_valid']}),"
                 f" simplified {o['simplified_length_m']:7.1f} m" if o["solved"] else ""))

    both = [r for r in results if r["ours"]["solved"] and r["ompl"]["solved"]]
    ours_ok = [r for r in results if r["ours"]["solved"]]
    ompl_ok = [r for r in results if r["ompl"]["solved"]]
    summary = {
        "queries": len(results),
        "ours_solved": len(ours_ok),
        "ompl_solved": len(ompl_ok),
        "both_solved": len(both),
        "ratio_ours_over_ompl_raw_median": median([r["ours"]["length_m"] / r["ompl"]["raw_length_m"] for r in both]),
        "ratio_ours_over_ompl_simplified_median": median(
            [r["ours"]["length_m"] / r["ompl"]["simplified_length_m"] for r in both]),
        "ratio_ours_planned_over_ompl_raw_median": median(
            [r["ours"]["planned_length_m"] / r["ompl"]["raw_length_m"] for r in both]),
        "ours_length_median_m": median([r["ours"]["length_m"] for r in ours_ok]),
        "ours_planned_length_median_m": median([r["ours"]["planned_length_m"] for r in ours_ok]),
        "ompl_raw_length_median_m": median([r["ompl"]["raw_length_m"] for r in ompl_ok]),
        "ompl_simplified_length_median_m": median([r["ompl"]["simplified_length_m"] for r in ompl_ok]),
        "ours_wall_median_s": median([r["ours"]["wall_median_s"] for r in results]),
        "ours_wall_max_s": max(r["ours"]["wall_median_s"] for r in results),
        "ompl_solve_median_s": median([r["ompl"]["solve_s"] for r in results]),
        "ompl_solve_max_s": max(r["ompl"]["solve_s"] for r in results),
        "ompl_simplify_median_s": median([r["ompl"]["simplify_s"] for r in ompl_ok]),
        "ompl_raw_forward_valid": sum(r["ompl"]["raw_forward_valid"] for r in ompl_ok),
        "ompl_simplified_forward_valid": sum(r["ompl"]["simplified_forward_valid"] for r in ompl_ok),
        "ompl_raw_min_obstacle_distance_m": min((r["ompl"]["raw_min_obstacle_distance_m"] for r in ompl_ok), default=None),
        "ompl_simplified_min_obstacle_distance_m": min(
            (r["ompl"]["simplified_min_obstacle_distance_m"] for r in ompl_ok), default=None),
        "ours_min_obstacle_distance_m": min((r["ours"]["min_obstacle_distance_m"] for r in ours_ok), default=None),
        "ompl_milestones_added_during_queries": planner.milestoneCount() - milestones_before,
        "ompl_milestones_after_queries": planner.milestoneCount(),
        "ompl_edges_after_queries": planner.edgeCount(),
    }
    report = {
        "setup": {
            "network_json": args.network_json,
            "scenario": args.scenario,
            "bounds": bounds,
            "turn_radius_m": net["turn_radius_m"],
            "clearance_m": net["clearance_m"],
            "resolution_m": space.getLongestValidSegmentLength(),
            "resolution_fraction": si.getStateValidityCheckingResolution(),
            "solve_time_cap_s": args.solve_time,
            "seed": args.seed,
            "ompl_seed": args.ompl_seed,
            "repeat": args.repeat,
            "checker_setup_s": checker_setup_s,
            "ours_vertices_invalid_for_ompl_checker": ours_invalid,
        },
        "ours_network": {"vertices": len(net["vertices"]), "edges": len(net["edges"])},
        "ompl_build": build,
        "summary": summary,
        "queries": results,
    }
    with open(args.report, "w") as f:
        json.dump(report, f, indent=1)
    print(json.dumps({"ompl_build": build, "summary": summary}, indent=1))
    print(f"report -> {args.report}")


if __name__ == "__main__":
    main()
