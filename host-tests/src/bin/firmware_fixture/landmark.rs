//! Landmark networks (Babel): the host plans from the network's stored start to its stored
//! goal in weather 0, loses the first landmark the route overflies (`update_rosette` with
//! all-zero qualities) and plans again, then plans from a pose that is no network vertex
//! (halfway along the re-plan's first edge, joined online with
//! [`ONLINE_RANGE_SHARE`] of the start's range left), as the `landmark` firmware will;
//! `query.rs` records the three answers.

use super::{
    capacity, lit, planner_bytes, write_fixture, Args, HostPlanner, FLASH_BYTES, HOST_E, HOST_V,
    P_CAP, RAM_BYTES, R_CAP,
};
use skyroute::planner::{PlanError, RouteSummary};
use skyroute::{Goal, Network, Query, Search};
use std::fmt::Write as _;

/// What the host planned on a landmark network, as the firmware will.
struct LandmarkPlan {
    budget: u64,
    /// Plan from the stored start to the stored goal in weather [`LANDMARK_WEATHER`].
    first: RouteSummary,
    first_edges: Vec<u32>,
    /// The landmark lost in flight: the first one the route overflies.
    lost: u32,
    /// The plan after losing it.
    replan: Result<RouteSummary, PlanError>,
    replan_edges: Vec<u32>,
    /// The online start `(x, y, heading)` and its range left, metres.
    online_start: ((f32, f32, f32), f32),
    /// The plan from it, the landmark still lost.
    online: Result<RouteSummary, PlanError>,
}

/// The share of the stored start's range left at the online start.
const ONLINE_RANGE_SHARE: f32 = 0.8;

/// The weather the landmark firmware plans in.
const LANDMARK_WEATHER: u32 = 0;

/// The landmark query: the network's stored start pose to its stored goal's position, free
/// heading, Dijkstra (as `host-tests/tests/landmark_plan.rs` builds it).
fn landmark_query(network: &Network<'_>) -> Result<Query, String> {
    let l = network.landmark().ok_or("not a landmark network")?;
    let start = network
        .vertex(l.start_vertex)
        .ok_or("the landmark network has no stored start")?;
    let goal = network
        .vertex(l.goal_vertex)
        .ok_or("the landmark network has no stored goal")?;
    Ok(Query {
        start,
        goal: Goal {
            position: goal.position,
            heading: None,
        },
        search: Search::Dijkstra,
    })
}

/// Plans on a landmark network exactly as the firmware does: load, `set_weather`, plan with
/// the worst-case budget, lose the first landmark overflown, plan again.
fn plan_landmark(bytes: &[u8]) -> Result<LandmarkPlan, String> {
    let mut planner = HostPlanner::new();
    planner.load(bytes).map_err(|e| format!("load: {e}"))?;
    let network = *planner.network();
    let l = *network.landmark().ok_or("not a landmark network")?;
    planner
        .set_weather(LANDMARK_WEATHER)
        .map_err(|e| format!("set_weather({LANDMARK_WEATHER}): {e}"))?;
    let query = landmark_query(&network)?;
    let budget = planner.worst_case_work();
    let first = planner
        .plan(&query, budget)
        .map_err(|e| format!("no route in weather {LANDMARK_WEATHER}: {e}"))?;
    let first_edges = planner.route_edges().to_vec();
    let overflights = l.landmark_count * l.directions;
    let lost = first_edges
        .iter()
        .filter_map(|&e| network.edge_link(e))
        .find(|r| r.target < overflights)
        .map(|r| r.target / l.directions)
        .ok_or("the route overflies no landmark")?;
    let zeros = vec![0.0f32; l.directions as usize];
    planner
        .update_rosette(lost, &zeros)
        .map_err(|e| format!("update_rosette({lost}): {e}"))?;
    let replan = planner.plan(&query, budget);
    let replan_edges = match replan {
        Ok(_) => planner.route_edges().to_vec(),
        Err(_) => Vec::new(),
    };
    // On the re-plan's route when there is one: it avoids the lost landmark.
    let first_edge = *replan_edges
        .first()
        .or(first_edges.first())
        .ok_or("the route has no edge")?;
    let piece = network
        .chain_piece(first_edge, network.chain_piece_count(first_edge) / 2)
        .ok_or("the first edge's middle piece does not rebuild")?;
    let t = piece.t_max() * 0.5;
    let (at, v) = piece
        .position(t)
        .zip(piece.velocity(t))
        .ok_or("the middle piece does not evaluate")?;
    let pose = (at.x, at.y, v.y.atan2(v.x));
    let range = l.start_range_m * ONLINE_RANGE_SHARE;
    planner
        .set_start_range(range)
        .map_err(|e| format!("set_start_range({range}): {e}"))?;
    let online_query = Query {
        start: skyroute::Pose::new(pose.0, pose.1, pose.2),
        ..query
    };
    let online = planner.plan(&online_query, budget);
    Ok(LandmarkPlan {
        budget,
        first,
        first_edges,
        lost,
        replan,
        replan_edges,
        online_start: (pose, range),
        online,
    })
}

/// The overflights along `edges`: `L<landmark>@<compass>°→<leg> m`, and the goal leg.
fn describe_landmark_route(network: &Network<'_>, edges: &[u32]) -> String {
    let Some(l) = network.landmark() else {
        return String::new();
    };
    let mut out = Vec::new();
    for &e in edges {
        let Some(r) = network.edge_link(e) else {
            continue;
        };
        if r.source == l.start_vertex {
            out.push(format!("start→{} m", r.cost));
        } else if r.source < l.landmark_count * l.directions {
            let (lm, k) = (r.source / l.directions, r.source % l.directions);
            out.push(format!(
                "L{lm}@{}°→{} m",
                360 * k / l.directions.max(1),
                r.cost
            ));
        }
    }
    out.join(", ")
}

/// A landmark network's fixture: the search states are the vertices (`V` ≥ vertex count; no
/// extra search states, unlike terrain), `E` ≥ edge count; the host plans the stored start →
/// goal query and the re-plan after a landmark is lost, and `query.rs` records both.
pub(super) fn run_landmark(
    args: &Args,
    bytes: &[u8],
    source: &str,
    network: &Network<'_>,
) -> Result<(), String> {
    if args.start.is_some()
        || args.goal.is_some()
        || args.popup.is_some()
        || args.popup_on_route.is_some()
    {
        return Err(format!(
            "{source}: a landmark network plans from its stored start to its stored goal; \
             --start, --goal, --popup and --popup-on-route do not apply"
        ));
    }
    let (nv, ne) = (network.vertex_count(), network.edge_count());
    let l = *network.landmark().ok_or("not a landmark network")?;
    let (v_cap, e_cap) = (capacity(nv, 64), capacity(ne, 256));
    // The very check the firmware's `Planner::load` makes (landmark mode adds none).
    Network::from_bytes_with_capacity(bytes, v_cap, e_cap)
        .map_err(|e| format!("{source}: does not load with V={v_cap} E={e_cap}: {e}"))?;
    if nv as usize > HOST_V || ne as usize > HOST_E {
        return Err(format!(
            "{source}: {nv} vertices / {ne} edges exceed the host planner's {HOST_V} / {HOST_E}"
        ));
    }
    // The capacities only gate `load`: the search, its work count and the route do not depend
    // on them, so the host planner's generous ones give the firmware's answer.
    let plan = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn({
            let bytes = bytes.to_vec();
            move || plan_landmark(&bytes)
        })
        .map_err(|e| format!("spawning the planning thread: {e}"))?
        .join()
        .map_err(|_| "the planning thread panicked".to_string())??;
    let LandmarkPlan {
        budget,
        first,
        first_edges,
        lost,
        replan,
        replan_edges,
        online_start,
        online,
    } = plan;
    if first_edges.len() > R_CAP {
        return Err(format!(
            "{source}: the route has {} edges, more than R_CAP = {R_CAP}",
            first_edges.len()
        ));
    }

    let ram = planner_bytes(v_cap, e_cap);
    eprintln!(
        "firmware_fixture: {source}: landmark network, {} landmarks × {} directions, {} weathers, \
         {nv} vertices, {ne} edges, {} line elements, {} bytes",
        l.landmark_count,
        l.directions,
        l.weather_count,
        l.element_count,
        bytes.len()
    );
    eprintln!(
        "firmware_fixture: weather {LANDMARK_WEATHER}: route {} m, {} edges, {} pieces, work {} \
         of {budget}\n  {}",
        first.length,
        first.network_edges,
        first.primitives,
        first.work.total(),
        describe_landmark_route(network, &first_edges)
    );
    match &replan {
        Ok(s) => eprintln!(
            "firmware_fixture: landmark {lost} lost: route {} m, {} edges, {} pieces, work {}\n  {}",
            s.length,
            s.network_edges,
            s.primitives,
            s.work.total(),
            describe_landmark_route(network, &replan_edges)
        ),
        Err(e) => eprintln!("firmware_fixture: landmark {lost} lost: no route: {e}"),
    }
    match &online {
        Ok(s) => eprintln!(
            "firmware_fixture: online start {:?} with {} m left: route {} m, {} edges, work {}",
            online_start.0,
            online_start.1,
            s.length,
            s.network_edges,
            s.work.total()
        ),
        Err(e) => eprintln!("firmware_fixture: online start {online_start:?}: no route: {e}"),
    }
    eprintln!("firmware_fixture: capacities V={v_cap} E={e_cap} P={P_CAP} R={R_CAP}: planner ≈ {ram} B of RAM");
    if ram > RAM_BYTES * 3 / 4 {
        eprintln!("firmware_fixture: warning: the planner needs ≈{ram} B, over three quarters of the STM32F405's 128 KiB RAM (the larger target, mps2-an500, has 1 MiB)");
    }
    if bytes.len() > FLASH_BYTES * 7 / 8 {
        eprintln!(
            "firmware_fixture: warning: the {} B image leaves little of the 1 MiB flash",
            bytes.len()
        );
    }

    let q = query_rs(
        source,
        (nv, ne),
        (v_cap, e_cap),
        budget,
        &first,
        lost,
        &replan,
        (online_start, &online),
    );

    write_fixture(&args.out_dir, Some(bytes), &q)
}

/// The online start and the host's plan from it.
type OnlinePlan<'a> = (((f32, f32, f32), f32), &'a Result<RouteSummary, PlanError>);

/// `query.rs` of a landmark network: capacities, weather, the host's answer, the budget, the
/// landmark lost, the re-plan, and the online start with its plan.
#[allow(clippy::too_many_arguments)]
fn query_rs(
    source: &str,
    (nv, ne): (u32, u32),
    (v_cap, e_cap): (usize, usize),
    budget: u64,
    first: &RouteSummary,
    lost: u32,
    replan: &Result<RouteSummary, PlanError>,
    (((x, y, heading), range), online): OnlinePlan<'_>,
) -> String {
    let mut q = String::new();
    let w = &mut q;
    let _ = writeln!(
        w,
        "// Generated by host-tests/src/bin/firmware_fixture/ from {source} (a landmark network). \
         Do not edit.\n"
    );
    let _ = writeln!(
        w,
        "/// Search-state capacity of the planner: the {nv} vertices (landmark mode searches \
         vertices)."
    );
    let _ = writeln!(w, "pub const V_CAP: usize = {v_cap};");
    let _ = writeln!(w, "/// Edge capacity of the planner ({ne} in the network).");
    let _ = writeln!(w, "pub const E_CAP: usize = {e_cap};");
    let _ = writeln!(w, "/// Pop-up slots of the planner.");
    let _ = writeln!(w, "pub const P_CAP: usize = {P_CAP};");
    let _ = writeln!(w, "/// Route edges (and primitives) the planner holds.");
    let _ = writeln!(w, "pub const R_CAP: usize = {R_CAP};");
    let _ = writeln!(w, "/// The weather in force (`Planner::set_weather`).");
    let _ = writeln!(w, "pub const WEATHER: u32 = {LANDMARK_WEATHER};");
    let _ = writeln!(
        w,
        "/// Route length the host computed, stored start → stored goal, metres."
    );
    let _ = writeln!(w, "pub const EXPECTED_LENGTH: f32 = {};", lit(first.length));
    let _ = writeln!(w, "/// Hermite pieces of that route.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_PRIMITIVES: u32 = {};",
        first.primitives
    );
    let _ = writeln!(w, "/// Network edges of that route.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_NETWORK_EDGES: u32 = {};",
        first.network_edges
    );
    let _ = writeln!(w, "/// Work the host counted.");
    let _ = writeln!(w, "pub const EXPECTED_WORK: u64 = {};", first.work.total());
    let _ = writeln!(
        w,
        "/// Work budget: the network's worst case (`Planner::worst_case_work`)."
    );
    let _ = writeln!(w, "pub const BUDGET: u64 = {budget};");
    let _ = writeln!(
        w,
        "/// The landmark lost in flight (all-zero rosette): the first one the route overflies."
    );
    let _ = writeln!(w, "pub const LOST_LANDMARK: u32 = {lost};");
    let replan_doc = match &replan {
        Ok(_) => "a route".to_string(),
        Err(e) => format!("no route ({e:?})"),
    };
    let _ = writeln!(
        w,
        "/// The re-plan after losing it, as the host found it: {replan_doc}. `Some((length m, \
         network edges, work))`, or `None` when `plan` fails."
    );
    let replan_value = answer_literal(replan);
    let _ = writeln!(
        w,
        "pub const EXPECTED_REPLAN: Option<(f32, u32, u64)> = {replan_value};"
    );
    let _ = writeln!(
        w,
        "/// A start that is no network vertex, `(x, y, heading)`: halfway along the re-plan's \
         first edge."
    );
    let _ = writeln!(
        w,
        "pub const ONLINE_START: (f32, f32, f32) = ({}, {}, {});",
        lit(x),
        lit(y),
        lit(heading)
    );
    let _ = writeln!(
        w,
        "/// The range left there (`Planner::set_start_range`), metres."
    );
    let _ = writeln!(w, "pub const ONLINE_RANGE: f32 = {};", lit(range));
    let online_value = answer_literal(online);
    let _ = writeln!(
        w,
        "/// The host's plan from it, the landmark still lost: `Some((length m, network edges, \
         work))`, or `None` when `plan` fails."
    );
    let _ = writeln!(
        w,
        "pub const EXPECTED_ONLINE: Option<(f32, u32, u64)> = {online_value};"
    );

    q
}

/// A plan's answer as `query.rs` writes it: `Some((length m, network edges, work))`, or `None`
/// when `plan` failed.
fn answer_literal(answer: &Result<RouteSummary, PlanError>) -> String {
    match answer {
        Ok(s) => format!(
            "Some(({}, {}, {}))",
            lit(s.length),
            s.network_edges,
            s.work.total()
        ),
        Err(_) => "None".to_string(),
    }
}
