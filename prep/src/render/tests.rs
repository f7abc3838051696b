//! Unit tests of the picture's helpers and route-file parsing.

use super::draw::{metres, nice_length, path_data, View};
use super::*;
use skyroute::{Arc, Primitive, Segment, Vec2};
use std::f64::consts::FRAC_PI_2;

#[test]
fn nice_lengths() {
    assert_eq!(nice_length(730.0), 500.0);
    assert_eq!(nice_length(2100.0), 2000.0);
    assert_eq!(nice_length(99.0), 50.0);
    assert_eq!(metres(1000.0), "1 km");
    assert_eq!(metres(250.0), "250 m");
}

#[test]
fn primitives_round_trip_through_json() {
    let a = Primitive::Arc(Arc {
        centre: Vec2::new(1.0, 2.0),
        radius: 64.0,
        start_angle: 0.5,
        sweep: -1.25,
    });
    let l = Primitive::Line(Segment::new(Vec2::new(0.0, 0.0), Vec2::new(3.0, 4.0)));
    for p in [a, l] {
        assert_eq!(
            primitive_from_json(&crate::route_json::primitive_json(&p)).unwrap(),
            p
        );
    }
}

#[test]
fn arcs_turn_the_right_way_on_screen() {
    let view = View {
        min_x: 0.0,
        max_y: 0.0,
        scale: 1.0,
        map_w: 100.0,
        map_h: 100.0,
    };
    // A left quarter turn about the origin from (1, 0) to (0, 1): counter-clockwise, flag 0.
    let left = Primitive::Arc(Arc {
        centre: Vec2::new(0.0, 0.0),
        radius: 1.0,
        start_angle: 0.0,
        sweep: FRAC_PI_2 as f32,
    });
    let mut d = String::new();
    path_data(&mut d, &left, &view, &mut None);
    assert!(d.contains(" 0 0 0 "), "{d}");
    let right = Primitive::Arc(Arc {
        centre: Vec2::new(0.0, 0.0),
        radius: 1.0,
        start_angle: 0.0,
        sweep: -std::f32::consts::PI * 1.5,
    });
    let mut d = String::new();
    path_data(&mut d, &right, &view, &mut None);
    assert_eq!(d.matches('A').count(), 3, "{d}");
    assert!(d.contains(" 0 0 1 "), "{d}");
}

#[test]
fn graticule_spacings_and_labels() {
    use super::graticule::{dms, spacing_deg, spacing_text};
    // 1° by 0.25°: ten-minute lines would leave one parallel; five minutes give three.
    assert_eq!(spacing_text(spacing_deg(1.0, 0.25)), "5′");
    // A square of 0.35°: at most eight lines over it.
    assert_eq!(spacing_text(spacing_deg(0.35, 0.35)), "5′");
    assert_eq!(spacing_text(spacing_deg(0.05, 0.04)), "30″");
    assert_eq!(spacing_text(spacing_deg(8.0, 8.0)), "1°");
    assert_eq!(dms(48.2, 5.0 / 60.0, 'N', 'S'), "48°12′N");
    assert_eq!(dms(-84.25, 5.0 / 60.0, 'E', 'W'), "84°15′W");
    assert_eq!(dms(11.625, 30.0 / 3600.0, 'E', 'W'), "11°37′30″E");
    assert_eq!(dms(12.0, 1.0, 'E', 'W'), "12°E");
    assert_eq!(dms(12.0, 10.0 / 60.0, 'E', 'W'), "12°00′E");
}

#[test]
fn labels_are_moved_inside_the_map() {
    use super::draw::{clamp_label, MARGIN_PX};
    let view = View {
        min_x: 0.0,
        max_y: 0.0,
        scale: 1.0,
        map_w: 300.0,
        map_h: 200.0,
    };
    let (right, bottom) = (MARGIN_PX + 300.0, MARGIN_PX + 200.0);
    // Ten characters of 10 px: at most 68 px wide.
    let s = "0123456789";
    let (x, y) = clamp_label(&view, (right - 10.0, 0.0), 10.0, "start", s);
    assert!(x + 68.0 <= right && y - 10.0 >= MARGIN_PX, "({x}, {y})");
    let (x, y) = clamp_label(&view, (MARGIN_PX, bottom + 50.0), 10.0, "end", s);
    assert!(x - 68.0 >= MARGIN_PX && y <= bottom, "({x}, {y})");
    let (x, _) = clamp_label(&view, (MARGIN_PX + 10.0, 100.0), 10.0, "middle", s);
    assert!(x - 34.0 >= MARGIN_PX, "{x}");
    // A label well inside stays where it is.
    assert_eq!(
        clamp_label(&view, (150.0, 120.0), 10.0, "middle", s),
        (150.0, 120.0)
    );
}

#[test]
fn a_landmark_name_keeps_clear_of_an_endpoint_label() {
    use super::draw::label_box;
    use super::landmark_layer::labels;
    let view = View {
        min_x: 0.0,
        max_y: 200.0,
        scale: 1.0,
        map_w: 300.0,
        map_h: 200.0,
    };
    let marks = [LandmarkMark {
        name: "L17".into(),
        position: (100.0, 100.0),
    }];
    let mut free = String::new();
    labels(&mut free, &marks, &view, &[]);
    assert!(free.contains(r#"text-anchor="start""#), "{free}");
    // An endpoint label right of and below the landmark: the name goes to its left.
    let (x, y) = view.px(100.0, 100.0);
    let avoid = [label_box(
        &view,
        (x + 10.0, y + 14.0),
        17.0,
        "start",
        "Q (goal)",
    )];
    let mut moved = String::new();
    labels(&mut moved, &marks, &view, &avoid);
    assert!(moved.contains(r#"text-anchor="end""#), "{moved}");
}
