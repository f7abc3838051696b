//! Planning a whole mission — start → waypoints in order → goal — with the onboard core, exactly
//! as the aircraft would, on the host.
//!
//! A waypoint without a heading enters as `H` heading copies (36: every 10°) and the best are
//! chosen jointly: every leg between consecutive copies is planned by the core, then a dynamic
//! programme over the stages picks the cheapest chain (optimal over the copies, where planning
//! leg by leg with the first-found heading would not be). A waypoint none of whose copies has a
//! collision-free way out is reported, by name, as an inevitable-collision state.

use crate::frame::LocalFrame;
pub use crate::free_heading::FreeHeadingRule;
pub use crate::local::LocalPopup;
use crate::local::{local, local_heading};
use crate::scenario::{Endpoint, Scenario};
use rayon::prelude::*;
use skyroute::geometry::vertical::VerticalProfile;
use skyroute::network::Mode;
use skyroute::planner::{
    ArcCheckStats, Goal, PlanError, PlannerConfig, Query, QueryField, RouteSummary, Search,
    TurnRule, Violation, Work,
};
use skyroute::{Planner, Pose, Primitive, Vec2};
use std::fmt;

/// The planner used on the host for missions: large enough for any network the ground tool
/// builds. Its `V` (search states) also holds a terrain query's states under the paper's turn
/// rule, one per transition (1 727 995 on medeiros-jacksboro with a 700 m level): about 43 MB,
/// built on a thread of [`PLANNER_STACK`].
pub type HostPlanner<'n> = Planner<'n, 2097152, 262144, 16, 4096>;

/// The host planner where no terrain query runs under the paper's turn rule (`skyroute info`,
/// landmark plans): `V` for a terrain network's directed edges; about 3 MB.
pub type CompactHostPlanner<'n> = Planner<'n, 131072, 262144, 16, 4096>;

/// Stack for threads that hold a [`HostPlanner`] by value while it is built.
pub const PLANNER_STACK: usize = 256 << 20;

/// The connection settings for terrain networks: 16 links to the 32 nearest nodes however far
/// (where the terrain is low, the nearest region corner may be far away; every connection's
/// check is bounded by the elevation grid's size).
pub const TERRAIN_CONFIG: PlannerConfig = PlannerConfig {
    start_candidates: 16,
    goal_candidates: 16,
    connect_radius_m: f32::INFINITY,
    free_goal_headings: 36,
    turn_rule: TurnRule::Paper,
};

/// Headings tried per junction by the heading smoothing (±90° about the current one).
pub const SMOOTHING_HEADINGS: u16 = 9;

/// Headings tried for a waypoint without one.
pub const FREE_HEADINGS: usize = 36;

/// A planned leg.
#[derive(Clone, Debug)]
pub struct Leg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// The core's summary of the leg (its length after post-processing).
    pub summary: RouteSummary,
    /// The leg's length as planned, before shortcuts and heading smoothing, metres.
    pub planned_length: f32,
    /// The leg's lines and arcs.
    pub primitives: Vec<Primitive>,
    /// On a three-dimensional roadmap, for each primitive: the altitude profile of the path it
    /// belongs to and the distance along that path at which it starts (its altitude `s`
    /// metres in is `profile.altitude_at(offset + s)`). Empty on other networks.
    pub vertical: Vec<(VerticalProfile, f32)>,
    /// Whether its connections needed the widened radius ([`MissionOptions`]).
    pub widened: bool,
    /// The turn-arc checks of the leg's search against the elevation grid (terrain networks;
    /// zero otherwise).
    pub arc_checks: ArcCheckStats,
    /// The most cells one turn-arc check may visit on this network (the bound the work bound
    /// uses; terrain networks, zero otherwise).
    pub cells_per_turn_bound: u64,
}

/// A planned mission.
#[derive(Clone, Debug)]
pub struct Mission {
    /// Legs in order.
    pub legs: Vec<Leg>,
    /// Sum of the legs' lengths, metres.
    pub length: f64,
    /// Queries run by the core to choose the waypoint headings.
    pub queries: usize,
    /// Work summed over every query run.
    pub work: Work,
    /// Under [`FreeHeadingRule::MostClearOutEdges`], each waypoint without a heading: its name,
    /// the heading fixed for it (radians, local frame; NaN when no heading had a clear way in
    /// and out, and the default rule chose) and its clear out-edges. Empty otherwise.
    pub fixed_headings: Vec<(String, f32, usize)>,
    /// The vertical limits of a three-dimensional roadmap's network (its legs' profiles fly
    /// within them); `None` for other networks.
    pub vertical_limits: Option<skyroute::geometry::vertical::VerticalLimits>,
}

/// Why a mission could not be planned.
#[derive(Clone, Debug, PartialEq)]
pub enum MissionError {
    /// The scenario has no start or no goal.
    Missing(&'static str),
    /// The core refused the network.
    Load(skyroute::LoadError),
    /// A pop-up could not be added.
    Popup(String, skyroute::PopupError),
    /// This waypoint can be reached, but none of the headings it can be reached with has a
    /// collision-free way on to the next stage.
    InevitableCollision(String),
    /// The stage named cannot be reached from the previous one.
    Unreachable {
        /// The stage left.
        from: String,
        /// The stage not reached.
        to: String,
        /// The core's reason.
        error: PlanError,
        /// What the host found out about it (which zone, how far the nearest vertex is), or
        /// empty.
        detail: String,
    },
}

impl MissionError {
    /// Whether the mission's input is at fault (a start in a no-fly zone, a bad number, a
    /// pop-up the core refuses) rather than the absence of a route.
    pub fn is_bad_input(&self) -> bool {
        match self {
            MissionError::Missing(_) | MissionError::Load(_) | MissionError::Popup(..) => true,
            MissionError::InevitableCollision(_) => false,
            MissionError::Unreachable { error, .. } => matches!(
                error,
                PlanError::NonFinite { .. }
                    | PlanError::OutOfRange { .. }
                    | PlanError::InsideObstacle { .. }
            ),
        }
    }
}

impl fmt::Display for MissionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MissionError::Missing(what) => write!(f, "the scenario has no {what}"),
            MissionError::Load(e) => write!(f, "the network does not load: {e}"),
            MissionError::Popup(name, e) => write!(f, "pop-up {name}: {e}"),
            MissionError::InevitableCollision(name) => {
                write!(f, "{name} is an inevitable-collision state: no heading it can be reached with has a collision-free way out")
            }
            MissionError::Unreachable {
                from,
                to,
                error,
                detail,
            } => {
                write!(f, "no route from {from} to {to}: {error}")?;
                if !detail.is_empty() {
                    write!(f, " ({detail})")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for MissionError {}

/// How the mission connects its stages to the network.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MissionOptions {
    /// `Some(r)`: connect the start and goal of every leg to vertices within `r` metres only.
    /// `None`: the network's usual radius (1 km for roadmaps, unbounded for terrain), widened
    /// to the nearest [`skyroute::planner::MAX_CANDIDATES`] vertices however far for a leg
    /// whose start or goal does not connect within it.
    pub connect_radius_m: Option<f32>,
    /// Terrain networks: how consecutive turns share a straight (`None`: the planner's
    /// default, the paper's rule, [`TurnRule::Paper`]).
    pub turn_rule: Option<TurnRule>,
    /// How a waypoint without a heading gets one.
    pub free_headings: FreeHeadingRule,
    /// Which shortcut pass post-processes each leg.
    pub shortcuts: Shortcuts,
}

/// The shortcut pass that post-processes each leg, before heading smoothing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shortcuts {
    /// The shortest chain through any subset of the leg's junctions
    /// ([`Planner::shortcut_best`](skyroute::Planner::shortcut_best)): never longer than the
    /// greedy pass, n(n−1)/2 pairs examined for n paths (the default).
    #[default]
    Best,
    /// Niendorf et al.'s greedy forward pass ([`Planner::shortcut`](skyroute::Planner::shortcut)):
    /// one pair per junction.
    Greedy,
}

/// Plans `q`, and when `adaptive` and an end did not connect, plans it again with the connect
/// radius unbounded (the nearest candidates however far). Returns whether it widened. On a
/// three-dimensional roadmap the query flies from `altitudes.0` to `altitudes.1`.
fn plan_query(
    p: &mut HostPlanner,
    q: &Query,
    altitudes: Option<(f32, f32)>,
    budget: u64,
    adaptive: bool,
) -> (Result<RouteSummary, PlanError>, bool) {
    if let Some((from, to)) = altitudes {
        if let Err(e) = p.set_query_altitudes(from, to) {
            return (Err(e), false);
        }
    }
    let first = p.plan(q, budget);
    let unconnected = matches!(
        first,
        Err(PlanError::StartUnconnected | PlanError::GoalUnconnected)
    );
    let config = p.config();
    if !(adaptive && unconnected && config.connect_radius_m.is_finite()) {
        return (first, false);
    }
    p.set_config(PlannerConfig {
        connect_radius_m: f32::INFINITY,
        ..config
    });
    let second = p.plan(q, budget);
    p.set_config(config);
    (second, second.is_ok())
}

/// What the host can add to the core's reason: the zone an end lies in, or how far the
/// vertices the connection tried lie.
fn explain(
    error: PlanError,
    from: Vec2,
    to: Vec2,
    bytes: &[u8],
    scenario: &Scenario,
    frame: &LocalFrame,
    options: &MissionOptions,
) -> String {
    let at = |field| match field {
        QueryField::Start => from,
        QueryField::Goal => to,
    };
    match error {
        PlanError::InsideObstacle { field, obstacle } => {
            match crate::local::obstacle_containing(scenario, frame, at(field)) {
                Some(name) => format!("{name} contains it"),
                // Within the clearance of an obstacle but outside it: name it by the core's index.
                None => crate::local::local_obstacles_named(scenario, frame)
                    .into_iter()
                    .nth(obstacle as usize)
                    .map_or_else(
                        || format!("network obstacle {obstacle} contains it"),
                        |(_, name)| format!("it lies within the clearance of {name}"),
                    ),
            }
        }
        PlanError::StartUnconnected | PlanError::GoalUnconnected => {
            let p = if error == PlanError::StartUnconnected {
                from
            } else {
                to
            };
            let Ok(net) = skyroute::Network::from_bytes(bytes) else {
                return String::new();
            };
            let nearest = (0..net.vertex_count())
                .filter_map(|v| net.vertex(v))
                .map(|v| v.position.distance(p))
                .fold(f32::INFINITY, f32::min);
            let end = if error == PlanError::StartUnconnected {
                "the start"
            } else {
                "the goal"
            };
            match options.connect_radius_m {
                Some(r) if nearest > r => format!(
                    "no vertex lies within --connect-radius {r} m of {end}: the nearest is \
                     {nearest:.0} m away"
                ),
                radius => format!(
                    "no collision-free Dubins path joins {end} to any of the {} nearest \
                     vertices{}, the nearest {nearest:.0} m away",
                    skyroute::planner::MAX_CANDIDATES,
                    radius.map_or(", however far".to_string(), |r| format!(" within {r} m"))
                ),
            }
        }
        _ => String::new(),
    }
}

/// One stage of the mission: its name and the poses (or the free-heading goal) to reach.
struct Stage {
    name: String,
    position: Vec2,
    /// Its altitude on a three-dimensional roadmap (the scenario's `altitude_m`).
    altitude: Option<f32>,
    /// `None`: the core picks among its own free goal headings (the final goal only).
    headings: Vec<Option<f32>>,
}

fn stage(frame: &LocalFrame, e: &Endpoint, last: bool) -> Stage {
    let headings = match e.heading_deg {
        Some(c) => vec![Some(local_heading(frame, e.lon, e.lat, c))],
        None if last => vec![None],
        None => (0..FREE_HEADINGS)
            .map(|k| Some((k as f32) * std::f32::consts::TAU / FREE_HEADINGS as f32))
            .collect(),
    };
    Stage {
        name: e.name.clone(),
        position: local(frame, e.lon, e.lat),
        altitude: e.altitude_m.map(|z| z as f32),
        headings,
    }
}

/// The altitudes a leg from `prev` to `next` flies between on a three-dimensional roadmap.
fn leg_altitudes(prev: &Stage, next: &Stage) -> Option<(f32, f32)> {
    prev.altitude.zip(next.altitude)
}

/// Loads `bytes` into a fresh boxed planner with the pop-ups added and the connect radius of
/// `options`.
fn planner<'n>(
    bytes: &'n [u8],
    popups: &[LocalPopup],
    options: &MissionOptions,
) -> Result<Box<HostPlanner<'n>>, MissionError> {
    let mut p: Box<HostPlanner<'n>> = Box::new(Planner::new());
    p.load(bytes).map_err(MissionError::Load)?;
    // Terrain nodes sit at region corners, often kilometres from a valley's start or goal.
    let config = match p.network().mode() {
        Mode::Terrain => TERRAIN_CONFIG,
        Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => PlannerConfig::DEFAULT,
    };
    p.set_config(config);
    if let Some(turn_rule) = options.turn_rule {
        let config = p.config();
        p.set_config(PlannerConfig {
            turn_rule,
            ..config
        });
    }
    if let Some(r) = options.connect_radius_m {
        let config = p.config();
        p.set_config(PlannerConfig {
            connect_radius_m: r,
            ..config
        });
    }
    for pop in popups {
        pop.add_to(&mut p)
            .map_err(|e| MissionError::Popup(pop.name.clone(), e))?;
    }
    Ok(p)
}

/// Plans start → waypoints → goal through the network `bytes` with the onboard core, with the
/// default [`MissionOptions`]. Runs on a thread pool with stacks large enough for the host
/// planner.
pub fn plan_mission(
    bytes: &[u8],
    scenario: &Scenario,
    frame: &LocalFrame,
    popups: &[LocalPopup],
) -> Result<Mission, MissionError> {
    plan_mission_with(bytes, scenario, frame, popups, &MissionOptions::default())
}

/// [`plan_mission`] with the connection settings of `options`.
pub fn plan_mission_with(
    bytes: &[u8],
    scenario: &Scenario,
    frame: &LocalFrame,
    popups: &[LocalPopup],
    options: &MissionOptions,
) -> Result<Mission, MissionError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .stack_size(PLANNER_STACK)
        .build()
        .map_err(|_| MissionError::Missing("thread pool"))?;
    pool.install(|| plan_mission_in_pool(bytes, scenario, frame, popups, options))
}

fn plan_mission_in_pool(
    bytes: &[u8],
    scenario: &Scenario,
    frame: &LocalFrame,
    popups: &[LocalPopup],
    options: &MissionOptions,
) -> Result<Mission, MissionError> {
    let mut stages = mission_stages(scenario, frame)?;
    let inputs = Inputs {
        bytes,
        scenario,
        frame,
        popups,
        options,
    };
    let fixed_headings = match options.free_headings {
        FreeHeadingRule::Cheapest => Vec::new(),
        FreeHeadingRule::MostClearOutEdges => fix_free_headings(&mut stages, &inputs)?,
    };
    let mut queries = 0;
    let mut work = Work::default();
    // best[i][k]: cheapest cost to stage i copy k, and the copy of stage i−1 it came from.
    let mut best: Vec<StageBest> = vec![vec![Some((0.0, 0))]];
    for i in 1..stages.len() {
        let (prev, next) = (&stages[i - 1], &stages[i]);
        let (stage_best, n) = best_into(&inputs, prev, next, &best[i - 1], i == 1, &mut work)?;
        queries += n;
        best.push(stage_best);
    }
    let chosen = walk_back(&stages, &best)?;
    let (legs, length) = plan_legs(bytes, popups, options, &stages, &chosen)?;
    let vertical_limits = skyroute::Network::from_bytes(bytes)
        .ok()
        .and_then(|n| n.vertical_limits());
    Ok(Mission {
        legs,
        length,
        queries,
        work,
        fixed_headings,
        vertical_limits,
    })
}

/// Fixes each free waypoint's heading by the paper's rule
/// ([`crate::free_heading::most_clear_out_edges`]): among its heading copies, the one with the
/// most clear out-edges to the network's vertices within `--connect-radius`, else the
/// scenario's neighbour radius, else the core's connect radius, against the scenario's
/// obstacles and `popups` (on a three-dimensional roadmap below their heights, from and to
/// the waypoint's altitude). A waypoint with no heading that has a clear way in and out keeps
/// all its copies (the default rule decides it; count 0). Returns each waypoint's name, the
/// heading fixed (NaN when none was) and its count.
fn fix_free_headings(
    stages: &mut [Stage],
    inputs: &Inputs,
) -> Result<Vec<(String, f32, usize)>, MissionError> {
    let Inputs {
        bytes,
        scenario,
        frame,
        popups,
        options,
    } = *inputs;
    let net = skyroute::Network::from_bytes(bytes).map_err(MissionError::Load)?;
    let mut obstacles = crate::local::local_obstacles(scenario, frame);
    // On a three-dimensional roadmap: every obstacle's height, the pop-ups' after the zones'.
    let vertical = crate::roadmap::vertical::vertical_input(scenario, frame).map(|mut v| {
        v.heights.resize(obstacles.len(), f32::INFINITY);
        v.heights
            .extend(popups.iter().map(|p| p.height.unwrap_or(f32::INFINITY)));
        v
    });
    obstacles.extend(
        popups
            .iter()
            .map(|p| skyroute::network::write::ObstacleSpec::Circle {
                centre: p.centre,
                radius: p.radius,
            }),
    );
    let radius = options.connect_radius_m.unwrap_or_else(|| {
        scenario
            .planner
            .neighbour_radius_m
            .map_or(PlannerConfig::DEFAULT.connect_radius_m, |r| r as f32)
    });
    let last = stages.len().saturating_sub(1);
    let mut fixed = Vec::new();
    for st in stages.iter_mut().take(last).skip(1) {
        if st.headings.len() < 2 {
            continue;
        }
        let headings: Vec<f32> = st.headings.iter().flatten().copied().collect();
        let surroundings = crate::free_heading::Surroundings {
            obstacles: &obstacles,
            vertical: vertical.as_ref().zip(st.altitude),
        };
        let (h, count) = crate::free_heading::most_clear_out_edges(
            &net,
            &surroundings,
            st.position,
            &headings,
            radius,
        );
        if count == 0 {
            fixed.push((st.name.clone(), f32::NAN, 0));
            continue;
        }
        st.headings = vec![Some(h)];
        fixed.push((st.name.clone(), h, count));
    }
    Ok(fixed)
}

/// Per copy of a stage: the cheapest cost to reach it and the copy of the previous stage it
/// came from; `None` if it was not reached.
type StageBest = Vec<Option<(f64, usize)>>;

/// What a mission is planned from.
struct Inputs<'a> {
    bytes: &'a [u8],
    scenario: &'a Scenario,
    frame: &'a LocalFrame,
    popups: &'a [LocalPopup],
    options: &'a MissionOptions,
}

/// The stages: the start (its pose), the waypoints, the goal.
fn mission_stages(scenario: &Scenario, frame: &LocalFrame) -> Result<Vec<Stage>, MissionError> {
    let start = scenario
        .start
        .as_ref()
        .ok_or(MissionError::Missing("start"))?;
    let goal = scenario
        .goal
        .as_ref()
        .ok_or(MissionError::Missing("goal"))?;
    // The parser refuses a start without a heading; a scenario built in code may still lack one.
    let start_heading = start
        .heading_deg
        .ok_or(MissionError::Missing("start heading"))?;
    let start_pose = Pose {
        position: local(frame, start.lon, start.lat),
        heading: local_heading(frame, start.lon, start.lat, start_heading),
    };
    let mut stages = vec![Stage {
        name: start.name.clone(),
        position: start_pose.position,
        altitude: start.altitude_m.map(|z| z as f32),
        headings: vec![Some(start_pose.heading)],
    }];
    stages.extend(scenario.waypoints.iter().map(|w| stage(frame, w, false)));
    stages.push(stage(frame, goal, true));

    Ok(stages)
}

/// The cheapest way into each copy of stage `next` from the copies of `prev` that were reached
/// (`best_prev`): one query per pair of copies, in parallel. Returns, per copy of `next`, its
/// cost and the copy of `prev` it came from, and the number of queries; adds their work to
/// `work`. `first_leg`: `prev` is the start.
fn best_into(
    inputs: &Inputs,
    prev: &Stage,
    next: &Stage,
    best_prev: &[Option<(f64, usize)>],
    first_leg: bool,
    work: &mut Work,
) -> Result<(StageBest, usize), MissionError> {
    let Inputs {
        bytes,
        scenario,
        frame,
        popups,
        options,
    } = *inputs;
    let adaptive = options.connect_radius_m.is_none();
    let budget = u64::MAX;
    let pairs: Vec<(usize, usize)> = (0..prev.headings.len())
        .filter(|&a| best_prev[a].is_some())
        .flat_map(|a| (0..next.headings.len()).map(move |b| (a, b)))
        .collect();
    let costs: Vec<(usize, usize, Result<RouteSummary, PlanError>)> = pairs
        .par_iter()
        .map_init(
            || planner(bytes, popups, options),
            |p, &(a, b)| {
                let Ok(p) = p else {
                    return (a, b, Err(PlanError::Internal));
                };
                let q = Query {
                    start: Pose {
                        position: prev.position,
                        heading: prev.headings[a].unwrap_or(0.0),
                    },
                    goal: Goal {
                        position: next.position,
                        heading: next.headings[b],
                    },
                    search: Search::AStar,
                };
                let altitudes = leg_altitudes(prev, next);
                (a, b, plan_query(p, &q, altitudes, budget, adaptive).0)
            },
        )
        .collect();
    // A failure to load or add pop-ups shows up identically in every pair: report it.
    planner(bytes, popups, options)?;
    let queries = costs.len();
    let mut stage_best: Vec<Option<(f64, usize)>> = vec![None; next.headings.len()];
    let mut last_error = PlanError::NoRoute;
    let mut way_out = vec![false; prev.headings.len()];
    for (a, b, r) in costs {
        match r {
            Ok(s) => {
                *work += s.work;
                way_out[a] = true;
                let total = best_prev[a].map_or(f64::INFINITY, |x| x.0) + s.length as f64;
                if stage_best[b].is_none_or(|x| total < x.0) {
                    stage_best[b] = Some((total, a));
                }
            }
            Err(e) => last_error = e,
        }
    }
    if !way_out.iter().any(|w| *w) {
        if !first_leg {
            // `prev` is a waypoint that was reached, but from no pose it was reached in is
            // there a collision-free way on.
            return Err(MissionError::InevitableCollision(prev.name.clone()));
        }
        return Err(MissionError::Unreachable {
            from: prev.name.clone(),
            to: next.name.clone(),
            error: last_error,
            detail: explain(
                last_error,
                prev.position,
                next.position,
                bytes,
                scenario,
                frame,
                options,
            ),
        });
    }
    Ok((stage_best, queries))
}

/// Walks back from the cheapest copy of the goal: the copy of each stage the route takes.
fn walk_back(stages: &[Stage], best: &[StageBest]) -> Result<Vec<usize>, MissionError> {
    let last = stages.len() - 1;
    let mut k = (0..stages[last].headings.len())
        .filter(|&b| best[last][b].is_some())
        .min_by(|&x, &y| {
            best[last][x]
                .map(|v| v.0)
                .unwrap_or(f64::INFINITY)
                .total_cmp(&best[last][y].map(|v| v.0).unwrap_or(f64::INFINITY))
        })
        .ok_or(MissionError::Unreachable {
            from: stages[last - 1].name.clone(),
            to: stages[last].name.clone(),
            error: PlanError::NoRoute,
            detail: String::new(),
        })?;
    let mut chosen = vec![0usize; stages.len()];
    for i in (1..stages.len()).rev() {
        chosen[i] = k;
        k = best[i][k].map(|v| v.1).unwrap_or(0);
    }
    Ok(chosen)
}

/// What a leg that began inside (or within the clearance of) a no-fly zone, threat or pop-up
/// did first, for the command line: the region's name and the exit's length; `None` for a leg
/// that began clear. The core numbers obstacles as [`crate::local::local_obstacles_named`]
/// does, and pop-ups by the order they were added (`popups`).
pub fn exit_note(leg: &Leg, scenario: &Scenario, popups: &[LocalPopup]) -> Option<String> {
    let exit = leg.summary.exit?;
    let region = match exit.violated {
        Violation::Obstacle(i) => {
            crate::local::local_obstacles_named(scenario, &scenario.local_frame())
                .into_iter()
                .nth(i as usize)
                .map_or_else(|| format!("network obstacle {i}"), |(_, name)| name)
        }
        Violation::Popup(id) => popups
            .get(id as usize)
            .map_or_else(|| format!("pop-up {id}"), |p| p.name.clone()),
    };
    let others = match exit.regions {
        1 => String::new(),
        n => format!(" and {} more", n - 1),
    };
    Some(format!(
        "{} lies inside or within the clearance of {region}{others}: the leg first leaves by a \
         {:.1} m exit",
        leg.from, exit.length
    ))
}

/// For each primitive of the planner's route on a three-dimensional roadmap, its path's
/// profile and the distance along the path at which it starts; empty otherwise (in the order
/// of [`Planner::route`], the paths' primitives in turn).
fn primitive_profiles(p: &HostPlanner) -> Vec<(VerticalProfile, f32)> {
    let mut out = Vec::new();
    for (k, path) in p.route_paths().iter().enumerate() {
        let Some(profile) = p.route_profile(k) else {
            return Vec::new();
        };
        let mut offset = 0.0;
        for (prim, length) in path.primitives().iter().zip(path.lengths) {
            if prim.is_some() {
                out.push((profile, offset));
            }
            offset += length;
        }
    }
    out
}

/// Plans the chosen legs once more to keep their geometry, post-processed; returns them and
/// the route's length.
fn plan_legs(
    bytes: &[u8],
    popups: &[LocalPopup],
    options: &MissionOptions,
    stages: &[Stage],
    chosen: &[usize],
) -> Result<(Vec<Leg>, f64), MissionError> {
    let adaptive = options.connect_radius_m.is_none();
    let budget = u64::MAX;
    let mut p = planner(bytes, popups, options)?;
    let mut legs = Vec::new();
    let mut length = 0.0;
    for i in 1..stages.len() {
        let (prev, next) = (&stages[i - 1], &stages[i]);
        let from = Pose {
            position: prev.position,
            heading: prev.headings[chosen[i - 1]].unwrap_or(0.0),
        };
        let q = Query {
            start: from,
            goal: Goal {
                position: next.position,
                heading: next.headings[chosen[i]],
            },
            search: Search::AStar,
        };
        let unreachable = |error| MissionError::Unreachable {
            from: prev.name.clone(),
            to: next.name.clone(),
            error,
            detail: String::new(),
        };
        let altitudes = leg_altitudes(prev, next);
        let (planned, widened) = plan_query(&mut p, &q, altitudes, budget, adaptive);
        let planned = planned.map_err(unreachable)?;
        let arc_checks = p.arc_check_stats();
        // Post-processing (Niendorf et al. §V): both passes keep the route collision-free.
        match options.shortcuts {
            Shortcuts::Best => p.shortcut_best(budget),
            Shortcuts::Greedy => p.shortcut(budget),
        }
        .map_err(unreachable)?;
        p.smooth_headings(SMOOTHING_HEADINGS, budget)
            .map_err(unreachable)?;
        let summary = *p.route_summary().ok_or(unreachable(PlanError::Internal))?;
        length += summary.length as f64;
        let vertical = primitive_profiles(&p);
        legs.push(Leg {
            from: prev.name.clone(),
            to: next.name.clone(),
            summary,
            planned_length: planned.length,
            primitives: p.route().to_vec(),
            vertical,
            widened,
            arc_checks,
            cells_per_turn_bound: match p.network().mode() {
                Mode::Terrain => p.terrain_bound_inputs().cells_per_turn,
                _ => 0,
            },
        });
    }
    Ok((legs, length))
}
