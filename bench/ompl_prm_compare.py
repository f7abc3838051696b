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
3. Grows PRM* roadmaps (`growRoadmap`, single-threaded) until each has as many milestones as
   skyroute's network has vertices, and records the wall time, the milestone and edge counts and
   the state validity checks. Two variants (`--variants`):
   * `stock`: OMPL as it comes. PRM's roadmap is an undirected graph; the edge {n, m} is checked
     only as the Dubins path n -> m (n the older milestone, m the new one), yet the graph search
     may use it m -> n, which is a different Dubins path that nobody checked.
   * `both-ways`: a motion validator that accepts an edge only when the Dubins paths n -> m and
     m -> n are both collision-free, so every route the search returns is flyable as checked
     (the search still weighs the edge with the n -> m length in both directions).
   Every roadmap is grown before any query: growth is single-threaded and reproducible with the
   seed, whereas solve() grows the roadmap further while its solution thread looks for a route.
4. Draws `--queries` start/goal pose pairs with a fixed seed (free positions at least
   `--min-free-m` beyond the clearance from every obstacle, at least `--min-separation-m` apart,
   fixed uniformly drawn headings), writes each as a scenario (a copy of the original scenario
   with its start, goal and waypoints replaced: start and goal both with a heading, no
   waypoints), plans it with `skyroute plan` (timed as a whole process: start-up, network load,
   planning, post-processing, writing the route), and solves the same pair on each grown PRM*
   roadmap: `solve` with a time cap, the objective's cost threshold set to infinity so that the
   first route found (A* on the roadmap once start and goal share a component) ends the solve,
   and a fresh problem definition (which clears the query) each time. Start and goal stay in
   the roadmap as milestones afterwards, as PRM does.
5. Compares lengths pair by pair (raw and after `PathSimplifier.simplify`), re-checks every OMPL
   route in its direction of flight, measures the closest approach to the obstacles of both
   planners' routes by sampling them every 0.5 m, and writes a JSON report with every number
   (`--report`).

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
        # Rounded to f32, the precision the onboard core works in (and kept inside OMPL's
        # SO(2) bounds [-pi, pi], which an f32 rounding of +-pi would leave).
        f32 = lambda v: float(np.float32(v))
        ha, hb = f32(rng.uniform(-3.14159, 3.14159)), f32(rng.uniform(-3.14159, 3.14159))
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


class OmplVariant:
    """PRM* over `DubinsStateSpace(r)` (forward-only) with the clearance checker.

    `both_ways=False` is stock OMPL: the default discrete motion validator, and PRM's roadmap is
    an undirected graph whose edge {n, m} is checked only as the Dubins path n -> m (n the older
    milestone). `both_ways=True` accepts an edge only when the Dubins paths n -> m and m -> n are
    both collision-free (OMPL's DubinsMotionValidator on each), so every edge is flyable in
    whichever direction the graph search uses it.
    """

    def __init__(self, name, network, bounds, obstacles, resolution_m, both_ways):
        self.name = name
        self.both_ways = both_ways
        self.bounds = bounds
        space = ob.DubinsStateSpace(float(network["turn_radius_m"]), False)
        b = ob.RealVectorBounds(2)
        b.setLow(0, bounds[0])
        b.setHigh(0, bounds[2])
        b.setLow(1, bounds[1])
        b.setHigh(1, bounds[3])
        space.setBounds(b)
        si = ob.SpaceInformation(space)
        self.calls = [0]
        calls, blocked = self.calls, obstacles.blocked

        def valid(s):
            calls[0] += 1
            return not blocked(s.getX(), s.getY())

        si.setStateValidityChecker(valid)
        # The resolution is a fraction of the space's maximum extent; OMPL's Dubins space cuts a
        # motion into ceil(dubins_length / (fraction * extent)) segments and checks each state.
        si.setStateValidityCheckingResolution(resolution_m / space.getMaximumExtent())
        # An independent forward-only validator, for re-checking solutions as they are flown.
        self.forward = ob.DubinsMotionValidator(si)
        if both_ways:
            fwd = ob.DubinsMotionValidator(si)

            class BothWays(ob.MotionValidator):
                def checkMotion(self, a, b, *rest):
                    return fwd.checkMotion(a, b) and fwd.checkMotion(b, a)

            self._mv = BothWays(si)  # keep the Python object alive
            si.setMotionValidator(self._mv)
        si.setup()
        self.space, self.si = space, si
        self.planner = og.PRMstar(si)
        # The first solution found ends solve(): any finite cost satisfies the objective. PRM*
        # otherwise keeps growing the roadmap to improve the route until the time cap.
        self.objective = ob.PathLengthOptimizationObjective(si)
        self.objective.setCostThreshold(self.objective.infiniteCost())
        pd = self.problem((0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
        self.planner.setProblemDefinition(pd)
        self.planner.setup()
        self.simplifier = og.PathSimplifier(si)

    def problem(self, start, goal):
        s, g = self.space.allocState(), self.space.allocState()
        set_pose(s, start)
        set_pose(g, goal)
        pd = ob.ProblemDefinition(self.si)
        pd.setStartAndGoalStates(s, g)
        pd.setOptimizationObjective(self.objective)
        self._keep = (s, g, pd)
        return pd

    def grow(self, target, obstacles):
        """Grows the roadmap to exactly `target` milestones (the termination condition is
        evaluated before every sample)."""
        p = self.planner
        ptc = ob.PlannerTerminationCondition(lambda: p.milestoneCount() >= target)
        self.calls[0], obstacles.exact_tests = 0, 0
        t0 = time.perf_counter()
        p.growRoadmapPtc(ptc) if hasattr(p, "growRoadmapPtc") else p.growRoadmap(ptc)
        seconds = time.perf_counter() - t0
        checks, exact = self.calls[0], obstacles.exact_tests
        # What one checked state costs inside a motion check (OMPL interpolates the Dubins path
        # in C++ and calls the Python checker): motions between random nearby free poses,
        # checked from C++, time divided by the states checked.
        rng = np.random.default_rng(7)
        a, b = self.space.allocState(), self.space.allocState()
        n0, t_cal = self.calls[0], 0.0
        done = 0
        while done < 300:
            x, y = rng.uniform(self.bounds[0], self.bounds[2]), rng.uniform(self.bounds[1], self.bounds[3])
            ang = rng.uniform(-math.pi, math.pi)
            set_pose(a, (x, y, rng.uniform(-3.14, 3.14)))
            set_pose(b, (x + 150 * math.cos(ang), y + 150 * math.sin(ang), rng.uniform(-3.14, 3.14)))
            t1 = time.perf_counter()
            self.forward.checkMotion(a, b)
            t_cal += time.perf_counter() - t1
            done += 1
        per_check = t_cal / max(1, self.calls[0] - n0)
        return {
            "seconds": seconds,
            "milestones": p.milestoneCount(),
            "edges": p.edgeCount(),
            "validity_checks": checks,
            "exact_point_tests": exact,
            "per_check_us": per_check * 1e6,
            "checking_seconds_estimate": per_check * checks,
        }

    def solve(self, q, mode, time_cap, simplify_time, obstacles):
        """One query. `mode`:

        * "fixed": on the roadmap as it is. solve() with a termination condition that is already
          true: PRM adds the start and the goal as milestones (connecting each to its k nearest
          with checked motions), grows nothing, finds no exact solution and returns its
          approximate one, an A* over the roadmap towards the goal; the goal was reached iff the
          reported difference is 0. A second solve() on the same problem (start and goal already
          in the roadmap) times the graph search alone.
        * "grow": PRM*'s own single-query behaviour: solve() grows the roadmap in the calling
          thread while a second thread looks for a route every millisecond; the first route found
          (A* once start and goal share a component) ends it, or the `time_cap`.
        """
        pd = self.problem(q["start"], q["goal"])
        p = self.planner
        p.setProblemDefinition(pd)  # also clears the previous query (clearQuery)
        m0 = p.milestoneCount()
        ptc = ob.timedPlannerTerminationCondition(0.0 if mode == "fixed" else time_cap)
        t0 = time.perf_counter()
        status = p.solve(ptc)
        o = {"status": str(status), "solve_s": time.perf_counter() - t0, "milestones_added": p.milestoneCount() - m0}
        if mode == "fixed":
            o["solved"] = bool(pd.hasSolution()) and pd.getSolutionDifference() == 0.0
            if o["solved"]:
                path = og.PathGeometric(pd.getSolutionPath())
                pd.clearSolutionPaths()
                t1 = time.perf_counter()
                p.solve(ob.timedPlannerTerminationCondition(0.0))
                o["search_only_s"] = time.perf_counter() - t1
        else:
            o["solved"] = bool(pd.hasExactSolution())
            path = pd.getSolutionPath() if o["solved"] else None
        if not o["solved"]:
            return o
        raw = og.PathGeometric(path)
        o.update(self.describe("raw", raw, obstacles))
        simp = og.PathGeometric(raw)
        t1 = time.perf_counter()
        self.simplifier.simplify(simp, simplify_time)
        o["simplify_s"] = time.perf_counter() - t1
        o.update(self.describe("simplified", simp, obstacles))
        return o

    def describe(self, tag, path, obstacles):
        """Length as flown (state i to state i+1 along the forward Dubins path), whether every
        motion passes OMPL's own discrete check in that direction, how many motions pass only
        in the reverse direction, and the closest approach to the obstacles (0.5 m sampling)."""
        n = path.getStateCount()
        fwd = [self.forward.checkMotion(path.getState(i), path.getState(i + 1)) for i in range(n - 1)]
        rev_only = sum(1 for i in range(n - 1)
                       if not fwd[i] and self.forward.checkMotion(path.getState(i + 1), path.getState(i)))
        return {
            f"{tag}_states": n,
            f"{tag}_length_m": path.length(),
            f"{tag}_forward_valid": all(fwd),
            f"{tag}_motions_failing_forward": fwd.count(False),
            f"{tag}_motions_valid_only_reversed": rev_only,
            f"{tag}_min_obstacle_distance_m": obstacles.min_distance_along(path_points(self.space, path)),
        }


def set_pose(state, pose):
    state.setXY(pose[0], pose[1])
    state.setYaw(pose[2])


def path_points(space, path, step=0.5):
    """Points every `step` metres along the Dubins curves joining the path's states in order."""
    tmp = space.allocState()  # owned by Python: not freed by hand
    pts = []
    for i in range(path.getStateCount() - 1):
        a, b = path.getState(i), path.getState(i + 1)
        n = max(1, int(math.ceil(space.distance(a, b) / step)))
        for k in range(n + 1):
            space.interpolate(a, b, k / n, tmp)
            pts.append((tmp.getX(), tmp.getY()))
    return np.array(pts)


# --------------------------------------------------------------------------------------------


def median(xs):
    return statistics.median(xs) if xs else None


def summarise(results, vname, mode, clearance):
    """Summary of one OMPL variant and query mode against ours over the queries."""
    key = f"{vname}/{mode}"
    ours_ok = [r for r in results if r["ours"]["solved"]]
    ompl_ok = [r for r in results if r[key]["solved"]]
    both = [r for r in ours_ok if r[key]["solved"]]
    tol = 1e-6

    def ratio(a, b):
        return median([r["ours"][a] / r[key][b] for r in both])

    return {
        "ompl_solved": len(ompl_ok),
        "both_solved": len(both),
        "ratio_ours_over_raw_median": ratio("length_m", "raw_length_m"),
        "ratio_ours_over_simplified_median": ratio("length_m", "simplified_length_m"),
        "ratio_ours_planned_over_raw_median": ratio("planned_length_m", "raw_length_m"),
        "raw_length_median_m": median([r[key]["raw_length_m"] for r in ompl_ok]),
        "simplified_length_median_m": median([r[key]["simplified_length_m"] for r in ompl_ok]),
        "solve_median_s": median([r[key]["solve_s"] for r in results]),
        "solve_max_s": max(r[key]["solve_s"] for r in results),
        "solve_median_solved_s": median([r[key]["solve_s"] for r in ompl_ok]),
        "solve_max_solved_s": max((r[key]["solve_s"] for r in ompl_ok), default=None),
        "simplify_median_s": median([r[key]["simplify_s"] for r in ompl_ok]),
        "raw_forward_valid": sum(r[key]["raw_forward_valid"] for r in ompl_ok),
        "simplified_forward_valid": sum(r[key]["simplified_forward_valid"] for r in ompl_ok),
        "raw_inside_clearance": sum(r[key]["raw_min_obstacle_distance_m"] < clearance - 0.5 for r in ompl_ok),
        "raw_inside_obstacle": sum(r[key]["raw_min_obstacle_distance_m"] <= tol for r in ompl_ok),
        "simplified_inside_clearance": sum(
            r[key]["simplified_min_obstacle_distance_m"] < clearance - 0.5 for r in ompl_ok),
        "simplified_inside_obstacle": sum(r[key]["simplified_min_obstacle_distance_m"] <= tol for r in ompl_ok),
        "raw_min_obstacle_distance_m": min((r[key]["raw_min_obstacle_distance_m"] for r in ompl_ok), default=None),
        "simplified_min_obstacle_distance_m": min(
            (r[key]["simplified_min_obstacle_distance_m"] for r in ompl_ok), default=None),
        "search_only_median_s": median([r[key]["search_only_s"] for r in ompl_ok if "search_only_s" in r[key]]),
        "search_only_max_s": max((r[key]["search_only_s"] for r in ompl_ok if "search_only_s" in r[key]), default=None),
        "milestones_added_during_queries": sum(r[key]["milestones_added"] for r in results),
    }


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
    ap.add_argument("--variants", default="stock,both-ways",
                    help="OMPL variants to run: stock (one-way edge checks), both-ways")
    args = ap.parse_args()

    with open(args.network_json) as f:
        net = json.load(f)
    with open(args.scenario) as f:
        scenario = json.load(f)
    fr = net["frame"]
    frame = Frame(fr["origin_lat_deg"], fr["origin_lon_deg"])
    bounds = scenario_bounds(scenario, frame.to_local)
    target = args.target or len(net["vertices"])
    clearance = float(net["clearance_m"])
    print(f"area {bounds[0]:.1f}..{bounds[2]:.1f} x {bounds[1]:.1f}..{bounds[3]:.1f} m, "
          f"r = {net['turn_radius_m']:.3f} m, clearance {clearance} m, "
          f"{len(net['obstacles'])} obstacles; skyroute: {len(net['vertices'])} vertices, {len(net['edges'])} edges")

    t0 = time.perf_counter()
    obstacles = Obstacles(net, bounds)
    checker_setup_s = time.perf_counter() - t0
    tested = obstacles.self_test(bounds)
    print(f"validity checker: grid {obstacles.nx}x{obstacles.ny} cells of {obstacles.cell} m, "
          f"{checker_setup_s:.2f} s to set up, agrees with the exact test on {tested} points")
    # Our vertices are valid states for the OMPL checker too (the same clearance rule).
    ours_invalid = sum(obstacles.blocked(v["x"], v["y"]) for v in net["vertices"])

    # The queries, and our side of them.
    os.makedirs(args.work_dir, exist_ok=True)
    queries = draw_queries(obstacles, bounds, args.queries, args.seed, args.min_free_m,
                           args.min_separation_m, args.edge_margin_m)
    results = []
    for i, q in enumerate(queries):
        name = f"q{i:02d}"
        spath = os.path.join(args.work_dir, f"{name}.geojson")
        rpath = os.path.join(args.work_dir, f"{name}.route.json")
        with open(spath, "w") as f:
            json.dump(query_scenario(scenario, q, frame, name), f, indent=1)
        route, times, err = run_skyroute(args.skyroute, args.network, spath, rpath, args.repeat)
        r = {"name": name, "scenario": spath, "start": q["start"], "goal": q["goal"],
             "euclidean_m": math.hypot(q["goal"][0] - q["start"][0], q["goal"][1] - q["start"][1])}
        if route is not None:
            prims = [p for leg in route["legs"] for p in leg["primitives"]]
            pts = sample_primitives(prims)
            r["ours"] = {
                "solved": True,
                "length_m": route["length_m"],
                "planned_length_m": sum(l["planned_length_m"] for l in route["legs"]),
                "network_edges": sum(l["network_edges"] for l in route["legs"]),
                "core_queries": route["queries"],
                "work_total": route["work_all_queries"]["total"],
                "wall_s": times,
                "wall_median_s": median(times),
                "min_obstacle_distance_m": obstacles.min_distance_along(pts),
                "start_offset_m": math.hypot(pts[0][0] - q["start"][0], pts[0][1] - q["start"][1]),
                "end_offset_m": math.hypot(pts[-1][0] - q["goal"][0], pts[-1][1] - q["goal"][1]),
            }
        else:
            r["ours"] = {"solved": False, "error": err, "wall_s": times, "wall_median_s": median(times)}
        ours = r["ours"]
        print(f"{name}: {r['euclidean_m']:6.0f} m apart | ours "
              + (f"{ours['length_m']:7.1f} m (planned {ours['planned_length_m']:7.1f}), "
                 f"{ours['wall_median_s'] * 1e3:4.0f} ms" if ours["solved"] else f"FAILED: {ours['error']}"),
              flush=True)
        results.append(r)

    report = {
        "setup": {
            "network_json": args.network_json, "scenario": args.scenario, "bounds": bounds,
            "turn_radius_m": net["turn_radius_m"], "clearance_m": clearance,
            "resolution_m": args.resolution_m, "solve_time_cap_s": args.solve_time,
            "simplify_time_cap_s": args.simplify_time, "seed": args.seed, "ompl_seed": args.ompl_seed,
            "repeat": args.repeat, "checker_setup_s": checker_setup_s,
            "ours_vertices_invalid_for_ompl_checker": ours_invalid,
        },
        "ours_network": {"vertices": len(net["vertices"]), "edges": len(net["edges"])},
        "ours_summary": {
            "solved": sum(r["ours"]["solved"] for r in results),
            "length_median_m": median([r["ours"]["length_m"] for r in results if r["ours"]["solved"]]),
            "wall_median_s": median([r["ours"]["wall_median_s"] for r in results]),
            "wall_max_s": max(r["ours"]["wall_median_s"] for r in results),
            "min_obstacle_distance_m": min(
                (r["ours"]["min_obstacle_distance_m"] for r in results if r["ours"]["solved"]), default=None),
        },
        "ompl": {},
        "queries": results,
    }

    ou.setLogLevel(ou.LOG_WARN)
    # One seed for the process (OMPL allows setting it once, before any sampling). Every roadmap
    # is grown before any query is solved: growing is single-threaded and reproducible, while
    # solve() grows the roadmap further for as long as its solution thread takes to answer.
    ou.RNG.setSeed(args.ompl_seed)
    variants = []
    for vname in [v.strip() for v in args.variants.split(",") if v.strip()]:
        if vname not in ("stock", "both-ways"):
            sys.exit(f"--variants: unknown variant {vname!r}")
        v = OmplVariant(vname, net, bounds, obstacles, args.resolution_m, vname == "both-ways")
        print(f"OMPL {vname}: DubinsStateSpace extent {v.space.getMaximumExtent():.1f} m, resolution "
              f"{v.si.getStateValidityCheckingResolution():.4e} of it = {v.space.getLongestValidSegmentLength():.3f} m",
              flush=True)
        v.build = v.grow(target, obstacles)
        b = v.build
        print(f"OMPL {vname}: PRM* {b['milestones']} milestones, {b['edges']} edges, {b['seconds']:.2f} s, "
              f"{b['validity_checks']} state validity checks (~{b['per_check_us']:.2f} us each, ~{b['checking_seconds_estimate']:.1f} s)", flush=True)
        variants.append(v)
    # All "fixed" queries first (the roadmaps then differ from the grown ones only by the start
    # and goal milestones the queries leave behind), then the "grow" queries.
    for mode in ("fixed", "grow"):
        for v in variants:
            key = f"{v.name}/{mode}"
            for r in results:
                o = v.solve(r, mode, args.solve_time, args.simplify_time, obstacles)
                r[key] = o
                print(f"  {key} {r['name']}: {o['status']}, {o['solve_s'] * 1e3:6.1f} ms"
                      + (f", raw {o['raw_length_m']:7.1f} m (flyable as checked: {o['raw_forward_valid']}, "
                         f"closest {o['raw_min_obstacle_distance_m']:.1f} m), simplified {o['simplified_length_m']:7.1f} m"
                         if o["solved"] else ""), flush=True)
            entry = report["ompl"].setdefault(v.name, {"build": v.build})
            entry[mode] = summarise(results, v.name, mode, clearance)
            entry[f"milestones_after_{mode}_queries"] = v.planner.milestoneCount()
            entry[f"edges_after_{mode}_queries"] = v.planner.edgeCount()
            print(key, json.dumps(entry[mode], indent=1), flush=True)

    with open(args.report, "w") as f:
        json.dump(report, f, indent=1)
    print(json.dumps({"ours_network": report["ours_network"], "ours_summary": report["ours_summary"]}, indent=1))
    print(f"report -> {args.report}")
    sys.stdout.flush()
    sys.stderr.flush()
    # Skips the interpreter's teardown, where nanobind lists the OMPL objects still shared with
    # C++ (the planner holds states, validators and callbacks) as "leaked": harmless, but noisy.
    os._exit(0)


if __name__ == "__main__":
    main()
