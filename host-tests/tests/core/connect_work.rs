//! The collision tests and Dubins solves of the start and goal links, counted exactly.
//!
//! A path's check costs, for each of its primitives in order, a box test per obstacle, and for
//! each obstacle whose box the primitive's box, widened by the clearance, overlaps, its exact
//! tests (n + 1 for a polygon of n vertices, 1 for a disc), until one conflicts; then each
//! pop-up's tests, as the pop-up counts them ([`Popup::conflicts`]). The boxes and the overlap
//! are recomputed here in f64 from the stored boxes; whether a primitive conflicts is the
//! ground tool's predicate (it decides only where the count stops).
//!
//! Each end reads its obstacle window first (one box distance per obstacle), then tries its
//! candidates, nearest first, until 8 links are made. A start candidate costs one Dubins solve
//! and its path's check. A goal candidate with free arrival headings first probes the heading
//! nearest the bearing to the goal (one solve and a check); if that path is blocked, it solves
//! every heading (one each) and checks them shortest first, ties in heading order, each pick
//! counting one solve more, until one is clear. A goal with its own heading has no probe: one
//! solve, one more for the pick, and the check.

use host_tests::world::{free_pose, nearest_vertices, work_at_phases, world, World};
use host_tests::{cases, Rng};
use skyroute::geometry::wrap_to_tau;
use skyroute::network::write::ObstacleSpec;
use skyroute::planner::{Phase, PlannerConfig, Popup};
use skyroute::{DubinsPath, Planner, Pose, Vec2};

pub type TestPlanner<'n> = Planner<'n, 4096, 65536, 4, 1024>;

/// Whether boxes `a` (widened by `c`) and `b` overlap, in f64, and whether a side lies within
/// 1 mm of deciding the other way (where f32 rounding could).
fn overlap(a: (Vec2, Vec2), b: (Vec2, Vec2), c: f64) -> (bool, bool) {
    let f = |v: f32| v as f64;
    // `apart` in the core's order: each side's gap, positive when apart.
    let gaps = [
        f(a.0.x) - c - f(b.1.x),
        f(b.0.x) - (f(a.1.x) + c),
        f(a.0.y) - c - f(b.1.y),
        f(b.0.y) - (f(a.1.y) + c),
    ];
    let apart = gaps.iter().any(|&g| g > 0.0);
    let near = gaps.iter().any(|&g| g.abs() < 1e-3);
    (!apart, near)
}

/// The exact tests an obstacle costs one primitive.
fn exact_tests(o: &ObstacleSpec) -> u64 {
    match o {
        ObstacleSpec::Polygon(pts) => pts.len() as u64 + 1,
        ObstacleSpec::Circle { .. } => 1,
    }
}

/// The obstacles and the pop-up a path is checked against, with what it counted.
pub struct Checks<'a> {
    pub obstacles: &'a [ObstacleSpec],
    pub boxes: Vec<(Vec2, Vec2)>,
    pub popup: Popup,
    pub clearance: f32,
    pub exact_counted: u64,
    pub blocked: u64,
}

impl Checks<'_> {
    /// The collision tests checking `path` counts, and whether it is clear; `None` when a box
    /// comparison lies within 1 mm of going the other way.
    pub fn path(&mut self, path: &DubinsPath) -> Option<(u64, bool)> {
        let c = self.clearance;
        let mut tests = 0;
        for prim in path.primitives().into_iter().flatten() {
            let bbox = prim.bounding_box();
            for (o, &obox) in self.obstacles.iter().zip(&self.boxes) {
                tests += 1;
                let (overlaps, ambiguous) = overlap(bbox, obox, c as f64);
                if ambiguous {
                    return None;
                }
                if overlaps {
                    tests += exact_tests(o);
                    self.exact_counted += 1;
                    if skyroute_prep::roadmap::primitive_conflicts(&prim, o, c) {
                        self.blocked += 1;
                        return Some((tests, false));
                    }
                }
            }
            let (conflict, popup_tests) = self.popup.conflicts(&prim, c);
            tests += popup_tests as u64;
            if conflict {
                self.blocked += 1;
                return Some((tests, false));
            }
        }
        Some((tests, true))
    }
}

/// A planner on `w` with the tests' connect radius and a disc pop-up of `radius` at a random
/// place clear of the obstacles, the checks that model it, and the pop-up's centre.
pub fn planner_with_popup<'w>(
    w: &'w World,
    rng: &mut Rng,
    radius: f32,
) -> (Box<TestPlanner<'w>>, Checks<'w>, Vec2) {
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(&w.bytes).unwrap();
    p.set_config(PlannerConfig {
        connect_radius_m: RADIUS,
        ..PlannerConfig::DEFAULT
    });
    assert_eq!(p.config().free_goal_headings, HEADINGS);
    let centre = free_pose(rng, w, 80.0).position;
    let popup = Popup::Circle { centre, radius };
    p.add_popup(popup.clone()).unwrap();
    let net = *p.network();
    let checks = Checks {
        obstacles: &w.obstacles,
        boxes: (0..net.obstacle_count())
            .map(|i| net.obstacle(i).unwrap().1)
            .collect(),
        popup,
        clearance: net.clearance(),
        exact_counted: 0,
        blocked: 0,
    };
    (p, checks, centre)
}

/// (collision tests, Dubins solves).
pub type Counts = (u64, u64);

/// A goal link as the search sees it: its vertex, its cost (for a pending link, the lower bound
/// of its length) and, if pending, what resolving it counts and costs.
#[derive(Clone, Copy, Debug)]
pub struct GoalLink {
    pub vertex: u32,
    pub cost: f32,
    /// A pending link's resolution: its (collision tests, Dubins solves) and exact cost.
    pub resolution: Option<(Counts, f32)>,
}

/// The (collision tests, Dubins solves) of the start's connection and its links (vertex, cost)
/// in the order they were made; `None` if ambiguous.
pub fn start_links(
    p: &TestPlanner<'_>,
    checks: &mut Checks<'_>,
    start: Pose,
) -> Option<(Counts, Vec<(u32, f32)>)> {
    let mut counted = (checks.obstacles.len() as u64, 0); // the window
    let mut links = Vec::new();
    for v in nearest_vertices(p.network(), start.position, RADIUS) {
        if links.len() == 8 {
            break;
        }
        counted.1 += 1;
        let Some(path) = DubinsPath::shortest(&start, &p.network().vertex(v).unwrap(), 40.0) else {
            continue;
        };
        let (tests, clear) = checks.path(&path)?;
        counted.0 += tests;
        if clear {
            links.push((v, path.length()));
        }
    }
    Some((counted, links))
}

/// The goal's pose at free arrival heading `k` of [`HEADINGS`], or at its own `heading`.
fn goal_pose(goal: Vec2, heading: Option<f32>, k: u16) -> Pose {
    Pose {
        position: goal,
        heading: heading.unwrap_or(k as f32 * std::f32::consts::TAU / HEADINGS as f32),
    }
}

/// The shortest clear path from `from` to the goal over its arrival headings: every heading
/// solved, then checked shortest first (ties: heading order), each pick one solve more. Its
/// (collision tests, Dubins solves) and length, if any is clear; `None` if ambiguous.
pub fn clear_over_headings(
    checks: &mut Checks<'_>,
    from: &Pose,
    goal: Vec2,
    heading: Option<f32>,
) -> Option<(Counts, Option<f32>)> {
    let headings = if heading.is_some() { 1 } else { HEADINGS };
    let mut counted = (0, headings as u64);
    let mut paths: Vec<(f32, u16, DubinsPath)> = (0..headings)
        .filter_map(|k| {
            DubinsPath::shortest(from, &goal_pose(goal, heading, k), 40.0)
                .map(|p| (p.length(), k, p))
        })
        .collect();
    paths.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    for (length, _, path) in paths {
        counted.1 += 1;
        let (tests, clear) = checks.path(&path)?;
        counted.0 += tests;
        if clear {
            return Some((counted, Some(length)));
        }
    }
    Some((counted, None))
}

/// The (collision tests, Dubins solves) of the goal's connection, at `heading` or, if it is
/// `None`, over `HEADINGS` free arrival headings, and its links in the order they were made;
/// `None` if ambiguous.
pub fn goal_links(
    p: &TestPlanner<'_>,
    checks: &mut Checks<'_>,
    goal: Vec2,
    heading: Option<f32>,
) -> Option<(Counts, Vec<GoalLink>)> {
    use std::f32::consts::TAU;
    let mut counted = (checks.obstacles.len() as u64, 0); // the window
    let mut links = Vec::new();
    for v in nearest_vertices(p.network(), goal, RADIUS) {
        if links.len() == 8 {
            break;
        }
        let from = p.network().vertex(v).unwrap();
        // The probe: the heading nearest the bearing from the vertex to the goal. A clear probe
        // makes the link pending, at the lower bound of its length.
        if heading.is_none() {
            let bearing = wrap_to_tau((goal - from.position).angle());
            let k = (bearing / (TAU / HEADINGS as f32) + 0.5) as u16 % HEADINGS;
            counted.1 += 1;
            if let Some(path) = DubinsPath::shortest(&from, &goal_pose(goal, None, k), 40.0) {
                let (tests, clear) = checks.path(&path)?;
                counted.0 += tests;
                if clear {
                    let (resolved, length) = clear_over_headings(checks, &from, goal, None)?;
                    links.push(GoalLink {
                        vertex: v,
                        cost: DubinsPath::length_lower_bound(from.position, goal, 40.0),
                        resolution: Some((resolved, length?)),
                    });
                    continue;
                }
            }
        }
        let ((tests, solves), length) = clear_over_headings(checks, &from, goal, heading)?;
        counted = (counted.0 + tests, counted.1 + solves);
        if let Some(cost) = length {
            links.push(GoalLink {
                vertex: v,
                cost,
                resolution: None,
            });
        }
    }
    Some((counted, links))
}

/// The connect radius of the tests.
pub const RADIUS: f32 = 400.0;
/// The free arrival headings of a goal ([`PlannerConfig::DEFAULT`]'s).
pub const HEADINGS: u16 = 36;

#[test]
fn each_link_counts_its_box_and_exact_tests_per_primitive_and_its_solves() {
    let mut rng = Rng(0x11AC);
    let mut checked = 0;
    let (mut exact_counted, mut blocked) = (0, 0);
    for seed in 0..cases(3, 12) as u64 {
        let w = world(90 + seed, 1200.0, 60.0, 40.0, 12);
        let (mut p, mut checks, centre) = planner_with_popup(&w, &mut rng, 60.0);
        let net = *p.network();
        for _ in 0..cases(20, 60) {
            let start: Pose = free_pose(&mut rng, &w, 10.0);
            let goal_pose = free_pose(&mut rng, &w, 10.0);
            let goal = goal_pose.position;
            // Every other goal with its own heading.
            let heading = (checked % 2 == 1).then_some(goal_pose.heading);
            let clear_of_popup = |q: Vec2| q.distance(centre) > 60.0 + net.clearance() + 1.0;
            if !clear_of_popup(start.position) || !clear_of_popup(goal) {
                continue;
            }
            let (Some((start_counts, _)), Some((goal_counts, _))) = (
                start_links(&p, &mut checks, start),
                goal_links(&p, &mut checks, goal, heading),
            ) else {
                continue;
            };
            let mut query = host_tests::world::query_to(start, goal);
            query.goal.heading = heading;
            let phases = [
                Phase::ConnectStart,
                Phase::ConnectGoal,
                Phase::ConnectDirect,
            ];
            let [a, b, c] = work_at_phases(&mut p, &query, phases, |work| {
                (work.collision_tests, work.dubins_solves)
            });
            assert_eq!(
                ((b.0 - a.0, b.1 - a.1), (c.0 - b.0, c.1 - b.1)),
                (start_counts, goal_counts),
                "{start:?} to {goal:?}"
            );
            checked += 1;
        }
        exact_counted += checks.exact_counted;
        blocked += checks.blocked;
    }
    assert!(
        checked >= cases(3, 12) * 15 && exact_counted >= 50 && blocked >= 5,
        "{checked} queries, {exact_counted} exact checks, {blocked} blocked paths"
    );
}
