//! `skyroute import`: a QGroundControl plan and a KML document become a scenario that builds
//! and plans; the route flies the plan's positions and keeps clear of every imported zone
//! (checked with geo's predicates on the imported rings, in metres).

mod common;
use common::{ok, one_line_error, skyroute, TempDir};
use geo::{Contains, Coord, Distance, Euclidean, LineString, Point, Polygon};
use serde_json::Value;

/// A plan as QGroundControl writes it (fence version 2): home, a take-off "here" (latitude and
/// longitude 0), a speed change, a waypoint, a land item; an exclusion polygon, an exclusion
/// circle and an inclusion polygon.
const PLAN: &str = r#"{
  "fileType": "Plan", "groundStation": "QGroundControl", "version": 1,
  "geoFence": {
    "circles": [{"circle": {"center": [48.093, 11.645], "radius": 300}, "inclusion": false, "version": 1}],
    "polygons": [
      {"inclusion": false, "polygon": [[48.096, 11.612], [48.096, 11.620], [48.104, 11.620], [48.104, 11.612]], "version": 1},
      {"inclusion": true, "polygon": [[48.0, 11.5], [48.0, 11.8], [48.2, 11.8], [48.2, 11.5]], "version": 1}
    ],
    "version": 2
  },
  "mission": {
    "cruiseSpeed": 30, "firmwareType": 12, "hoverSpeed": 5, "vehicleType": 1, "version": 2,
    "plannedHomePosition": [48.100, 11.600, 500],
    "items": [
      {"autoContinue": true, "command": 22, "doJumpId": 1, "frame": 3, "params": [15, 0, 0, null, 0, 0, 50], "type": "SimpleItem"},
      {"autoContinue": true, "command": 178, "doJumpId": 2, "frame": 2, "params": [1, 30, -1, 0, 0, 0, 0], "type": "SimpleItem"},
      {"autoContinue": true, "command": 16, "doJumpId": 3, "frame": 3, "params": [0, 0, 0, null, 48.112, 11.630, 100], "type": "SimpleItem"},
      {"autoContinue": true, "command": 21, "doJumpId": 4, "frame": 3, "params": [0, 0, 0, null, 48.100, 11.660, 0], "type": "SimpleItem"}
    ]
  },
  "rallyPoints": {"points": [], "version": 2}
}"#;

/// A KML zone with a hole, between the waypoint and the goal, and a point placemark.
const KML: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document>
<Placemark><name>Quarry</name><Polygon>
<outerBoundaryIs><LinearRing><coordinates>11.640,48.101 11.650,48.101 11.650,48.108 11.640,48.108 11.640,48.101</coordinates></LinearRing></outerBoundaryIs>
<innerBoundaryIs><LinearRing><coordinates>11.643,48.103 11.647,48.103 11.647,48.106 11.643,48.103</coordinates></LinearRing></innerBoundaryIs>
</Polygon></Placemark>
<Placemark><name>Tower</name><Point><coordinates>11.62,48.09</coordinates></Point></Placemark>
</Document></kml>"#;

/// Writes the plan and the KML into `dir`; returns their paths.
fn inputs(dir: &TempDir) -> (String, String) {
    let (plan, kml) = (dir.file("mission.plan"), dir.file("zones.kml"));
    std::fs::write(&plan, PLAN).unwrap();
    std::fs::write(&kml, KML).unwrap();
    (plan, kml)
}

#[test]
fn a_plan_and_a_kml_become_a_scenario_whose_route_flies_the_plan_round_every_zone() {
    let dir = TempDir::new("import");
    let (plan, kml) = inputs(&dir);
    let sc = dir.file("s.geojson");
    let o = ok(skyroute(&["import", &plan, &kml, "-o", &sc]), "import");
    let said = common::stdout(&o);
    assert!(said.contains("inclusion fence polygon 1"), "{said}");
    assert!(said.contains("point \"Tower\""), "{said}");
    let s = skyroute_prep::scenario::load(std::path::Path::new(&sc)).unwrap();
    let names: Vec<&str> = s.no_fly.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(names, ["FENCE0", "FENCE_CIRCLE0", "Quarry"]);
    assert_eq!(s.no_fly[2].holes.len(), 1);
    assert_eq!(s.start.as_ref().unwrap().name, "HOME");
    assert_eq!(s.waypoints.len(), 1);
    assert_eq!(s.goal.as_ref().unwrap().name, "ITEM3");
    // The start heads for the waypoint: north of east.
    let h = s.start.as_ref().unwrap().heading_deg.unwrap();
    assert!((50.0..60.0).contains(&h), "{h}");

    let (net, route) = (dir.file("n.bin"), dir.file("r.geojson"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &route]),
        "plan",
    );
    let frame = s.local_frame();
    let local = |(lon, lat): (f64, f64)| frame.to_local(lon, lat);
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&route).unwrap()).unwrap();
    let mut pts = Vec::new();
    for f in v["features"].as_array().unwrap() {
        if f["geometry"]["type"] == "LineString" {
            for c in f["geometry"]["coordinates"].as_array().unwrap() {
                pts.push(local((c[0].as_f64().unwrap(), c[1].as_f64().unwrap())));
            }
        }
    }
    let zones: Vec<Polygon<f64>> = s
        .no_fly
        .iter()
        .map(|z| {
            let ring = |r: &[(f64, f64)]| {
                LineString::from(r.iter().map(|&p| local(p)).collect::<Vec<_>>())
            };
            Polygon::new(ring(&z.ring), z.holes.iter().map(|h| ring(h)).collect())
        })
        .collect();
    for &(x, y) in &pts {
        for (z, name) in zones.iter().zip(&names) {
            assert!(!z.contains(&Coord { x, y }), "({x}, {y}) inside {name}");
            let gap = Euclidean.distance(&Point::new(x, y), z);
            assert!(gap >= 20.0 + 1.5 - 0.5, "({x}, {y}) {gap:.2} m from {name}");
        }
    }
    // The circle fence's polygon covers the circle: no route point within 300 m of its centre.
    let c = local((11.645, 48.093));
    let nearest = pts
        .iter()
        .map(|p| (p.0 - c.0).hypot(p.1 - c.1))
        .fold(f64::MAX, f64::min);
    assert!(nearest >= 300.0, "{nearest:.1} m from the circle's centre");
    // The route flies over the waypoint.
    let w = local((11.630, 48.112));
    let over = pts
        .iter()
        .map(|p| (p.0 - w.0).hypot(p.1 - w.1))
        .fold(f64::MAX, f64::min);
    assert!(over < 1.0, "the route passes {over:.2} m from the waypoint");
}

#[test]
fn bad_imports_are_refused_by_name_and_write_nothing() {
    let dir = TempDir::new("import-bad");
    let (plan, kml) = inputs(&dir);
    let sc = dir.file("s.geojson");
    let e = one_line_error(&skyroute(&["import", &plan, &plan, "-o", &sc]));
    assert!(e.contains("a second route"), "{e}");
    let txt = dir.file("zones.txt");
    std::fs::write(&txt, "x").unwrap();
    let e = one_line_error(&skyroute(&["import", &txt, "-o", &sc]));
    assert!(
        e.contains("import reads KML (.kml) and QGroundControl plans (.plan)"),
        "{e}"
    );
    let e = one_line_error(&skyroute(&["import", &kml, "-o", &dir.file("s.kml")]));
    assert!(e.contains("name the output .geojson or .json"), "{e}");
    let survey = PLAN.replacen(
        r#"{"autoContinue": true, "command": 178"#,
        r#"{"type": "ComplexItem", "complexItemType": "survey"}, {"autoContinue": true, "command": 178"#,
        1,
    );
    let bad = dir.file("survey.plan");
    std::fs::write(&bad, survey).unwrap();
    let e = one_line_error(&skyroute(&["import", &bad, "-o", &sc]));
    assert!(
        e.contains("survey.plan: mission.items[1]: a complex item (survey)"),
        "{e}"
    );
    // A waypoint inside an exclusion fence: the assembled scenario is refused, nothing written.
    let inside = PLAN.replace("48.112, 11.630", "48.100, 11.616");
    let bad = dir.file("inside.plan");
    std::fs::write(&bad, inside).unwrap();
    let e = one_line_error(&skyroute(&["import", &bad, "-o", &sc]));
    assert!(e.contains("nothing was written"), "{e}");
    assert!(
        e.contains("assembled from") && e.contains("inside.plan"),
        "{e}"
    );
    assert!(e.contains("waypoint lies inside no-fly"), "{e}");
    assert!(!std::path::Path::new(&sc).exists());
    // An existing output is kept without --force.
    ok(skyroute(&["import", &kml, "-o", &sc]), "import");
    let e = one_line_error(&skyroute(&["import", &kml, "-o", &sc]));
    assert!(e.contains("exists; pass --force"), "{e}");
}

#[test]
fn a_plan_holding_only_a_fence_adds_its_zones_and_keeps_the_bases_route() {
    let dir = TempDir::new("import-fence");
    let base = dir.file("base.geojson");
    ok(skyroute(&["init", &base]), "init");
    // Home and no mission items: the fence alone (an exclusion circle north of the template's
    // route, and one item at 0, 0 that is listed as left out).
    let fence = r#"{"fileType": "Plan", "groundStation": "QGroundControl", "version": 1,
      "geoFence": {"circles": [{"circle": {"center": [48.125, 11.645], "radius": 200},
                                "inclusion": false, "version": 1}],
                   "polygons": [], "version": 2},
      "mission": {"plannedHomePosition": [48.100, 11.600, 500], "version": 2, "items": [
        {"autoContinue": true, "command": 16, "doJumpId": 1, "frame": 3,
         "params": [0, 0, 0, null, 0, 0, 50], "type": "SimpleItem"}]},
      "rallyPoints": {"points": [], "version": 2}}"#;
    let plan = dir.file("fence.plan");
    std::fs::write(&plan, fence).unwrap();
    let sc = dir.file("s.geojson");
    let o = ok(
        skyroute(&["import", &plan, "--base", &base, "-o", &sc]),
        "import",
    );
    let said = common::stdout(&o);
    assert!(
        said.contains("ITEM0 (at latitude and longitude 0"),
        "{said}"
    );
    assert!(said.contains("HOME (no route)"), "{said}");
    let s = skyroute_prep::scenario::load(std::path::Path::new(&sc)).unwrap();
    let names: Vec<&str> = s.no_fly.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(names, ["Z1", "FENCE_CIRCLE0"]);
    assert_eq!(s.start.as_ref().unwrap().name, "S");
    assert_eq!(s.goal.as_ref().unwrap().name, "G");
}
