//! Planning in slices (`Planner::start_plan` + `Planner::step`) against one `Planner::plan`
//! call, in every mode on the shipped networks: for random queries and slices of 1, 7, 1000
//! and unlimited work, the same result (route, summary and work, or error) bit for bit; every
//! step within its slice plus the documented unit bound; pop-ups and other changes mid-query
//! cancel it and keep the previous route; roadmap and terrain queries report their phases to
//! an observer, landmark and Voronoi ones only their end.

use host_tests::rng::Rng;
use host_tests::scenarios;
use host_tests::tier::cases;
use skyroute::geometry::Pose;
use skyroute::planner::{Phase, PlanStep, VoronoiStorage};
use skyroute::{Goal, PlanError, Planner, Popup, Query, RouteSummary, Search, Vec2};
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::scenario::Mode;

/// The slices every query is stepped with.
const SLICES: [u64; 4] = [1, 7, 1000, u64::MAX];

/// What a query left: its result and the route (its Debug text, so that floats compare bit for
/// bit, signed zeros included).
type Outcome = (Result<RouteSummary, PlanError>, String);

fn outcome<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &Planner<'_, V, E, P, R>,
    result: Result<RouteSummary, PlanError>,
) -> Outcome {
    (result, format!("{:?} {:?}", p.route(), p.route_paths()))
}

/// What stepping one query took: the steps, and the most work one step counted.
struct Stepped {
    steps: u64,
    most: u64,
}

/// Runs `query` as `start_plan` + `step(slice)` until done, checking every step's work against
/// `slice + unit` (exclusive of the unit's last count: `slice − 1 + unit`).
fn stepped<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
    query: &Query,
    budget: u64,
    slice: u64,
    unit: u64,
) -> (Outcome, Stepped) {
    if let Err(e) = p.start_plan(query, budget) {
        assert!(!p.is_planning());
        assert_eq!(p.step(slice), PlanStep::Idle);
        return (outcome(p, Err(e)), Stepped { steps: 0, most: 0 });
    }
    assert!(p.is_planning());
    let (mut before, mut steps, mut most) = (0u64, 0u64, 0u64);
    loop {
        let step = p.step(slice);
        steps += 1;
        let after = match step {
            PlanStep::InProgress { work_so_far } => Some(work_so_far),
            PlanStep::Done(Ok(summary)) => Some(summary.work.total()),
            PlanStep::Done(Err(PlanError::BudgetExhausted { used, .. })) => Some(used),
            PlanStep::Done(Err(_)) => None,
            PlanStep::Idle => panic!("a query in progress stepped to idle"),
        };
        if let Some(after) = after {
            let w = after - before;
            most = most.max(w);
            assert!(
                w < slice.saturating_add(unit),
                "a step of slice {slice} counted {w} (unit bound {unit}) for {query:?}"
            );
            before = after;
        }
        if let PlanStep::Done(result) = step {
            assert!(!p.is_planning());
            assert_eq!(p.step(slice), PlanStep::Idle);
            return (outcome(p, result), Stepped { steps, most });
        }
        assert!(steps < 100_000_000, "a query that does not end");
    }
}

/// The phases `plan_observed` reports for `query`, in order, and its result.
fn phases<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
    query: &Query,
    budget: u64,
) -> (Vec<Phase>, Result<RouteSummary, PlanError>) {
    let mut seen = Vec::new();
    let result = p.plan_observed(query, budget, &mut |phase, _| seen.push(phase));
    (seen, result)
}

/// Plans every query once with `plan` and once per slice with `start_plan` + `step`, and
/// checks they agree; and that the query's observer is told the search and route phases, then
/// the end, if `reports_phases`, and only the end otherwise. Returns the most work one step of
/// slice 1 counted (one unit) and the results' kinds seen.
fn compare<const V: usize, const E: usize, const P: usize, const R: usize>(
    name: &str,
    p: &mut Planner<'_, V, E, P, R>,
    queries: &[(Query, u64)],
    reports_phases: bool,
) -> (u64, usize, usize) {
    let unit = p.step_unit_bound();
    let (mut most_unit, mut ok, mut err, mut largest) = (0u64, 0usize, 0usize, 0u64);
    for (q, budget) in queries {
        let (seen, observed) = phases(p, q, *budget);
        if !reports_phases {
            assert_eq!(seen, [Phase::Done], "{name}: {q:?}");
        } else if observed.is_ok() {
            let n = seen.len();
            assert!(n >= 3, "{name}: {seen:?} for {q:?}");
            assert_eq!(
                seen[n - 3..],
                [Phase::Search, Phase::Route, Phase::Done],
                "{name}: {q:?}"
            );
        }
        let want = {
            let r = p.plan(q, *budget);
            outcome(p, r)
        };
        assert_eq!(want.0, observed, "{name}: plan_observed differs from plan");
        match want.0 {
            Ok(s) => {
                ok += 1;
                largest = largest.max(s.work.total());
            }
            Err(_) => err += 1,
        }
        for slice in SLICES {
            // `plan` left its route (or the previous one) in place: the route a failing
            // stepped query must keep, and the one a succeeding one must replace identically.
            let (got, s) = stepped(p, q, *budget, slice, unit);
            assert_eq!(
                got, want,
                "{name}: slice {slice} differs from plan for {q:?}"
            );
            if slice == 1 {
                most_unit = most_unit.max(s.most);
            }
            if slice == u64::MAX && want.0.is_ok() {
                assert_eq!(s.steps, 1, "an unlimited slice runs the query in one step");
            }
        }
    }
    println!(
        "{name}: {} queries ({ok} routes, {err} refusals), unit bound {unit}, \
         most work in one unit {most_unit}, in one routed query {largest}",
        queries.len()
    );
    (most_unit, ok, err)
}

/// A random pose near a random vertex of `p`'s network (within `spread` metres).
fn pose_near<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &Planner<'_, V, E, P, R>,
    rng: &mut Rng,
    spread: f32,
) -> Pose {
    let net = p.network();
    let v = rng.below(net.vertex_count() as u64) as u32;
    let at = net.vertex(v).unwrap().position;
    Pose {
        position: Vec2::new(
            at.x + rng.range_f32(-spread, spread),
            at.y + rng.range_f32(-spread, spread),
        ),
        heading: rng.range_f32(-3.2, 3.2),
    }
}

/// Random queries between points near vertices: free and fixed goal headings, Dijkstra and
/// A*, the full budget or a fraction of what the query takes (exhausted midway), and a few
/// refused outright (non-finite).
fn random_queries<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
    rng: &mut Rng,
    n: usize,
    spread: f32,
) -> Vec<(Query, u64)> {
    let full = p.worst_case_work();
    (0..n)
        .map(|k| {
            let start = pose_near(p, rng, spread);
            let goal = pose_near(p, rng, spread);
            let mut q = Query {
                start,
                goal: Goal {
                    position: goal.position,
                    heading: rng.chance(0.5).then_some(goal.heading),
                },
                search: if rng.chance(0.5) {
                    Search::Dijkstra
                } else {
                    Search::AStar
                },
            };
            if k % 17 == 16 {
                q.start.position.x = f32::NAN;
            }
            let budget = if k % 5 == 4 {
                // A budget the query runs out of: a fraction of its own work, if it succeeds.
                match p.plan(&q, full) {
                    Ok(s) => (s.work.total() as f64 * rng.range(0.05, 0.95)) as u64,
                    Err(_) => full,
                }
            } else {
                full
            };
            (q, budget)
        })
        .collect()
}

type RoadmapPlanner<'n> = Planner<'n, 4096, 65536, 4, 1024>;

#[test]
fn roadmap_slices_match_one_call() {
    let built = scenarios::built("niendorf-urban");
    let mut p: Box<RoadmapPlanner<'_>> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    let mut rng = Rng(0x511CE);
    let queries = random_queries(&mut *p, &mut rng, cases(40, 400), 300.0);
    let (most, ok, err) = compare("niendorf-urban", &mut *p, &queries, true);
    assert!(
        ok > queries.len() / 4 && err > 0,
        "{ok} routes, {err} refusals"
    );
    // Slicing is real: one unit is far below a whole query.
    assert!(most < p.worst_case_work() / 10, "{most}");
}

#[test]
fn roadmap_slices_with_a_popup_and_exits_match_one_call() {
    let built = scenarios::built("niendorf-urban");
    let mut p: Box<RoadmapPlanner<'_>> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    let mut rng = Rng(0x9090);
    let centre = pose_near(&*p, &mut rng, 0.0).position;
    p.add_popup(Popup::Circle {
        centre,
        radius: 150.0,
    })
    .unwrap();
    // Starts near the pop-up: some inside it or within the clearance, which need an exit.
    let mut queries = random_queries(&mut *p, &mut rng, cases(20, 200), 300.0);
    for (q, _) in queries.iter_mut().step_by(3) {
        q.start.position = centre + Vec2::new(rng.range_f32(-160.0, 160.0), 0.0);
    }
    compare("niendorf-urban with a pop-up", &mut *p, &queries, true);
}

#[test]
fn a_change_mid_query_cancels_it_and_keeps_the_route() {
    let built = scenarios::built("niendorf-urban");
    let mut p: Box<RoadmapPlanner<'_>> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    let mut rng = Rng(77);
    let budget = p.worst_case_work();
    let queries = random_queries(&mut *p, &mut rng, 60, 300.0);
    let mut pairs = queries
        .iter()
        .filter(|(q, b)| *b == budget && p.plan(q, budget).is_ok())
        .map(|(q, _)| *q);
    let (first, second) = (pairs.next().unwrap(), pairs.next().unwrap());
    let first_route = {
        let r = p.plan(&first, budget);
        outcome(&*p, r)
    };
    let route_now = || first_route.1.clone();

    // A pop-up mid-query: the query is cancelled, the route is the previous one.
    p.start_plan(&second, budget).unwrap();
    assert!(matches!(p.step(500), PlanStep::InProgress { .. }));
    assert_eq!(outcome(&*p, Ok(first_route.0.unwrap())).1, route_now());
    let popup = p
        .add_popup(Popup::Circle {
            centre: second.goal.position + Vec2::new(400.0, 400.0),
            radius: 50.0,
        })
        .unwrap();
    assert!(!p.is_planning());
    assert_eq!(p.step(1000), PlanStep::Idle);
    assert_eq!(outcome(&*p, Ok(first_route.0.unwrap())).1, route_now());
    assert_eq!(p.route_summary().copied(), first_route.0.ok());
    // Started again, it answers as `plan` does with the pop-up in force.
    let want = {
        let r = p.plan(&second, budget);
        outcome(&*p, r)
    };
    let unit = p.step_unit_bound();
    let (got, _) = stepped(&mut *p, &second, budget, 1000, unit);
    assert_eq!(got, want);

    // Each other change cancels too; a new start cancels the query in progress.
    for change in 0..5 {
        // What the second query gives as things stand (the pop-up is gone from change 0 on).
        let expected = p.plan(&second, budget);
        p.start_plan(&first, budget).unwrap();
        assert!(matches!(p.step(200), PlanStep::InProgress { .. }));
        match change {
            0 => p.remove_popup(popup.id).unwrap(),
            1 => p.set_config(p.config()),
            2 => p.cancel_plan(),
            3 => {
                let _ = p.smooth_headings(4, budget);
            }
            _ => p.start_plan(&second, budget).unwrap(),
        }
        if change == 4 {
            assert!(p.is_planning());
            let mut last = p.step(u64::MAX);
            while let PlanStep::InProgress { .. } = last {
                last = p.step(u64::MAX);
            }
            assert_eq!(
                last,
                PlanStep::Done(expected),
                "the second query, not the first"
            );
        } else {
            assert!(!p.is_planning(), "change {change}");
            assert_eq!(p.step(1), PlanStep::Idle);
        }
    }

    // A refused start ends the query in progress and keeps the route.
    p.start_plan(&first, budget).unwrap();
    let _ = p.step(100);
    let route = format!("{:?}", p.route());
    let mut bad = first;
    bad.goal.heading = Some(f32::INFINITY);
    assert_eq!(
        p.start_plan(&bad, budget),
        Err(p.plan(&bad, budget).unwrap_err())
    );
    assert!(!p.is_planning());
    assert_eq!(format!("{:?}", p.route()), route);
}

/// A planner of `mode` on `scenario`'s network (the process's cached build when the scenario's
/// own mode), boxed.
fn build_as(name: &str, mode: Mode) -> Vec<u8> {
    let s = scenarios::scenario(name);
    if s.planner.mode == mode {
        return scenarios::built(name).bytes.clone();
    }
    let mut s = s.clone();
    s.planner.mode = mode;
    build(&s, &BuildOptions::default(), &|_, _| {})
        .unwrap()
        .bytes
}

#[test]
fn voronoi_slices_match_one_call() {
    let bytes = build_as("ruz-popups", Mode::Voronoi);
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<Planner<'_, 1024, 1024, 4, 4096>> = Box::new(Planner::new());
    p.load_voronoi(&bytes, storage).unwrap();
    let mut rng = Rng(0xF00D);
    let queries = random_queries(&mut *p, &mut rng, cases(12, 120), 500.0);
    let (_, ok, _) = compare("ruz-popups (voronoi)", &mut *p, &queries, false);
    assert!(ok > 0);
}

#[test]
fn landmark_slices_match_one_call() {
    let name = "babel-II-N";
    let built = scenarios::built(name);
    let mut p: Box<Planner<'_, 1024, 40000, 4, 128>> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    // From the stored start and from random overflights (pose and heading, as a start must
    // match one) to the stored goal, the only goal a landmark network plans to.
    let l = *p.network().landmark().unwrap();
    let goal = p.network().vertex(l.goal_vertex).unwrap().position;
    let budget = p.worst_case_work();
    let mut queries = Vec::new();
    let mut rng = Rng(5);
    for k in 0..cases(12, 60) {
        let v = if k == 0 {
            l.start_vertex
        } else {
            rng.below(p.network().vertex_count() as u64) as u32
        };
        let q = Query {
            start: p.network().vertex(v).unwrap(),
            goal: Goal {
                position: goal,
                heading: None,
            },
            search: if k % 2 == 0 {
                Search::Dijkstra
            } else {
                Search::AStar
            },
        };
        queries.push((q, if k % 4 == 3 { budget / 1000 } else { budget }));
    }
    let (_, ok, _) = compare(name, &mut *p, &queries, false);
    assert!(ok > 0);
}

/// The scenario's own start and goal (free goal heading) in the network's frame.
fn scenario_query(name: &str, frame: &skyroute_prep::frame::LocalFrame) -> Query {
    let s = scenarios::scenario(name);
    let (st, g) = (s.start.as_ref().unwrap(), s.goal.as_ref().unwrap());
    Query {
        start: Pose {
            position: skyroute_prep::build::local(frame, st.lon, st.lat),
            heading: skyroute_prep::build::local_heading(
                frame,
                st.lon,
                st.lat,
                st.heading_deg.unwrap_or(0.0),
            ),
        },
        goal: Goal {
            position: skyroute_prep::build::local(frame, g.lon, g.lat),
            heading: None,
        },
        search: Search::Dijkstra,
    }
}

/// A host planner with room for the Jacksboro network's search states (as `terrain_plan`).
type TerrainPlanner<'n> = Planner<'n, 2097152, 131072, 4, 1024>;

#[test]
fn terrain_slices_match_one_call() {
    let built = scenarios::built("medeiros-jacksboro");
    let bytes = built.bytes.clone();
    let scenario = scenario_query("medeiros-jacksboro", &built.frame);
    // Its planner is large: build it on a thread with the stack for it.
    std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || {
            let mut p: Box<TerrainPlanner<'_>> = Box::new(Planner::new());
            p.load(&bytes).unwrap();
            p.set_config(skyroute_prep::mission::TERRAIN_CONFIG);
            let mut rng = Rng(0x7E44);
            let mut queries = vec![(scenario, u64::MAX)];
            queries.extend(random_queries(&mut *p, &mut rng, cases(5, 30), 1000.0));
            let (most, ok, _) = compare("medeiros-jacksboro (terrain)", &mut *p, &queries, true);
            assert!(ok > 0 && most > 0);
        })
        .unwrap()
        .join()
        .unwrap();
}
