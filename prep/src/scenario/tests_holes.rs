//! No-fly polygons with holes: what is accepted, and each way a hole can be wrong.

use super::error::ErrorKind;
use super::parse;
use super::tests::{doc, fails, point, polygon, start, FILE};
use super::ParseOptions;
use std::path::Path;

/// A closed ring of the axis-aligned rectangle `[x0, x1] × [y0, y1]` (degrees), as JSON.
fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> String {
    format!("[[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}], [{x0}, {y0}]]")
}

/// A zone "Z" over `[11.0, 11.1] × [48.0, 48.1]` with the given holes.
fn zone_with(holes: &[String]) -> String {
    let mut rings = vec![rect(11.0, 48.0, 11.1, 48.1)];
    rings.extend(holes.iter().cloned());
    polygon("Z", &rings.join(", "))
}

#[test]
fn a_polygon_with_two_holes_is_one_zone_with_its_holes() {
    let z = zone_with(&[
        rect(11.02, 48.02, 11.04, 48.04),
        rect(11.06, 48.06, 11.08, 48.08),
    ]);
    let s = parse(&doc(&format!("{}, {z}", start())), Path::new(FILE)).unwrap();
    assert_eq!(s.no_fly.len(), 1);
    assert_eq!(s.no_fly[0].ring.len(), 4);
    assert_eq!(s.no_fly[0].holes.len(), 2);
    assert_eq!(s.no_fly[0].holes[1][0], (11.06, 48.06));
}

#[test]
fn a_multipolygon_member_keeps_its_holes() {
    let m = format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "M"}},
            "geometry": {{"type": "MultiPolygon", "coordinates": [[{}, {}], [{}]]}}}}"#,
        rect(11.0, 48.0, 11.1, 48.1),
        rect(11.02, 48.02, 11.04, 48.04),
        rect(12.0, 48.0, 12.1, 48.1),
    );
    let s = parse(&doc(&format!("{}, {m}", start())), Path::new(FILE)).unwrap();
    let holes: Vec<usize> = s.no_fly.iter().map(|z| z.holes.len()).collect();
    assert_eq!(holes, [1, 0]);
    assert_eq!(s.no_fly[0].name, "M[0]");
}

#[test]
fn a_hole_crossing_touching_or_outside_the_exterior_is_refused() {
    for hole in [
        rect(11.05, 48.05, 11.2, 48.07), // crosses the exterior
        rect(11.05, 48.05, 11.1, 48.07), // touches it along an edge
        rect(11.3, 48.3, 11.4, 48.4),    // lies outside
        rect(10.9, 47.9, 11.2, 48.2),    // holds the exterior
    ] {
        let e = fails(
            &doc(&format!("{}, {}", start(), zone_with(&[hole]))),
            &[
                "feature 1 (Z)",
                "geometry.coordinates[1]",
                "not strictly inside the polygon's exterior ring",
            ],
        );
        assert!(matches!(e.kind, ErrorKind::HoleOutside));
    }
}

#[test]
fn holes_that_meet_or_nest_are_refused_naming_both() {
    let a = rect(11.02, 48.02, 11.05, 48.05);
    for b in [
        rect(11.04, 48.04, 11.07, 48.07), // crosses a
        rect(11.05, 48.02, 11.07, 48.05), // shares an edge with a
        rect(11.03, 48.03, 11.04, 48.04), // lies inside a
    ] {
        let e = fails(
            &doc(&format!("{}, {}", start(), zone_with(&[a.clone(), b]))),
            &["feature 1 (Z)", "geometry.coordinates[", "meets hole"],
        );
        assert!(matches!(e.kind, ErrorKind::HolesMeet(_)), "{e}");
    }
    // A hole holding an earlier one: the inner one is named.
    let outer = rect(11.01, 48.01, 11.09, 48.09);
    fails(
        &doc(&format!("{}, {}", start(), zone_with(&[a, outer]))),
        &["geometry.coordinates[1]", "meets hole 2"],
    );
}

#[test]
fn a_self_intersecting_hole_is_refused_even_where_an_exterior_would_be_hulled() {
    let bow_tie =
        "[[11.02, 48.02], [11.04, 48.04], [11.04, 48.02], [11.02, 48.04], [11.02, 48.02]]";
    let text = doc(&format!("{}, {}", start(), zone_with(&[bow_tie.into()])));
    let options = ParseOptions {
        hull_self_intersecting_no_fly: true,
    };
    let e = super::parse_with(&text, Path::new(FILE), &options).expect_err("a bow-tie hole");
    assert!(e.to_string().contains("geometry.coordinates[1]"), "{e}");
    assert!(matches!(e.kind, ErrorKind::SelfIntersecting { .. }));
}

#[test]
fn an_endpoint_in_a_hole_is_outside_the_zone_and_on_its_edge_is_inside() {
    let z = zone_with(&[rect(11.02, 48.02, 11.08, 48.08)]);
    let inside_hole = point("goal", "Q", 11.05, 48.05, "");
    parse(
        &doc(&format!("{}, {z}, {inside_hole}", start())),
        Path::new(FILE),
    )
    .unwrap();
    let on_hole_edge = point("goal", "Q", 11.02, 48.05, "");
    fails(
        &doc(&format!("{}, {z}, {on_hole_edge}", start())),
        &["goal lies inside no-fly feature 1 (Z)"],
    );
    let in_zone = point("goal", "Q", 11.01, 48.05, "");
    fails(
        &doc(&format!("{}, {z}, {in_zone}", start())),
        &["goal lies inside no-fly feature 1 (Z)"],
    );
}
