//! The pop-up shape checks (`Popup::validate`, run by `Planner::add_popup`): a circle's radius
//! is bounded by `MAX_COORDINATE_M` even when its centre is in range, and a polygon must be
//! simple as `polygon_is_simple` documents it: "at least three vertices, all finite, no two
//! non-adjacent edges touching, no zero-length edge" — for any number of vertices, not only
//! triangles.

use skyroute::geometry::predicates::polygon_is_simple;
use skyroute::geometry::MAX_COORDINATE_M;
use skyroute::planner::Popup;
use skyroute::{Planner, PopupError, Vec2};

fn pts(xy: &[(f32, f32)]) -> Vec<Vec2> {
    xy.iter().map(|&(x, y)| Vec2::new(x, y)).collect()
}

fn polygon(points: &[Vec2]) -> Popup {
    Popup::Polygon(heapless::Vec::from_slice(points).unwrap())
}

/// The vertices of a regular pentagon of radius 10 about (20, 20), counter-clockwise.
fn pentagon() -> Vec<Vec2> {
    (0..5)
        .map(|k| {
            let a = std::f32::consts::FRAC_PI_2 + k as f32 * 2.0 * std::f32::consts::PI / 5.0;
            Vec2::new(20.0 + 10.0 * a.cos(), 20.0 + 10.0 * a.sin())
        })
        .collect()
}

/// `polygon_is_simple` and `Popup::validate` agree, and both say `simple`.
fn check(name: &str, points: &[Vec2], simple: bool) {
    assert_eq!(polygon_is_simple(points), simple, "{name}: {points:?}");
    // The reversed order describes the same polygon.
    let reversed: Vec<Vec2> = points.iter().rev().copied().collect();
    assert_eq!(polygon_is_simple(&reversed[..]), simple, "{name} reversed");
    // So does every rotation of the start vertex (which edge pairs count as adjacent moves).
    for k in 0..points.len() {
        let mut rotated = points.to_vec();
        rotated.rotate_left(k);
        assert_eq!(
            polygon_is_simple(&rotated[..]),
            simple,
            "{name} rotated by {k}"
        );
    }
    let expected = if simple {
        Ok(())
    } else {
        Err(PopupError::NotSimple)
    };
    assert_eq!(polygon(points).validate(), expected, "{name}: validate");
}

#[test]
fn quadrilaterals_are_simple_unless_two_edges_cross() {
    check(
        "square",
        &pts(&[(0., 0.), (4., 0.), (4., 4.), (0., 4.)]),
        true,
    );
    // A dart: concave, still simple.
    check(
        "dart",
        &pts(&[(0., 0.), (2., 1.), (4., 0.), (2., 4.)]),
        true,
    );
    // A bow-tie: edges 0-1 and 2-3 cross at (2, 2).
    check(
        "bow-tie",
        &pts(&[(0., 0.), (4., 4.), (4., 0.), (0., 4.)]),
        false,
    );
    // A thin bow-tie whose crossing is near one end.
    check(
        "thin bow-tie",
        &pts(&[(0., 0.), (10., 1.), (10., 0.), (0., 0.5)]),
        false,
    );
}

#[test]
fn pentagons_are_simple_unless_two_edges_cross() {
    let p = pentagon();
    check("regular pentagon", &p, true);
    check(
        "concave pentagon",
        &pts(&[(0., 0.), (6., 0.), (6., 6.), (3., 2.), (0., 6.)]),
        true,
    );
    // The pentagram: the same points in star order, every non-adjacent pair crossing.
    let star: Vec<Vec2> = [0, 2, 4, 1, 3].iter().map(|&k| p[k]).collect();
    check("pentagram", &star, false);
    // The closing edge (2,6)-(0,0) crosses edge (4,0)-(0,4) at (1, 3) and edge (0,4)-(4,4).
    check(
        "closing edge crossing",
        &pts(&[(0., 0.), (4., 0.), (0., 4.), (4., 4.), (2., 6.)]),
        false,
    );
}

#[test]
fn repeated_vertices_and_zero_length_edges_are_not_simple() {
    // A triangle with a vertex repeated: every edge pair is adjacent, so only the zero-length
    // edge rule refuses it.
    check(
        "triangle, vertex repeated",
        &pts(&[(0., 0.), (4., 0.), (4., 0.)]),
        false,
    );
    check(
        "square, vertex repeated",
        &pts(&[(0., 0.), (4., 0.), (4., 0.), (4., 4.), (0., 4.)]),
        false,
    );
    // The closing edge of zero length: the last point repeats the first.
    check(
        "square, closed explicitly",
        &pts(&[(0., 0.), (4., 0.), (4., 4.), (0., 4.), (0., 0.)]),
        false,
    );
    // A figure eight through one point visited twice (non-adjacent edges share it).
    check(
        "figure eight",
        &pts(&[(0., 0.), (2., 2.), (4., 0.), (4., 4.), (2., 2.), (0., 4.)]),
        false,
    );
}

#[test]
fn fewer_than_three_points_are_not_simple() {
    check("two points", &pts(&[(0., 0.), (4., 0.)]), false);
    check("one point", &pts(&[(1., 1.)]), false);
    assert!(!polygon_is_simple(&[][..] as &[Vec2]));
    assert_eq!(polygon(&[]).validate(), Err(PopupError::NotSimple));
}

/// "Touching counts": a vertex lying on a non-adjacent edge (without crossing it) makes the
/// polygon not simple; lifted 1 cm off that edge it is simple.
#[test]
fn a_vertex_touching_a_non_adjacent_edge_is_not_simple() {
    check(
        "vertex on the bottom edge",
        &pts(&[(0., 0.), (6., 0.), (6., 6.), (3., 0.), (0., 6.)]),
        false,
    );
    check(
        "vertex 1 cm above the bottom edge",
        &pts(&[(0., 0.), (6., 0.), (6., 6.), (3., 0.01), (0., 6.)]),
        true,
    );
    // A vertex visited twice: two non-adjacent edges meet at (0, 0).
    check(
        "vertex visited twice",
        &pts(&[(0., 0.), (6., 0.), (6., 6.), (0., 0.), (-6., 6.)]),
        false,
    );
    // A collinear overlap of non-adjacent edges.
    check(
        "collinear overlap",
        &pts(&[(0., 0.), (6., 0.), (6., 3.), (4., 0.), (2., 0.), (0., 3.)]),
        false,
    );
}

/// A circle whose centre is in range but whose radius exceeds `MAX_COORDINATE_M` is refused
/// as out of range, by `validate` and by `add_popup`; a radius of exactly the limit is not.
#[test]
fn circle_radius_above_the_coordinate_limit_is_out_of_range() {
    let above = f32::from_bits(MAX_COORDINATE_M.to_bits() + 1);
    assert!(above > MAX_COORDINATE_M);
    for centre in [Vec2::new(0.0, 0.0), Vec2::new(-5e6, 9e6)] {
        assert!(centre.is_in_range());
        for radius in [above, 2.0 * MAX_COORDINATE_M, f32::MAX] {
            let popup = Popup::Circle { centre, radius };
            assert_eq!(
                popup.validate(),
                Err(PopupError::OutOfRange),
                "{centre:?} {radius}"
            );
            let mut p: Box<Planner<'_, 16, 16, 2, 8>> = Box::new(Planner::new());
            assert_eq!(p.add_popup(popup), Err(PopupError::OutOfRange));
            assert_eq!(p.popups().count(), 0);
        }
        let at_limit = Popup::Circle {
            centre,
            radius: MAX_COORDINATE_M,
        };
        assert_eq!(at_limit.validate(), Ok(()));
    }
}
