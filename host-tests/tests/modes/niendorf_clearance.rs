//! The niendorf-urban network and mission, checked from the outside.
//!
//! The network is built and the mission planned by the ground tool's library, then exported to
//! JSON (`skyroute export`'s function and `skyroute plan`'s route file). Everything after that
//! works only from the JSON text and from the scenario's lon/lat building footprints, read here
//! straight from the GeoJSON and projected with `LocalFrame`: the primitives are evaluated and
//! sampled in f64 every ≤ 0.5 m, and distances to the buildings come from the point–polygon
//! distance below, not from the core's predicates.

use serde_json::Value;
use skyroute::Network;

use skyroute_prep::export::network_json;
use skyroute_prep::frame::LocalFrame;
use skyroute_prep::mission::plan_mission;
use skyroute_prep::route_json::mission_json;

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::PathBuf;
use std::time::Instant;

use host_tests::reference::{dist, dist_polygon, P};
use host_tests::scenarios;

/// Largest spacing of the samples along a primitive, metres.
const STEP: f64 = 0.5;
/// Clearance may be missed by this much (f32 storage of the network), metres.
const CLEARANCE_TOL: f64 = 1e-2;
/// Gap allowed where one primitive meets the next, or an edge its vertex, metres.
const JOIN_TOL: f64 = 1e-2;
/// Heading change allowed where one primitive meets the next, radians.
const HEADING_TOL: f64 = 2e-3;
/// Lines shorter than this have no reliable direction once their ends are rounded to f32
/// (a few mm at coordinates of a km give directions off by degrees): their heading is not
/// compared, their ends still are.
const SHORT_LINE: f64 = 0.5;
/// A leg must end this close to its endpoint, metres.
const ARRIVAL_TOL: f64 = 0.05;

fn scenario_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios/niendorf-urban.geojson")
}

// ------------------------------------------------------------------------------------------------
// Geometry, in f64, independent of the core

/// A primitive as read from the JSON.
#[derive(Clone, Copy, Debug)]
enum Prim {
    Line { a: P, b: P },
    Arc { c: P, r: f64, a0: f64, sweep: f64 },
}

fn pair(v: &Value) -> P {
    let a = v.as_array().expect("[x, y]");
    assert_eq!(a.len(), 2, "{v}");
    (a[0].as_f64().unwrap(), a[1].as_f64().unwrap())
}

fn f(v: &Value, k: &str) -> f64 {
    v[k].as_f64().unwrap_or_else(|| panic!("{k} in {v}"))
}

fn prim(v: &Value) -> Prim {
    match v["type"].as_str() {
        Some("line") => Prim::Line {
            a: pair(&v["start"]),
            b: pair(&v["end"]),
        },
        Some("arc") => {
            let p = Prim::Arc {
                c: pair(&v["centre"]),
                r: f(v, "radius"),
                a0: f(v, "start_angle"),
                sweep: f(v, "sweep"),
            };
            let turn = v["turn"].as_str().unwrap();
            assert_eq!(
                turn,
                if f(v, "sweep") >= 0.0 {
                    "left"
                } else {
                    "right"
                },
                "{v}"
            );
            p
        }
        t => panic!("unknown primitive type {t:?}"),
    }
}

impl Prim {
    fn length(&self) -> f64 {
        match *self {
            Prim::Line { a, b } => (b.0 - a.0).hypot(b.1 - a.1),
            Prim::Arc { r, sweep, .. } => r * sweep.abs(),
        }
    }
    /// Point at fraction `t` ∈ [0, 1].
    fn at(&self, t: f64) -> P {
        match *self {
            Prim::Line { a, b } => (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t),
            Prim::Arc { c, r, a0, sweep } => {
                let ang = a0 + sweep * t;
                (c.0 + r * ang.cos(), c.1 + r * ang.sin())
            }
        }
    }
    /// Heading (radians counter-clockwise from x) at fraction `t`, from the geometry: a line's
    /// direction, an arc's tangent in the direction of its sweep. `None` for a line too short to
    /// have a reliable direction.
    fn heading(&self, t: f64) -> Option<f64> {
        match *self {
            Prim::Line { a, b } => {
                (self.length() >= SHORT_LINE).then(|| (b.1 - a.1).atan2(b.0 - a.0))
            }
            Prim::Arc { a0, sweep, .. } => {
                Some(a0 + sweep * t + if sweep >= 0.0 { FRAC_PI_2 } else { -FRAC_PI_2 })
            }
        }
    }
    /// A box that holds the whole primitive (an arc's full circle).
    fn bbox(&self) -> (P, P) {
        match *self {
            Prim::Line { a, b } => ((a.0.min(b.0), a.1.min(b.1)), (a.0.max(b.0), a.1.max(b.1))),
            Prim::Arc { c, r, .. } => ((c.0 - r, c.1 - r), (c.0 + r, c.1 + r)),
        }
    }
    /// Points every ≤ STEP metres, both ends included.
    fn samples(&self) -> impl Iterator<Item = P> + '_ {
        let n = (self.length() / STEP).ceil().max(1.0) as usize;
        (0..=n).map(move |i| self.at(i as f64 / n as f64))
    }
}

/// Difference of two angles, wrapped to [0, π].
fn angle_diff(a: f64, b: f64) -> f64 {
    (a - b).rem_euclid(TAU).min((b - a).rem_euclid(TAU))
}

/// A building footprint in the local frame, with its bounding box.
struct Building {
    name: String,
    ring: Vec<P>,
    lo: P,
    hi: P,
}

/// The smallest distance from the primitive to any building, sampled every ≤ STEP metres, and
/// the building and point where it occurs. Buildings whose widened box misses the primitive's
/// box are skipped (they are farther than `reach` everywhere).
fn closest_building(p: &Prim, buildings: &[Building], reach: f64) -> Option<(f64, usize, P)> {
    let (lo, hi) = p.bbox();
    let mut best: Option<(f64, usize, P)> = None;
    for (k, b) in buildings.iter().enumerate() {
        if hi.0 < b.lo.0 - reach
            || lo.0 > b.hi.0 + reach
            || hi.1 < b.lo.1 - reach
            || lo.1 > b.hi.1 + reach
        {
            continue;
        }
        for q in p.samples() {
            let d = dist_polygon(q, &b.ring);
            if best.is_none_or(|x| d < x.0) {
                best = Some((d, k, q));
            }
        }
    }
    best
}

// ------------------------------------------------------------------------------------------------
// The scenario, read straight from the GeoJSON

struct Endpoint {
    name: String,
    lon: f64,
    lat: f64,
    heading_deg: Option<f64>,
}

struct Raw {
    clearance_m: f64,
    /// Building rings, lon/lat, closing position dropped.
    buildings: Vec<(String, Vec<P>)>,
    /// Start, waypoints in file order, goal.
    stops: Vec<Endpoint>,
}

fn read_raw() -> Raw {
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(scenario_path()).unwrap()).unwrap();
    let mut buildings = Vec::new();
    let (mut start, mut goal, mut waypoints) = (None, None, Vec::new());
    for feat in v["features"].as_array().unwrap() {
        let props = &feat["properties"];
        let name = props["name"].as_str().unwrap_or("?").to_string();
        let geom = &feat["geometry"]["coordinates"];
        match props["kind"].as_str().unwrap() {
            "no_fly" => {
                let rings = geom.as_array().unwrap();
                assert_eq!(rings.len(), 1, "{name}: one ring");
                let mut ring: Vec<P> = rings[0].as_array().unwrap().iter().map(pair).collect();
                assert_eq!(ring.first(), ring.last(), "{name}: closed ring");
                ring.pop();
                buildings.push((name, ring));
            }
            kind @ ("start" | "goal" | "waypoint") => {
                let (lon, lat) = pair(geom);
                let e = Endpoint {
                    name,
                    lon,
                    lat,
                    heading_deg: props["heading_deg"].as_f64(),
                };
                match kind {
                    "start" => start = Some(e),
                    "goal" => goal = Some(e),
                    _ => waypoints.push(e),
                }
            }
            other => panic!("unexpected feature kind {other} in niendorf-urban"),
        }
    }
    let mut stops = vec![start.expect("start")];
    stops.extend(waypoints);
    stops.push(goal.expect("goal"));
    Raw {
        clearance_m: v["planner"]["clearance_m"].as_f64().unwrap(),
        buildings,
        stops,
    }
}

fn project(raw: &Raw, frame: &LocalFrame) -> Vec<Building> {
    raw.buildings
        .iter()
        .map(|(name, ring)| {
            let ring: Vec<P> = ring
                .iter()
                .map(|&(lon, lat)| frame.to_local(lon, lat))
                .collect();
            let lo = ring.iter().fold((f64::INFINITY, f64::INFINITY), |a, p| {
                (a.0.min(p.0), a.1.min(p.1))
            });
            let hi = ring
                .iter()
                .fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |a, p| {
                    (a.0.max(p.0), a.1.max(p.1))
                });
            Building {
                name: name.clone(),
                ring,
                lo,
                hi,
            }
        })
        .collect()
}

/// Local heading (radians counter-clockwise from x) of a compass heading at (lon, lat).
fn local_heading(frame: &LocalFrame, lon: f64, lat: f64, compass_deg: f64) -> f64 {
    FRAC_PI_2 - frame.heading_to_local(lon, lat, compass_deg).to_radians()
}

// ------------------------------------------------------------------------------------------------

#[test]
fn niendorf_network_and_route_keep_clearance_from_every_building() {
    let t0 = Instant::now();
    // The one niendorf-urban build of this process (shared with `roadmap_build`).
    let s = scenarios::scenario("niendorf-urban");
    let built = scenarios::built("niendorf-urban");
    let net = Network::from_bytes(&built.bytes).unwrap();
    let text = serde_json::to_string(&network_json(&net)).unwrap();
    let t_build = t0.elapsed();

    // ---- From here on: the exported JSON and the GeoJSON only.
    let exported: Value = serde_json::from_str(&text).unwrap();
    let raw = read_raw();
    let frame = LocalFrame::new(
        f(&exported["frame"], "origin_lat_deg"),
        f(&exported["frame"], "origin_lon_deg"),
    );
    let clearance = f(&exported, "clearance_m");
    assert!(
        (clearance - raw.clearance_m).abs() < 1e-6,
        "{clearance} vs the scenario's {}",
        raw.clearance_m
    );
    let buildings = project(&raw, &frame);
    assert_eq!(buildings.len(), 60);

    // The exported obstacles are the buildings, in order, to f32 rounding.
    let obstacles = exported["obstacles"].as_array().unwrap();
    assert_eq!(obstacles.len(), buildings.len());
    for (o, b) in obstacles.iter().zip(&buildings) {
        assert_eq!(o["kind"], "polygon");
        let pts: Vec<P> = o["points"].as_array().unwrap().iter().map(pair).collect();
        assert_eq!(pts.len(), b.ring.len(), "{}", b.name);
        for (p, q) in pts.iter().zip(&b.ring) {
            assert!(
                dist(*p, *q) < 1e-3,
                "{}: exported {p:?}, projected {q:?}",
                b.name
            );
        }
    }

    // Vertices: poses, and lon/lat consistent with x/y.
    let vertices = exported["vertices"].as_array().unwrap();
    let poses: Vec<(P, f64)> = vertices
        .iter()
        .enumerate()
        .map(|(i, v)| {
            assert_eq!(v["id"].as_u64(), Some(i as u64));
            let p = (f(v, "x"), f(v, "y"));
            let (x, y) = frame.to_local(f(v, "lon"), f(v, "lat"));
            assert!(dist(p, (x, y)) < 1e-6, "vertex {i}: lon/lat is not x/y");
            let h = f(v, "heading_rad");
            let hc = local_heading(
                &frame,
                f(v, "lon"),
                f(v, "lat"),
                f(v, "heading_compass_deg"),
            );
            assert!(
                angle_diff(h, hc) < 1e-5,
                "vertex {i}: compass heading is not heading_rad"
            );
            (p, h)
        })
        .collect();

    // Edges: continuous, from the from-vertex's pose to the to-vertex's, clear of every building.
    let edges = exported["edges"].as_array().unwrap();
    assert!(edges.len() > 10_000, "{} edges", edges.len());
    let reach = clearance + 1.0;
    let (mut samples, mut worst_gap, mut worst_turn) = (0usize, 0.0f64, 0.0f64);
    let mut closest = (f64::INFINITY, String::new());
    for (i, e) in edges.iter().enumerate() {
        assert_eq!(e["id"].as_u64(), Some(i as u64));
        let (from, to) = (
            e["from"].as_u64().unwrap() as usize,
            e["to"].as_u64().unwrap() as usize,
        );
        let prims: Vec<Prim> = e["primitives"]
            .as_array()
            .unwrap()
            .iter()
            .map(prim)
            .collect();
        let (fp, fh) = poses[from];
        let (tp, th) = poses[to];
        let Some((first, last)) = prims.first().zip(prims.last()) else {
            assert!(
                dist(fp, tp) < JOIN_TOL && angle_diff(fh, th) < HEADING_TOL,
                "edge {i}: empty but from ≠ to"
            );
            continue;
        };
        let length: f64 = prims.iter().map(Prim::length).sum();
        assert!(
            (length - f(e, "cost")).abs() < 1e-2 + 1e-5 * length,
            "edge {i}: cost {} vs length {length}",
            f(e, "cost")
        );
        let mut check = |what: &str, gap: f64, turn: Option<f64>| {
            worst_gap = worst_gap.max(gap);
            assert!(
                gap <= JOIN_TOL,
                "edge {i} ({from} -> {to}): {what}: {gap} m apart"
            );
            if let Some(t) = turn {
                worst_turn = worst_turn.max(t);
                assert!(
                    t <= HEADING_TOL,
                    "edge {i} ({from} -> {to}): {what}: heading differs by {t} rad"
                );
            }
        };
        check(
            "start vs from-vertex",
            dist(first.at(0.0), fp),
            first.heading(0.0).map(|h| angle_diff(h, fh)),
        );
        check(
            "end vs to-vertex",
            dist(last.at(1.0), tp),
            last.heading(1.0).map(|h| angle_diff(h, th)),
        );
        for (k, w) in prims.windows(2).enumerate() {
            let turn = w[0]
                .heading(1.0)
                .zip(w[1].heading(0.0))
                .map(|(a, b)| angle_diff(a, b));
            check(
                &format!("primitive {k} -> {}", k + 1),
                dist(w[0].at(1.0), w[1].at(0.0)),
                turn,
            );
        }
        for (k, p) in prims.iter().enumerate() {
            samples += (p.length() / STEP).ceil().max(1.0) as usize + 1;
            if let Some((d, b, q)) = closest_building(p, &buildings, reach) {
                assert!(
                    d >= clearance - CLEARANCE_TOL,
                    "edge {i} ({from} -> {to}) primitive {k} comes {d} m from building {} at {q:?} (clearance {clearance})",
                    buildings[b].name
                );
                if d < closest.0 {
                    closest = (d, format!("edge {i}, building {}", buildings[b].name));
                }
            }
        }
    }
    let t_edges = t0.elapsed();
    eprintln!(
        "{} edges, {samples} samples: closest approach {:.4} m ({}), clearance {clearance} m; \
         largest gap {worst_gap:.2e} m, largest heading jump {worst_turn:.2e} rad",
        edges.len(),
        closest.0,
        closest.1
    );

    // ---- The mission, from the route file's JSON.
    let m = plan_mission(&built.bytes, s, &built.frame, &[]).unwrap();
    let route_text = serde_json::to_string(&mission_json(&m, &built.frame, &s.name)).unwrap();
    let route: Value = serde_json::from_str(&route_text).unwrap();
    assert_eq!(f(&route["frame"], "origin_lat_deg"), frame.origin().0);
    assert_eq!(f(&route["frame"], "origin_lon_deg"), frame.origin().1);
    let legs = route["legs"].as_array().unwrap();
    assert_eq!(legs.len(), raw.stops.len() - 1);
    let names: Vec<&str> = raw.stops.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["P", "W1", "W2", "W3", "W4", "Q"]);
    let stop_at = |e: &Endpoint| frame.to_local(e.lon, e.lat);

    let mut all: Vec<Prim> = Vec::new();
    let mut total = 0.0;
    for (k, leg) in legs.iter().enumerate() {
        let (a, b) = (&raw.stops[k], &raw.stops[k + 1]);
        assert_eq!(
            (leg["from"].as_str().unwrap(), leg["to"].as_str().unwrap()),
            (a.name.as_str(), b.name.as_str())
        );
        let prims: Vec<Prim> = leg["primitives"]
            .as_array()
            .unwrap()
            .iter()
            .map(prim)
            .collect();
        let (first, last) = (prims.first().unwrap(), prims.last().unwrap());
        let d0 = dist(first.at(0.0), stop_at(a));
        let d1 = dist(last.at(1.0), stop_at(b));
        assert!(
            d0 <= ARRIVAL_TOL,
            "leg {} -> {} starts {d0} m from {}",
            a.name,
            b.name,
            a.name
        );
        assert!(
            d1 <= ARRIVAL_TOL,
            "leg {} -> {} ends {d1} m from {}",
            a.name,
            b.name,
            b.name
        );
        // Fixed headings (the start's and the goal's) are flown.
        if let (Some(c), Some(h)) = (a.heading_deg, first.heading(0.0)) {
            let want = local_heading(&frame, a.lon, a.lat, c);
            assert!(
                angle_diff(h, want) < HEADING_TOL,
                "{} leaves at heading {h}, not {want}",
                a.name
            );
        }
        if let (Some(c), Some(h)) = (b.heading_deg, last.heading(1.0)) {
            let want = local_heading(&frame, b.lon, b.lat, c);
            assert!(
                angle_diff(h, want) < HEADING_TOL,
                "{} is reached at heading {h}, not {want}",
                b.name
            );
        }
        let length: f64 = prims.iter().map(Prim::length).sum();
        assert!(
            (length - f(leg, "length_m")).abs() < 0.05,
            "leg {k}: {length} vs {}",
            f(leg, "length_m")
        );
        total += length;
        all.extend(prims);
    }
    assert!(
        (total - f(&route, "length_m")).abs() < 0.1,
        "{total} vs {}",
        f(&route, "length_m")
    );
    // Continuous in position and heading across every primitive and every leg.
    let mut last_heading: Option<f64> = None;
    for (k, w) in all.windows(2).enumerate() {
        let gap = dist(w[0].at(1.0), w[1].at(0.0));
        assert!(
            gap <= JOIN_TOL,
            "route primitive {k} -> {}: {gap} m apart",
            k + 1
        );
        // Compare headings across short lines too: against the last reliable heading.
        if let Some(h) = w[0].heading(1.0) {
            last_heading = Some(h);
        }
        if let (Some(a), Some(b)) = (last_heading, w[1].heading(0.0)) {
            let t = angle_diff(a, b);
            assert!(
                t <= HEADING_TOL,
                "route primitive {k} -> {}: heading jumps {t} rad",
                k + 1
            );
        }
    }
    // Clear of every building.
    let mut route_closest = f64::INFINITY;
    for (k, p) in all.iter().enumerate() {
        if let Some((d, b, q)) = closest_building(p, &buildings, reach) {
            assert!(
                d >= clearance - CLEARANCE_TOL,
                "route primitive {k} comes {d} m from building {} at {q:?} (clearance {clearance})",
                buildings[b].name
            );
            route_closest = route_closest.min(d);
        }
    }
    eprintln!(
        "route: {} legs, {} primitives, {total:.1} m, closest approach {route_closest:.4} m; \
         build+export {:.1} s, edge checks {:.1} s, total {:.1} s",
        legs.len(),
        all.len(),
        t_build.as_secs_f64(),
        (t_edges - t_build).as_secs_f64(),
        t0.elapsed().as_secs_f64()
    );
}
