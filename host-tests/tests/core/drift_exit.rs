//! A start inside (or within the clearance of) an obstacle or pop-up: the route begins with the
//! shortest exit of the documented family, checked against an f64 reference that marches
//! along each candidate in 1 cm steps; the rest of the route keeps the clearance; the work
//! stays within the bound.

use host_tests::reference::{dist, dist_point_segment, inside};
use host_tests::world::{query_to, work_at_phases, world, world_at, World};
use host_tests::{cases, Rng};
use skyroute::network::write::ObstacleSpec;
use skyroute::planner::{
    Exit, Goal, Phase, PlanError, Popup, Query, QueryField, Search, Violation, EXIT_MARGIN_M,
    EXIT_TURN_STEPS,
};
use skyroute::{DubinsPath, Planner, Pose, Vec2};

type TestPlanner<'n> = Planner<'n, 4096, 65536, 16, 1024>;

type P = (f64, f64);

/// A region in f64: a polygon or a disc.
enum Region {
    Polygon(Vec<P>),
    Disc(P, f64),
}

impl Region {
    fn from_spec(o: &ObstacleSpec) -> Region {
        match o {
            ObstacleSpec::Polygon(pts) => {
                Region::Polygon(pts.iter().map(|v| (v.x as f64, v.y as f64)).collect())
            }
            ObstacleSpec::Circle { centre, radius } => {
                Region::Disc((centre.x as f64, centre.y as f64), *radius as f64)
            }
        }
    }

    /// Distance from `p` to the region's area (0 inside).
    fn distance(&self, p: P) -> f64 {
        match self {
            Region::Polygon(poly) => {
                if inside(p, poly) {
                    return 0.0;
                }
                (0..poly.len())
                    .map(|i| dist_point_segment(p, poly[i], poly[(i + 1) % poly.len()]))
                    .fold(f64::INFINITY, f64::min)
            }
            Region::Disc(c, r) => (dist(p, *c) - r).max(0.0),
        }
    }
}

/// The exit the reference finds: the shortest candidate of the family (turn `kπ/32` either
/// way on radius `r`, then straight out of the regions containing the start, plus the
/// margin) whose sampled points keep more than `clearance + slack` from every other region.
/// A positive `slack` is strict, a negative one lenient: the core's exact answer lies
/// between the two.
fn reference_exit(start: Pose, r: f64, c: f64, regions: &[Region], slack: f64) -> Option<f64> {
    let s = (start.position.x as f64, start.position.y as f64);
    let h = start.heading as f64;
    let containing: Vec<bool> = regions.iter().map(|g| g.distance(s) <= c).collect();
    let in_union = |p: P| {
        regions
            .iter()
            .zip(&containing)
            .any(|(g, &cont)| cont && g.distance(p) <= c)
    };
    let clear_of_others = |p: P| {
        regions
            .iter()
            .zip(&containing)
            .all(|(g, &cont)| cont || g.distance(p) > c + slack)
    };
    // The exit's end is found in 1 cm steps; clearance from the other regions is sampled every
    // 5 cm, which can miss at most 2.5 cm of approach (distance is 1-Lipschitz): callers pass
    // a slack of at least that.
    let (step, clear_step) = (0.01, 0.05);
    let mut best: Option<f64> = None;
    for k in 0..=EXIT_TURN_STEPS {
        for sign in [1.0f64, -1.0] {
            if k == 0 && sign < 0.0 {
                continue;
            }
            let phi = k as f64 * std::f64::consts::PI / EXIT_TURN_STEPS as f64;
            // The arc about the turn centre.
            let centre = (s.0 - sign * r * h.sin(), s.1 + sign * r * h.cos());
            let at_angle = |a: f64| {
                let heading = h + sign * a;
                (
                    centre.0 + sign * r * heading.sin(),
                    centre.1 - sign * r * heading.cos(),
                )
            };
            let o = at_angle(phi);
            let u = ((h + sign * phi).cos(), (h + sign * phi).sin());
            let point = |t: f64| (o.0 + t * u.0, o.1 + t * u.1);
            let mut t = 0.0;
            while in_union(point(t)) && t < 1e5 {
                t += step;
            }
            let end = t + EXIT_MARGIN_M as f64;
            let length = r * phi + end;
            if best.is_some_and(|b| b <= length) {
                continue;
            }
            let arc_steps = (r * phi / clear_step).ceil() as usize;
            let arc_clear = (0..=arc_steps)
                .all(|i| clear_of_others(at_angle(phi * i as f64 / arc_steps.max(1) as f64)));
            let straight_steps = (end / clear_step).ceil() as usize;
            let straight_clear = (0..=straight_steps)
                .all(|i| clear_of_others(point(end * i as f64 / straight_steps as f64)));
            let end_free = regions.iter().all(|g| g.distance(point(end)) > c + slack);
            if arc_clear && straight_clear && end_free {
                best = Some(length);
            }
        }
    }
    best
}

/// A point within `c` of obstacle `o` (inside it, or in its clearance band).
fn point_in_keepout(rng: &mut Rng, o: &ObstacleSpec, c: f32) -> Vec2 {
    match o {
        ObstacleSpec::Polygon(pts) => {
            let (lo, hi) = pts.iter().fold(
                (Vec2::new(f32::MAX, f32::MAX), Vec2::new(f32::MIN, f32::MIN)),
                |(lo, hi), p| {
                    (
                        Vec2::new(lo.x.min(p.x), lo.y.min(p.y)),
                        Vec2::new(hi.x.max(p.x), hi.y.max(p.y)),
                    )
                },
            );
            Vec2::new(
                rng.range_f32(lo.x - 0.9 * c, hi.x + 0.9 * c),
                rng.range_f32(lo.y - 0.9 * c, hi.y + 0.9 * c),
            )
        }
        ObstacleSpec::Circle { centre, radius } => {
            let a = rng.range_f32(0.0, std::f32::consts::TAU);
            let d = rng.range_f32(0.0, radius + 0.9 * c);
            *centre + Vec2::from_angle(a) * d
        }
    }
}

/// Checks a planned route that began with `exit`: the first path starts at the start, is
/// the exit, and leaves every region; every later path keeps the clearance (sampled, f64).
fn check_route(p: &TestPlanner<'_>, w: &World, start: Pose, exit: &Exit) {
    let paths: &[DubinsPath] = p.route_paths();
    let first = paths[0];
    assert_eq!(first.start, start);
    assert!((first.length() - exit.length).abs() < 1e-3);
    let c = w.spec.clearance_m as f64;
    let regions: Vec<Region> = w.obstacles.iter().map(Region::from_spec).collect();
    // The exit keeps the clearance from every obstacle the start is not within the clearance
    // of (those it leaves, it may cross).
    let s = (start.position.x as f64, start.position.y as f64);
    let others: Vec<&Region> = regions
        .iter()
        .filter(|g| g.distance(s) > c + 0.05)
        .collect();
    assert!(
        path_clearance(&first, &others) > c - 0.05,
        "the exit {first:?} comes within the clearance of an obstacle it did not start in"
    );
    for path in &paths[1..] {
        let n = (path.length() / 0.5).ceil().max(1.0) as usize;
        for i in 0..=n {
            let q = path.sample(path.length() * i as f32 / n as f32).position;
            let q = (q.x as f64, q.y as f64);
            for g in &regions {
                assert!(
                    g.distance(q) > c - 0.05,
                    "route point {q:?} within the clearance"
                );
            }
        }
    }
}

/// The least distance from `path` (sampled every 5 cm) to any of `regions`, metres.
fn path_clearance(path: &DubinsPath, regions: &[&Region]) -> f64 {
    let n = (path.length() / 0.05).ceil().max(1.0) as usize;
    (0..=n)
        .map(|i| path.sample(path.length() * i as f32 / n as f32).position)
        .flat_map(|q| {
            regions
                .iter()
                .map(move |g| g.distance((q.x as f64, q.y as f64)))
        })
        .fold(f64::INFINITY, f64::min)
}

/// The area of every other world below lies in negative coordinates, where a box test that
/// scales a coordinate instead of shifting it by the clearance would narrow the box.
fn world_of_seed(seed: u64) -> World {
    let origin = match seed % 2 {
        0 => Vec2::new(0.0, 0.0),
        _ => Vec2::new(-2300.0, -1900.0),
    };
    world_at(seed, origin, 1500.0, 50.0, 40.0, 6)
}

#[test]
fn a_start_in_an_obstacle_leaves_by_the_shortest_exit_of_the_family() {
    let mut rng = Rng(0x5EED_0E1D);
    let (mut exits, mut refused) = (0, 0);
    for seed in 0..cases(4, 24) as u64 {
        let w = world_of_seed(300 + seed);
        let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
        p.load(&w.bytes).unwrap();
        let regions: Vec<Region> = w.obstacles.iter().map(Region::from_spec).collect();
        let c = w.spec.clearance_m;
        for _ in 0..20 {
            let o = rng.below(w.obstacles.len() as u64) as usize;
            let position = point_in_keepout(&mut rng, &w.obstacles[o], c);
            let pos64 = (position.x as f64, position.y as f64);
            if regions.iter().all(|g| g.distance(pos64) > c as f64) {
                continue; // the box corner outside the band
            }
            let start = Pose {
                position,
                heading: rng.range_f32(-3.1, 3.1),
            };
            let goal = host_tests::world::free_pose(&mut rng, &w, 10.0);
            let q = Query {
                start,
                goal: Goal {
                    position: goal.position,
                    heading: None,
                },
                search: Search::Dijkstra,
            };
            let strict = reference_exit(start, 40.0, c as f64, &regions, 0.03);
            let lenient = reference_exit(start, 40.0, c as f64, &regions, -0.03);
            match p.plan(&q, u64::MAX) {
                Ok(summary) => {
                    let exit = summary.exit.expect("the start lies in a keep-out region");
                    assert!(matches!(exit.violated, Violation::Obstacle(_)));
                    let lenient = lenient.expect("the reference finds an exit too");
                    assert!(exit.length as f64 >= lenient - 0.03, "{exit:?} < {lenient}");
                    if let Some(strict) = strict {
                        assert!(exit.length as f64 <= strict + 0.03, "{exit:?} > {strict}");
                    }
                    assert!(summary.work.total() <= p.worst_case_work());
                    check_route(&p, &w, start, &exit);
                    exits += 1;
                }
                Err(PlanError::InsideObstacle {
                    field: QueryField::Start,
                    ..
                }) => {
                    assert!(strict.is_none(), "the reference exits by {strict:?}");
                    refused += 1;
                }
                // After the exit the query goes on like any other.
                Err(
                    PlanError::StartUnconnected | PlanError::GoalUnconnected | PlanError::NoRoute,
                ) => {}
                Err(e) => panic!("{e:?}"),
            }
        }
    }
    assert!(exits >= 10, "{exits} exits, {refused} refusals");
}

#[test]
fn a_popup_over_the_aircraft_is_left_by_at_most_the_straight_ahead_exit() {
    let w = world(41, 1500.0, 50.0, 40.0, 6);
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let mut rng = Rng(77);
    let c = w.spec.clearance_m as f64;
    let mut exits = 0;
    for _ in 0..cases(20, 200) {
        let start = host_tests::world::free_pose(&mut rng, &w, 200.0);
        let goal = host_tests::world::free_pose(&mut rng, &w, 10.0);
        let radius = rng.range_f32(20.0, 80.0);
        let offset = Vec2::from_angle(rng.range_f32(0.0, std::f32::consts::TAU))
            * rng.range_f32(0.0, radius);
        let centre = start.position + offset;
        let id = p.add_popup(Popup::Circle { centre, radius }).unwrap().id;
        let q = Query {
            start,
            goal: Goal {
                position: goal.position,
                heading: None,
            },
            search: Search::Dijkstra,
        };
        if let Ok(summary) = p.plan(&q, u64::MAX) {
            let exit = summary.exit.expect("the start lies in the pop-up");
            assert_eq!(exit.violated, Violation::Popup(id));
            // Straight ahead leaves the disc widened by the clearance where
            // |s + t·u − centre| = radius + c (the larger root).
            let (s, m) = (start.position, centre);
            let u = Vec2::from_angle(start.heading);
            let w0 = ((s.x - m.x) as f64, (s.y - m.y) as f64);
            let b = w0.0 * u.x as f64 + w0.1 * u.y as f64;
            let k = w0.0 * w0.0 + w0.1 * w0.1 - (radius as f64 + c).powi(2);
            let straight = -b + (b * b - k).sqrt() + EXIT_MARGIN_M as f64;
            assert!(
                exit.length as f64 <= straight + 0.01,
                "{exit:?} > {straight}"
            );
            assert!(exit.length as f64 >= (radius as f64 + c) - offset.norm() as f64);
            exits += 1;
        }
        p.remove_popup(id).unwrap();
    }
    assert!(exits >= cases(20, 200) / 2, "{exits} exits");
}

/// A pop-up over the aircraft with a second one beside the end of its straight-ahead exit:
/// the straight exit would end within the clearance of the second, so the exit turns away,
/// and keeps the clearance from it (sampled in f64).
#[test]
fn an_exit_that_would_end_near_another_popup_turns_away_from_it() {
    let w = world(41, 1500.0, 50.0, 40.0, 6);
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let c = w.spec.clearance_m;
    let mut rng = Rng(0xE417);
    let mut turned = 0;
    for _ in 0..cases(10, 60) {
        let start = host_tests::world::free_pose(&mut rng, &w, 200.0);
        let ahead = Vec2::from_angle(start.heading);
        // The straight exit from the first disc ends at E, 8 + c + 1 m ahead. The second
        // disc lies to the left of E with its clearance reaching 1 m past E, and √((9 + c)² +
        // (7 + c)²) m from the start, outside its clearance: exits that turn right stay clear.
        let left = Vec2::new(-ahead.y, ahead.x);
        let end = start.position + ahead * (8.0 + c + EXIT_MARGIN_M);
        let first = (start.position, 8.0);
        let second = (end + left * (8.0 + c - 1.0), 8.0);
        let ids: Vec<u8> = [first, second]
            .iter()
            .map(|&(centre, radius)| p.add_popup(Popup::Circle { centre, radius }).unwrap().id)
            .collect();
        let goal = host_tests::world::free_pose(&mut rng, &w, 10.0);
        match p.plan(&query_to(start, goal.position), u64::MAX) {
            Ok(summary) => {
                let exit = summary.exit.expect("the start lies in the first pop-up");
                assert_eq!((exit.violated, exit.regions), (Violation::Popup(ids[0]), 1));
                let other = Region::Disc((second.0.x as f64, second.0.y as f64), second.1 as f64);
                let path = p.route_paths()[0];
                assert!(
                    path_clearance(&path, &[&other]) > c as f64 - 0.05,
                    "{path:?}"
                );
                assert!(exit.length > 8.0 + c + EXIT_MARGIN_M, "{exit:?}");
                turned += 1;
            }
            Err(PlanError::StartUnconnected | PlanError::GoalUnconnected | PlanError::NoRoute) => {}
            Err(e) => panic!("{e:?}"),
        }
        for id in ids {
            p.remove_popup(id).unwrap();
        }
    }
    assert!(turned >= cases(10, 60) / 2, "{turned} exits");
}

/// The same beside each disc obstacle of the network, from 16 headings: a pop-up over the
/// aircraft is placed so that its straight-ahead exit would pass 1 m within the obstacle's
/// clearance at its middle, with the obstacle to its left, and end outside it (so that only
/// the check of the exit's line, not of its end, refuses it). A refusal, when no exit of the
/// family keeps the clearance, is allowed; an exit that does not keep it is not. In a world
/// at positive coordinates and in one at negative coordinates.
#[test]
fn an_exit_that_would_pass_near_an_obstacle_turns_away_from_it() {
    exits_pass_clear_of_obstacles(&world(41, 1500.0, 50.0, 40.0, 6));
    exits_pass_clear_of_obstacles(&world_of_seed(41));
}

fn exits_pass_clear_of_obstacles(w: &World) {
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let c = w.spec.clearance_m;
    // The pop-up's radius: its straight exit, RHO + c + 1 m long, ends outside the clearance
    // of an obstacle of radius up to 90 m beside its middle, and the exits that turn away on
    // the 40 m turn radius keep the clearance.
    const RHO: f32 = 39.0;
    let regions: Vec<Region> = w.obstacles.iter().map(Region::from_spec).collect();
    let mut rng = Rng(0x0B57);
    let (mut tried, mut turned) = (0, 0);
    for (i, o) in w.obstacles.iter().enumerate() {
        let ObstacleSpec::Circle { centre, radius } = *o else {
            continue;
        };
        for k in 0..16 {
            let heading = k as f32 * std::f32::consts::TAU / 16.0;
            let ahead = Vec2::from_angle(heading);
            let left = Vec2::new(-ahead.y, ahead.x);
            let start =
                centre - left * (radius + c - 1.0) - ahead * (0.5 * (RHO + c + EXIT_MARGIN_M));
            let s = (start.x as f64, start.y as f64);
            let clear_of_others = regions
                .iter()
                .enumerate()
                .all(|(j, g)| j == i || g.distance(s) > (RHO + 2.0 * c) as f64);
            if !clear_of_others || regions[i].distance(s) <= c as f64 + 0.05 {
                continue;
            }
            let id = p
                .add_popup(Popup::Circle {
                    centre: start,
                    radius: RHO,
                })
                .unwrap()
                .id;
            let goal = host_tests::world::free_pose(&mut rng, w, 10.0);
            let start = Pose {
                position: start,
                heading,
            };
            tried += 1;
            match p.plan(&query_to(start, goal.position), u64::MAX) {
                Ok(summary) => {
                    let exit = summary.exit.expect("the start lies in the pop-up");
                    assert_eq!((exit.violated, exit.regions), (Violation::Popup(id), 1));
                    let path = p.route_paths()[0];
                    assert!(
                        path_clearance(&path, &[&regions[i]]) > c as f64 - 0.05,
                        "obstacle {i}, heading {heading}: {path:?}"
                    );
                    turned += 1;
                }
                // No exit of the family keeps the clearance, or none connects after it.
                Err(
                    PlanError::InsidePopup { .. }
                    | PlanError::StartUnconnected
                    | PlanError::GoalUnconnected
                    | PlanError::NoRoute,
                ) => {}
                Err(e) => panic!("{e:?}"),
            }
            p.remove_popup(id).unwrap();
        }
    }
    assert!(
        turned >= 8 && turned >= tried / 2,
        "{turned} exits of {tried}"
    );
}

/// A U-shaped pop-up over the aircraft, which sits in one arm heading across the gap toward
/// the other: the exit's straight leaves the arm, and the union of the regions it is in ends
/// there, so the exit ends in the gap (1 m past the arm's clearance), not past the far arm.
/// The gap is wide enough for the aircraft to turn up it and out, so that the query goes on
/// to a route.
/// Checked against the f64 reference, which marches along the line until it first leaves the
/// regions, in 16 orientations.
#[test]
fn a_concave_popup_is_left_at_the_first_gap_on_the_exit_line() {
    let w = world(41, 1500.0, 50.0, 40.0, 6);
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let c = w.spec.clearance_m;
    // Arms 20 m wide and 180 m tall, 150 m apart, joined at the bottom; the start in the left
    // arm, 130 m up, heading across the gap: the straight reaches the arm's side 10 m ahead,
    // its clearance c further, and the gap is 150 − 2c m wide.
    let u_shape = [
        (0.0, 0.0),
        (190.0, 0.0),
        (190.0, 200.0),
        (170.0, 200.0),
        (170.0, 20.0),
        (20.0, 20.0),
        (20.0, 200.0),
        (0.0, 200.0),
    ];
    let mut rng = Rng(0x0C0C);
    let mut regions: Vec<Region> = w.obstacles.iter().map(Region::from_spec).collect();
    let mut exits = 0;
    for k in 0..16 {
        let at = host_tests::world::free_pose(&mut rng, &w, 320.0).position;
        let heading = k as f32 * std::f32::consts::TAU / 16.0;
        // Local (x across the arms, y along them) to world: rotated by `heading`, the start at `at`.
        let (cos, sin) = (heading.cos(), heading.sin());
        let place = |(x, y): (f32, f32)| {
            let (x, y) = (x - 10.0, y - 130.0);
            at + Vec2::new(x * cos - y * sin, x * sin + y * cos)
        };
        let points: Vec<Vec2> = u_shape.iter().map(|&v| place(v)).collect();
        let id = p
            .add_popup(Popup::Polygon(points.iter().copied().collect()))
            .unwrap()
            .id;
        regions.push(Region::Polygon(
            points.iter().map(|v| (v.x as f64, v.y as f64)).collect(),
        ));
        let start = Pose {
            position: at,
            heading,
        };
        let goal = host_tests::world::free_pose(&mut rng, &w, 10.0);
        let strict = reference_exit(start, 40.0, c as f64, &regions, 0.03);
        let lenient = reference_exit(start, 40.0, c as f64, &regions, -0.03)
            .expect("the straight exit into the gap");
        // The straight exit ends in the gap: 10 m to the arm's side, then c, then the margin.
        assert!(
            (lenient - (10.0 + c + EXIT_MARGIN_M) as f64).abs() < 0.05,
            "{lenient}"
        );
        match p.plan(&query_to(start, goal.position), u64::MAX) {
            Ok(summary) => {
                let exit = summary.exit.expect("the start lies in the pop-up");
                assert_eq!((exit.violated, exit.regions), (Violation::Popup(id), 1));
                assert!(exit.length as f64 >= lenient - 0.03, "{exit:?} < {lenient}");
                if let Some(strict) = strict {
                    assert!(exit.length as f64 <= strict + 0.03, "{exit:?} > {strict}");
                }
                exits += 1;
            }
            Err(PlanError::StartUnconnected | PlanError::GoalUnconnected | PlanError::NoRoute) => {}
            Err(e) => panic!("heading {heading}: {e:?}"),
        }
        regions.pop();
        p.remove_popup(id).unwrap();
    }
    assert!(exits >= 8, "{exits} exits");
}

#[test]
fn a_start_in_more_regions_than_the_limit_is_refused_naming_the_first() {
    let w = world(41, 1500.0, 50.0, 40.0, 6);
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let mut rng = Rng(5);
    let start = host_tests::world::free_pose(&mut rng, &w, 200.0);
    let mut ids = Vec::new();
    for i in 0..=skyroute::planner::MAX_EXIT_REGIONS {
        let centre = start.position + Vec2::new(i as f32, 0.0);
        ids.push(
            p.add_popup(Popup::Circle {
                centre,
                radius: 30.0,
            })
            .unwrap()
            .id,
        );
    }
    let q = Query {
        start,
        goal: Goal {
            position: start.position + Vec2::new(500.0, 0.0),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    assert_eq!(
        p.plan(&q, u64::MAX),
        Err(PlanError::InsidePopup {
            field: QueryField::Start,
            popup: ids[0]
        })
    );
    // One fewer is left by an exit.
    p.remove_popup(ids[skyroute::planner::MAX_EXIT_REGIONS])
        .unwrap();
    let exit = p.plan(&q, u64::MAX).map(|s| s.exit);
    assert!(matches!(exit, Ok(Some(e)) if e.regions == 4), "{exit:?}");
}

/// Whether `p` lies in the box `lo..hi` widened by `w`, and whether it lies within 1 cm of
/// one of its sides (where f32 rounding could decide either way).
fn in_widened_box(p: Vec2, (lo, hi): (P, P), w: f64) -> (bool, bool) {
    let (x, y) = (p.x as f64, p.y as f64);
    let sides = [lo.0 - w, lo.1 - w, hi.0 + w, hi.1 + w];
    let near = [x, y, x, y]
        .iter()
        .zip(sides)
        .any(|(v, s)| (v - s).abs() < 0.01);
    let inside = x >= sides[0] && y >= sides[1] && x <= sides[2] && y <= sides[3];
    (inside, near)
}

/// A region's bounding box and the exact tests the exit counts for a point within the
/// clearance of that box: a polygon's n edges and its inside, n + 1; a disc's one.
fn box_and_exact_tests(o: &ObstacleSpec) -> ((P, P), u64) {
    match o {
        ObstacleSpec::Polygon(pts) => {
            let xs = pts.iter().map(|v| v.x as f64);
            let ys = pts.iter().map(|v| v.y as f64);
            let lo = (
                xs.clone().fold(f64::MAX, f64::min),
                ys.clone().fold(f64::MAX, f64::min),
            );
            let hi = (xs.fold(f64::MIN, f64::max), ys.fold(f64::MIN, f64::max));
            ((lo, hi), pts.len() as u64 + 1)
        }
        ObstacleSpec::Circle { centre, radius } => {
            let (x, y, r) = (centre.x as f64, centre.y as f64, *radius as f64);
            (((x - r, y - r), (x + r, y + r)), 1)
        }
    }
}

/// The work of the checks before the connections, counted exactly. With a start and goal
/// outside every obstacle and pop-up and its clearance, the `CheckFree` phase counts:
///
/// * for the goal's free-space check, a box test per obstacle, a containment test per
///   obstacle whose box holds the goal, and one per pop-up;
/// * for the regions the start lies in, a box test per obstacle widened by the clearance, the
///   exact tests of each obstacle whose widened box holds the start (n + 1 for a polygon of
///   n vertices, 1 for a disc), and each pop-up's exact tests (n + 1, or 1).
///
/// Random starts and goals near the obstacles, then starts exactly on a side of a widened box
/// and goals exactly on a corner of a disc's box: a box holds the points on its sides.
#[test]
fn the_checks_before_the_connections_count_each_box_and_exact_test() {
    let w = world(41, 1500.0, 50.0, 40.0, 6);
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    let triangle: Vec<Vec2> = [(100.0, 100.0), (160.0, 110.0), (120.0, 170.0)]
        .iter()
        .map(|&(x, y)| Vec2::new(x, y))
        .collect();
    let popups = [
        Popup::Circle {
            centre: Vec2::new(1400.0, 1400.0),
            radius: 30.0,
        },
        Popup::Polygon(triangle.iter().copied().collect()),
    ];
    for popup in &popups {
        p.add_popup(popup.clone()).unwrap();
    }
    let popup_regions = [
        Region::Disc((1400.0, 1400.0), 30.0),
        Region::Polygon(triangle.iter().map(|v| (v.x as f64, v.y as f64)).collect()),
    ];
    let popup_tests: u64 = 1 + (triangle.len() as u64 + 1);
    let c = w.spec.clearance_m as f64;
    let obstacles: Vec<((P, P), u64)> = w.obstacles.iter().map(box_and_exact_tests).collect();
    let regions: Vec<Region> = w.obstacles.iter().map(Region::from_spec).collect();
    let free = |q: Vec2| {
        let q = (q.x as f64, q.y as f64);
        regions
            .iter()
            .chain(&popup_regions)
            .all(|g| g.distance(q) > c + 0.05)
    };
    let mut rng = Rng(0xC0DE);
    let (mut checked, mut start_in_box, mut goal_in_box) = (0, 0, 0);
    while checked < cases(60, 400) {
        // Points near a random obstacle, so that they often lie in its (widened) box.
        let near = |rng: &mut Rng, widen: f64| {
            let ((lo, hi), _) = obstacles[rng.below(obstacles.len() as u64) as usize];
            let (x0, y0) = (lo.0 - widen, lo.1 - widen);
            let (x1, y1) = (hi.0 + widen, hi.1 + widen);
            Vec2::new(
                rng.range_f32(x0 as f32, x1 as f32),
                rng.range_f32(y0 as f32, y1 as f32),
            )
        };
        let (s, g) = (near(&mut rng, 2.0 * c), near(&mut rng, c));
        if !free(s) || !free(g) {
            continue;
        }
        let mut expected = popup_tests + popups.len() as u64;
        let mut ambiguous = false;
        for &(bounds, exact) in &obstacles {
            let (goal_in, goal_near) = in_widened_box(g, bounds, 0.0);
            let (start_in, start_near) = in_widened_box(s, bounds, c);
            ambiguous |= goal_near || start_near;
            expected += 2 + goal_in as u64 + start_in as u64 * exact;
            goal_in_box += goal_in as usize;
            start_in_box += start_in as usize;
        }
        if ambiguous {
            continue;
        }
        let heading = rng.range_f32(-3.1, 3.1);
        assert_eq!(
            checks_work(&mut p, s, heading, g),
            expected,
            "{s:?} to {g:?}"
        );
        checked += 1;
    }
    assert!(start_in_box >= checked / 4 && goal_in_box >= checked / 4);

    // Starts exactly on a side of an obstacle's box widened by the clearance (in f32, as the
    // box is stored and widened), half the clearance past the next side: √1.25 clearances
    // from the box's corner, so outside every clearance, yet in the widened box, whose sides
    // belong to it: the obstacle's exact tests are counted.
    let goal = Vec2::new(1000.0, 1000.0);
    let c32 = w.spec.clearance_m;
    let h = 0.5 * c32;
    let mut on_sides = 0;
    for (o, &(_, exact)) in w.obstacles.iter().zip(&obstacles) {
        let (lo, hi) = o.bounding_box();
        for s in [
            Vec2::new(lo.x - c32, lo.y - h),
            Vec2::new(lo.x - h, lo.y - c32),
            Vec2::new(hi.x + c32, hi.y + h),
            Vec2::new(hi.x + h, hi.y + c32),
        ] {
            if !free(s) {
                continue; // near another obstacle
            }
            let mut expected = popup_tests + popups.len() as u64;
            for (other, &(_, exact_other)) in w.obstacles.iter().zip(&obstacles) {
                let (lo, hi) = other.bounding_box();
                let in_goal_box =
                    goal.x >= lo.x && goal.y >= lo.y && goal.x <= hi.x && goal.y <= hi.y;
                let in_start_box = s.x >= lo.x - c32
                    && s.y >= lo.y - c32
                    && s.x <= hi.x + c32
                    && s.y <= hi.y + c32;
                expected += 2 + in_goal_box as u64 + in_start_box as u64 * exact_other;
            }
            assert!(expected >= popup_tests + popups.len() as u64 + exact);
            assert_eq!(
                checks_work(&mut p, s, 0.0, goal),
                expected,
                "{s:?} on {o:?}"
            );
            on_sides += 1;
        }
    }
    assert!(
        free(goal) && on_sides >= 12,
        "{on_sides} starts on a box side"
    );

    // Goals on the corners of a disc's box: outside the disc, in its box (whose sides belong
    // to it), so the goal's containment test is counted. The start is the free point above.
    let start = goal;
    let mut on_corners = 0;
    for o in &w.obstacles {
        let ObstacleSpec::Circle { .. } = o else {
            continue;
        };
        let (lo, hi) = o.bounding_box();
        for g in [lo, hi] {
            let mut expected = popup_tests + popups.len() as u64;
            for (other, &(_, exact)) in w.obstacles.iter().zip(&obstacles) {
                let (lo, hi) = other.bounding_box();
                let in_goal_box = g.x >= lo.x && g.y >= lo.y && g.x <= hi.x && g.y <= hi.y;
                let in_start_box = start.x >= lo.x - c32
                    && start.y >= lo.y - c32
                    && start.x <= hi.x + c32
                    && start.y <= hi.y + c32;
                expected += 2 + in_goal_box as u64 + in_start_box as u64 * exact;
            }
            assert_eq!(
                checks_work(&mut p, start, 0.0, g),
                expected,
                "goal {g:?} on {o:?}"
            );
            on_corners += 1;
        }
    }
    assert!(on_corners >= 2);
}

/// The collision tests a roadmap query from `start` (heading `heading`) to `goal` counts from
/// the start of its [`Phase::CheckFree`] to the start of its [`Phase::ConnectStart`].
pub(crate) fn checks_work<const VN: usize, const EN: usize, const PN: usize, const RN: usize>(
    p: &mut Planner<'_, VN, EN, PN, RN>,
    start: Vec2,
    heading: f32,
    goal: Vec2,
) -> u64 {
    let q = query_to(
        Pose {
            position: start,
            heading,
        },
        goal,
    );
    let phases = [Phase::CheckFree, Phase::ConnectStart];
    let [before, after] = work_at_phases(p, &q, phases, |work| work.collision_tests);
    after - before
}
