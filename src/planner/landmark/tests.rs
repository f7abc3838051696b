//! Landmark mode's weather, rosettes, navigability, query ends, written route and pop-up
//! tests, on a network small enough to work out by hand: two landmarks crossed in four
//! directions, two weathers, a stored start and goal, and three straight chains. Each result
//! is checked against the definitions: an edge from overflight `(L, α)` is navigable iff its
//! length is at most `d_max(L)·q(α, ω)`, a start edge iff at most the start's range.

extern crate std;
use super::*;
use crate::geometry::hermite::{FlyLimits, LineElement};
use crate::geometry::Pose;
use crate::network::write::{encode, EdgeSpec, LandmarkSiteSpec, LandmarkSpec, NetworkSpec};
use crate::planner::search::{Ends, LandmarkEnd};
use crate::planner::{Goal, Search};
use core::f32::consts::{FRAC_PI_2, FRAC_PI_6};
use std::vec;
use std::vec::Vec as StdVec;

pub(in crate::planner) type Small<'n> = Planner<'n, 64, 64, 4, 16>;

/// Nominal speed, m/s.
pub(in crate::planner) const SPEED: f32 = 25.0;
/// Directions per landmark, landmarks, weathers.
pub(in crate::planner) const D: u32 = 4;
pub(in crate::planner) const L: u32 = 2;
pub(in crate::planner) const W: u32 = 2;
/// The start's range, metres: the start edge (600 m) is navigable from it exactly.
pub(in crate::planner) const START_RANGE: f32 = 600.0;
/// `d_max` of each landmark, metres: 4 000 × q(0, 1, 0) = 4 000 × 0.25 = 1 000 m, exactly the
/// edge from overflight 0.
pub(in crate::planner) const D_MAX: [f32; 2] = [4000.0, 2000.0];

/// A point `s` metres along 30° from the origin (landmark 0).
pub(in crate::planner) fn along(s: f32) -> Vec2 {
    Vec2::from_angle(FRAC_PI_6) * s
}

pub(in crate::planner) fn element(s: f32) -> LineElement {
    LineElement::new(along(s), Vec2::from_angle(FRAC_PI_6) * SPEED)
}

/// The stored quality of landmark `l` in weather `w` and direction `k`: all sixteen distinct,
/// `(l·W + w)·D + k + 1` twentieths.
pub(in crate::planner) fn quality(l: u32, w: u32, k: u32) -> f32 {
    ((l * W + w) * D + k + 1) as f32 / 20.0
}

/// Landmark 0 at the origin and landmark 1 1 km along 30°; the stored start 600 m before
/// landmark 0 and the goal 1 km after landmark 1, both heading 30°. Vertices 0–3 and 4–7 are
/// the overflights (direction k heading 30° + k·90°), 8 the start, 9 the goal; edges, as
/// written (grouped by source): 0: 0 → 4 through a middle element (2 pieces, 1 000 m),
/// 1: 4 → 9 (1 000 m), 2: 8 → 0 (600 m).
pub(in crate::planner) fn spec() -> NetworkSpec {
    let mut vertices = StdVec::new();
    for l in 0..L {
        for k in 0..D {
            vertices.push(Pose {
                position: along(1000.0 * l as f32),
                heading: FRAC_PI_6 + k as f32 * FRAC_PI_2,
            });
        }
    }
    for s in [-600.0, 2000.0] {
        vertices.push(Pose {
            position: along(s),
            heading: FRAC_PI_6,
        });
    }
    let qualities = (0..L)
        .flat_map(|l| (0..W).flat_map(move |w| (0..D).map(move |k| quality(l, w, k))))
        .collect();
    NetworkSpec {
        origin_lat_deg: 48.1,
        origin_lon_deg: 11.6,
        turn_radius_m: SPEED * SPEED / 5.0,
        clearance_m: 10.0,
        vertices,
        edges: vec![
            EdgeSpec::chain(0, 4, 1000.0),
            EdgeSpec::chain(4, 9, 1000.0),
            EdgeSpec::chain(8, 0, 600.0),
        ],
        obstacles: StdVec::new(),
        grid_cell_m: 100.0,
        terrain: None,
        voronoi: None,
        landmark: Some(LandmarkSpec {
            directions: D,
            weather_count: W,
            v_nominal: SPEED,
            limits: FlyLimits {
                v_min: 15.0,
                v_max: 35.0,
                a_long_min: -3.0,
                a_long_max: 3.0,
                a_lat_max: 5.0,
            },
            landmarks: (0..L as usize)
                .map(|l| LandmarkSiteSpec {
                    position: along(1000.0 * l as f32),
                    d_max_m: D_MAX[l],
                })
                .collect(),
            qualities,
            start_vertex: Some(8),
            goal_vertex: Some(9),
            start_range_m: START_RANGE,
            chains: vec![
                vec![element(0.0), element(500.0), element(1000.0)],
                vec![element(1000.0), element(2000.0)],
                vec![element(-600.0), element(0.0)],
            ],
        }),
        provenance: StdVec::new(),
    }
}

pub(in crate::planner) fn image() -> StdVec<u8> {
    encode(&spec()).expect("the small landmark network")
}

/// A roadmap of one vertex: no landmark section.
pub(in crate::planner) fn roadmap() -> StdVec<u8> {
    let mut s = spec();
    s.landmark = None;
    s.vertices.truncate(1);
    s.edges.clear();
    encode(&s).expect("a roadmap")
}

pub(in crate::planner) fn query(start: Pose, goal: Vec2) -> Query {
    Query {
        start,
        goal: Goal {
            position: goal,
            heading: None,
        },
        search: Search::Dijkstra,
    }
}

pub(in crate::planner) fn stored_start() -> Pose {
    let p = along(-600.0);
    Pose::new(p.x, p.y, FRAC_PI_6)
}

#[test]
fn the_weather_is_set_only_to_one_the_network_has() {
    let (bytes, other) = (image(), roadmap());
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    assert_eq!(planner.weather(), 0);
    assert_eq!(planner.set_weather(1), Ok(()));
    assert_eq!(planner.weather(), 1);
    assert_eq!(
        planner.set_weather(2),
        Err(PlanError::UnknownWeather {
            weather: 2,
            count: 2
        })
    );
    assert_eq!(planner.weather(), 1, "kept");
    planner.load(&other).unwrap();
    assert_eq!(planner.set_weather(0), Err(PlanError::NotLandmarkNetwork));
    assert_eq!(planner.weather(), 0);
    assert_eq!(planner.quality(0, 0), None);
    assert!(planner.is_navigable(0), "any edge of another mode");
    assert!(planner.route_edges().is_empty());
    assert!(!planner.clear_rosette(0));
    assert_eq!(
        planner.update_rosette(0, &[1.0; 4]),
        Err(PlanError::NotLandmarkNetwork)
    );
}

/// The quality in force is the stored rosette of the weather in force, or the landmark's
/// override; an override replaces the landmark's row (a second one replaces the first), leaves
/// the other landmark alone, and is dropped by clearing it.
#[test]
fn a_rosette_override_replaces_the_stored_qualities_until_cleared() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    for w in 0..W {
        planner.set_weather(w).unwrap();
        for l in 0..L {
            for k in 0..D {
                assert_eq!(
                    planner.quality(l, k),
                    Some(quality(l, w, k)),
                    "({l}, {w}, {k})"
                );
            }
            assert_eq!(planner.quality(l, D), None, "no direction {D}");
        }
    }
    assert_eq!(planner.quality(L, 0), None, "no landmark {L}");
    planner.set_weather(0).unwrap();
    assert_eq!(planner.update_rosette(1, &[0.0, 1.0, 0.5, 0.25]), Ok(()));
    assert_eq!(planner.update_rosette(0, &[0.9, 0.8, 0.7, 0.6]), Ok(()));
    assert_eq!(planner.quality(1, 1), Some(1.0));
    assert_eq!(planner.quality(1, 3), Some(0.25));
    assert_eq!(planner.quality(0, 2), Some(0.7));
    assert_eq!(planner.quality(1, 4), None);
    assert_eq!(planner.update_rosette(1, &[0.1, 0.2, 0.3, 0.4]), Ok(()));
    assert_eq!(planner.quality(1, 2), Some(0.3));
    assert_eq!(
        planner.quality(0, 2),
        Some(0.7),
        "the other landmark's override stays"
    );
    planner.set_weather(1).unwrap();
    assert_eq!(planner.quality(0, 2), Some(0.7), "whatever the weather");
    assert!(planner.clear_rosette(1));
    assert!(!planner.clear_rosette(1), "already cleared");
    assert_eq!(planner.quality(1, 2), Some(quality(1, 1, 2)));
    assert_eq!(planner.quality(0, 2), Some(0.7));
    assert!(planner.clear_rosette(0));
    assert_eq!(planner.quality(0, 2), Some(quality(0, 1, 2)));
}

/// Refused: a landmark past the network's, a row of the wrong length, a quality outside
/// [0, 1] or NaN; 0 and 1 themselves are accepted.
#[test]
fn a_rosette_override_is_refused_for_an_unknown_landmark_or_a_bad_row() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    assert_eq!(
        planner.update_rosette(2, &[0.5; 4]),
        Err(PlanError::UnknownLandmark {
            landmark: 2,
            count: 2
        })
    );
    for row in [&[0.5; 3][..], &[0.5; 5][..], &[][..]] {
        assert_eq!(
            planner.update_rosette(0, row),
            Err(PlanError::InvalidRosette {
                given: row.len() as u32,
                directions: 4
            })
        );
    }
    for bad in [-0.01, 1.01, f32::NAN, f32::INFINITY] {
        assert_eq!(
            planner.update_rosette(0, &[0.5, bad, 0.5, 0.5]),
            Err(PlanError::InvalidRosette {
                given: 4,
                directions: 4
            }),
            "{bad}"
        );
    }
    assert_eq!(
        planner.quality(0, 1),
        Some(quality(0, 0, 1)),
        "nothing kept"
    );
    assert_eq!(planner.update_rosette(0, &[0.0, 1.0, 0.0, 1.0]), Ok(()));
    assert_eq!(planner.quality(0, 1), Some(1.0));
}

/// Edge 0 (1 000 m from overflight (0, 0)) is navigable iff 1 000 ≤ 4 000·q: in weather 1
/// (q = 0.25, exactly) and not in weather 0 (q = 0.05); edge 1 (1 000 m from (1, 0)) iff
/// 1 000 ≤ 2 000·q: weather 1 (q = 0.65), not 0 (q = 0.45); the start edge (600 m) always,
/// the start's range being 600 m. An override of q = 0.2499 makes edge 0 unnavigable, of
/// 0.5 on landmark 1 makes edge 1 navigable exactly.
#[test]
fn an_edge_is_navigable_iff_its_length_is_within_d_max_times_the_quality() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    assert_eq!(
        [0, 1, 2].map(|e| planner.is_navigable(e)),
        [false, false, true],
        "weather 0"
    );
    planner.set_weather(1).unwrap();
    assert_eq!(
        [0, 1, 2].map(|e| planner.is_navigable(e)),
        [true, true, true]
    );
    planner.update_rosette(0, &[0.2499, 1.0, 1.0, 1.0]).unwrap();
    assert!(!planner.is_navigable(0));
    planner.set_weather(0).unwrap();
    planner.update_rosette(1, &[0.5, 0.0, 0.0, 0.0]).unwrap();
    assert!(planner.is_navigable(1));
    assert!(!planner.is_navigable(3), "no edge 3");

    let mut short = spec();
    if let Some(l) = short.landmark.as_mut() {
        l.start_range_m = 599.9;
    }
    let bytes = encode(&short).unwrap();
    planner.load(&bytes).unwrap();
    assert!(!planner.is_navigable(2), "the start's range 10 cm short");
}

/// From the stored start to the stored goal in weather 1 the route is edges 2, 0, 1: 2 600 m
/// of four Hermite pieces (one, two, one), arriving on the goal's heading; in weather 0 edges
/// 0 and 1 are not navigable and there is none. A planner with room for two route edges
/// refuses the three.
#[test]
fn a_route_from_the_stored_start_is_written_edge_by_edge() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let goal = along(2000.0);
    assert_eq!(
        planner.plan(&query(stored_start(), goal), u64::MAX),
        Err(PlanError::NoRoute)
    );
    planner.set_weather(1).unwrap();
    let summary = planner
        .plan(&query(stored_start(), goal), u64::MAX)
        .unwrap();
    assert_eq!(planner.route_edges(), &[2, 0, 1]);
    assert!((summary.length - 2600.0).abs() < 1e-2, "{summary:?}");
    assert_eq!((summary.primitives, summary.network_edges), (4, 3));
    assert!((summary.arrival_heading - FRAC_PI_6).abs() < 1e-6);
    assert!(planner.start_piece().is_none() && planner.goal_piece().is_none());
    // Written again from the search's predecessors: the walk back reads the route's four
    // vertices, and the writer counts them once more (one scan per vertex of a route of three
    // edges), 8 in all.
    let mut meter = Meter::new(u64::MAX);
    let again = planner
        .write_landmark_route(
            &query(stored_start(), goal),
            (LandmarkEnd::Vertex(8), 9, None),
            &mut meter,
        )
        .unwrap();
    assert_eq!(planner.route_edges(), &[2, 0, 1]);
    assert_eq!(again.length, summary.length);
    assert_eq!(meter.work.vertex_scans, 8);
    assert_eq!(meter.work.total(), 8);

    let mut narrow: Planner<'_, 64, 64, 4, 2> = Planner::new();
    narrow.load(&bytes).unwrap();
    narrow.set_weather(1).unwrap();
    assert_eq!(
        narrow.plan(&query(stored_start(), goal), u64::MAX),
        Err(PlanError::RouteTooLong {
            primitives: 3,
            capacity: 2
        })
    );
    assert!(narrow.route_edges().is_empty());
    let mut exact: Planner<'_, 64, 64, 4, 3> = Planner::new();
    exact.load(&bytes).unwrap();
    exact.set_weather(1).unwrap();
    exact.plan(&query(stored_start(), goal), u64::MAX).unwrap();
    assert_eq!(exact.route_edges(), &[2, 0, 1], "three edges fit three");
}

/// From the stored start to a goal 300 m ahead of it (before landmark 0), the goal is joined
/// online from the stored start itself, within its 600 m range: the route is that one piece,
/// with no network edge.
#[test]
fn a_goal_within_the_start_range_is_joined_from_the_stored_start() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    planner.set_weather(1).unwrap();
    let summary = planner
        .plan(&query(stored_start(), along(-300.0)), u64::MAX)
        .unwrap();
    assert!(planner.route_edges().is_empty());
    let piece = planner.goal_piece().expect("the goal's piece");
    assert!(piece.start().position.distance(along(-600.0)) < 1e-3);
    assert!((summary.length - 300.0).abs() < 0.01, "{summary:?}");
    assert_eq!(summary.network_edges, 0);
}

/// The query's start matches the stored start, or an overflight, within 1 m and 10⁻³ rad;
/// its goal the stored goal within 1 m; anything else is joined online. Each match reads the
/// stored goal and start once, and the overflights in order up to the one matched.
#[test]
fn a_query_end_matches_a_vertex_within_a_metre_and_a_milliradian() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    planner.set_weather(1).unwrap();
    let goal = along(2000.0);
    let beside = |p: Vec2, d: f32| p + Vec2::from_angle(FRAC_PI_6 + FRAC_PI_2) * d;
    let pose = |p: Vec2, h: f32| Pose::new(p.x, p.y, h);
    let online = LandmarkEnd::Online;
    let cases = [
        (
            pose(along(-600.0), FRAC_PI_6),
            goal,
            LandmarkEnd::Vertex(8),
            LandmarkEnd::Vertex(9),
            2,
        ),
        (
            pose(beside(along(-600.0), 0.99), FRAC_PI_6 + 0.99e-3),
            beside(goal, 0.99),
            LandmarkEnd::Vertex(8),
            LandmarkEnd::Vertex(9),
            2,
        ),
        (
            pose(along(0.0), FRAC_PI_6),
            goal,
            LandmarkEnd::Vertex(0),
            LandmarkEnd::Vertex(9),
            3,
        ),
        (
            pose(along(1000.0), FRAC_PI_6 + FRAC_PI_2),
            goal,
            LandmarkEnd::Vertex(5),
            LandmarkEnd::Vertex(9),
            8,
        ),
        (
            pose(along(1000.0), FRAC_PI_6 - FRAC_PI_2),
            goal,
            LandmarkEnd::Vertex(7),
            LandmarkEnd::Vertex(9),
            10,
        ),
    ];
    for (k, (start, goal, from, to, scans)) in cases.into_iter().enumerate() {
        let mut meter = Meter::new(u64::MAX);
        let ends = planner
            .landmark_prepare(&query(start, goal), &mut meter)
            .unwrap();
        assert!(
            matches!(ends, Ends::Landmark { from: f, to: t } if f == from && t == to),
            "case {k}: {ends:?}"
        );
        assert_eq!(meter.work.vertex_scans, scans, "case {k}");
    }
    // Off by more than the tolerances: no match, so that end is joined online, which here
    // finds no piece (a start 1 m beside the stored one cannot turn onto the chain in time)
    // or one.
    for (start, goal_at, from, to) in [
        (
            pose(beside(along(-600.0), 1.01), FRAC_PI_6),
            goal,
            online,
            LandmarkEnd::Vertex(9),
        ),
        (
            pose(along(-600.0), FRAC_PI_6 + 1.01e-3),
            goal,
            online,
            LandmarkEnd::Vertex(9),
        ),
        (
            pose(along(-600.0), FRAC_PI_6),
            beside(goal, 1.01),
            LandmarkEnd::Vertex(8),
            online,
        ),
    ] {
        let ends = planner.landmark_prepare(&query(start, goal_at), &mut Meter::new(u64::MAX));
        match ends {
            Ok(Ends::Landmark { from: f, to: t }) => {
                assert!(f == from && t == to, "{start:?}: {f:?} {t:?}")
            }
            Err(PlanError::StartUnconnected) => assert_eq!(from, online, "{start:?}"),
            Err(PlanError::GoalUnconnected) => assert_eq!(to, online, "{start:?}"),
            other => panic!("{start:?}: {other:?}"),
        }
    }
}

fn no_summary() -> PopupSummary {
    PopupSummary {
        id: 0,
        edges_blocked: 0,
        cells_visited: 0,
        entries_visited: 0,
        predicate_tests: 0,
        pieces_rebuilt: 0,
    }
}

/// Whether piece `k` of edge 0 (two straight 500 m pieces along 30°) has a reach box that
/// meets the box of a disc of radius `r` at `c` widened by the 10 m clearance, worked out in
/// f64: a piece's length is at most the edge's less the other's chord (with the 10⁻⁵
/// allowance), 500.005 m, and its reach the chord's midpoint ± (half that + 10⁻⁴ of it + 1 cm).
/// `None` where a box edge lies within `margin` metres.
fn piece_reached(c: Vec2, r: f32, k: u32, margin: f64) -> Option<bool> {
    let bound = 1000.0 - 500.0 * (1.0 - 1e-5);
    let half = 0.5 * bound + 1e-4 * bound + 0.01;
    let reach = half + r as f64 + 10.0;
    let mid = along(250.0 + 500.0 * k as f32);
    let gaps = [(c.x - mid.x) as f64, (c.y - mid.y) as f64].map(|d| d.abs() - reach);
    if gaps.iter().any(|g| g.abs() < margin) {
        return None;
    }
    Some(gaps.iter().all(|&g| g < 0.0))
}

/// How many pieces of edge 0 [`piece_reached`] finds for a disc of radius `r` at `c`.
fn pieces_reached(c: Vec2, r: f32, margin: f64) -> Option<u32> {
    (0..2).try_fold(0, |n, k| {
        Some(n + u32::from(piece_reached(c, r, k, margin)?))
    })
}

/// Edge 0 against discs of radius 5 m: one on the chain conflicts after one piece is rebuilt
/// (16 chords tested); ones 14 m and 18 m beside it conflict (within 5 + 10 m) and do not; far
/// ones rebuild nothing; ones half a metre inside and outside each side of the second piece's
/// reach box rebuild exactly the pieces whose boxes they meet, and so do ones 1.25 mm inside and
/// outside: a bound lowered to the chord (500 m) shrinks the box by 2.5 mm.
#[test]
fn a_chain_is_tested_against_a_popup_only_on_the_pieces_that_may_reach_it() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let side = Vec2::from_angle(FRAC_PI_6 + FRAC_PI_2);
    let disc = |centre: Vec2| Popup::Circle {
        centre,
        radius: 5.0,
    };
    let mut cases = vec![
        (along(250.0), true, 1),
        (along(750.0) + side * 14.0, true, 1),
        (along(750.0) + side * 18.0, false, 1),
        (along(5000.0), false, 0),
        (along(500.0) + side * 2000.0, false, 0),
    ];
    let bound = 1000.0 - 500.0 * (1.0 - 1e-5);
    let reach = (0.5 * bound + 1e-4 * bound + 0.01 + 15.0) as f32;
    let mid = along(750.0);
    for delta in [-0.5, -0.00125, 0.00125, 0.5] {
        for dir in [
            Vec2::new(1.0, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, -1.0),
        ] {
            let c = mid + dir * (reach + delta);
            let count = pieces_reached(c, 5.0, 0.001).expect("over a millimetre from the box");
            cases.push((c, false, count));
        }
    }
    let mut counts = StdVec::new();
    for (centre, conflict, rebuilt) in cases {
        let mut summary = no_summary();
        let found = planner.chain_conflicts(0, &disc(centre), 10.0, &mut summary);
        assert_eq!(found, conflict, "{centre:?}");
        assert_eq!(summary.pieces_rebuilt, rebuilt, "{centre:?}");
        assert_eq!(summary.predicate_tests, 16 * rebuilt, "{centre:?}");
        counts.push(rebuilt);
    }
    assert!(
        counts.contains(&0) && counts.contains(&1) && counts.contains(&2),
        "{counts:?}"
    );
    let mut summary = no_summary();
    assert!(
        planner.chain_conflicts(7, &disc(along(250.0)), 10.0, &mut summary),
        "no edge 7: fail safe"
    );
}

/// A disc whose widened box touches the second piece's reach box, on each of its four sides,
/// is tested against that piece: boxes that share an edge meet. The reach box is the
/// documented one, computed in f32 as the planner reads its chain; the disc is placed so that
/// its box edge equals the reach box's exactly.
#[test]
fn a_popup_box_touching_a_piece_reach_box_rebuilds_the_piece() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let net = &planner.network;
    let (length, range) = (net.edge_length(0).unwrap(), net.chain_elements(0));
    let position = |k: u32| net.chain_element(k).unwrap().position;
    let chord = |k: u32| position(k).distance(position(k + 1));
    let chords = chord(range.start) + chord(range.start + 1);
    let piece = range.start + 1;
    let bound = (length - (chords - chord(piece)) * (1.0 - 1e-5)).max(chord(piece));
    let (lo, hi) = net.edge_reach(position(piece), position(piece + 1), bound);
    let mid = along(750.0);
    // The disc's box edge is its centre ∓ 1 m ∓ the 10 m clearance, exact at these magnitudes.
    let touching = [
        (Vec2::new(hi.x + 11.0, mid.y), hi.x, 0),
        (Vec2::new(lo.x - 11.0, mid.y), lo.x, 0),
        (Vec2::new(mid.x, hi.y + 11.0), hi.y, 1),
        (Vec2::new(mid.x, lo.y - 11.0), lo.y, 1),
    ];
    for (centre, edge, axis) in touching {
        let disc = Popup::Circle {
            centre,
            radius: 1.0,
        };
        let (dlo, dhi) = disc.bounding_box();
        let (dlo, dhi) = (dlo - Vec2::new(10.0, 10.0), dhi + Vec2::new(10.0, 10.0));
        let sides = [[dlo.x, dhi.x], [dlo.y, dhi.y]][axis];
        assert!(sides.contains(&edge), "{centre:?} touches exactly");
        let first = piece_reached(centre, 1.0, 0, 0.001).expect("clear of the first piece");
        let mut summary = no_summary();
        assert!(!planner.chain_conflicts(0, &disc, 10.0, &mut summary));
        assert_eq!(summary.pieces_rebuilt, 1 + u32::from(first), "{centre:?}");
    }
}

/// A landmark network of `landmarks` landmarks at 1 km spacing, each crossed in `directions`
/// directions (evenly spread), one weather, no stored start or goal, and no edges.
fn sites_only(landmarks: u32, directions: u32) -> StdVec<u8> {
    sites_along(landmarks, directions, 1000.0)
}

/// [`sites_only`] with the landmarks `spacing` metres apart along 30°.
pub(in crate::planner) fn sites_along(landmarks: u32, directions: u32, spacing: f32) -> StdVec<u8> {
    let mut s = spec();
    s.vertices = (0..landmarks)
        .flat_map(|l| {
            (0..directions).map(move |k| Pose {
                position: along(spacing * l as f32),
                heading: k as f32 * core::f32::consts::TAU / directions as f32,
            })
        })
        .collect();
    s.edges.clear();
    if let Some(spec) = s.landmark.as_mut() {
        spec.directions = directions;
        spec.weather_count = 1;
        spec.landmarks = (0..landmarks)
            .map(|l| LandmarkSiteSpec {
                position: along(spacing * l as f32),
                d_max_m: 1000.0,
            })
            .collect();
        spec.qualities = vec![0.5; (landmarks * directions) as usize];
        spec.start_vertex = None;
        spec.goal_vertex = None;
        spec.chains.clear();
    }
    encode(&s).expect("a landmark network without edges")
}

/// An override row holds up to [`MAX_ROSETTE_DIRECTIONS`] (24) directions: a network of 24
/// takes one, a network of 25 refuses it; and [`MAX_ROSETTE_OVERRIDES`] (8) landmarks may have
/// one at a time, the ninth refused with the capacity.
#[test]
fn an_override_holds_at_most_24_directions_and_8_landmarks() {
    let (wide, wider, many) = (sites_only(1, 24), sites_only(1, 25), sites_only(9, 1));
    let mut planner = Small::new();
    planner.load(&wide).unwrap();
    assert_eq!(planner.update_rosette(0, &[1.0; 24]), Ok(()));
    assert_eq!(planner.quality(0, 23), Some(1.0));
    planner.load(&wider).unwrap();
    assert_eq!(
        planner.update_rosette(0, &[1.0; 25]),
        Err(PlanError::InvalidRosette {
            given: 25,
            directions: 25
        })
    );
    planner.load(&many).unwrap();
    for landmark in 0..8 {
        assert_eq!(
            planner.update_rosette(landmark, &[1.0]),
            Ok(()),
            "{landmark}"
        );
    }
    assert_eq!(
        planner.update_rosette(8, &[1.0]),
        Err(PlanError::RosetteTableFull { capacity: 8 })
    );
    assert_eq!(
        planner.update_rosette(3, &[0.0]),
        Ok(()),
        "a landmark that has one"
    );
    assert!(planner.clear_rosette(5));
    assert_eq!(planner.update_rosette(8, &[1.0]), Ok(()), "room again");
}
