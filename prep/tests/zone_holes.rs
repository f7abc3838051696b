//! No-fly zones with holes, end to end from the CLI: a roadmap built round a zone with a hole
//! routes round the whole zone from outside, and stays inside the hole when the start and goal
//! are both in it. Every point of each route is checked against the zone with its holes by geo's
//! own predicates (not by the pieces the core was given), in the local frame, in metres.

mod common;
use common::{ok, skyroute, TempDir};
use geo::{Contains, Coord, Distance, Euclidean, LineString, Point, Polygon};
use serde_json::Value;

/// The zone: `[11.600, 11.660] × [48.090, 48.130]` (about 4.5 × 4.4 km) with a hole
/// `[11.615, 11.645] × [48.100, 48.120]` (about 2.2 × 2.2 km).
const EXTERIOR: [(f64, f64); 4] = [
    (11.600, 48.090),
    (11.660, 48.090),
    (11.660, 48.130),
    (11.600, 48.130),
];
const HOLE: [(f64, f64); 4] = [
    (11.615, 48.100),
    (11.645, 48.100),
    (11.645, 48.120),
    (11.615, 48.120),
];

/// The clearance the scenario asks for plus half the wingspan, metres.
const KEPT_M: f64 = 20.0 + 1.5;

fn ring_json(ring: &[(f64, f64)]) -> String {
    let pts: Vec<String> = ring
        .iter()
        .chain(ring.first())
        .map(|(x, y)| format!("[{x}, {y}]"))
        .collect();
    format!("[{}]", pts.join(", "))
}

/// A roadmap scenario with the zone, a start and a goal heading east at the given positions,
/// and two small zones at opposite corners that widen the mission box (the roadmap samples the
/// box round the scenario's positions) to leave room round the zone.
fn scenario(start: (f64, f64), goal: (f64, f64)) -> String {
    format!(
        r#"{{"type": "FeatureCollection", "name": "holes",
  "vehicle": {{"v_nominal_mps": 30.0, "v_min_mps": 25.0, "v_max_mps": 35.0,
    "a_lat_max_mps2": 3.0, "a_long_min_mps2": -3.0, "a_long_max_mps2": 3.0, "wingspan_m": 3.0}},
  "planner": {{"mode": "roadmap", "sample_spacing_m": 200.0, "neighbour_radius_m": 900.0,
    "k_nearest_fallback": 8, "allow_ccc": false, "clearance_m": 20.0, "arc_step_m": 40.0,
    "seed": 1}},
  "features": [
    {{"type": "Feature", "geometry": {{"type": "Point", "coordinates": [{}, {}]}},
      "properties": {{"kind": "start", "name": "S", "heading_deg": 90.0}}}},
    {{"type": "Feature", "geometry": {{"type": "Point", "coordinates": [{}, {}]}},
      "properties": {{"kind": "goal", "name": "G", "heading_deg": 90.0}}}},
    {{"type": "Feature", "geometry": {{"type": "Polygon", "coordinates": [{}, {}]}},
      "properties": {{"kind": "no_fly", "name": "Z"}}}},
    {{"type": "Feature", "geometry": {{"type": "Polygon", "coordinates": [{}]}},
      "properties": {{"kind": "no_fly", "name": "M1"}}}},
    {{"type": "Feature", "geometry": {{"type": "Polygon", "coordinates": [{}]}},
      "properties": {{"kind": "no_fly", "name": "M2"}}}}
  ]}}"#,
        start.0,
        start.1,
        goal.0,
        goal.1,
        ring_json(&EXTERIOR),
        ring_json(&HOLE),
        ring_json(&[(11.570, 48.150), (11.571, 48.150), (11.571, 48.151)]),
        ring_json(&[(11.690, 48.070), (11.691, 48.070), (11.691, 48.071)])
    )
}

/// Builds and plans `text` in `dir`; returns the route's points `(lon, lat)` and the scenario's
/// local frame.
fn plan(dir: &TempDir, text: &str) -> (Vec<(f64, f64)>, skyroute_prep::frame::LocalFrame) {
    let sc = dir.file("s.geojson");
    std::fs::write(&sc, text).unwrap();
    let (net, route) = (dir.file("n.bin"), dir.file("r.geojson"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &route]),
        "plan",
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&route).unwrap()).unwrap();
    let mut pts = Vec::new();
    for f in v["features"].as_array().unwrap() {
        if f["geometry"]["type"] == "LineString" {
            for c in f["geometry"]["coordinates"].as_array().unwrap() {
                pts.push((c[0].as_f64().unwrap(), c[1].as_f64().unwrap()));
            }
        }
    }
    assert!(pts.len() > 10, "a route of {} points", pts.len());
    let frame = skyroute_prep::scenario::load(std::path::Path::new(&sc))
        .unwrap()
        .local_frame();
    (pts, frame)
}

/// The zone with its hole in `frame`, metres.
fn zone_in(frame: &skyroute_prep::frame::LocalFrame) -> Polygon<f64> {
    let ring = |r: &[(f64, f64)]| {
        LineString::from(
            r.iter()
                .map(|&(lon, lat)| frame.to_local(lon, lat))
                .collect::<Vec<_>>(),
        )
    };
    Polygon::new(ring(&EXTERIOR), vec![ring(&HOLE)])
}

/// Every route point is outside the zone (a hole's inside is outside it) by at least the
/// clearance; returns how many points lie inside the hole.
fn check_clear(pts: &[(f64, f64)], frame: &skyroute_prep::frame::LocalFrame) -> usize {
    let zone = zone_in(frame);
    let hole = Polygon::new(zone.interiors()[0].clone(), vec![]);
    let mut in_hole = 0;
    for &(lon, lat) in pts {
        let (x, y) = frame.to_local(lon, lat);
        let p = Point::new(x, y);
        assert!(
            !zone.contains(&Coord { x, y }),
            "({lon}, {lat}) in the zone"
        );
        let gap = Euclidean.distance(&p, &zone);
        // 0.5 m for the f32 route and the sampled arcs.
        assert!(
            gap >= KEPT_M - 0.5,
            "({lon}, {lat}) is {gap:.2} m from the zone"
        );
        if hole.contains(&p) {
            in_hole += 1;
        }
    }
    in_hole
}

#[test]
fn a_route_from_outside_goes_round_the_whole_zone() {
    let dir = TempDir::new("holes-outside");
    let (pts, frame) = plan(&dir, &scenario((11.585, 48.110), (11.675, 48.110)));
    assert_eq!(check_clear(&pts, &frame), 0, "the route entered the hole");
}

#[test]
fn a_route_from_a_point_in_the_hole_to_another_stays_in_the_hole() {
    let dir = TempDir::new("holes-inside");
    let (pts, frame) = plan(&dir, &scenario((11.622, 48.106), (11.638, 48.114)));
    assert_eq!(
        check_clear(&pts, &frame),
        pts.len(),
        "the route left the hole"
    );
}

#[test]
fn kml_keeps_the_hole_and_the_geofence_fences_the_zone_but_not_the_hole() {
    let dir = TempDir::new("holes-outputs");
    let sc = dir.file("s.geojson");
    std::fs::write(&sc, scenario((11.585, 48.110), (11.675, 48.110))).unwrap();
    let net = dir.file("n.bin");
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    let (kml, plan) = (dir.file("r.kml"), dir.file("r.plan"));
    for out in [&kml, &plan] {
        ok(
            skyroute(&["plan", &net, "--scenario", &sc, "-o", out]),
            "plan",
        );
    }
    let kml = std::fs::read_to_string(&kml).unwrap();
    let doc = roxmltree::Document::parse(&kml).unwrap();
    let zone = doc
        .descendants()
        .find(|n| n.has_tag_name("Placemark") && n.children().any(|c| c.text() == Some("Z")))
        .expect("zone Z in the KML");
    let inner = zone
        .descendants()
        .filter(|n| n.has_tag_name("innerBoundaryIs"))
        .count();
    assert_eq!(inner, 1);
    // The geofence: exclusion polygons (a fence polygon has no holes), none over the hole.
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&plan).unwrap()).unwrap();
    let fences: Vec<Polygon<f64>> = v["geoFence"]["polygons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            assert_eq!(f["inclusion"], false);
            let pts: Vec<(f64, f64)> = f["polygon"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| (p[1].as_f64().unwrap(), p[0].as_f64().unwrap()))
                .collect();
            Polygon::new(LineString::from(pts), vec![])
        })
        .collect();
    assert!(fences.len() >= 4, "{} fence polygons", fences.len());
    let fenced = |lon: f64, lat: f64| fences.iter().any(|f| f.contains(&Coord { x: lon, y: lat }));
    assert!(!fenced(11.630, 48.110), "the hole is fenced");
    for (lon, lat) in [
        (11.605, 48.110),
        (11.655, 48.110),
        (11.630, 48.095),
        (11.630, 48.125),
    ] {
        assert!(fenced(lon, lat), "({lon}, {lat}) in the zone is not fenced");
    }
}
