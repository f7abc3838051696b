//! Voronoi networks (Judd & McLain): the host plans start → goal, adds a radar that pops up in
//! flight (`add_threat`), and re-plans from a pose further along the first route, exactly as
//! the `voronoi` firmware will, with the firmware's own planner type; `query.rs` records the
//! query, the threat, every answer and the work bounds.
//!
//! The start pose and goal are the scenario's (`--scenario FILE`: its start and goal, with
//! their compass headings, in the network's local frame, as `skyroute plan` takes them;
//! waypoints are ignored), or `--start x,y,heading` and `--goal x,y[,heading]` in local metres.
//! The threat is `--threat x,y,r`, or by default a radar of reference distance
//! [`DEFAULT_THREAT_RADIUS_M`] (`--threat-on-route r` to change it) on the middle of the
//! longest straight piece of the first route. The re-plan starts where the aircraft is after
//! flying `--replan-after m` ([`DEFAULT_REPLAN_AFTER_M`]) along the first route's pieces
//! ([`pose_along`]).

use super::{lit, write_fixture, Args, FLASH_BYTES, P_CAP, RAM_BYTES};
use skyroute::geometry::spline::Piece;
use skyroute::network::Network;
use skyroute::planner::{
    threat_rebuild_work_bound, RouteSummary, ThreatSummary, VoronoiStorage, VORONOI_GRAPH_EDGES,
    VORONOI_GRAPH_VERTICES,
};
use skyroute::{Goal, Planner, Pose, Query, Search, Vec2};
use std::fmt::Write as _;

/// Search-state capacity of the firmware's planner: the graph's bound for any Voronoi network
/// (`VORONOI_GRAPH_VERTICES`), rounded up to a multiple of 64.
const V_CAP: usize = VORONOI_GRAPH_VERTICES.next_multiple_of(64);
/// Edge capacity: every half-edge the graph of any Voronoi network can store, rounded up to a
/// multiple of 256.
const E_CAP: usize = (2 * VORONOI_GRAPH_EDGES).next_multiple_of(256);
/// Route chords the firmware's planner holds (`Planner::route`).
const R_CAP: usize = 256;

/// The firmware's planner type, used on the host too so that both run the same code.
type FirmwarePlanner<'n> = Planner<'n, V_CAP, E_CAP, P_CAP, R_CAP>;

/// The pop-up radar's reference distance by default, metres.
pub(super) const DEFAULT_THREAT_RADIUS_M: f32 = 3000.0;
/// How far along the first route the re-plan starts by default, metres.
pub(super) const DEFAULT_REPLAN_AFTER_M: f32 = 5000.0;

/// What one plan answered: the figures the firmware compares.
#[derive(Clone, Copy, Debug)]
struct Answer {
    summary: RouteSummary,
    /// Smoothed pieces (`Planner::route_pieces`).
    pieces: usize,
    /// Line chords (`Planner::route`).
    chords: usize,
}

/// Everything the host computed, in the firmware's order.
struct VoronoiPlan {
    budget: u64,
    first: Answer,
    threat: (f32, f32, f32),
    added: ThreatSummary,
    replan_start: Pose,
    replan: Answer,
    /// Threat sites of the network (the diagram `load_voronoi` builds).
    sites: u32,
    /// `size_of::<VoronoiStorage>()` on the host.
    storage_bytes: usize,
}

/// The start pose and goal: `--start`/`--goal` when given, else the scenario's.
fn endpoints(args: &Args, network: &Network<'_>) -> Result<(Pose, Goal), String> {
    let scenario = match &args.scenario {
        Some(path) => Some(
            skyroute_prep::scenario::load(path).map_err(|e| format!("{}: {e}", path.display()))?,
        ),
        None => None,
    };
    let frame = skyroute_prep::export::network_frame(network);
    let start = match (args.start, &scenario) {
        (Some(s), _) => s,
        (None, Some(sc)) => {
            let s = sc.start.as_ref().ok_or("the scenario has no start")?;
            skyroute_prep::local::local_pose(&frame, s.lon, s.lat, s.heading_deg)
        }
        (None, None) => return Err("a Voronoi network needs --scenario or --start".into()),
    };
    let goal = match (args.goal, &scenario) {
        (Some(g), _) => g,
        (None, Some(sc)) => {
            let g = sc.goal.as_ref().ok_or("the scenario has no goal")?;
            Goal {
                position: skyroute_prep::local::local(&frame, g.lon, g.lat),
                heading: g
                    .heading_deg
                    .map(|h| skyroute_prep::local::local_heading(&frame, g.lon, g.lat, h)),
            }
        }
        (None, None) => return Err("a Voronoi network needs --scenario or --goal".into()),
    };
    Ok((start, goal))
}

/// The pose after flying `distance` metres along `pieces` (the end of the route if it is
/// shorter): on a line piece the point at that distance, on a cubic piece its end (so that
/// the pose lies on the route exactly), with the route's heading there.
fn pose_along(pieces: &[Piece], distance: f32) -> Option<Pose> {
    let mut flown = 0.0f32;
    for piece in pieces {
        let length = piece.length();
        if flown + length >= distance {
            let t = match piece {
                Piece::Line { .. } => ((distance - flown) / length).clamp(0.0, 1.0),
                Piece::Cubic { .. } => 1.0,
            };
            let tangent = piece.tangent(t)?;
            return Some(Pose::new(
                piece.point(t).x,
                piece.point(t).y,
                tangent.y.atan2(tangent.x),
            ));
        }
        flown += length;
    }
    let last = pieces.last()?;
    let tangent = last.tangent(1.0)?;
    Some(Pose::new(
        last.end().x,
        last.end().y,
        tangent.y.atan2(tangent.x),
    ))
}

/// The middle of the longest line piece, the default pop-up radar's site.
fn longest_straight_middle(pieces: &[Piece]) -> Option<Vec2> {
    pieces
        .iter()
        .filter_map(|p| match p {
            Piece::Line { a, b } => Some((*a, *b)),
            Piece::Cubic { .. } => None,
        })
        .max_by(|x, y| x.0.distance(x.1).total_cmp(&y.0.distance(y.1)))
        .map(|(a, b)| (a + b) * 0.5)
}

/// One plan with the planner's own worst case as budget, and what it answered.
fn plan_once(
    planner: &mut FirmwarePlanner<'_>,
    query: &Query,
    budget: u64,
) -> Result<Answer, String> {
    let summary = planner
        .plan(query, budget)
        .map_err(|e| format!("plan {query:?}: {e}"))?;
    Ok(Answer {
        summary,
        pieces: planner.route_pieces().len(),
        chords: planner.route().len(),
    })
}

/// Plans as the firmware does: `load_voronoi`, plan start → goal with the worst-case budget,
/// `add_threat`, re-plan from the pose [`Args::replan_after`] metres along the first route.
fn plan_voronoi(bytes: &[u8], args: &Args, start: Pose, goal: Goal) -> Result<VoronoiPlan, String> {
    let mut storage = Box::new(VoronoiStorage::new());
    let mut planner: Box<FirmwarePlanner<'_>> = Box::new(Planner::new());
    planner
        .load_voronoi(bytes, &mut storage)
        .map_err(|e| format!("load_voronoi: {e}"))?;
    let sites = planner.threats().len() as u32;
    let budget = planner.worst_case_work();
    let query = Query {
        start,
        goal,
        search: Search::Dijkstra,
    };
    let first = plan_once(&mut planner, &query, budget)?;
    let pieces = planner.route_pieces().to_vec();
    let threat = match args.threat {
        Some(t) => t,
        None => {
            let r = args.threat_on_route.unwrap_or(DEFAULT_THREAT_RADIUS_M);
            let m = longest_straight_middle(&pieces).ok_or("the first route has no straight")?;
            (m.x, m.y, r)
        }
    };
    let added = planner
        .add_threat(Vec2::new(threat.0, threat.1), threat.2)
        .map_err(|e| format!("add_threat {threat:?}: {e}"))?;
    if planner.worst_case_work() != budget {
        return Err("the worst case changed with the threat: the firmware's budget is one".into());
    }
    let after = args.replan_after.unwrap_or(DEFAULT_REPLAN_AFTER_M);
    let replan_start = pose_along(&pieces, after).ok_or("the first route has no pieces")?;
    let replan_query = Query {
        start: replan_start,
        ..query
    };
    let replan = plan_once(&mut planner, &replan_query, budget)?;
    Ok(VoronoiPlan {
        budget,
        first,
        threat,
        added,
        replan_start,
        replan,
        sites,
        storage_bytes: std::mem::size_of::<VoronoiStorage>(),
    })
}

/// A Voronoi network's fixture: plans with [`plan_voronoi`], reports it, and writes
/// `OUT_DIR/network.bin` and `OUT_DIR/query.rs`.
pub(super) fn run_voronoi(
    args: &Args,
    bytes: &[u8],
    source: &str,
    network: &Network<'_>,
) -> Result<(), String> {
    if args.popup.is_some() || args.popup_on_route.is_some() {
        return Err(format!(
            "{source}: a Voronoi fixture adds a threat (--threat, --threat-on-route), not a pop-up"
        ));
    }
    Network::from_bytes_with_capacity(bytes, V_CAP, E_CAP)
        .map_err(|e| format!("{source}: does not load with V={V_CAP} E={E_CAP}: {e}"))?;
    let (start, goal) = endpoints(args, network)?;
    let plan = plan_voronoi(bytes, args, start, goal).map_err(|e| format!("{source}: {e}"))?;
    report(source, network, bytes.len(), start, goal, &plan);
    let q = query_rs(source, start, goal, &plan);
    write_fixture(&args.out_dir, Some(bytes), &q)
}

/// The host's answers on stderr.
fn report(
    source: &str,
    network: &Network<'_>,
    len: usize,
    start: Pose,
    goal: Goal,
    p: &VoronoiPlan,
) {
    let ram = std::mem::size_of::<FirmwarePlanner<'static>>() + p.storage_bytes;
    eprintln!(
        "firmware_fixture: {source}: Voronoi network, {} threat sites, {} vertices, {} edges, \
         {len} bytes",
        p.sites,
        network.vertex_count(),
        network.edge_count()
    );
    eprintln!("firmware_fixture: start {start:?}\n  goal {goal:?}");
    let answer = |what: &str, a: &Answer| {
        eprintln!(
            "firmware_fixture: {what}: route {} m, {} pieces, {} chords, {} network edges, work {} \
             of {}",
            a.summary.length,
            a.pieces,
            a.chords,
            a.summary.network_edges,
            a.summary.work.total(),
            p.budget
        );
    };
    answer("plan", &p.first);
    eprintln!(
        "firmware_fixture: add_threat {:?}: {:?} (bound {})",
        p.threat,
        p.added,
        threat_rebuild_work_bound(p.added.threats as u64)
    );
    eprintln!("firmware_fixture: re-plan from {:?}", p.replan_start);
    answer("re-plan", &p.replan);
    eprintln!(
        "firmware_fixture: capacities V={V_CAP} E={E_CAP} P={P_CAP} R={R_CAP}: planner + storage \
         ≈ {ram} B of RAM on this host ({} B storage)",
        p.storage_bytes
    );
    if ram > RAM_BYTES * 3 / 4 {
        eprintln!("firmware_fixture: warning: ≈{ram} B is over three quarters of the STM32F405's 128 KiB RAM (the larger target, mps2-an500, has 1 MiB)");
    }
    if len > FLASH_BYTES * 7 / 8 {
        eprintln!("firmware_fixture: warning: the {len} B image leaves little of the 1 MiB flash");
    }
}

/// The constants of one answer, prefixed `prefix`.
fn answer_rs(w: &mut String, prefix: &str, what: &str, a: &Answer) {
    let s = &a.summary;
    let _ = writeln!(w, "/// {what}: route length the host computed, metres.");
    let _ = writeln!(w, "pub const {prefix}_LENGTH: f32 = {};", lit(s.length));
    let _ = writeln!(w, "/// {what}: smoothed pieces (`Planner::route_pieces`).");
    let _ = writeln!(w, "pub const {prefix}_PIECES: u32 = {};", a.pieces);
    let _ = writeln!(w, "/// {what}: line chords (`Planner::route`).");
    let _ = writeln!(w, "pub const {prefix}_CHORDS: u32 = {};", a.chords);
    let _ = writeln!(w, "/// {what}: graph edges and links of the coarse route.");
    let _ = writeln!(
        w,
        "pub const {prefix}_NETWORK_EDGES: u32 = {};",
        s.network_edges
    );
    let _ = writeln!(w, "/// {what}: work the host counted.");
    let _ = writeln!(w, "pub const {prefix}_WORK: u64 = {};", s.work.total());
}

/// `query.rs`: capacities, query, threat, the host's answers and the bounds.
fn query_rs(source: &str, start: Pose, goal: Goal, p: &VoronoiPlan) -> String {
    let mut q = String::new();
    let w = &mut q;
    let _ = writeln!(
        w,
        "// Generated by host-tests/src/bin/firmware_fixture/ from {source} (a Voronoi network). \
         Do not edit.\n"
    );
    let _ = writeln!(
        w,
        "/// Search-state capacity of the planner (≥ `VORONOI_GRAPH_VERTICES` = {VORONOI_GRAPH_VERTICES})."
    );
    let _ = writeln!(w, "pub const V_CAP: usize = {V_CAP};");
    let _ = writeln!(
        w,
        "/// Edge capacity of the planner (any Voronoi network's half-edges)."
    );
    let _ = writeln!(w, "pub const E_CAP: usize = {E_CAP};");
    let _ = writeln!(w, "/// Pop-up slots of the planner.");
    let _ = writeln!(w, "pub const P_CAP: usize = {P_CAP};");
    let _ = writeln!(w, "/// Route chords the planner holds.");
    let _ = writeln!(w, "pub const R_CAP: usize = {R_CAP};");
    let pose = |w: &mut String, name: &str, doc: &str, s: Pose| {
        let _ = writeln!(w, "/// {doc}");
        let _ = writeln!(
            w,
            "pub const {name}: skyroute::Pose = skyroute::Pose::new({}, {}, {});",
            lit(s.position.x),
            lit(s.position.y),
            lit(s.heading)
        );
    };
    pose(
        w,
        "START",
        "The aircraft's pose when it first plans.",
        start,
    );
    let heading = goal
        .heading
        .map_or("None".to_string(), |h| format!("Some({})", lit(h)));
    let _ = writeln!(w, "/// Where to go.");
    let _ = writeln!(
        w,
        "pub const GOAL: skyroute::Goal = skyroute::Goal {{\n    position: skyroute::Vec2::new({}, {}),\n    heading: {heading},\n}};",
        lit(goal.position.x),
        lit(goal.position.y)
    );
    let _ = writeln!(
        w,
        "/// Work budget of every plan: the network's worst case (`Planner::worst_case_work`)."
    );
    let _ = writeln!(w, "pub const BUDGET: u64 = {};", p.budget);
    answer_rs(w, "EXPECTED", "First plan", &p.first);
    let _ = writeln!(
        w,
        "/// The radar that pops up in flight: site x, y and reference distance (metres)."
    );
    let _ = writeln!(
        w,
        "pub const THREAT: (f32, f32, f32) = ({}, {}, {});",
        lit(p.threat.0),
        lit(p.threat.1),
        lit(p.threat.2)
    );
    let a = &p.added;
    let _ = writeln!(w, "/// What the host's `add_threat` answered.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_THREAT: skyroute::planner::ThreatSummary = \
         skyroute::planner::ThreatSummary {{\n    id: {},\n    threats: {},\n    graph: ({}, {}),\n    work: {},\n}};",
        a.id, a.threats, a.graph.0, a.graph.1, a.work
    );
    let _ = writeln!(
        w,
        "/// `threat_rebuild_work_bound` of the network's {} sites (the diagram `load_voronoi` builds).",
        p.sites
    );
    let _ = writeln!(
        w,
        "pub const LOAD_DIAGRAM_BOUND: u64 = {};",
        threat_rebuild_work_bound(p.sites as u64)
    );
    let _ = writeln!(
        w,
        "/// `threat_rebuild_work_bound` of the {} threats after `add_threat`.",
        a.threats
    );
    let _ = writeln!(
        w,
        "pub const THREAT_BOUND: u64 = {};",
        threat_rebuild_work_bound(a.threats as u64)
    );
    pose(
        w,
        "REPLAN_START",
        "The pose the re-plan starts from: a few km along the first route.",
        p.replan_start,
    );
    answer_rs(w, "REPLAN", "Re-plan after the threat", &p.replan);
    q
}
