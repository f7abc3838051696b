//! The greedy shortcut pass and heading smoothing against a second implementation of their
//! documented definitions, on routes of sampled junctions among sampled discs: the same
//! paths, the same number of changes, the same Dubins solves, the route's primitive capacity
//! `R` respected, and the budget's verdict. The second implementation judges a path clear with
//! the exact predicate the documentation names (`conflicts_with_circle` at the clearance).

extern crate std;
use crate::geometry::predicates::conflicts_with_circle;
use crate::geometry::vertical::{VerticalLimits, VerticalProfile};
use crate::geometry::{wrap_to_pi, DubinsPath, Pose, Vec2};
use crate::network::write::{
    encode, encode_three_dimensional, NetworkSpec, ObstacleSpec, VerticalSpec,
};
use crate::planner::state::ModeState;
use crate::planner::{PlanError, Planner};
use crate::test_rng::Rng;
use core::f32::consts::PI;
use std::vec;
use std::vec::Vec;

const RADIUS: f32 = 30.0;
const CLEARANCE: f32 = 5.0;

/// A roadmap whose four vertices mark the corners of the test area, with `discs`.
fn roadmap_spec(discs: &[(Vec2, f32)]) -> NetworkSpec {
    NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: RADIUS,
        clearance_m: CLEARANCE,
        vertices: [
            (-300.0, -400.0),
            (900.0, -400.0),
            (-300.0, 400.0),
            (900.0, 400.0),
        ]
        .iter()
        .map(|&(x, y)| Pose::new(x, y, 0.0))
        .collect(),
        edges: Vec::new(),
        obstacles: discs
            .iter()
            .map(|&(centre, radius)| ObstacleSpec::Circle { centre, radius })
            .collect(),
        grid_cell_m: 100.0,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    }
}

fn network(discs: &[(Vec2, f32)]) -> Vec<u8> {
    encode(&roadmap_spec(discs)).expect("a valid roadmap")
}

fn pieces(p: &DubinsPath) -> usize {
    p.primitives().iter().flatten().count()
}

/// Whether every primitive of `path` keeps the clearance from every disc.
fn clear(path: &DubinsPath, discs: &[(Vec2, f32)]) -> bool {
    path.primitives().iter().flatten().all(|p| {
        discs
            .iter()
            .all(|&(c, r)| !conflicts_with_circle(p, c, r, CLEARANCE))
    })
}

/// The shortest Dubins path if clear.
fn solve(from: &Pose, to: &Pose, discs: &[(Vec2, f32)]) -> Option<DubinsPath> {
    DubinsPath::shortest(from, to, RADIUS).filter(|p| clear(p, discs))
}

/// What a pass did: the paths after it, the changes, the Dubins solves, whether it ran out of
/// a budget of `budget` solves (checked after each junction or candidate, as documented), and
/// how many changes added primitives (counted by the second implementation only; 0 for the
/// planner's outcome).
#[derive(Debug, PartialEq)]
struct Outcome {
    paths: Vec<DubinsPath>,
    changes: u32,
    solves: u64,
    exhausted: bool,
    grown: u32,
}

/// The greedy pass as `shortcut` documents it: at each junction `i` between paths `i − 1` and
/// `i`, the previous junction joined to the next directly when that path is clear, shorter
/// than the two it replaces, and leaves the route within `capacity` primitives; the junction
/// is then dropped and the same `i` tried again.
fn greedy(paths: &[DubinsPath], discs: &[(Vec2, f32)], capacity: usize, budget: u64) -> Outcome {
    let mut paths = paths.to_vec();
    let (mut changes, mut solves, mut grown) = (0, 0, 0);
    let mut i = 1;
    while i < paths.len() {
        let (a, b) = (paths[i - 1], paths[i]);
        solves += 1;
        let count: usize = paths.iter().map(pieces).sum();
        match solve(&a.start, &b.end(), discs) {
            Some(j)
                if j.length() < a.length() + b.length()
                    && count - pieces(&a) - pieces(&b) + pieces(&j) <= capacity =>
            {
                grown += u32::from(pieces(&j) > pieces(&a) + pieces(&b));
                paths[i - 1] = j;
                paths.remove(i);
                changes += 1;
            }
            _ => i += 1,
        }
        if solves > budget {
            break;
        }
    }
    let exhausted = solves > budget;
    Outcome {
        paths,
        changes,
        solves,
        exhausted,
        grown,
    }
}

/// Heading smoothing as `smooth_headings` documents it: at each junction between two paths,
/// `n` headings spread evenly over ±90° about its own (its own alone when `n` = 1) and the
/// chord's from the previous junction to the next; the pair of shortest paths through it that
/// are both clear and shorter than the best so far (the first not tried further when it alone
/// is no shorter) replaces the two when within `capacity` primitives.
fn smooth(
    paths: &[DubinsPath],
    discs: &[(Vec2, f32)],
    candidates: u16,
    capacity: usize,
    budget: u64,
) -> Outcome {
    let mut paths = paths.to_vec();
    let (mut changes, mut solves, mut grown) = (0, 0, 0);
    let n = candidates.max(1) as usize;
    'junctions: for i in 1..paths.len() {
        let (a, b) = (paths[i - 1], paths[i]);
        let junction = b.start;
        let mut best = (a.length() + b.length(), a, b);
        let chord = b.end().position - a.start.position;
        for k in 0..=n {
            if solves > budget {
                break 'junctions;
            }
            let heading = match (k == n, n) {
                (true, _) if chord.x == 0.0 && chord.y == 0.0 => continue,
                (true, _) => chord.angle(),
                (false, 1) => junction.heading,
                (false, _) => {
                    wrap_to_pi(junction.heading - PI / 2.0 + PI * k as f32 / (n - 1) as f32)
                }
            };
            let pose = Pose {
                position: junction.position,
                heading,
            };
            solves += 1;
            let Some(first) = solve(&a.start, &pose, discs) else {
                continue;
            };
            if first.length() >= best.0 {
                continue;
            }
            solves += 1;
            let Some(second) = solve(&pose, &b.end(), discs) else {
                continue;
            };
            if first.length() + second.length() < best.0 {
                best = (first.length() + second.length(), first, second);
            }
        }
        let count: usize = paths.iter().map(pieces).sum();
        let fits = count - pieces(&a) - pieces(&b) + pieces(&best.1) + pieces(&best.2) <= capacity;
        if best.0 < a.length() + b.length() && fits {
            grown += u32::from(pieces(&best.1) + pieces(&best.2) > pieces(&a) + pieces(&b));
            paths[i - 1] = best.1;
            paths[i] = best.2;
            changes += 1;
        }
    }
    let exhausted = solves > budget;
    Outcome {
        paths,
        changes,
        solves,
        exhausted,
        grown,
    }
}

/// A route of 3–6 paths through junctions about 100 m apart eastward with random sideways
/// offsets and headings, every path clear of `discs` (discs that block one are moved away).
fn sampled_route(rng: &mut Rng) -> (Vec<DubinsPath>, Vec<(Vec2, f32)>) {
    let n = 3 + (rng.unit() * 4.0) as usize;
    let junctions: Vec<Pose> = (0..=n)
        .map(|k| {
            Pose::new(
                100.0 * k as f32 + rng.range(-20.0, 20.0),
                rng.range(-80.0, 80.0),
                rng.range(-1.2, 1.2),
            )
        })
        .collect();
    let paths: Vec<DubinsPath> = junctions
        .windows(2)
        .map(|w| DubinsPath::shortest(&w[0], &w[1], RADIUS).unwrap())
        .collect();
    let discs: Vec<(Vec2, f32)> = (0..4)
        .map(|_| {
            (
                Vec2::new(rng.range(0.0, 100.0 * n as f32), rng.range(-120.0, 120.0)),
                rng.range(5.0, 25.0),
            )
        })
        .filter(|&d| paths.iter().all(|p| clear(p, &[d])))
        .collect();
    (paths, discs)
}

/// A planner of route capacity `C` whose route is `paths`.
fn with_route<'n, const C: usize>(
    image: &'n [u8],
    paths: &[DubinsPath],
) -> Planner<'n, 16, 16, 4, C> {
    let mut planner = Planner::new();
    planner.load(image).unwrap();
    for p in paths {
        planner.paths.push(*p).unwrap();
    }
    planner.flatten_route();
    planner
}

fn outcome_of<const C: usize>(
    planner: &Planner<'_, 16, 16, 4, C>,
    result: Result<super::SmoothSummary, PlanError>,
) -> Outcome {
    let (changes, solves, exhausted) = match result {
        Ok(s) => (s.changes, s.work.dubins_solves, false),
        Err(PlanError::BudgetExhausted { .. }) => (u32::MAX, u64::MAX, true),
        Err(e) => panic!("{e:?}"),
    };
    Outcome {
        paths: planner.paths.to_vec(),
        changes,
        solves,
        exhausted,
        grown: 0,
    }
}

/// Runs `pass` on a planner of capacity `C` over `paths` and compares it with `expected`
/// (changes and solves only when the budget held); the route of primitives is the paths'.
fn check<const C: usize>(
    image: &[u8],
    paths: &[DubinsPath],
    expected: &Outcome,
    pass: impl Fn(&mut Planner<'_, 16, 16, 4, C>) -> Result<super::SmoothSummary, PlanError>,
    what: &str,
) {
    let mut planner = with_route::<C>(image, paths);
    let before: f32 = paths.iter().map(|p| p.length()).sum();
    let result = pass(&mut planner);
    if let Ok(summary) = result {
        assert_eq!(summary.length_before, before, "{what}");
        let after: f32 = planner.paths.iter().map(|p| p.length()).sum();
        assert_eq!(summary.length_after, after, "{what}");
        assert!(after <= before, "{what}");
    }
    let found = outcome_of(&planner, result);
    assert_eq!(found.paths, expected.paths, "{what}");
    assert_eq!(found.exhausted, expected.exhausted, "{what}");
    if !expected.exhausted {
        assert_eq!(
            (found.changes, found.solves),
            (expected.changes, expected.solves),
            "{what}"
        );
    }
    let primitives: Vec<_> = planner
        .paths
        .iter()
        .flat_map(|p| p.primitives())
        .flatten()
        .collect();
    assert_eq!(planner.route.as_slice(), primitives.as_slice(), "{what}");
    assert!(planner.route.len() <= C, "{what}");
}

/// A route that loops: a single arc of 206°–320° left or right, a straight of 80–250 m, then
/// the shortest path to a pose further on. Its first two paths are one primitive each, and the
/// path that joins their ends is shorter with more, so at a capacity of the route's own
/// primitives the shortcut (and often the smoothing) is refused for room.
fn loop_route(rng: &mut Rng) -> Vec<DubinsPath> {
    let start = Pose::new(
        rng.range(0.0, 100.0),
        rng.range(-50.0, 50.0),
        rng.range(-PI, PI),
    );
    loop_route_from(rng, start)
}

/// [`loop_route`] from `start`.
fn loop_route_from(rng: &mut Rng, start: Pose) -> Vec<DubinsPath> {
    let word = match rng.unit() < 0.5 {
        true => crate::geometry::DubinsWord::Lsl,
        false => crate::geometry::DubinsWord::Rsr,
    };
    let arc = DubinsPath {
        start,
        radius: RADIUS,
        word,
        lengths: [RADIUS * rng.range(3.6, 5.6), 0.0, 0.0],
    };
    let straight = DubinsPath {
        start: arc.end(),
        radius: RADIUS,
        word: crate::geometry::DubinsWord::Lsl,
        lengths: [0.0, rng.range(80.0, 250.0), 0.0],
    };
    let on = straight.end();
    let ahead = Pose::new(
        on.position.x + rng.range(-150.0, 150.0),
        on.position.y + rng.range(-150.0, 150.0),
        rng.range(-PI, PI),
    );
    let last = DubinsPath::shortest(&on, &ahead, RADIUS).unwrap();
    vec![arc, straight, last]
}

/// A loop route (see [`loop_route`]) after a bend and a straight: the shortest path from a
/// random pose to a random junction, then a straight of 60–160 m to the loop's start. The
/// first path is often three primitives, as is the shorter path that skips the junction, so
/// a shortcut there saves exactly the straight's primitive; at a capacity of the route's own
/// count, a later shortcut of one more primitive (the loop's, where discs keep the first
/// junctions' shortcuts from swallowing it) fits only by that saving.
fn bent_loop_route(rng: &mut Rng) -> Vec<DubinsPath> {
    let from = Pose::new(
        rng.range(-250.0, -100.0),
        rng.range(-150.0, 150.0),
        rng.range(-PI, PI),
    );
    let junction = Pose::new(0.0, 0.0, rng.range(-PI, PI));
    let bend = DubinsPath::shortest(&from, &junction, RADIUS).unwrap();
    let straight = DubinsPath {
        start: bend.end(),
        radius: RADIUS,
        word: crate::geometry::DubinsWord::Lsl,
        lengths: [0.0, rng.range(60.0, 160.0), 0.0],
    };
    let mut paths = vec![bend, straight];
    paths.append(&mut loop_route_from(rng, straight.end()));
    paths
}

/// The greedy pass, and smoothing with each of `candidates`, on `paths` among `discs` at
/// capacity `C`, against the second implementation; returns the expected outcomes, the
/// greedy pass's first.
fn both_at<const C: usize>(
    image: &[u8],
    paths: &[DubinsPath],
    discs: &[(Vec2, f32)],
    candidates: &[u16],
    what: &str,
) -> Vec<Outcome> {
    let expected = greedy(paths, discs, C, u64::MAX);
    let label = std::format!("{what}, shortcut, capacity {C}");
    check::<C>(image, paths, &expected, |p| p.shortcut(u64::MAX), &label);
    let mut outcomes = vec![expected];
    for &n in candidates {
        let expected = smooth(paths, discs, n, C, u64::MAX);
        let label = std::format!("{what}, smoothing with {n}, capacity {C}");
        check::<C>(
            image,
            paths,
            &expected,
            |p| p.smooth_headings(n, u64::MAX),
            &label,
        );
        outcomes.push(expected);
    }
    outcomes
}

/// How many of two passes' outcomes, taken in pairs, end with different paths.
fn differing(a: &[&Outcome], b: &[&Outcome]) -> u32 {
    a.iter().zip(b).filter(|(x, y)| x.paths != y.paths).count() as u32
}

/// Sampled routes among sampled discs: the greedy pass and heading smoothing (1, 2, 5 and 9
/// candidates) give what the second implementation gives at a roomy capacity and, for the
/// routes of exactly 9 or 12 primitives, at that capacity (where a change that adds
/// primitives is refused). Without discs (so the work is the solves alone), budgets of 2 and 5
/// solves run out, keeping the changes made before. Loop routes, at their own count and one
/// more; bent loop routes among discs, at their own count, where at least 30 shortcuts add a
/// primitive that fits only by what earlier shortcuts saved.
#[test]
fn shortcuts_and_heading_smoothing_match_their_definitions() {
    let mut rng = Rng(0x5300_7a11_2026_1206);
    let open = network(&[]);
    let (mut changed, mut smoothed, mut at_capacity, mut refused_for_room) = (0, 0, 0, 0);
    for case in 0..150 {
        let (paths, discs) = sampled_route(&mut rng);
        let image = network(&discs);
        let own: usize = paths.iter().map(pieces).sum();
        let what = |pass: &str, capacity: usize, budget: u64| {
            std::format!("case {case}, {pass}, capacity {capacity}, budget {budget}")
        };
        let label = std::format!("case {case}");
        let roomy = both_at::<64>(&image, &paths, &discs, &[1, 2, 5, 9], &label);
        changed += u32::from(roomy[0].changes > 0);
        smoothed += roomy[1..].iter().filter(|o| o.changes > 0).count() as u32;
        if own == 9 || own == 12 {
            at_capacity += 1;
            let tight = match own {
                9 => both_at::<9>(&image, &paths, &discs, &[1, 5], &label),
                _ => both_at::<12>(&image, &paths, &discs, &[1, 5], &label),
            };
            // The greedy pass, then smoothing with 1 and with 5 candidates.
            let tight: Vec<&Outcome> = tight.iter().collect();
            refused_for_room += differing(&tight, &[&roomy[0], &roomy[1], &roomy[3]]);
        }
        for budget in [2, 5] {
            let expected = greedy(&paths, &[], 64, budget);
            check::<64>(
                &open,
                &paths,
                &expected,
                |p| p.shortcut(budget),
                &what("shortcut", 64, budget),
            );
            let expected = smooth(&paths, &[], 5, 64, budget);
            check::<64>(
                &open,
                &paths,
                &expected,
                |p| p.smooth_headings(5, budget),
                &what("smoothing", 64, budget),
            );
        }
    }
    for case in 0..40 {
        let paths = loop_route(&mut rng);
        let own: usize = paths.iter().map(pieces).sum();
        let label = std::format!("loop {case}");
        let roomy = both_at::<64>(&open, &paths, &[], &[5], &label);
        // At the route's own count and one more: a shortcut of 3 pieces for two of 1 fits
        // only the second.
        let tight = match own {
            4 => {
                let tight = both_at::<4>(&open, &paths, &[], &[5], &label);
                both_at::<5>(&open, &paths, &[], &[5], &label);
                tight
            }
            5 => {
                let tight = both_at::<5>(&open, &paths, &[], &[5], &label);
                both_at::<6>(&open, &paths, &[], &[5], &label);
                tight
            }
            _ => panic!("a loop route of {own} primitives"),
        };
        let (tight, roomy): (Vec<&Outcome>, Vec<&Outcome>) =
            (tight.iter().collect(), roomy.iter().collect());
        refused_for_room += differing(&tight, &roomy);
    }
    // Bent loop routes among discs at their own count: a change that adds primitives fits only
    // by what earlier changes saved, as the planner counts them.
    let mut grown = 0;
    for case in 0..1000 {
        let paths = bent_loop_route(&mut rng);
        let discs: Vec<(Vec2, f32)> = (0..8)
            .map(|_| {
                let centre = Vec2::new(rng.range(-250.0, 300.0), rng.range(-250.0, 250.0));
                (centre, rng.range(5.0, 60.0))
            })
            .filter(|&d| paths.iter().all(|p| clear(p, &[d])))
            .collect();
        let image = network(&discs);
        let own: usize = paths.iter().map(pieces).sum();
        let label = std::format!("bent loop {case}");
        let outcomes = match own {
            5 => both_at::<5>(&image, &paths, &discs, &[], &label),
            6 => both_at::<6>(&image, &paths, &discs, &[], &label),
            7 => both_at::<7>(&image, &paths, &discs, &[], &label),
            8 => both_at::<8>(&image, &paths, &discs, &[], &label),
            9 => both_at::<9>(&image, &paths, &discs, &[], &label),
            _ => panic!("a bent loop route of {own} primitives"),
        };
        grown += outcomes[0].grown;
    }
    assert!(
        grown >= 30,
        "{grown} shortcuts adding primitives at the routes' own counts"
    );
    assert!(
        changed >= 50 && smoothed >= 100 && at_capacity >= 10 && refused_for_room >= 20,
        "{changed} shortened, {smoothed} smoothed, {at_capacity} at capacity, {refused_for_room} refused for room"
    );
}

/// On a three-dimensional roadmap a new path must also fly its climb between the altitudes of
/// the junctions it joins (the start's for junction 0, then the route's): sampled routes whose
/// junctions lie at 0–250 m, so that many joins are too short to climb, against the second
/// implementation with that rule (a rest-to-rest profile within Niendorf et al.'s limits at
/// 25 m/s). The greedy pass also drops the altitude of each junction it drops.
#[test]
fn on_a_three_dimensional_roadmap_new_paths_must_fly_their_climbs() {
    let limits = VerticalLimits::niendorf(25.0);
    let vertical = VerticalSpec {
        limits,
        altitudes: vec![30.0; 4],
        heights: Vec::new(),
    };
    let image = encode_three_dimensional(&roadmap_spec(&[]), &vertical, None).unwrap();
    let flies = |p: &DubinsPath, from: f32, to: f32| {
        VerticalProfile::new(from, to, p.length(), &limits).is_some()
    };
    let mut rng = Rng(0x3d5a_0071_2026_1206);
    let (mut refused, mut changed) = (0, 0);
    for case in 0..80 {
        let (paths, _) = sampled_route(&mut rng);
        let n = paths.len();
        let zs: Vec<f32> = (0..=n).map(|_| rng.range(0.0, 250.0)).collect();
        let start = |planner: &mut Planner<'_, 16, 16, 4, 64>| {
            planner.set_query_altitudes(zs[0], zs[n]).unwrap();
            if let ModeState::Roadmap(state) = &mut planner.state {
                state.route_altitudes = heapless::Vec::from_slice(&zs[1..]).unwrap();
            }
        };

        // The greedy pass: junction i's neighbours joined at their own altitudes.
        let (mut route, mut at) = (paths.clone(), zs.clone());
        let (mut solves, mut changes, mut i) = (0, 0, 1);
        while i < route.len() {
            let (a, b) = (route[i - 1], route[i]);
            solves += 1;
            let joined = DubinsPath::shortest(&a.start, &b.end(), RADIUS);
            match joined {
                Some(j) if !flies(&j, at[i - 1], at[i + 1]) => {
                    refused += 1;
                    i += 1;
                }
                Some(j) if j.length() < a.length() + b.length() => {
                    route[i - 1] = j;
                    route.remove(i);
                    at.remove(i);
                    changes += 1;
                }
                _ => i += 1,
            }
        }
        changed += u32::from(changes > 0);
        let mut planner = with_route::<64>(&image, &paths);
        start(&mut planner);
        let summary = planner.shortcut(u64::MAX).unwrap();
        assert_eq!(planner.paths.as_slice(), route.as_slice(), "case {case}");
        assert_eq!(planner.route_altitudes(), &at[1..], "case {case}");
        assert_eq!(
            (summary.changes, summary.work.dubins_solves),
            (changes, solves)
        );

        // Smoothing with 5 candidates: the path into junction i climbs from i − 1 to i, the
        // path out of it from i to i + 1.
        let mut route = paths.clone();
        let (mut solves, mut changes) = (0, 0);
        for i in 1..n {
            let (a, b) = (route[i - 1], route[i]);
            let junction = b.start;
            let mut best = (a.length() + b.length(), a, b);
            let chord = b.end().position - a.start.position;
            for k in 0..=5 {
                let heading = match k {
                    5 => chord.angle(),
                    _ => wrap_to_pi(junction.heading - PI / 2.0 + PI * k as f32 / 4.0),
                };
                let pose = Pose {
                    position: junction.position,
                    heading,
                };
                solves += 1;
                let first = DubinsPath::shortest(&a.start, &pose, RADIUS);
                let Some(first) = first.filter(|p| flies(p, zs[i - 1], zs[i])) else {
                    continue;
                };
                if first.length() >= best.0 {
                    continue;
                }
                solves += 1;
                let second = DubinsPath::shortest(&pose, &b.end(), RADIUS);
                let Some(second) = second.filter(|p| flies(p, zs[i], zs[i + 1])) else {
                    continue;
                };
                if first.length() + second.length() < best.0 {
                    best = (first.length() + second.length(), first, second);
                }
            }
            if best.0 < a.length() + b.length() {
                route[i - 1] = best.1;
                route[i] = best.2;
                changes += 1;
            }
        }
        let mut planner = with_route::<64>(&image, &paths);
        start(&mut planner);
        let summary = planner.smooth_headings(5, u64::MAX).unwrap();
        assert_eq!(planner.paths.as_slice(), route.as_slice(), "case {case}");
        assert_eq!(planner.route_altitudes(), &zs[1..], "case {case}");
        assert_eq!(
            (summary.changes, summary.work.dubins_solves),
            (changes, solves)
        );
    }
    assert!(
        refused >= 20 && changed >= 20,
        "{refused} joins refused for their climb, {changed} routes shortened"
    );
}
