//! Landmark mode's online ends on the small network of `planner/landmark`'s tests: the start
//! range, each overflight's range `d_max·q`, the links found on each side against the rules
//! of the module documentation (the chord, then the piece, within the range; flyable; clear
//! of obstacles and pop-ups), their order and work, and the goal links offered to the search.

extern crate std;
use super::*;
use crate::network::write::{encode, ObstacleSpec};
use crate::planner::landmark::tests::{
    along, image, quality, query, roadmap, sites_along, spec, Small, D_MAX, START_RANGE,
};
use crate::planner::{Goal, Popup, Search};
use core::f32::consts::{FRAC_PI_2, FRAC_PI_6};
use std::vec;
use std::vec::Vec as StdVec;

/// Offers 40 keys in a scrambled order (with ties): the kept are the `MAX_LINKS` smallest,
/// sorted, and of equal keys the earlier offered.
#[test]
fn keep_cheapest_keeps_the_smallest_keys_sorted() {
    let key_of = |i: u32| ((i * 17) % 23) as f32; // 0..22, 17 of them twice
    let mut kept: Vec<(f32, OnlineLink), MAX_LINKS> = Vec::new();
    for i in 0..40u32 {
        let link = OnlineLink {
            vertex: i,
            length: key_of(i),
        };
        keep_cheapest(&mut kept, key_of(i), link);
    }
    // The expected order by brute force: every (key, offer) pair ranked by how many come
    // before it.
    let rank = |i: u32| {
        (0..40u32)
            .filter(|&j| key_of(j) < key_of(i) || (key_of(j) == key_of(i) && j < i))
            .count()
    };
    assert_eq!(kept.len(), MAX_LINKS);
    for (position, (key, link)) in kept.iter().enumerate() {
        assert_eq!(rank(link.vertex), position, "{kept:?}");
        assert_eq!(*key, key_of(link.vertex));
    }
}

/// The start range is the network's until set; set only to a finite value of at least 0;
/// restored by a load; none on another network.
#[test]
fn the_start_range_is_the_networks_until_set_to_a_finite_non_negative_value() {
    let (bytes, other) = (image(), roadmap());
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    assert_eq!(planner.start_range(), Some(START_RANGE));
    assert_eq!(planner.set_start_range(250.0), Ok(()));
    assert_eq!(planner.start_range(), Some(250.0));
    for bad in [-0.01, f32::NAN, f32::INFINITY] {
        assert_eq!(
            planner.set_start_range(bad),
            Err(PlanError::InvalidRange),
            "{bad}"
        );
        assert_eq!(planner.start_range(), Some(250.0), "kept");
    }
    assert_eq!(planner.set_start_range(0.0), Ok(()));
    assert_eq!(planner.start_range(), Some(0.0));
    planner.load(&bytes).unwrap();
    assert_eq!(planner.start_range(), Some(START_RANGE), "restored");
    planner.load(&other).unwrap();
    assert_eq!(planner.start_range(), None);
    assert_eq!(
        planner.set_start_range(1.0),
        Err(PlanError::NotLandmarkNetwork)
    );
    assert_eq!(planner.overflight_range(0), None);
    assert!(planner.start_piece().is_none() && planner.goal_piece().is_none());
    assert!(planner.online_links(LinkSide::Start).is_empty());
}

/// Overflight `v` allows `d_max(v / 4)·q(v / 4, v % 4)` in the weather and rosettes in force;
/// the stored start and goal are no overflights.
#[test]
fn an_overflights_range_is_d_max_times_its_quality_in_force() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    for w in 0..2 {
        planner.set_weather(w).unwrap();
        for v in 0..8 {
            let (l, k) = (v / 4, v % 4);
            assert_eq!(
                planner.overflight_range(v),
                Some(D_MAX[l as usize] * quality(l, w, k)),
                "vertex {v}, weather {w}"
            );
        }
    }
    planner.update_rosette(1, &[0.5, 0.25, 1.0, 0.0]).unwrap();
    assert_eq!(planner.overflight_range(5), Some(500.0));
    assert_eq!(planner.overflight_range(6), Some(2000.0));
    assert_eq!(planner.overflight_range(8), None);
    assert_eq!(planner.overflight_range(9), None);
}

fn pose_at(s: f32, heading: f32) -> Pose {
    let p = along(s);
    Pose::new(p.x, p.y, heading)
}

/// The links one side should have, by the module documentation's rules on a network without
/// obstacles or pop-ups, with their keys (the piece, then the chord to the other end), sorted;
/// and how many pieces were built (vertices whose chord is within the range).
fn expected_links(
    planner: &Small,
    query: &Query,
    side: LinkSide,
    extra: Option<u32>,
) -> (StdVec<(f32, u32, f32)>, u64) {
    let limits = planner.network.fly_limits().unwrap();
    let mut links = StdVec::new();
    let mut built = 0;
    for v in (0..8).chain(extra) {
        let at = planner.network.vertex(v).unwrap();
        let (from, to, range) = match side {
            LinkSide::Start => (query.start, at, planner.start_range().unwrap()),
            LinkSide::Goal => {
                let range = match v {
                    8 => START_RANGE,
                    _ => planner.overflight_range(v).unwrap(),
                };
                let d = query.goal.position - at.position;
                let heading = query.goal.heading.unwrap_or(libm::atan2f(d.y, d.x));
                let goal = Pose::new(query.goal.position.x, query.goal.position.y, heading);
                (at, goal, range)
            }
        };
        if from.position.distance(to.position) > range {
            continue;
        }
        built += 1;
        let piece = HermiteSegment::new(
            &LineElement::from_pose(&from, 25.0),
            &LineElement::from_pose(&to, 25.0),
            25.0,
        )
        .unwrap();
        if piece.length() > range || piece.check_flyable(&limits).is_err() {
            continue;
        }
        let rest = match side {
            LinkSide::Start => to.position.distance(query.goal.position),
            LinkSide::Goal => query.start.position.distance(from.position),
        };
        links.push((piece.length() + rest, v, piece.length()));
    }
    links.sort_by(|a, b| a.0.total_cmp(&b.0));
    (links, built)
}

fn found_links(planner: &Small, side: LinkSide) -> StdVec<(u32, f32)> {
    planner
        .online_links(side)
        .iter()
        .map(|k| (k.vertex, k.length))
        .collect()
}

/// A start 300 m before landmark 0 on the chains' line, to the stored goal: within the
/// network's 600 m range only landmark 0's overflights, whose pieces are built and kept where
/// flyable, cheapest first; the stored goal, 2.3 km away, is tried and out of range. One
/// vertex scan per vertex tried, one solve per piece built, one relaxation per link. With a
/// range of 250 m none is within it and the start is unconnected.
#[test]
fn start_links_are_the_flyable_pieces_within_the_range_left() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let q = query(pose_at(-300.0, FRAC_PI_6), along(2000.0));
    let l = *planner.network.landmark().unwrap();
    let mut meter = Meter::new(u64::MAX);
    planner
        .connect_online(&l, &q, LinkSide::Start, Some(9), &mut meter)
        .unwrap();
    let (expected, built) = expected_links(&planner, &q, LinkSide::Start, Some(9));
    let expected: StdVec<(u32, f32)> = expected.iter().map(|e| (e.1, e.2)).collect();
    assert_eq!(found_links(&planner, LinkSide::Start), expected);
    assert!(
        !expected.is_empty() && expected.len() < 4,
        "some of landmark 0's: {expected:?}"
    );
    assert_eq!(expected[0].0, 0, "straight on first");
    assert!((expected[0].1 - 300.0).abs() < 0.01);
    assert_eq!(built, 4);
    assert_eq!(meter.work.vertex_scans, 9);
    assert_eq!(meter.work.dubins_solves, built);
    assert_eq!(meter.work.relaxations, expected.len() as u64);
    assert_eq!(meter.work.collision_tests, 0, "no obstacle or pop-up");

    planner.set_start_range(250.0).unwrap();
    assert_eq!(
        planner.connect_online(&l, &q, LinkSide::Start, Some(9), &mut Meter::new(u64::MAX)),
        Err(PlanError::StartUnconnected)
    );
    assert!(planner.online_links(LinkSide::Start).is_empty());
}

/// A goal 950 m past landmark 1 without a heading, from the stored start: the overflights
/// whose range `d_max·q` holds their piece along the chord to the goal: in weather 1
/// overflight 4 (2 000 × 0.65 = 1 300 m), in weather 0 none (900 m), so the goal is
/// unconnected; the stored start (range 600 m, 2.55 km away) never. A goal with a heading is
/// reached on it.
#[test]
fn goal_links_are_the_pieces_each_overflights_range_allows() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let l = *planner.network.landmark().unwrap();
    let mut counts = StdVec::new();
    for (w, heading) in [(1, None), (0, None), (1, Some(FRAC_PI_6 + 0.3))] {
        planner.set_weather(w).unwrap();
        let mut q = query(pose_at(-600.0, FRAC_PI_6), along(1950.0));
        q.goal.heading = heading;
        let mut meter = Meter::new(u64::MAX);
        let result = planner.connect_online(&l, &q, LinkSide::Goal, Some(8), &mut meter);
        let (expected, built) = expected_links(&planner, &q, LinkSide::Goal, Some(8));
        let expected: StdVec<(u32, f32)> = expected.iter().map(|e| (e.1, e.2)).collect();
        assert_eq!(result.is_ok(), !expected.is_empty());
        assert_eq!(
            found_links(&planner, LinkSide::Goal),
            expected,
            "weather {w}, {heading:?}"
        );
        assert_eq!(meter.work.vertex_scans, 9);
        assert_eq!(meter.work.dubins_solves, built);
        counts.push(expected.len());
        for (k, link) in planner.online_links(LinkSide::Goal).iter().enumerate() {
            let piece = planner
                .rebuild_online_piece(&q, LinkSide::Goal, k, &mut Meter::new(u64::MAX))
                .unwrap();
            assert_eq!(piece.length(), link.length);
            let end = piece.end();
            assert!(end.position.distance(q.goal.position) < 1e-3);
            if let Some(h) = heading {
                let v = end.velocity;
                assert!((libm::atan2f(v.y, v.x) - h).abs() < 1e-4);
            }
        }
        let past = planner.online_links(LinkSide::Goal).len();
        assert!(matches!(
            planner.rebuild_online_piece(&q, LinkSide::Goal, past, &mut Meter::new(u64::MAX)),
            Err(PlanError::Internal)
        ));
    }
    assert!(
        counts[0] >= 1 && counts[1] == 0 && counts[2] >= 1,
        "{counts:?}"
    );
}

/// A pop-up on the straight piece from the start to overflight 0 drops that link, and one far
/// away drops none; each costs one box test per piece within range and flyable, and the
/// chords of the pieces whose reach meets it. A stored obstacle likewise.
#[test]
fn a_piece_near_an_obstacle_or_popup_is_no_link() {
    let bytes = image();
    let q = query(pose_at(-300.0, FRAC_PI_6), along(2000.0));
    let straight_on = |planner: &Small| {
        planner
            .online_links(LinkSide::Start)
            .iter()
            .any(|k| k.vertex == 0)
    };
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    let l = *planner.network.landmark().unwrap();
    let (links, _) = expected_links(&planner, &q, LinkSide::Start, None);
    let tested = links.len() as u64;
    planner
        .add_popup(Popup::Circle {
            centre: along(5000.0),
            radius: 20.0,
        })
        .unwrap();
    let mut meter = Meter::new(u64::MAX);
    planner
        .connect_online(&l, &q, LinkSide::Start, None, &mut meter)
        .unwrap();
    assert!(straight_on(&planner));
    assert_eq!(meter.work.collision_tests, tested, "one box test per piece");
    planner
        .add_popup(Popup::Circle {
            centre: along(-150.0),
            radius: 5.0,
        })
        .unwrap();
    let mut meter = Meter::new(u64::MAX);
    let _ = planner.connect_online(&l, &q, LinkSide::Start, None, &mut meter);
    assert!(!straight_on(&planner), "the pop-up on it drops it");
    assert!(meter.work.collision_tests > 2 * tested, "chords tested");

    let mut walled = spec();
    walled.obstacles = vec![ObstacleSpec::Circle {
        centre: along(-150.0) + Vec2::from_angle(FRAC_PI_6 + FRAC_PI_2) * 12.0,
        radius: 5.0,
    }];
    let walled = encode(&walled).unwrap();
    let mut planner = Small::new();
    planner.load(&walled).unwrap();
    let mut meter = Meter::new(u64::MAX);
    let _ = planner.connect_online(&l, &q, LinkSide::Start, None, &mut meter);
    assert!(!straight_on(&planner), "12 m from it, within 5 + 10 m");
    assert!(meter.work.collision_tests > 16, "a box test and 16 chords");
}

/// The goal links leaving the vertex expanded are offered at its cost plus their length; a
/// cheaper arrival found before is kept; every link is one relaxation.
#[test]
fn the_goal_links_leaving_a_vertex_are_offered_at_its_cost_plus_their_length() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    if let ModeState::Landmark(state) = &mut planner.state {
        for (vertex, length) in [(4, 300.0), (5, 350.0), (4, 250.0)] {
            state
                .goal_links
                .push(OnlineLink { vertex, length })
                .unwrap();
        }
    }
    let mut best = None;
    let mut meter = Meter::new(u64::MAX);
    planner.offer_online_goal_links(4, 100.0, &mut best, &mut meter);
    let (total, arrival) = best.unwrap();
    assert_eq!(total, 350.0);
    assert!(matches!(arrival, Arrival::FromState { state: 4, link: 2 }));
    assert_eq!(meter.work.relaxations, 3);
    planner.offer_online_goal_links(5, 10.0, &mut best, &mut meter);
    assert_eq!(best.unwrap().0, 350.0, "360 is dearer");
    planner.offer_online_goal_links(5, 0.0, &mut best, &mut meter);
    assert!(
        matches!(best, Some((_, Arrival::FromState { state: 4, link: 2 }))),
        "a tie keeps the earlier"
    );
    let mut none = None;
    planner.offer_online_goal_links(6, 0.0, &mut none, &mut meter);
    assert!(none.is_none());
    assert_eq!(meter.work.relaxations, 12);
}

/// Online ends planned through: the start's piece and the goal's are the route's first and
/// last, and their lengths add to the edges'.
#[test]
fn a_route_with_online_ends_carries_both_pieces() {
    let bytes = image();
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    planner.set_weather(1).unwrap();
    let q = Query {
        start: pose_at(-300.0, FRAC_PI_6),
        goal: Goal {
            position: along(1300.0),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let summary = planner.plan(&q, u64::MAX).unwrap();
    let (start, goal) = (
        planner.start_piece().unwrap(),
        planner.goal_piece().unwrap(),
    );
    let edges: f32 = planner
        .route_edges()
        .iter()
        .map(|&e| planner.network.edge_cost_target(e).unwrap().0)
        .sum();
    assert!((summary.length - (start.length() + edges + goal.length())).abs() < 1e-2);
    assert!(start.start().position.distance(q.start.position) < 1e-3);
    assert!(goal.end().position.distance(q.goal.position) < 1e-3);
}

/// Of more than [`MAX_LINKS`] links found, the [`MAX_LINKS`] with the smallest lower bound of
/// a route through them (the piece, then the chord to the goal) are kept, in that order:
/// twelve landmarks 100 m apart crossed in four directions, the start 300 m before the first
/// with a range of 2 km, the goal 300 m off the line beyond the last.
#[test]
fn of_more_links_than_room_the_cheapest_bounds_are_kept() {
    let bytes = sites_along(12, 4, 100.0);
    let mut planner = Small::new();
    planner.load(&bytes).unwrap();
    planner.set_start_range(2000.0).unwrap();
    let goal = along(1200.0) + Vec2::from_angle(FRAC_PI_6 + FRAC_PI_2) * 300.0;
    let q = query(pose_at(-300.0, FRAC_PI_6), goal);
    let l = *planner.network.landmark().unwrap();
    let mut meter = Meter::new(u64::MAX);
    planner
        .connect_online(&l, &q, LinkSide::Start, None, &mut meter)
        .unwrap();
    let limits = planner.network.fly_limits().unwrap();
    let mut all = StdVec::new();
    for v in 0..48 {
        let at = planner.network.vertex(v).unwrap();
        let piece = HermiteSegment::new(
            &LineElement::from_pose(&q.start, 25.0),
            &LineElement::from_pose(&at, 25.0),
            25.0,
        )
        .unwrap();
        if piece.length() <= 2000.0 && piece.check_flyable(&limits).is_ok() {
            all.push((
                piece.length() + at.position.distance(goal),
                v,
                piece.length(),
            ));
        }
    }
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(all.len() > MAX_LINKS, "{} links found", all.len());
    let expected: StdVec<(u32, f32)> = all[..MAX_LINKS].iter().map(|e| (e.1, e.2)).collect();
    assert_eq!(found_links(&planner, LinkSide::Start), expected);
    assert_eq!(meter.work.relaxations, all.len() as u64);
}

/// The box test before a piece's chord tests, against the piece's reach (its chord's midpoint
/// ± half its length, plus 10⁻⁴ of it and 1 cm) and each obstacle's or pop-up's box widened by
/// the 10 m clearance: with a range of 300.5 m only the straight 300 m piece to overflight 0
/// is tested. Discs 192 m from its midpoint along one axis (beyond the reach on that side
/// alone) cost one test each; discs 157 m out along x, and a square 157 m out along y, meet the
/// widened reach and add their chord tests: 16 per disc, 16 × (4 + 1) for the square, so
/// 6 + 2 × 16 + 1 + 80 = 119 in all; none is within the clearance of the piece.
#[test]
fn the_box_test_skips_exactly_what_lies_beyond_the_widened_reach() {
    let mid = along(-150.0);
    let square = |c: Vec2, h: f32| {
        ObstacleSpec::Polygon(vec![
            c + Vec2::new(-h, -h),
            c + Vec2::new(h, -h),
            c + Vec2::new(h, h),
            c + Vec2::new(-h, h),
        ])
    };
    let mut s = spec();
    s.obstacles = vec![square(mid + Vec2::new(0.0, 157.0), 3.0)];
    let bytes = encode(&s).unwrap();
    let mut planner: Planner<'_, 64, 64, 8, 16> = Planner::new();
    planner.load(&bytes).unwrap();
    planner.set_start_range(300.5).unwrap();
    let offsets = [
        (192.0, 0.0),
        (-192.0, 0.0),
        (0.0, 192.0),
        (0.0, -192.0),
        (157.0, 0.0),
        (-157.0, 0.0),
    ];
    for (dx, dy) in offsets {
        let centre = mid + Vec2::new(dx, dy);
        planner
            .add_popup(Popup::Circle {
                centre,
                radius: 2.0,
            })
            .unwrap();
    }
    let q = query(pose_at(-300.0, FRAC_PI_6), along(2000.0));
    let l = *planner.network.landmark().unwrap();
    let mut meter = Meter::new(u64::MAX);
    planner
        .connect_online(&l, &q, LinkSide::Start, None, &mut meter)
        .unwrap();
    assert_eq!(
        planner.online_links(LinkSide::Start).len(),
        1,
        "the straight piece alone"
    );
    // The reference: the reach box in f64 and each box widened by the clearance.
    let length = planner.online_links(LinkSide::Start)[0].length as f64;
    let half = 0.5 * length + 1e-4 * length + 0.01;
    let meets = |lo: (f64, f64), hi: (f64, f64)| {
        let (mx, my) = (mid.x as f64, mid.y as f64);
        !(mx + half < lo.0 - 10.0
            || my + half < lo.1 - 10.0
            || mx - half > hi.0 + 10.0
            || my - half > hi.1 + 10.0)
    };
    let mut expected = 0;
    for (dx, dy) in offsets {
        let (cx, cy) = ((mid.x + dx) as f64, (mid.y + dy) as f64);
        expected += 1 + 16 * u64::from(meets((cx - 2.0, cy - 2.0), (cx + 2.0, cy + 2.0)));
    }
    let (cx, cy) = (mid.x as f64, (mid.y + 157.0) as f64);
    expected += 1 + 80 * u64::from(meets((cx - 3.0, cy - 3.0), (cx + 3.0, cy + 3.0)));
    assert_eq!(expected, 119, "worked by hand");
    assert_eq!(meter.work.collision_tests, expected);
}

/// A full list keeps its worst entry against a later offer of the same key (ties keep the
/// earlier), and gives it up for a smaller one.
#[test]
fn keep_cheapest_keeps_the_earlier_of_equal_keys_at_the_boundary() {
    let mut kept: Vec<(f32, OnlineLink), MAX_LINKS> = Vec::new();
    let link = |vertex: u32, length: f32| OnlineLink { vertex, length };
    for i in 0..MAX_LINKS as u32 {
        keep_cheapest(&mut kept, i as f32, link(i, i as f32));
    }
    let worst = (MAX_LINKS - 1) as f32;
    keep_cheapest(&mut kept, worst, link(100, worst));
    assert_eq!(
        kept.last().map(|(_, l)| l.vertex),
        Some(MAX_LINKS as u32 - 1)
    );
    keep_cheapest(&mut kept, worst - 0.5, link(101, worst - 0.5));
    assert_eq!(kept.last().map(|(_, l)| l.vertex), Some(101));
    assert_eq!(kept.len(), MAX_LINKS);
}
