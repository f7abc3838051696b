//! The two ways a waypoint without a heading gets one, side by side on a mission: skyroute's
//! default (the cheapest chain over 36 heading copies) and Niendorf et al.'s (the heading with
//! the most clear out-edges, `plan --free-headings paper`). For each rule: the mission's length
//! and core queries, then its robustness: for every leg leaving a waypoint (every leg but the
//! first; on the urban mission every waypoint is free), a pop-up disc of
//! `RADIUS_M` is placed `d` metres straight ahead of the waypoint along the heading the rule
//! gave it, and the leg is re-planned from that pose to its end (free arrival heading) with the
//! onboard core. Reported: how many re-plans find a route, and their mean detour over the same
//! query without the pop-up.
//!
//! `cargo run --release -p skyroute-prep --example free_heading_study -- scenarios/niendorf-urban.geojson`
use skyroute::planner::{Goal, Query, Search};
use skyroute::{Planner, Popup, Pose, Vec2};
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::mission::{
    plan_mission_with, CompactHostPlanner, FreeHeadingRule, Mission, MissionOptions, PLANNER_STACK,
};
use skyroute_prep::scenario;

/// The pop-up's radius, metres.
const RADIUS_M: f32 = 100.0;
/// Distances ahead of the waypoint of the pop-up's centre, metres.
const AHEAD_M: [f32; 3] = [150.0, 250.0, 400.0];

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: free_heading_study SCENARIO");
    let s = scenario::load(path.as_ref()).expect("scenario");
    let built = build(&s, &BuildOptions::default(), &|_, _| {}).expect("build");
    let frame = s.local_frame();
    let bytes = built.bytes;
    std::thread::Builder::new()
        .stack_size(PLANNER_STACK)
        .spawn(move || {
            println!("| rule | mission length (m) | core queries | re-plans with a pop-up ahead that route (150 / 250 / 400 m ahead) | mean detour (m) |");
            println!("|---|---:|---:|---:|---:|");
            for (name, rule) in [
                ("cheapest (default)", FreeHeadingRule::Cheapest),
                ("paper: most clear out-edges", FreeHeadingRule::MostClearOutEdges),
            ] {
                let options = MissionOptions {
                    free_headings: rule,
                    ..MissionOptions::default()
                };
                let m = plan_mission_with(&bytes, &s, &frame, &[], &options).expect("mission");
                let (routed, tried, detour) = robustness(&bytes, &m);
                let per: Vec<String> = routed.iter().map(|r| r.to_string()).collect();
                println!(
                    "| {name} | {:.1} | {} | {} of {tried} ({}) | {:.1} |",
                    m.length,
                    m.queries,
                    routed.iter().sum::<usize>(),
                    per.join(" / "),
                    detour
                );
            }
        })
        .expect("thread")
        .join()
        .expect("study");
}

/// Re-plans every leg that leaves a waypoint (not the start) with a pop-up ahead of it, at each
/// of [`AHEAD_M`]: returns the re-plans that found a route per distance, those tried, and their
/// mean detour (negative when the pop-up's blocked edges let the connection take candidates that
/// happen to be better).
fn robustness(bytes: &[u8], m: &Mission) -> ([usize; AHEAD_M.len()], usize, f64) {
    let mut p: Box<CompactHostPlanner> = Box::new(Planner::new());
    p.load(bytes).expect("network");
    let (mut routed, mut tried, mut detour) = ([0; AHEAD_M.len()], 0, 0.0);
    for leg in m.legs.iter().skip(1) {
        let (Some(first), Some(last)) = (leg.primitives.first(), leg.primitives.last()) else {
            continue;
        };
        let start: Pose = first.pose_at(0.0);
        let query = Query {
            start,
            goal: Goal {
                position: last.pose_at(last.length()).position,
                heading: None,
            },
            search: Search::AStar,
        };
        let Ok(clear) = p.plan(&query, u64::MAX) else {
            continue;
        };
        for (k, d) in AHEAD_M.into_iter().enumerate() {
            let centre = start.position + Vec2::from_angle(start.heading) * d;
            let id = p
                .add_popup(Popup::Circle {
                    centre,
                    radius: RADIUS_M,
                })
                .expect("pop-up")
                .id;
            tried += 1;
            if let Ok(r) = p.plan(&query, u64::MAX) {
                routed[k] += 1;
                detour += (r.length - clear.length) as f64;
            }
            p.remove_popup(id).expect("remove");
        }
    }
    let n: usize = routed.iter().sum();
    (routed, tried, detour / n.max(1) as f64)
}
