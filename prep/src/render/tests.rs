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
