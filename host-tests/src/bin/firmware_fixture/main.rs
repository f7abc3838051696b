//! Generates the fixture the `firmware-example` embeds: a network image and the query to plan
//! on it, with the route length the host computes with the same core code.
//!
//! ```text
//! firmware_fixture NETWORK.bin OUT_DIR [--start x,y,heading] [--goal x,y[,heading]]
//!     [--popup x,y,r | --popup-on-route r] [--altitudes zs,zg] [--popup-height h]
//! firmware_fixture --synthetic OUT_DIR [same options]
//! firmware_fixture LANDMARK-NETWORK.bin OUT_DIR
//! ```
//!
//! Writes `OUT_DIR/network.bin` (a copy of the image) and `OUT_DIR/query.rs` (constants the
//! firmware `include!`s). Headings are radians counter-clockwise from east. Defaults: start at
//! vertex 0's pose, goal at the position of the vertex farthest from it with a free heading, a
//! circular pop-up at their midpoint with a tenth of their distance as radius; when that has no
//! route, the next farthest goal, then the next start vertex (see [`choose`]). On a
//! three-dimensional roadmap the query flies from the altitude of the vertex nearest its start to
//! that of the vertex nearest its goal, and the pop-up reaches up to the middle of the vertices'
//! altitudes, unless `--altitudes` and `--popup-height` say otherwise ([`vertical`]).
//!
//! `--synthetic` builds a small grid network in place of the ground tool's output (for
//! development, and as the fallback while `skyroute build` does not exist).
//!
//! A landmark network (Babel) takes no query options: the firmware plans from the network's
//! stored start to its stored goal in weather 0, then loses the first landmark the route
//! overflies (`update_rosette` with all-zero qualities) and plans again; `query.rs` then holds
//! both answers of the host (see [`landmark::run_landmark`]).
//!
//! A Voronoi network (Judd & McLain) takes its start and goal from `--scenario FILE` (or
//! `--start`/`--goal`), and `--threat x,y,r | --threat-on-route r` and `--replan-after m`: the
//! firmware plans, adds the radar in flight and re-plans (see [`voronoi`]).
//!
//! ```text
//! firmware_fixture VORONOI-NETWORK.bin OUT_DIR (--scenario FILE | --start x,y,h --goal x,y[,h])
//!     [--threat x,y,r | --threat-on-route r] [--replan-after m]
//! ```
//!
//! `--ruz --scenario FILE` on a roadmap network built from that scenario (`ruz-popups`) writes
//! only `OUT_DIR/query.rs`: every pop-up's bypass alternatives' figures, a sequence of
//! announcements with the host's decisions, and a worst-case instance (see [`ruz`]).
//!
//! ```text
//! firmware_fixture RUZ-NETWORK.bin OUT_DIR --ruz --scenario FILE
//! ```

mod landmark;
mod ruz;
mod vertical;
mod voronoi;

use skyroute::geometry::predicates::{
    conflicts_with_polygon, point_in_polygon, point_segment_distance, PolygonView,
};
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec, ObstacleSpec};
use skyroute::network::Mode;
use skyroute::planner::{PlannerConfig, PopupSummary, RouteSummary, MAX_LINKS};
use skyroute::{DubinsPath, Goal, Network, Planner, Popup, Pose, Query, Search, Vec2};
use std::f32::consts::{FRAC_PI_2, PI};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Pop-up slots of the firmware's planner (written to `query.rs` as `P_CAP`).
const P_CAP: usize = 4;
/// Route primitives the firmware's planner holds (written to `query.rs` as `R_CAP`).
const R_CAP: usize = 128;
/// The host planner's vertex and edge capacities. They only gate `load` (the search, its work
/// count and the route do not depend on them), so the host uses generous ones and checks the
/// firmware's capacities separately with `Network::from_bytes_with_capacity`.
const HOST_V: usize = 1 << 16;
const HOST_E: usize = 1 << 20;
/// The firmware's RAM and flash (memory.x), for warnings.
const RAM_BYTES: usize = 128 * 1024;
const FLASH_BYTES: usize = 1024 * 1024;

type HostPlanner<'n> = Planner<'n, HOST_V, HOST_E, P_CAP, R_CAP>;

const USAGE: &str = "usage: firmware_fixture (NETWORK.bin | --synthetic) OUT_DIR \
[--start x,y,heading_rad] [--goal x,y[,heading_rad]] [--popup x,y,radius | --popup-on-route radius] \
[--altitudes start_m,goal_m] [--popup-height m] (3-D roadmap) [--scenario FILE] [--threat x,y,radius | --threat-on-route radius] [--replan-after m] (Voronoi) \
| --ruz --scenario FILE (the Ruz decision)";

#[derive(Debug, Default)]
struct Args {
    network: Option<PathBuf>,
    out_dir: PathBuf,
    start: Option<Pose>,
    goal: Option<Goal>,
    popup: Option<(f32, f32, f32)>,
    /// Radius of a pop-up centred on the middle of the longest straight of the route planned
    /// without it (so that it certainly changes the route).
    popup_on_route: Option<f32>,
    /// Voronoi: the scenario whose start and goal to plan between.
    scenario: Option<PathBuf>,
    /// Voronoi: the radar that pops up (x, y, reference distance).
    threat: Option<(f32, f32, f32)>,
    /// Voronoi: the pop-up radar's reference distance, on the first route's longest straight.
    threat_on_route: Option<f32>,
    /// Voronoi: metres flown along the first route before the re-plan.
    replan_after: Option<f32>,
    /// The Ruz decision's fixture (with `scenario`) instead of a route's.
    ruz: bool,
    /// Three-dimensional roadmap: the start's and goal's altitudes.
    altitudes: Option<(f32, f32)>,
    /// Three-dimensional roadmap: the pop-up's top.
    popup_height: Option<f32>,
}

fn floats(s: &str, what: &str, counts: &[usize]) -> Result<Vec<f32>, String> {
    let v = s
        .split(',')
        .map(|x| x.trim().parse::<f32>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| format!("{what}: {e} in {s:?}"))?;
    if !counts.contains(&v.len()) || v.iter().any(|x| !x.is_finite()) {
        return Err(format!(
            "{what}: expected {counts:?} finite numbers, got {s:?}"
        ));
    }
    Ok(v)
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args::default();
    let mut positional = Vec::new();
    let mut synthetic = false;
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match a.as_str() {
            "--synthetic" => synthetic = true,
            "--ruz" => args.ruz = true,
            "--start" => {
                let v = floats(&value("--start")?, "--start", &[3])?;
                args.start = Some(Pose::new(v[0], v[1], v[2]));
            }
            "--goal" => {
                let v = floats(&value("--goal")?, "--goal", &[2, 3])?;
                args.goal = Some(Goal {
                    position: Vec2::new(v[0], v[1]),
                    heading: v.get(2).copied(),
                });
            }
            "--popup" => {
                let v = floats(&value("--popup")?, "--popup", &[3])?;
                args.popup = Some((v[0], v[1], v[2]));
            }
            "--popup-on-route" => {
                let v = floats(&value("--popup-on-route")?, "--popup-on-route", &[1])?;
                args.popup_on_route = Some(v[0]);
            }
            "--altitudes" => {
                let v = floats(&value("--altitudes")?, "--altitudes", &[2])?;
                args.altitudes = Some((v[0], v[1]));
            }
            "--popup-height" => {
                let v = floats(&value("--popup-height")?, "--popup-height", &[1])?;
                args.popup_height = Some(v[0]);
            }
            "--scenario" => args.scenario = Some(PathBuf::from(value("--scenario")?)),
            "--threat" => {
                let v = floats(&value("--threat")?, "--threat", &[3])?;
                args.threat = Some((v[0], v[1], v[2]));
            }
            "--threat-on-route" => {
                let v = floats(&value("--threat-on-route")?, "--threat-on-route", &[1])?;
                args.threat_on_route = Some(v[0]);
            }
            "--replan-after" => {
                let v = floats(&value("--replan-after")?, "--replan-after", &[1])?;
                args.replan_after = Some(v[0]);
            }
            "-h" | "--help" => return Err(USAGE.into()),
            s if s.starts_with("--") => return Err(format!("unknown option {s}\n{USAGE}")),
            _ => positional.push(PathBuf::from(a)),
        }
    }
    match (synthetic, positional.as_slice()) {
        (true, [out]) => args.out_dir = out.clone(),
        (false, [net, out]) => {
            args.network = Some(net.clone());
            args.out_dir = out.clone();
        }
        _ => return Err(USAGE.into()),
    }
    Ok(args)
}

/// A 10 × 10 grid of positions 150 m apart, four headings each (400 poses less those an
/// obstacle removes), Dubins edges (turn radius 40 m) to the poses ahead within 400 m, and two
/// square obstacles.
fn synthetic_network() -> Result<Vec<u8>, String> {
    const N: usize = 10;
    const SPACING: f32 = 150.0;
    const RADIUS: f32 = 40.0;
    const CLEARANCE: f32 = 10.0;
    const REACH: f32 = 400.0;
    let square = |cx: f32, cy: f32, half: f32| {
        vec![
            Vec2::new(cx - half, cy - half),
            Vec2::new(cx + half, cy - half),
            Vec2::new(cx + half, cy + half),
            Vec2::new(cx - half, cy + half),
        ]
    };
    // One between grid points, one over grid point (7, 3) (its four poses are dropped).
    let obstacles = [square(375.0, 975.0, 60.0), square(1050.0, 450.0, 100.0)];
    let blocked = |p: Vec2| {
        obstacles.iter().any(|poly| {
            point_in_polygon(p, poly.as_slice())
                || (0..poly.len()).any(|i| {
                    poly.as_slice()
                        .edge(i)
                        .is_some_and(|e| point_segment_distance(p, &e) <= CLEARANCE)
                })
        })
    };

    let mut vertices = Vec::new();
    for iy in 0..N {
        for ix in 0..N {
            let (x, y) = (ix as f32 * SPACING, iy as f32 * SPACING);
            if blocked(Vec2::new(x, y)) {
                continue;
            }
            for k in 0..4 {
                vertices.push(Pose::new(x, y, k as f32 * FRAC_PI_2));
            }
        }
    }
    let mut edges = Vec::new();
    for (i, a) in vertices.iter().enumerate() {
        for (j, b) in vertices.iter().enumerate() {
            let d = b.position - a.position;
            let chord = d.norm();
            // Ahead within ±60°, not reversing the heading.
            if chord == 0.0 || chord > REACH || a.direction().dot(d) < 0.5 * chord {
                continue;
            }
            if (a.heading - b.heading).abs() == PI {
                continue;
            }
            let Some(path) = DubinsPath::shortest(a, b, RADIUS) else {
                continue;
            };
            if path.length() > chord + PI * RADIUS {
                continue; // a loop, not a useful edge
            }
            let clear = path.primitives().into_iter().flatten().all(|prim| {
                obstacles
                    .iter()
                    .all(|poly| !conflicts_with_polygon(&prim, poly.as_slice(), CLEARANCE))
            });
            if clear {
                edges.push(EdgeSpec::dubins(i as u32, j as u32, &path));
            }
        }
    }
    let spec = NetworkSpec {
        origin_lat_deg: 53.6373,
        origin_lon_deg: 9.9510,
        turn_radius_m: RADIUS,
        clearance_m: CLEARANCE,
        vertices,
        edges,
        obstacles: obstacles
            .iter()
            .map(|p| ObstacleSpec::Polygon(p.clone()))
            .collect(),
        grid_cell_m: 100.0,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    encode(&spec).map_err(|e| format!("synthetic network: {e}"))
}

/// Start poses tried by default (vertices 0, 1, …), and goals per start (the farthest vertices).
const DEFAULT_STARTS: u32 = 32;
const DEFAULT_GOALS: usize = 16;

/// The query the fixture settles on and what the host planned for it.
struct Chosen {
    start: Pose,
    goal: Goal,
    popup: (f32, f32, f32),
    /// Three-dimensional roadmap: the query's altitudes.
    altitudes: Option<(f32, f32)>,
    /// The pop-up's top (`f32::INFINITY` in the plane).
    popup_height: f32,
    /// The host's [`vertical::altitude_sum`] of the route with the pop-up.
    altitude_sum: f32,
    budget: u64,
    /// Route length without the pop-up.
    before: Option<f32>,
    added: PopupSummary,
    summary: RouteSummary,
    /// Default (start, goal) pairs tried and rejected before this one.
    rejected: usize,
}

/// Plans with the pop-up for the given start, goal and pop-up; for each one not given, tries
/// defaults in a fixed order until a route exists: start at vertex 0's pose, then vertex 1's, …
/// (a roadmap may have dead-end vertices); goal at the position of the vertex farthest from the
/// start, then the next farthest, …, with a free heading; pop-up at their midpoint with a tenth
/// of their distance as radius. On a three-dimensional roadmap the query flies between
/// `vertical.0`'s altitudes and the pop-up reaches up to `vertical.1` ([`vertical`]'s defaults
/// when not given).
fn choose(
    bytes: &[u8],
    start: Option<Pose>,
    goal: Option<Goal>,
    (popup, popup_on_route): (Option<(f32, f32, f32)>, Option<f32>),
    vertical: (Option<(f32, f32)>, Option<f32>),
) -> Result<Chosen, String> {
    let mut planner = HostPlanner::new();
    planner.load(bytes).map_err(|e| format!("load: {e}"))?;
    planner.set_config(config_for(planner.network()));
    let budget = planner.worst_case_work();
    let network = *planner.network();
    let popup_height = vertical::popup_height(&network, vertical.1);
    let starts: Vec<Pose> = match start {
        Some(s) => vec![s],
        None => (0..network.vertex_count().min(DEFAULT_STARTS))
            .filter_map(|v| network.vertex(v))
            .collect(),
    };
    let mut rejected = 0;
    let mut last_error = None;
    for start in starts {
        let goals: Vec<Goal> = match goal {
            Some(g) => vec![g],
            None => {
                let mut far: Vec<Vec2> = (0..network.vertex_count())
                    .filter_map(|v| network.vertex(v))
                    .map(|p| p.position)
                    .collect();
                far.sort_by(|a, b| {
                    let (da, db) = (a.distance(start.position), b.distance(start.position));
                    db.total_cmp(&da)
                });
                far.dedup();
                far.into_iter()
                    .take(DEFAULT_GOALS)
                    .map(|position| Goal {
                        position,
                        heading: None,
                    })
                    .collect()
            }
        };
        for goal in goals {
            let query = Query {
                start,
                goal,
                search: Search::Dijkstra,
            };
            let altitudes =
                vertical::query_altitudes(&network, vertical.0, start.position, goal.position);
            if let Some((from, to)) = altitudes {
                planner
                    .set_query_altitudes(from, to)
                    .map_err(|e| format!("set_query_altitudes({from}, {to}): {e}"))?;
            }
            let before = planner.plan(&query, budget).ok().map(|s| s.length);
            let on_route = popup_on_route.and_then(|r| {
                before?;
                let longest = planner
                    .route()
                    .iter()
                    .filter_map(|p| match p {
                        skyroute::Primitive::Line(s) => Some(*s),
                        _ => None,
                    })
                    .max_by(|a, b| a.length().total_cmp(&b.length()))?;
                let mid = (longest.start + longest.end) * 0.5;
                Some((mid.x, mid.y, r))
            });
            let popup = popup.or(on_route).unwrap_or_else(|| {
                let mid = (start.position + goal.position) * 0.5;
                let r = (0.1 * start.position.distance(goal.position)).max(1.0);
                (mid.x, mid.y, r)
            });
            let disc = Popup::Circle {
                centre: Vec2::new(popup.0, popup.1),
                radius: popup.2,
            };
            let added = planner
                .add_popup_with_height(disc, popup_height)
                .map_err(|e| format!("add_popup {popup:?} up to {popup_height} m: {e}"))?;
            let planned = planner.plan(&query, budget);
            let altitude_sum = vertical::altitude_sum(&planner);
            planner
                .remove_popup(added.id)
                .map_err(|e| format!("remove_popup: {e}"))?;
            match planned {
                Ok(summary) => {
                    return Ok(Chosen {
                        start,
                        goal,
                        popup,
                        altitudes,
                        popup_height,
                        altitude_sum,
                        budget,
                        before,
                        added,
                        summary,
                        rejected,
                    })
                }
                Err(e) => {
                    rejected += 1;
                    last_error = Some(format!("{start:?} → {goal:?} with pop-up {popup:?}: {e}"));
                }
            }
        }
    }
    Err(format!(
        "no route for any start/goal tried ({rejected}); last: {}",
        last_error.unwrap_or_default()
    ))
}

/// The connection settings the firmware uses: the default for a roadmap; for a terrain network,
/// 16 links to the 32 nearest nodes however far (region corners can be kilometres away), and
/// the equal split of each straight between its turns: the paper's turn rule needs a search
/// state per transition (38 424 on the STM32F405's 4 084-edge network, about 0.8 MB of planner;
/// 729 820 on the whole network, about 15 MB), beyond both boards' RAM.
fn config_for(network: &Network<'_>) -> PlannerConfig {
    match network.mode() {
        Mode::Terrain => PlannerConfig {
            start_candidates: 16,
            goal_candidates: 16,
            connect_radius_m: f32::INFINITY,
            turn_rule: skyroute::TurnRule::SharedEqually,
            ..PlannerConfig::DEFAULT
        },
        Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => PlannerConfig::DEFAULT,
    }
}

/// The firmware planner's size for its capacities ([`skyroute_prep::capacity::planner_bytes`]).
fn planner_bytes(v: usize, e: usize) -> usize {
    skyroute_prep::capacity::planner_bytes::<P_CAP, R_CAP>(v, e)
}

/// `n` with the firmware's headroom ([`skyroute_prep::capacity::with_headroom`]).
fn capacity(n: u32, step: usize) -> usize {
    skyroute_prep::capacity::with_headroom(n as usize, step)
}

/// `pub const NAME: PlannerConfig = …;`, the settings of `config` as a Rust item.
fn config_rs(name: &str, config: &PlannerConfig) -> String {
    let radius = if config.connect_radius_m.is_finite() {
        lit(config.connect_radius_m)
    } else {
        "f32::INFINITY".to_string()
    };
    format!(
        "pub const {name}: skyroute::planner::PlannerConfig = skyroute::planner::PlannerConfig {{\n    \
         start_candidates: {},\n    goal_candidates: {},\n    connect_radius_m: {radius},\n    \
         free_goal_headings: {},\n    turn_rule: skyroute::planner::TurnRule::{:?},\n}};",
        config.start_candidates,
        config.goal_candidates,
        config.free_goal_headings,
        config.turn_rule
    )
}

/// An `f32` literal that reads back as exactly the same value.
fn lit(x: f32) -> String {
    format!("{x:?}_f32")
}

fn run(args: Args) -> Result<(), String> {
    let bytes = match &args.network {
        Some(path) => std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?,
        None => synthetic_network()?,
    };
    let source = match &args.network {
        Some(p) => p.display().to_string(),
        None => "--synthetic".to_string(),
    };
    let network = Network::from_bytes(&bytes).map_err(|e| format!("{source}: {e}"))?;
    let (nv, ne) = (network.vertex_count(), network.edge_count());
    if nv == 0 {
        return Err(format!("{source}: the network has no vertices"));
    }
    if args.ruz {
        return ruz::run_ruz(&args, &bytes, &source, &network);
    }
    // Search states: the vertices of a roadmap; a terrain search runs over directed edges and
    // start links.
    let voronoi_options = args.scenario.is_some()
        || args.threat.is_some()
        || args.threat_on_route.is_some()
        || args.replan_after.is_some();
    let states = match network.mode() {
        Mode::Roadmap | Mode::Terrain | Mode::Landmark | Mode::Unknown(_) if voronoi_options => {
            return Err(format!(
                "{source}: --scenario, --threat, --threat-on-route and --replan-after apply to \
                 Voronoi networks only"
            ))
        }
        Mode::Landmark => return landmark::run_landmark(&args, &bytes, &source, &network),
        Mode::Terrain => ne + MAX_LINKS as u32,
        Mode::Voronoi => return voronoi::run_voronoi(&args, &bytes, &source, &network),
        Mode::Roadmap | Mode::Unknown(_) => nv,
    };
    let (v_cap, e_cap) = (capacity(states, 64), capacity(ne, 256));
    // The very check the firmware's `Planner::load` makes.
    Network::from_bytes_with_capacity(&bytes, v_cap, e_cap)
        .map_err(|e| format!("{source}: does not load with V={v_cap} E={e_cap}: {e}"))?;
    if nv as usize > HOST_V || ne as usize > HOST_E {
        return Err(format!(
            "{source}: {nv} vertices / {ne} edges exceed the host planner's {HOST_V} / {HOST_E} \
             (and any STM32F405's RAM)"
        ));
    }

    // Plan exactly as the firmware does, on a thread with room for the host planner's arrays.
    let chosen = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn({
            let bytes = bytes.clone();
            let (start, goal, popup) = (args.start, args.goal, args.popup);
            let on_route = args.popup_on_route;
            let vertical = (args.altitudes, args.popup_height);
            move || choose(&bytes, start, goal, (popup, on_route), vertical)
        })
        .map_err(|e| format!("spawning the planning thread: {e}"))?
        .join()
        .map_err(|_| "the planning thread panicked".to_string())??;
    let Chosen {
        start,
        goal,
        popup,
        altitudes,
        popup_height,
        budget,
        before,
        added,
        summary,
        rejected,
        ..
    } = chosen;

    let ram = planner_bytes(v_cap, e_cap);
    eprintln!(
        "firmware_fixture: {source}: {nv} vertices, {ne} edges, {} obstacles, {} bytes",
        network.obstacle_count(),
        bytes.len()
    );
    eprintln!(
        "firmware_fixture: start {start:?}\n  goal {goal:?}\n  popup {popup:?} blocks {} edges \
         ({rejected} default start/goal pairs rejected first)",
        added.edges_blocked
    );
    if let Some((from, to)) = altitudes {
        eprintln!(
            "firmware_fixture: three-dimensional: from {from} m to {to} m, the pop-up's top at \
             {popup_height} m"
        );
    }
    eprintln!(
        "firmware_fixture: route {} m ({} without the pop-up), {} primitives, {} network edges, \
         work {} of {budget}",
        summary.length,
        before.map_or("no route".to_string(), |l| format!("{l} m")),
        summary.primitives,
        summary.network_edges,
        summary.work.total()
    );
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

    let q = query_rs(&source, &network, (v_cap, e_cap), &chosen)?;

    write_fixture(&args.out_dir, Some(&bytes), &q)
}

/// `query.rs` of a roadmap or terrain network: capacities, connection settings, query, pop-up,
/// the host's answer and the budget.
fn query_rs(
    source: &str,
    network: &Network<'_>,
    (v_cap, e_cap): (usize, usize),
    chosen: &Chosen,
) -> Result<String, String> {
    let (nv, ne) = (network.vertex_count(), network.edge_count());
    let &Chosen {
        start,
        goal,
        popup,
        altitudes,
        popup_height,
        altitude_sum,
        budget,
        summary,
        ..
    } = chosen;
    let mut q = String::new();
    let w = &mut q;
    let _ = writeln!(
        w,
        "// Generated by host-tests/src/bin/firmware_fixture/ from {source}. Do not edit.\n"
    );
    let _ = writeln!(
        w,
        "/// Search-state capacity of the planner ({nv} vertices, {ne} edges in the network)."
    );
    let _ = writeln!(w, "pub const V_CAP: usize = {v_cap};");
    let _ = writeln!(w, "/// Edge capacity of the planner ({ne} in the network).");
    let _ = writeln!(w, "pub const E_CAP: usize = {e_cap};");
    let _ = writeln!(w, "/// Pop-up slots of the planner.");
    let _ = writeln!(w, "pub const P_CAP: usize = {P_CAP};");
    let _ = writeln!(w, "/// Route primitives the planner holds.");
    let _ = writeln!(w, "pub const R_CAP: usize = {R_CAP};");
    let _ = writeln!(w, "/// The planner's connection settings.");
    let _ = writeln!(w, "{}", config_rs("CONFIG", &config_for(network)));
    let _ = writeln!(w, "/// The aircraft's pose when it plans.");
    let _ = writeln!(
        w,
        "pub const START: skyroute::Pose = skyroute::Pose::new({}, {}, {});",
        lit(start.position.x),
        lit(start.position.y),
        lit(start.heading)
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
        "/// The pop-up disc: centre x, centre y, radius (metres)."
    );
    let _ = writeln!(
        w,
        "pub const POPUP: (f32, f32, f32) = ({}, {}, {});",
        lit(popup.0),
        lit(popup.1),
        lit(popup.2)
    );
    let _ = writeln!(w, "/// Route length the host computed, metres.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_LENGTH: f32 = {};",
        lit(summary.length)
    );
    let _ = writeln!(w, "/// Route primitives the host computed.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_PRIMITIVES: u32 = {};",
        summary.primitives
    );
    let _ = writeln!(w, "/// Work the host counted.");
    let _ = writeln!(
        w,
        "pub const EXPECTED_WORK: u64 = {};",
        summary.work.total()
    );
    let _ = writeln!(
        w,
        "/// Work budget: the network's worst case (`Planner::worst_case_work`)."
    );
    let _ = writeln!(w, "pub const BUDGET: u64 = {budget};");
    vertical::vertical_rs(w, altitudes, popup_height, altitude_sum);
    geo_rs(w, network, &start)?;

    Ok(q)
}

/// The start as an autopilot gives it (longitude, latitude, compass heading, through the
/// network's frame) and the pose the host converts it back to: the firmware converts
/// `START_GEO` itself and must get `START_FROM_GEO` bit for bit.
fn geo_rs(w: &mut String, network: &Network<'_>, start: &skyroute::Pose) -> Result<(), String> {
    let frame = network.local_frame();
    let refused = |e: skyroute::GeoError| format!("the start {start:?} through lon/lat: {e}");
    let (lon, lat) = frame.lon_lat(start.position).map_err(refused)?;
    let compass = frame.compass_deg(start).map_err(refused)?;
    let back = frame.pose(lon, lat, compass).map_err(refused)?;
    let _ = writeln!(
        w,
        "/// The start as the autopilot gives it: longitude, latitude (degrees), compass heading\n\
         /// (degrees clockwise from true north), from the network's frame on the host."
    );
    let _ = writeln!(
        w,
        "pub const START_GEO: (f64, f64, f64) = ({lon:?}_f64, {lat:?}_f64, {compass:?}_f64);"
    );
    let _ = writeln!(
        w,
        "/// `START_GEO` in the network's frame as the host converts it (`LocalFrame::pose`)."
    );
    let _ = writeln!(
        w,
        "pub const START_FROM_GEO: skyroute::Pose = skyroute::Pose::new({}, {}, {});",
        lit(back.position.x),
        lit(back.position.y),
        lit(back.heading)
    );
    Ok(())
}

/// Writes the fixture into `out`: `network.bin` (when the firmware embeds a network) and
/// `query.rs`.
fn write_fixture(out: &Path, network: Option<&[u8]>, query_rs: &str) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    if let Some(bytes) = network {
        write(&out.join("network.bin"), bytes)?;
    }
    write(&out.join("query.rs"), query_rs.as_bytes())?;
    let files = if network.is_some() {
        "{network.bin,query.rs}"
    } else {
        "query.rs"
    };
    eprintln!("firmware_fixture: wrote {}/{files}", out.display());
    Ok(())
}

/// Writes a file only when its contents change (keeps the firmware build from redoing work).
fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

fn main() -> ExitCode {
    match parse_args().and_then(run) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("firmware_fixture: {e}");
            ExitCode::FAILURE
        }
    }
}
