//! skyroute's queries timed in-process, and OMPL's routes checked with skyroute's predicates.

use crate::{network, read, write_json, Args};
use serde_json::{json, Value};
use skyroute::planner::{Goal, PlanError, Query, RouteSummary, Search};
use skyroute::{DubinsPath, DubinsWord, Planner, Pose};
use skyroute_peers::queries::{self, PosePair};
use skyroute_peers::stats;
use skyroute_peers::world::World;
use std::time::Instant;

/// The planner of `skyroute plan` (`prep/src/mission.rs`'s `HostPlanner`): large enough for
/// any network the ground tool builds.
type BenchPlanner<'n> = Planner<'n, 131072, 262144, 16, 4096>;

/// Headings per junction of the heading smoothing, as `skyroute plan` (`SMOOTHING_HEADINGS`).
const SMOOTHING_HEADINGS: u16 = 9;

/// One query, the unit the wall clock and callgrind (`--toggle-collect=*measured_plan*`)
/// measure: `Planner::plan` with A* and the goal's heading fixed, no work budget.
#[inline(never)]
fn measured_plan(p: &mut BenchPlanner, q: &Query) -> Result<RouteSummary, PlanError> {
    p.plan(q, u64::MAX)
}

/// The post-processing of `skyroute plan`: shortcuts, then heading smoothing.
#[inline(never)]
fn measured_post(p: &mut BenchPlanner) -> Result<f32, PlanError> {
    p.shortcut(u64::MAX)?;
    p.smooth_headings(SMOOTHING_HEADINGS, u64::MAX)?;
    Ok(p.route_summary().map_or(f32::NAN, |s| s.length))
}

fn query(q: &PosePair) -> Query {
    Query {
        start: q.start,
        goal: Goal {
            position: q.goal.position,
            heading: Some(q.goal.heading),
        },
        search: Search::AStar,
    }
}

/// `plan NET.bin QUERIES.txt OUT.json [REPS]`: loads the network once, then per query runs
/// `REPS` times (default 11) the query, then the post-processing on its route, and records
/// the median over the runs of the query's time and of the query's and post-processing's
/// together, the first run's time, both lengths, the work counted and whether skyroute's
/// exact predicates find the final route clear (they always should).
pub fn plan(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let world = World::new(network(&bytes)?);
    let text = String::from_utf8_lossy(&read(args.get(1, "queries")?)?).into_owned();
    let pairs = queries::from_text(&text).ok_or("queries: malformed line")?;
    let reps: usize = args.parse_or(3, "reps", 11)?.max(1);
    let mut p: Box<BenchPlanner> = Box::new(Planner::new());
    p.load(&bytes).map_err(|e| format!("load: {e:?}"))?;
    let mut rows = Vec::new();
    let (mut plan_s, mut total_s) = (Vec::new(), Vec::new());
    for (i, pair) in pairs.iter().enumerate() {
        let q = query(pair);
        let (mut t_plan, mut t_total) = (Vec::new(), Vec::new());
        let mut outcome = Err(PlanError::NoRoute);
        let (mut final_len, mut clear) = (f32::NAN, None);
        for _ in 0..reps {
            let t0 = Instant::now();
            outcome = measured_plan(&mut p, &q);
            let planned = t0.elapsed().as_secs_f64();
            t_plan.push(planned);
            let t1 = Instant::now();
            let post = outcome.and_then(|_| measured_post(&mut p));
            t_total.push(planned + t1.elapsed().as_secs_f64());
            if let Ok(l) = post {
                final_len = l;
                clear = Some(
                    p.route_paths()
                        .iter()
                        .all(|path| !world.path_conflicts(path)),
                );
            }
        }
        let med = stats::median(&t_plan);
        plan_s.push(med);
        total_s.push(stats::median(&t_total));
        rows.push(json!({
            "query": i,
            "solved": outcome.is_ok(),
            "error": outcome.err().map(|e| format!("{e:?}")),
            "planned_length_m": outcome.ok().map(|s| s.length),
            "final_length_m": outcome.ok().map(|_| final_len),
            "exactly_clear": clear,
            "work": outcome.ok().map(|s| s.work.total()),
            "plan_median_s": med,
            "plan_first_s": t_plan[0],
            "plan_and_post_median_s": stats::median(&t_total),
        }));
    }
    let solved = rows.iter().filter(|r| r["solved"] == true).count();
    let summary = json!({
        "queries": pairs.len(),
        "solved": solved,
        "reps": reps,
        "plan_s": {"median": stats::median(&plan_s), "p90": stats::quantile(&plan_s, 0.9),
                   "max": stats::max(&plan_s)},
        "plan_and_post_s": {"median": stats::median(&total_s),
                            "p90": stats::quantile(&total_s, 0.9), "max": stats::max(&total_s)},
    });
    write_json(
        args.get(2, "output")?,
        &json!({"summary": summary, "queries": Value::Array(rows)}),
    )
}

/// One motion of an OMPL route: its start state and the Dubins word and piece lengths that
/// OMPL's `DubinsStateSpace::dubins` chose for it.
struct Motion {
    start: Pose,
    word: DubinsWord,
    lengths: [f32; 3],
}

/// One OMPL route: its header fields (query, planner, kind, motions) and its motions.
struct Route {
    header: Vec<String>,
    motions: Vec<Motion>,
}

fn word(name: &str) -> Option<DubinsWord> {
    DubinsWord::ALL.into_iter().find(|w| w.name() == name)
}

/// Parses the C++ program's routes file: a header line `route QUERY PLANNER KIND MOTIONS`,
/// then one line `x y heading WORD l0 l1 l2` per motion.
fn parse_routes(text: &str) -> Result<Vec<Route>, String> {
    let mut out: Vec<Route> = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let t: Vec<&str> = line.split_whitespace().collect();
        if t[0] == "route" {
            out.push(Route {
                header: t[1..].iter().map(|s| s.to_string()).collect(),
                motions: Vec::new(),
            });
            continue;
        }
        let bad = || format!("routes: malformed motion line {line:?}");
        let num = |k: usize| {
            t.get(k)
                .and_then(|s| s.parse::<f64>().ok())
                .map(|x| x as f32)
        };
        let (Some(x), Some(y), Some(h), Some(w)) = (num(0), num(1), num(2), t.get(3)) else {
            return Err(bad());
        };
        let (Some(l0), Some(l1), Some(l2)) = (num(4), num(5), num(6)) else {
            return Err(bad());
        };
        let motion = Motion {
            start: Pose::new(x, y, h),
            word: word(w).ok_or_else(bad)?,
            lengths: [l0, l1, l2],
        };
        out.last_mut().ok_or_else(bad)?.motions.push(motion);
    }
    Ok(out)
}

/// `check NET.bin ROUTES.txt OUT.json`: flies every OMPL route as the chain of its Dubins
/// motions (forward, in the order of the states) and checks each motion with skyroute's exact
/// predicates against the network's obstacles and clearance. Records per route whether it
/// conflicts, how many motions do, and how far a motion's end lies from the next motion's
/// start (a consistency check of the file).
pub fn check(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let world = World::new(network(&bytes)?);
    let text = String::from_utf8_lossy(&read(args.get(1, "routes")?)?).into_owned();
    let radius = world.net.turn_radius();
    let mut rows = Vec::new();
    for Route { header, motions } in parse_routes(&text)? {
        let (mut conflicts, mut gap) = (0usize, 0.0f32);
        for (k, m) in motions.iter().enumerate() {
            let path = DubinsPath {
                start: m.start,
                radius,
                word: m.word,
                lengths: m.lengths,
            };
            if world.path_conflicts(&path) {
                conflicts += 1;
            }
            if let Some(next) = motions.get(k + 1) {
                gap = gap.max(path.end().position.distance(next.start.position));
            }
        }
        rows.push(json!({
            "route": header,
            "motions": motions.len(),
            "conflicting_motions": conflicts,
            "max_joint_gap_m": gap,
        }));
    }
    write_json(args.get(2, "output")?, &Value::Array(rows))
}
