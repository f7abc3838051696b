//! The three-dimensional roadmap (Niendorf et al.) of `scenarios/niendorf-urban-3d.geojson`,
//! checked from its network image by means of its own: every edge is flown again in f64 (its
//! Dubins path integrated from its source pose, its altitude from the rest-to-rest profile
//! re-evaluated) and sampled every 0.5 m, and no sample may lie inside a building's prism
//! grown by the clearance (horizontally within the clearance of the footprint, by an f64
//! point-in-polygon test and distance to the polygon's edges, and below the height plus the
//! clearance). Some edges must fly over a low building's footprint, so the check is not
//! vacuous; and the shortest routes between the scenario's stops are shorter in 3-D than in
//! the planar niendorf-urban.

mod common;
use common::{ok, scenario, skyroute, stderr, stdout, TempDir};
use skyroute::geometry::vertical::{VerticalLimits, VerticalProfile};
use skyroute::geometry::Turn;
use skyroute::network::write::ObstacleSpec;
use skyroute::Network;
use skyroute_prep::build::{build, BuildOptions, Built};
use skyroute_prep::roadmap::Sagitta;
use skyroute_prep::scenario::{self, Mode, Scenario};
use std::path::Path;

/// Sampling step along each edge, metres.
const STEP_M: f64 = 0.5;

/// What the f32 image may be off from an exact evaluation, metres: positions are f32 values
/// of a few kilometres (ulp 0.25 mm), the path is integrated in f64.
const TOLERANCE_M: f64 = 1e-3;

fn load(name: &str) -> Scenario {
    scenario::load(Path::new(&scenario(name))).unwrap_or_else(|e| panic!("{e}"))
}

fn built(s: &Scenario, options: &BuildOptions) -> Built {
    build(s, options, &|_, _| {}).unwrap_or_else(|e| panic!("{e}"))
}

/// A building: its footprint in the local frame (f64) and its height (`INFINITY`: unbounded).
struct Prism {
    ring: Vec<(f64, f64)>,
    height: f64,
    lo: (f64, f64),
    hi: (f64, f64),
}

/// The built network's footprints with the scenario's heights (no zone of the scenario has
/// holes, so there is one footprint per zone, in file order).
fn prisms(s: &Scenario, b: &Built) -> Vec<Prism> {
    assert_eq!(b.obstacles.len(), s.no_fly.len() + s.threats.len());
    b.obstacles
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let ObstacleSpec::Polygon(points) = o else {
                panic!("obstacle {i} is not a polygon");
            };
            let ring: Vec<(f64, f64)> = points.iter().map(|p| (p.x as f64, p.y as f64)).collect();
            let fold = |f: fn(f64, f64) -> f64, init: f64, k: usize| {
                ring.iter()
                    .map(|p| if k == 0 { p.0 } else { p.1 })
                    .fold(init, f)
            };
            Prism {
                lo: (fold(f64::min, f64::MAX, 0), fold(f64::min, f64::MAX, 1)),
                hi: (fold(f64::max, f64::MIN, 0), fold(f64::max, f64::MIN, 1)),
                height: s.no_fly[i].height_m.unwrap_or(f64::INFINITY),
                ring,
            }
        })
        .collect()
}

/// Whether `p` lies inside the ring (crossing number).
fn inside(p: (f64, f64), ring: &[(f64, f64)]) -> bool {
    let mut c = false;
    for i in 0..ring.len() {
        let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
        if (a.1 > p.1) != (b.1 > p.1) {
            let x = a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0);
            if p.0 < x {
                c = !c;
            }
        }
    }
    c
}

/// Distance from `p` to the footprint: 0 inside, else to the nearest edge.
fn distance(p: (f64, f64), ring: &[(f64, f64)]) -> f64 {
    if inside(p, ring) {
        return 0.0;
    }
    (0..ring.len())
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            ((a.0 + t * dx - p.0).powi(2) + (a.1 + t * dy - p.1).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Points `(s, x, y)` every `STEP_M` along a Dubins path (and its end), integrated in f64 from
/// the start pose `(x, y, heading)`: heading counter-clockwise from the x axis, a left arc of
/// radius r about the centre r to the left.
fn flown(
    start: (f64, f64, f64),
    r: f64,
    turns: [Option<Turn>; 3],
    lengths: [f64; 3],
) -> Vec<(f64, f64, f64)> {
    let at = |(x, y, th): (f64, f64, f64), turn: Option<Turn>, l: f64| match turn {
        None => (x + l * th.cos(), y + l * th.sin(), th),
        Some(Turn::Left) => {
            let (cx, cy) = (x - r * th.sin(), y + r * th.cos());
            let t = th + l / r;
            (cx + r * t.sin(), cy - r * t.cos(), t)
        }
        Some(Turn::Right) => {
            let (cx, cy) = (x + r * th.sin(), y - r * th.cos());
            let t = th - l / r;
            (cx - r * t.sin(), cy + r * t.cos(), t)
        }
    };
    let total: f64 = lengths.iter().sum();
    let mut out = Vec::new();
    let mut s: f64 = 0.0;
    loop {
        let s_here = s.min(total);
        // Walk the pieces up to s_here.
        let (mut pose, mut left) = (start, s_here);
        for k in 0..3 {
            let l = left.min(lengths[k]);
            pose = at(pose, turns[k], l);
            left -= l;
        }
        out.push((s_here, pose.0, pose.1));
        if s_here >= total {
            return out;
        }
        s += STEP_M;
    }
}

/// Niendorf et al.'s rest-to-rest altitude `s` metres along an edge of `length` from `from` to
/// `to`, re-evaluated in f64: gradient g = v_c / v, curvature k = a_z / v²; bang-coast-bang
/// when the move reaches g (d ≥ g²/k), else bang-bang; a climb starts at once, a descent ends
/// at the edge's end.
fn altitude(l: &VerticalLimits, from: f64, to: f64, length: f64, s: f64) -> f64 {
    let v = l.airspeed as f64;
    let (g, k) = (l.climb_rate as f64 / v, l.vertical_accel as f64 / (v * v));
    let d = (to - from).abs();
    let (ease, ramp) = if d >= g * g / k {
        (g / k, d / g + g / k)
    } else {
        let e = (d / k).sqrt();
        (e, 2.0 * e)
    };
    let begin = if to >= from { 0.0 } else { length - ramp };
    let u = (s - begin).clamp(0.0, ramp);
    let moved = if u <= ease {
        0.5 * k * u * u
    } else if u >= ramp - ease {
        d - 0.5 * k * (ramp - u).powi(2)
    } else {
        0.5 * k * ease * ease + k * ease * (u - ease)
    };
    if to >= from {
        from + moved.min(d)
    } else {
        from - moved.min(d)
    }
}

/// What the prism check found.
#[derive(Debug, Default)]
struct Checked {
    edges: usize,
    samples: usize,
    /// Edges with a sample inside a low building's footprint.
    over_low: usize,
    /// Edge indices of those.
    over_low_edges: Vec<u32>,
}

/// Samples every edge of the 3-D image `bytes` and checks it against `prisms` with clearance
/// `c`; panics at the first sample inside a grown prism.
fn check_prisms(bytes: &[u8], prisms: &[Prism], c: f64) -> Checked {
    let net = Network::from_bytes(bytes).expect("the image loads");
    let limits = net.vertical_limits().expect("three-dimensional");
    let mut out = Checked::default();
    for e in 0..net.edge_count() {
        let path = net.edge_path(e).unwrap();
        let src = net.edge_source(e).unwrap();
        let dst = net.edge_record(e).unwrap().target as u32;
        let (za, zb) = (
            net.vertex_altitude(src).unwrap() as f64,
            net.vertex_altitude(dst).unwrap() as f64,
        );
        let (t0, t1, t2) = path.word.letters();
        let turns = [Some(t0), t1, Some(t2)];
        let lengths = path.lengths.map(|l| l as f64);
        let length: f64 = lengths.iter().sum();
        let st = path.start;
        let points = flown(
            (
                st.position.x as f64,
                st.position.y as f64,
                st.heading as f64,
            ),
            path.radius as f64,
            turns,
            lengths,
        );
        // The f64 integration lands on the target vertex: the sampler flies the stored path.
        let end = points.last().unwrap();
        let target = net.vertex(dst).unwrap().position;
        let miss = ((end.1 - target.x as f64).powi(2) + (end.2 - target.y as f64).powi(2)).sqrt();
        assert!(
            miss < 0.05,
            "edge {e}: the f64 path ends {miss} m from its target"
        );
        let profile = VerticalProfile::new(za as f32, zb as f32, path.length(), &limits)
            .unwrap_or_else(|| panic!("edge {e}: {za} m to {zb} m over {length} m is too steep"));
        let mut over_low = false;
        for &(s, x, y) in &points {
            let z = altitude(&limits, za, zb, length, s);
            let core = profile.altitude_at(s as f32) as f64;
            assert!(
                (z - core).abs() < 1e-3 * (1.0 + z.abs()),
                "edge {e} at {s} m: f64 altitude {z}, the core's {core}"
            );
            for (i, b) in prisms.iter().enumerate() {
                if x < b.lo.0 - c || x > b.hi.0 + c || y < b.lo.1 - c || y > b.hi.1 + c {
                    continue;
                }
                let d = distance((x, y), &b.ring);
                assert!(
                    !(d < c - TOLERANCE_M && z < b.height + c - TOLERANCE_M),
                    "edge {e} ({src} -> {dst}) at {s:.1} m of {length:.1} m: ({x:.3}, {y:.3}) at \
                     {z:.3} m is {d:.3} m from building {i} of height {} m (clearance {c} m)",
                    b.height
                );
                over_low |= d == 0.0 && b.height.is_finite();
            }
            out.samples += 1;
        }
        out.edges += 1;
        if over_low {
            out.over_low += 1;
            out.over_low_edges.push(e);
        }
    }
    out
}

#[test]
fn every_edge_keeps_out_of_every_building_prism() {
    let s = load("niendorf-urban-3d.geojson");
    let b = built(&s, &BuildOptions::default());
    let r = b.roadmap.as_ref().unwrap();
    let v = s.vertical().unwrap();
    assert_eq!(r.altitudes.len(), r.vertices.len());
    assert!(r
        .altitudes
        .iter()
        .all(|&z| (v.altitude_min_m..=v.altitude_max_m).contains(&(z as f64))));
    // The image holds the scenario's heights, never rounded down.
    let net = Network::from_bytes(&b.bytes).unwrap();
    for (i, z) in s.no_fly.iter().enumerate() {
        let h = net.obstacle_height(i as u32).unwrap() as f64;
        assert!(
            h >= z.height_m.unwrap() && h - z.height_m.unwrap() < 1e-4,
            "{i}: {h}"
        );
    }
    let c = s.planner.clearance_m.unwrap();
    let got = check_prisms(&b.bytes, &prisms(&s, &b), c);
    println!(
        "{} edges, {} samples; {} edges over a low building (the builder counts {})",
        got.edges, got.samples, got.over_low, r.edges_over_low_obstacles
    );
    assert_eq!(got.edges, r.edges.len());
    // Not vacuous: many edges cross a low building's footprint, above it.
    assert!(got.over_low >= 100, "{got:?}");
    assert!(got.over_low <= r.edges_over_low_obstacles);
}

#[test]
fn the_discretised_check_keeps_out_too() {
    let s = load("niendorf-urban-3d.geojson");
    let options = BuildOptions {
        discretised: Some(Sagitta::Added),
        ..BuildOptions::default()
    };
    let b = built(&s, &options);
    let got = check_prisms(&b.bytes, &prisms(&s, &b), s.planner.clearance_m.unwrap());
    assert!(got.over_low >= 100, "{got:?}");
}

/// Shortest distances over the image's graph (Dijkstra) from `from`.
fn dijkstra(net: &Network, from: u32) -> (Vec<f64>, Vec<Option<u32>>) {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = net.vertex_count() as usize;
    let (mut dist, mut via) = (vec![f64::INFINITY; n], vec![None; n]);
    let mut heap = BinaryHeap::new();
    dist[from as usize] = 0.0;
    heap.push(Reverse((0u64, from)));
    while let Some(Reverse((d, v))) = heap.pop() {
        let d = f64::from_bits(d);
        if d > dist[v as usize] {
            continue;
        }
        for e in net.out_edges(v) {
            let (cost, t) = net.edge_cost_target(e).unwrap();
            let nd = d + cost as f64;
            if nd < dist[t as usize] {
                dist[t as usize] = nd;
                via[t as usize] = Some(e);
                // Non-negative f64 order as bits.
                heap.push(Reverse((nd.to_bits(), t)));
            }
        }
    }
    (dist, via)
}

/// The total graph distance over the scenario's stops (start, waypoints, goal), each taken as
/// its nearest vertex, and the edges of the route.
fn route(s: &Scenario, bytes: &[u8]) -> (f64, Vec<u32>) {
    let net = Network::from_bytes(bytes).unwrap();
    let frame = s.local_frame();
    let stops: Vec<u32> = s
        .start
        .iter()
        .chain(&s.waypoints)
        .chain(s.goal.iter())
        .map(|e| {
            let p = skyroute_prep::local::local(&frame, e.lon, e.lat);
            (0..net.vertex_count())
                .min_by(|&a, &b| {
                    let da = net.vertex(a).unwrap().position.distance(p);
                    let db = net.vertex(b).unwrap().position.distance(p);
                    da.total_cmp(&db)
                })
                .unwrap()
        })
        .collect();
    let (mut total, mut edges) = (0.0, Vec::new());
    for leg in stops.windows(2) {
        let (dist, via) = dijkstra(&net, leg[0]);
        assert!(dist[leg[1] as usize].is_finite(), "no route {leg:?}");
        total += dist[leg[1] as usize];
        let mut v = leg[1];
        while let Some(e) = via[v as usize] {
            edges.push(e);
            v = net.edge_source(e).unwrap();
        }
    }
    (total, edges)
}

#[test]
fn flying_over_low_buildings_shortens_the_route() {
    let s3 = load("niendorf-urban-3d.geojson");
    let b3 = built(&s3, &BuildOptions::default());
    let s2 = load("niendorf-urban.geojson");
    let b2 = built(&s2, &BuildOptions::default());
    let (planar, _) = route(&s2, &b2.bytes);
    let (three_d, edges) = route(&s3, &b3.bytes);
    let c = s3.planner.clearance_m.unwrap();
    let over = check_prisms(&b3.bytes, &prisms(&s3, &b3), c).over_low_edges;
    let overflown = edges.iter().filter(|e| over.contains(e)).count();
    println!(
        "graph route P-W1-W2-W3-W4-Q: planar {planar:.0} m, three-dimensional {three_d:.0} m \
         ({overflown} of its {} edges over a low building)",
        edges.len()
    );
    assert!(three_d < planar, "{three_d} >= {planar}");
    assert!(overflown > 0);
}

#[test]
fn the_command_line_says_three_dimensional() {
    let dir = TempDir::new("roadmap-3d");
    let out = dir.file("u3.bin");
    let o = ok(
        skyroute(&["build", &scenario("niendorf-urban-3d.geojson"), "-o", &out]),
        "build",
    );
    let text = stdout(&o);
    assert!(
        text.contains("three-dimensional: vertex altitudes 40.0–120.0 m;"),
        "{text}"
    );
    let o = ok(skyroute(&["info", &out]), "info");
    let text = stdout(&o);
    assert!(
        text.contains(
            "three-dimensional roadmap (Niendorf et al.): airspeed 25 m/s, climb rate 10 m/s, \
             vertical acceleration 20 m/s²"
        ),
        "{text}"
    );
    assert!(text.contains("vertex altitudes 40.0 to 120.0 m"), "{text}");
    assert!(
        text.contains("obstacle heights: 60 of bounded height (15.5 to 299.2 m), 0 unbounded"),
        "{text}"
    );
    // A planar network says nothing of it.
    let planar = dir.file("u2.bin");
    ok(
        skyroute(&["build", &scenario("niendorf-urban.geojson"), "-o", &planar]),
        "build",
    );
    let o = ok(skyroute(&["info", &planar]), "info");
    assert!(!stdout(&o).contains("three-dimensional"));
}

#[test]
fn a_three_dimensional_scenario_is_built_only_as_a_roadmap() {
    let dir = TempDir::new("roadmap-3d-mode");
    let o = skyroute(&[
        "build",
        &scenario("niendorf-urban-3d.geojson"),
        "--mode",
        "voronoi",
        "-o",
        &dir.file("x.bin"),
    ]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains(
            "niendorf-urban-3d.geojson: planner.altitude_min_m: the scenario is a \
             three-dimensional roadmap and cannot be built as a voronoi network"
        ),
        "{e}"
    );
    let mut s = load("niendorf-urban-3d.geojson");
    s.planner.mode = Mode::Terrain;
    let e = build(&s, &BuildOptions::default(), &|_, _| {}).unwrap_err();
    assert!(e.to_string().contains("as a terrain network"), "{e}");
}

/// Pop-ups with heights, from the scenario (`height_m`) and from `--popup LON,LAT,R,H`, on
/// the urban mission (waypoint headings by the paper's rule, to keep it quick): a 60 m disc
/// on the route with its top at 30 m (below every vertex's 40 m, so below the route plus the
/// clearance) changes nothing; one at 100 m makes the route go round it, like the same disc
/// as a wall. The build stores no bypass alternatives for them, and says so; a planar network
/// refuses a height by the pop-up's name.
#[test]
fn pop_ups_with_heights_are_flown_over_when_low_and_round_when_tall() {
    let dir = TempDir::new("roadmap-3d-popup");
    let (net, sc) = (dir.file("u3.bin"), scenario("niendorf-urban-3d.geojson"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    let disc = "11.639436,48.104092,60";
    let plan = |scenario: &str, popup: Option<String>, out: &str| {
        let mut args = vec![
            "plan",
            &net,
            "--scenario",
            scenario,
            "--free-headings",
            "paper",
            "-o",
            out,
        ];
        let popup = popup.map(|p| ["--popup".to_string(), p]);
        args.extend(popup.iter().flatten().map(String::as_str));
        let o = ok(skyroute(&args), "plan");
        let route: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
        (route["length_m"].as_f64().unwrap(), route, stdout(&o))
    };
    let (none, ..) = plan(&sc, None, &dir.file("none.json"));
    let (low, route, _) = plan(&sc, Some(format!("{disc},30")), &dir.file("low.json"));
    let (tall, ..) = plan(&sc, Some(format!("{disc},100")), &dir.file("tall.json"));
    let (wall, ..) = plan(&sc, Some(disc.to_string()), &dir.file("wall.json"));
    assert_eq!(route["popups"][0]["height_m"], 30.0);
    assert_eq!(low, none, "a pop-up below the route changes nothing");
    assert!(tall > none + 10.0, "{tall} against {none}");
    assert_eq!(tall, wall, "a pop-up above the route is gone round");
    // The same pop-up as a scenario feature: built without stored alternatives, and applied
    // with its height.
    let text = std::fs::read_to_string(&sc).unwrap();
    let feature = |h: u32| {
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "popup", "name": "U1",
            "radius_m": 60, "probability": 0.5, "height_m": {h}}},
            "geometry": {{"type": "Point", "coordinates": [11.639436, 48.104092]}}}},"#
        )
    };
    for (h, expected) in [(30, none), (100, tall)] {
        let with = text.replacen(
            "\"features\": [",
            &format!("\"features\": [{}", feature(h)),
            1,
        );
        let path = dir.file(&format!("popup-{h}.geojson"));
        std::fs::write(&path, with).unwrap();
        let built = ok(skyroute(&["build", &path, "-o", &net]), "build");
        assert!(
            stdout(&built).contains("scenario pop-ups: 1; `plan` applies them with their heights"),
            "{}",
            stdout(&built)
        );
        let (length, route, _) = plan(&path, None, &dir.file("s.json"));
        assert_eq!(length, expected, "scenario pop-up at {h} m");
        assert_eq!(route["popups"][0]["height_m"], h as f64);
    }
    // A height on a planar network is refused by the pop-up's name.
    let planar_sc = scenario("niendorf-urban.geojson");
    let planar = dir.file("u2.bin");
    ok(skyroute(&["build", &planar_sc, "-o", &planar]), "build");
    let o = skyroute(&[
        "plan",
        &planar,
        "--scenario",
        &planar_sc,
        "--popup",
        &format!("{disc},30"),
        "-o",
        &dir.file("p.json"),
    ]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("--popup #1") && e.contains("the network has no altitudes"),
        "{e}"
    );
    assert!(!stdout(&o).contains("applied"), "{}", stdout(&o));
}

/// `skyroute plan` on the 3-D network (waypoint headings by the paper's rule, to keep it quick):
/// the route file carries the vertical limits and each
/// primitive's altitude, the GeoJSON and KML points their altitudes within the scenario's band
/// and the endpoints' altitudes, and the one-altitude mission formats refuse the route by name.
#[test]
fn plan_writes_altitudes_and_refuses_one_altitude_mission_formats() {
    let dir = TempDir::new("roadmap-3d-plan");
    let (net, sc) = (dir.file("u3.bin"), scenario("niendorf-urban-3d.geojson"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    let plan = |out: &str| {
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--free-headings",
            "paper",
            "-o",
            out,
        ])
    };
    let json = dir.file("r.json");
    ok(plan(&json), "plan");
    let route: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(route["vertical"]["climb_rate_mps"], 10.0);
    let first = &route["legs"][0]["primitives"][0]["altitude"];
    assert_eq!(first["start_m"], 60.0, "{first}");
    let last_leg = route["legs"].as_array().unwrap().last().unwrap();
    let last = last_leg["primitives"].as_array().unwrap().last().unwrap();
    assert_eq!(last["altitude"]["end_m"], 60.0, "{last}");
    for p in route["geometry"]["coordinates"].as_array().unwrap() {
        let z = p[2].as_f64().expect("[lon, lat, altitude]");
        assert!((40.0 - 1e-3..=120.0 + 1e-3).contains(&z), "{z}");
    }
    let geojson = dir.file("r.geojson");
    ok(plan(&geojson), "plan");
    let g: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&geojson).unwrap()).unwrap();
    let legs: Vec<&serde_json::Value> = g["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["properties"]["kind"] == "leg")
        .collect();
    assert!(!legs.is_empty());
    for f in legs {
        for p in f["geometry"]["coordinates"].as_array().unwrap() {
            assert_eq!(p.as_array().unwrap().len(), 3, "{p}");
        }
    }
    let kml = dir.file("r.kml");
    ok(plan(&kml), "plan");
    let text = std::fs::read_to_string(&kml).unwrap();
    assert!(
        text.contains(",60</coordinates></Point>"),
        "endpoints at 60 m"
    );
    for format in ["plan", "waypoints"] {
        let out = dir.file(&format!("r.{format}"));
        let o = plan(&out);
        assert_ne!(o.status.code(), Some(0), "{format}");
        let err = stderr(&o);
        assert!(
            err.contains("a three-dimensional route's altitude changes along its paths"),
            "{format}: {err}"
        );
        assert!(
            !std::path::Path::new(&out).exists(),
            "{format}: nothing written"
        );
    }
}
