//! Random queries on every mode's scenario network, each checked against the documented work
//! bound (`Planner::worst_case_work`); the worst query found is then re-run with a budget one
//! below its work, which must be refused with the previous route kept.
//!
//! ```text
//! work_sweep [--queries N] [--mode roadmap|terrain|landmark|voronoi]   # N per mode, default 100 000
//! ```
//!
//! Roadmap (niendorf-urban): random start and goal poses, 0–3 circular pop-ups, Dijkstra or A*.
//! Terrain (medeiros-jacksboro, the firmware's turn rule `SharedEqually`): random poses, the
//! built altitude and three others (−150, −75, +100 m), 0–2 pop-ups.
//! Landmark (babel-II-N): the network's start and goal, or (each two times in three) a
//! random pose within 8 km of a random overflight, joined online with a random range left,
//! and a random goal point likewise; a random weather, random rosette losses and 0–2
//! pop-ups. Voronoi (voronoi-dense): random poses and threat weights, threats
//! popped and removed. Every roadmap and terrain route is also checked for continuity and the
//! turn radius ([`route_is_flyable`]). Prints one line per mode; exits 1 if any work exceeds
//! its bound or a route is not flyable.

use host_tests::scenarios::built;
use host_tests::Rng;
use skyroute::planner::{PlanError, VoronoiStorage};
use skyroute::{Goal, Network, Planner, Popup, Pose, Query, Search, Vec2};
use skyroute_prep::scenario::Mode;
use std::process::ExitCode;
use std::time::Instant;

type Big<'n> = Planner<'n, 131072, 131072, 4, 4096>;

/// What a mode's sweep found.
#[derive(Default)]
struct Sweep {
    queries: u64,
    routes: u64,
    worst_work: u64,
    bound: u64,
    over_bound: u64,
    worst_refused_below: bool,
    /// Roadmap and terrain routes that broke an invariant of [`route_is_flyable`].
    not_flyable: u64,
}

/// The invariants of a route of Dubins pieces (roadmap and terrain): it starts at the start
/// pose and ends at the goal (and its heading, when fixed); each primitive starts where the
/// previous ends with the same heading (within 10⁻³ rad, plus for a line the rounding of the
/// direction between its f32 ends: 4ε·|start| / length); every arc's radius is at least the
/// network's turn radius (less 10⁻⁴ relative). Positions agree within 1 cm plus 2·10⁻⁶ of the
/// primitive's length and of the point's distance from the origin: the f32 rounding of a
/// primitive computed tens of kilometres long and away (a 20 km straight ends 4 cm off).
/// `Err` says which failed.
fn route_is_flyable(
    route: &[skyroute::Primitive],
    q: &Query,
    turn_radius: f32,
) -> Result<(), String> {
    let (Some(first), Some(last)) = (route.first(), route.last()) else {
        return Err("empty route".into());
    };
    let heading_gap = |a: f32, b: f32| {
        let d = (a - b).rem_euclid(std::f32::consts::TAU);
        d.min(std::f32::consts::TAU - d)
    };
    let tolerance = |p: &skyroute::Primitive, at: Vec2| 0.01 + 2e-6 * (p.length() + at.norm());
    let start = first.pose_at(0.0);
    let end = last.pose_at(last.length());
    if start.position.distance(q.start.position) > tolerance(first, start.position)
        || heading_gap(start.heading, q.start.heading) > 1e-3
    {
        return Err(format!("starts at {start:?}, not {:?}", q.start));
    }
    if end.position.distance(q.goal.position) > tolerance(last, end.position)
        || q.goal
            .heading
            .is_some_and(|h| heading_gap(end.heading, h) > 1e-3)
    {
        return Err(format!("ends at {end:?}, not {:?}", q.goal));
    }
    for (i, pair) in route.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        let (a_end, b_start) = (a.pose_at(a.length()), b.pose_at(0.0));
        let gap = a_end.position.distance(b_start.position);
        // A zero-length primitive has no heading of its own; a line's heading is that of the
        // difference of its ends, off by up to 2 ulp of their coordinates over its length.
        let turn = if a.length() > 0.0 && b.length() > 0.0 {
            heading_gap(a_end.heading, b_start.heading)
        } else {
            0.0
        };
        let line_slack = |p: &skyroute::Primitive| match p {
            skyroute::Primitive::Line(l) => 4.0 * f32::EPSILON * l.start.norm() / l.length(),
            skyroute::Primitive::Arc(_) => 0.0,
        };
        let allowed = tolerance(a, a_end.position).max(tolerance(b, b_start.position));
        if gap > allowed || turn > 1e-3 + line_slack(a) + line_slack(b) {
            return Err(format!(
                "primitives {i} and {}: {gap} m apart, headings {turn} rad apart ({a:?} then {b:?})",
                i + 1
            ));
        }
    }
    for p in route {
        if let skyroute::Primitive::Arc(a) = p {
            if a.radius < turn_radius * (1.0 - 1e-4) {
                return Err(format!("an arc of radius {} < {turn_radius}", a.radius));
            }
        }
    }
    Ok(())
}

/// Uniform in the network's extent.
fn at(rng: &mut Rng, net: &Network) -> Vec2 {
    let (lo, hi) = net.extent();
    Vec2::new(
        rng.range(lo.x as f64, hi.x as f64) as f32,
        rng.range(lo.y as f64, hi.y as f64) as f32,
    )
}

/// A random query in the network's extent: start pose, goal position, the goal's heading
/// fixed half of the time.
fn random_query(rng: &mut Rng, net: &Network, search: Search) -> Query {
    let goal = pose(rng, net);
    Query {
        start: pose(rng, net),
        goal: Goal {
            position: goal.position,
            heading: rng.chance(0.5).then_some(goal.heading),
        },
        search,
    }
}

fn pose(rng: &mut Rng, net: &Network) -> Pose {
    Pose {
        position: at(rng, net),
        heading: rng.range(-3.2, 3.2) as f32,
    }
}

/// Runs `queries` random queries through `step` (which prepares the planner's in-flight
/// state and returns the query), recording the worst; each new worst is re-run at once one
/// unit short.
fn sweep<'n>(
    p: &mut Big<'n>,
    queries: u64,
    seed: u64,
    dubins_routes: bool,
    mut step: impl FnMut(&mut Big<'n>, &mut Rng, u64) -> Query,
) -> Sweep {
    let mut rng = Rng(seed);
    let mut s = Sweep::default();
    let mut bound = 0;
    for i in 0..queries {
        let q = step(p, &mut rng, i);
        // Every step changes the in-flight state (pop-ups, altitude, weather, threats) only at
        // multiples of 4, so the bound is read again there: a terrain bound scans every edge.
        if i % 4 == 0 {
            bound = p.worst_case_work();
        }
        s.queries += 1;
        if let Ok(r) = p.plan(&q, u64::MAX) {
            s.routes += 1;
            let used = r.work.total();
            if used > bound {
                s.over_bound += 1;
            }
            if dubins_routes {
                if let Err(why) = route_is_flyable(p.route(), &q, p.network().turn_radius()) {
                    if s.not_flyable == 0 {
                        eprintln!("work_sweep: query {i} {q:?}: the route is not flyable: {why}");
                    }
                    s.not_flyable += 1;
                }
            }
            if used > s.worst_work {
                // The new worst, at once in the state it ran in: one unit short is refused,
                // and the route just planned is kept.
                let before = p.route().to_vec();
                let refused =
                    matches!(p.plan(&q, used - 1), Err(PlanError::BudgetExhausted { .. }))
                        && p.route() == &before[..];
                s.worst_refused_below = (s.worst_work == 0 || s.worst_refused_below) && refused;
                s.worst_work = used;
                s.bound = bound;
            }
        }
    }
    s
}

/// Replaces the planner's pop-ups by `n` random discs of 50–500 m.
fn random_popups(p: &mut Big<'_>, rng: &mut Rng, n: u64, net: &Network) {
    let ids: Vec<u8> = p.popups().map(|(id, _)| id).collect();
    for id in ids {
        let _ = p.remove_popup(id);
    }
    for _ in 0..n {
        let centre = at(rng, net);
        let radius = rng.range(50.0, 500.0) as f32;
        let _ = p.add_popup(Popup::Circle { centre, radius });
    }
}

fn roadmap(queries: u64) -> Sweep {
    let b = built("niendorf-urban");
    let net = Network::from_bytes(&b.bytes).unwrap();
    let mut p: Box<Big<'_>> = Box::new(Planner::new());
    p.load(&b.bytes).unwrap();
    sweep(&mut p, queries, 1, true, |p, rng, i| {
        if i % 16 == 0 {
            let n = rng.below(4);
            random_popups(p, rng, n, &net);
        }
        let search = if i % 2 == 0 {
            Search::Dijkstra
        } else {
            Search::AStar
        };
        random_query(rng, &net, search)
    })
}

/// The three-dimensional roadmap: as [`roadmap`], each query between random altitudes in the
/// band the network's vertices were sampled in (and 20 m beyond it either way).
fn roadmap_3d(queries: u64) -> Sweep {
    let b = built("niendorf-urban-3d");
    let net = Network::from_bytes(&b.bytes).unwrap();
    let altitudes = (0..net.vertex_count()).filter_map(|v| net.vertex_altitude(v));
    let (low, high) = altitudes.fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), z| {
        (l.min(z), h.max(z))
    });
    let mut p: Box<Big<'_>> = Box::new(Planner::new());
    p.load(&b.bytes).unwrap();
    sweep(&mut p, queries, 5, true, |p, rng, i| {
        if i % 16 == 0 {
            let n = rng.below(4);
            random_popups(p, rng, n, &net);
        }
        let mut altitude = || rng.range((low - 20.0) as f64, (high + 20.0) as f64) as f32;
        let (from, to) = (altitude(), altitude());
        p.set_query_altitudes(from, to).unwrap();
        let search = if i % 2 == 0 {
            Search::Dijkstra
        } else {
            Search::AStar
        };
        random_query(rng, &net, search)
    })
}

fn terrain(queries: u64) -> Sweep {
    let b = built("medeiros-jacksboro");
    let net = Network::from_bytes(&b.bytes).unwrap();
    let mut p: Box<Big<'_>> = Box::new(Planner::new());
    p.load(&b.bytes).unwrap();
    // The rule the firmware runs: the paper's needs far more states than this planner has.
    p.set_config(skyroute::planner::PlannerConfig {
        turn_rule: skyroute::planner::TurnRule::SharedEqually,
        ..p.config()
    });
    let t = *net.terrain().unwrap();
    // The built altitude and three others: lower ones block more of the network.
    let levels = [-150.0, -75.0, 0.0, 100.0].map(|d| t.altitude_m + d);
    sweep(&mut p, queries, 2, true, |p, rng, i| {
        if i % 16 == 0 {
            let a = levels[rng.below(levels.len() as u64) as usize];
            let _ = p.set_altitude(a, t.safety_height_m);
            let n = rng.below(3);
            random_popups(p, rng, n, &net);
        }
        random_query(rng, &net, Search::Dijkstra)
    })
}

fn landmark(queries: u64) -> Sweep {
    let b = built("babel-II-N");
    let net = Network::from_bytes(&b.bytes).unwrap();
    let l = *net.landmark().unwrap();
    let mut p: Box<Big<'_>> = Box::new(Planner::new());
    p.load(&b.bytes).unwrap();
    let q = Query {
        start: net.vertex(l.start_vertex).unwrap(),
        goal: Goal {
            position: net.vertex(l.goal_vertex).unwrap().position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let overflights = (l.landmark_count * l.directions) as u64;
    // Within 8 km of a random overflight.
    let near_an_overflight = |rng: &mut Rng| {
        let v = net.vertex(rng.below(overflights) as u32).unwrap().position;
        v + Vec2::new(
            rng.range(-8000.0, 8000.0) as f32,
            rng.range(-8000.0, 8000.0) as f32,
        )
    };
    sweep(&mut p, queries, 3, false, |p, rng, i| {
        if i % 4 == 0 {
            let _ = p.set_weather(rng.below(l.weather_count as u64) as u32);
            let lost = rng.below(l.landmark_count as u64) as u32;
            let quality = rng.unit() as f32;
            let _ = p.update_rosette(lost, &vec![quality; l.directions as usize]);
            let n = rng.below(3);
            random_popups(p, rng, n, &net);
        }
        let mut query = q;
        if rng.below(3) > 0 {
            let at = near_an_overflight(rng);
            let heading = rng.range(-3.2, 3.2) as f32;
            query.start = Pose::new(at.x, at.y, heading);
            let _ = p.set_start_range(rng.range(2000.0, 14000.0) as f32);
        }
        if rng.below(3) > 0 {
            query.goal = Goal {
                position: near_an_overflight(rng),
                heading: rng.chance(0.5).then(|| rng.range(-3.2, 3.2) as f32),
            };
        }
        query
    })
}

fn voronoi(queries: u64) -> Sweep {
    let mut s = host_tests::scenarios::scenario("voronoi-dense").clone();
    s.planner.mode = Mode::Voronoi;
    let b = skyroute_prep::build::build(&s, &Default::default(), &|_, _| {}).unwrap();
    let bytes: &'static [u8] = Box::leak(b.bytes.into_boxed_slice());
    let net = Network::from_bytes(bytes).unwrap();
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<Big<'_>> = Box::new(Planner::new());
    p.load_voronoi(bytes, storage).unwrap();
    sweep(&mut p, queries, 4, false, |p, rng, i| {
        if i % 16 == 0 {
            let popped: Vec<u8> = p
                .threats()
                .iter()
                .filter_map(|t| match t.origin {
                    skyroute::planner::ThreatOrigin::Popped(id) => Some(id),
                    skyroute::planner::ThreatOrigin::Network(_) => None,
                })
                .collect();
            for id in popped {
                let _ = p.remove_threat(id);
            }
            for _ in 0..rng.below(3) {
                let r = rng.range(500.0, 5000.0) as f32;
                let _ = p.add_threat(at(rng, &net), r);
            }
            let _ = p.set_threat_weight(rng.unit() as f32);
        }
        random_query(rng, &net, Search::Dijkstra)
    })
}

/// A mode's name and its sweep.
type ModeSweep = (&'static str, fn(u64) -> Sweep);

/// Whether a mode's routes are Dubins pieces (checked by [`route_is_flyable`]).
fn dubins(name: &str) -> bool {
    name.starts_with("roadmap") || name.starts_with("terrain")
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let queries = match args.iter().position(|a| a == "--queries") {
        Some(i) => match args.get(i + 1).and_then(|n| n.parse::<u64>().ok()) {
            Some(n) if n > 0 => n,
            _ => {
                eprintln!("work_sweep: --queries takes a positive count");
                return ExitCode::from(2);
            }
        },
        None => 100_000,
    };
    let only = args
        .iter()
        .position(|a| a == "--mode")
        .and_then(|i| args.get(i + 1));
    let modes: [ModeSweep; 5] = [
        ("roadmap niendorf-urban", roadmap),
        ("roadmap niendorf-urban-3d", roadmap_3d),
        ("terrain medeiros-jacksboro", terrain),
        ("landmark babel-II-N", landmark),
        ("voronoi voronoi-dense", voronoi),
    ];
    let results: Vec<(&str, Sweep, f64)> = std::thread::scope(|scope| {
        let handles: Vec<_> = modes
            .iter()
            .filter(|(name, _)| only.is_none_or(|m| name.starts_with(m.as_str())))
            .map(|&(name, run)| {
                // A planner built in place may pass through the thread's stack first.
                std::thread::Builder::new()
                    .stack_size(64 << 20)
                    .spawn_scoped(scope, move || {
                        let t = Instant::now();
                        (name, run(queries), t.elapsed().as_secs_f64())
                    })
                    .expect("a sweep thread starts")
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut failed = false;
    println!("| mode, scenario | queries | routes | worst work | its bound | worst / bound | over the bound | worst re-run with work − 1 refused, route kept | routes not flyable | seconds |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, s, secs) in results {
        println!(
            "| {name} | {} | {} | {} | {} | {:.4} | {} | {} | {} | {secs:.0} |",
            s.queries,
            s.routes,
            s.worst_work,
            s.bound,
            s.worst_work as f64 / s.bound.max(1) as f64,
            s.over_bound,
            if s.worst_refused_below { "yes" } else { "NO" },
            if dubins(name) {
                s.not_flyable.to_string()
            } else {
                "–".into()
            },
        );
        failed |= s.over_bound > 0 || !s.worst_refused_below || s.routes == 0 || s.not_flyable > 0;
    }
    if failed {
        eprintln!("work_sweep: a query exceeded its bound, or the worst was not refused below it");
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
