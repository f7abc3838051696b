//! Planning on a landmark network with the onboard core, as the aircraft would, on the host:
//! choose the weather, add pop-ups, plan the stored start (or where the aircraft is, with the
//! range it has left) to the stored goal, and describe the route (overflights with their
//! heading and the range they allow, Hermite pieces) for the `skyroute plan` route file.

use crate::frame::LocalFrame;
use crate::mission::{CompactHostPlanner, LocalPopup};
use crate::scenario::Scenario;
use serde_json::{json, Value};
use skyroute::geometry::compass_deg_from_heading;
use skyroute::geometry::hermite::HermiteSegment;
use skyroute::planner::{Goal, PlanError, Query, RouteSummary, Search};
use skyroute::{LoadError, Network, Planner, PopupError, Pose};
use std::fmt;

/// An overflight on the route and the leg that leaves it.
#[derive(Clone, Debug, PartialEq)]
pub struct Overflight {
    /// The landmark's name (from the scenario).
    pub landmark: String,
    /// Overflight heading, compass degrees (grid north of the local frame).
    pub heading_deg: f32,
    /// Quality `q(α, ω)` in the planned weather (or the in-flight override).
    pub quality: f32,
    /// The range it allows, `d_max · q`, metres.
    pub range_m: f32,
    /// Length of the leg that leaves it, metres.
    pub leg_m: f32,
}

/// A start that is not the network's (`skyroute plan --start`): where the aircraft is, and
/// what fixes the range it has left.
#[derive(Clone, Debug, PartialEq)]
pub struct OnlineStart {
    /// The aircraft's pose, local frame.
    pub pose: Pose,
    /// Metres flown since the last overflight (`--flown-m`).
    pub flown_m: f32,
    /// The last overflight (`--last-overflight`): a landmark's name and the compass heading it
    /// was crossed at. `None`: the range counts from the scenario's start (its `dist_m`).
    pub last_overflight: Option<(String, f64)>,
}

/// A planned landmark route.
#[derive(Clone, Debug)]
pub struct LandmarkRoute {
    /// The weather's name.
    pub weather: String,
    /// The core's summary.
    pub summary: RouteSummary,
    /// The route's network edges, start to goal.
    pub edges: Vec<u32>,
    /// The overflights in order.
    pub overflights: Vec<Overflight>,
    /// Edges removed by navigability pruning in this weather, and edges between overflights.
    pub pruned: (u32, u32),
    /// From an [`OnlineStart`]: the range it had left, metres, and the piece that joins it to
    /// the first overflight (or the goal).
    pub online_start: Option<(f32, HermiteSegment)>,
    /// To a goal that is not the network's: the piece from the last overflight.
    pub goal_piece: Option<HermiteSegment>,
}

/// Why a landmark route could not be planned.
#[derive(Clone, Debug, PartialEq)]
pub enum LandmarkPlanError {
    /// The network is not a landmark network.
    NotLandmark,
    /// The weather is not one of the scenario's.
    UnknownWeather(String, Vec<String>),
    /// The network's landmark or weather count differs from the scenario's.
    ScenarioMismatch(String),
    /// The core refused the network.
    Load(LoadError),
    /// A pop-up could not be added.
    Popup(String, PopupError),
    /// `--last-overflight` names no landmark of the scenario.
    UnknownLandmark(String),
    /// The range flown since the last overflight exceeds the range it allowed (metres: flown,
    /// allowed).
    RangeSpent(f32, f32),
    /// No overflight within the range left is reachable by one flyable piece clear of the
    /// zones and pop-ups (the range left, metres).
    OnlineStartUnconnected(f32),
    /// No overflight reaches the goal (not the network's) by one flyable piece clear of the
    /// zones and pop-ups within the range it allows.
    OnlineGoalUnconnected,
    /// The core found no route.
    Plan(PlanError),
}

impl fmt::Display for LandmarkPlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotLandmark => write!(f, "not a landmark network"),
            Self::UnknownWeather(w, known) => {
                write!(f, "weather {w:?} is not one of the scenario's: {known:?}")
            }
            Self::ScenarioMismatch(what) => {
                write!(f, "the network does not match the scenario: {what}")
            }
            Self::Load(e) => write!(f, "the network does not load: {e}"),
            Self::Popup(name, e) => write!(f, "pop-up {name}: {e}"),
            Self::UnknownLandmark(name) => {
                write!(
                    f,
                    "--last-overflight: {name:?} is not a landmark of the scenario"
                )
            }
            Self::RangeSpent(flown, allowed) => write!(
                f,
                "--flown-m: {flown} m flown since the last overflight, which allows {allowed} m: \
                 no landmark can be reached in range"
            ),
            Self::OnlineStartUnconnected(range) => write!(
                f,
                "--start: no overflight within the range left ({:.1} km) is reached by one \
                 flyable Hermite piece clear of the no-fly zones and pop-ups",
                range / 1000.0
            ),
            Self::OnlineGoalUnconnected => write!(
                f,
                "--goal: no overflight reaches it by one flyable Hermite piece clear of the \
                 no-fly zones and pop-ups within the range the overflight allows"
            ),
            Self::Plan(e) => write!(f, "no navigable route from the start to the goal: {e}"),
        }
    }
}

impl std::error::Error for LandmarkPlanError {}

/// Plans the network's start (or `online`) → the network's goal (or `online_goal`) in
/// `weather` (a name of `s.weather`; `None`: the first) with `popups` added.
pub fn plan_landmark(
    bytes: &[u8],
    s: &Scenario,
    weather: Option<&str>,
    popups: &[LocalPopup],
    online: Option<&OnlineStart>,
    online_goal: Option<Goal>,
) -> Result<LandmarkRoute, LandmarkPlanError> {
    let net = Network::from_bytes(bytes).map_err(LandmarkPlanError::Load)?;
    let l = *net.landmark().ok_or(LandmarkPlanError::NotLandmark)?;
    if l.landmark_count as usize != s.landmarks.len() || l.weather_count as usize != s.weather.len()
    {
        return Err(LandmarkPlanError::ScenarioMismatch(format!(
            "{} landmarks and {} weathers in the network, {} and {} in the scenario",
            l.landmark_count,
            l.weather_count,
            s.landmarks.len(),
            s.weather.len()
        )));
    }
    let w = match weather {
        None => 0,
        Some(name) => s.weather.iter().position(|x| x == name).ok_or_else(|| {
            LandmarkPlanError::UnknownWeather(name.to_string(), s.weather.clone())
        })?,
    } as u32;
    // About 4 MiB: on the heap.
    let mut p: Box<CompactHostPlanner> = Box::new(Planner::new());
    p.load(bytes).map_err(LandmarkPlanError::Load)?;
    p.set_weather(w).map_err(LandmarkPlanError::Plan)?;
    for pop in popups {
        pop.add_to(&mut p)
            .map_err(|e| LandmarkPlanError::Popup(pop.name.clone(), e))?;
    }
    let overflight_count = l.landmark_count * l.directions;
    let between: Vec<u32> = (0..net.edge_count())
        .filter(|&e| {
            net.edge_source(e)
                .is_some_and(|source| source < overflight_count)
        })
        .collect();
    let pruned = between.iter().filter(|&&e| !p.is_navigable(e)).count() as u32;
    let start = match online {
        None => net
            .vertex(l.start_vertex)
            .ok_or(LandmarkPlanError::NotLandmark)?,
        Some(o) => {
            let range = range_left(&p, &net, s, o)?;
            p.set_start_range(range).map_err(LandmarkPlanError::Plan)?;
            o.pose
        }
    };
    let goal = net
        .vertex(l.goal_vertex)
        .ok_or(LandmarkPlanError::NotLandmark)?;
    let query = Query {
        start,
        goal: online_goal.unwrap_or(Goal {
            position: goal.position,
            heading: None,
        }),
        search: Search::Dijkstra,
    };
    let summary = p
        .plan(&query, p.worst_case_work())
        .map_err(|e| match (e, p.start_range()) {
            (PlanError::StartUnconnected, Some(range)) if online.is_some() => {
                LandmarkPlanError::OnlineStartUnconnected(range)
            }
            (PlanError::GoalUnconnected, _) => LandmarkPlanError::OnlineGoalUnconnected,
            (e, _) => LandmarkPlanError::Plan(e),
        })?;
    let online_start = match online {
        Some(_) => Some((
            p.start_range().unwrap_or(0.0),
            p.start_piece()
                .ok_or(LandmarkPlanError::Plan(PlanError::Internal))?,
        )),
        None => None,
    };
    let edges = p.route_edges().to_vec();
    let goal_piece = p.goal_piece();
    // Each overflight with the leg that leaves it: the edges' sources, then, before an online
    // goal's piece, the last edge's target (or the online start's).
    let mut legs: Vec<(u32, f32)> = edges
        .iter()
        .filter_map(|&e| Some((net.edge_source(e)?, net.edge_record(e)?.cost)))
        .collect();
    if let Some(piece) = goal_piece {
        // No edge: the piece leaves the query's start itself.
        if let Some(v) = edges
            .last()
            .and_then(|&e| net.edge_link(e))
            .map(|r| r.target)
        {
            legs.push((v, piece.length()));
        }
    }
    let mut overflights = Vec::new();
    for (source, leg_m) in legs {
        if source >= overflight_count {
            continue;
        }
        let (lm, k) = (source / l.directions, source % l.directions);
        let quality = p.quality(lm, k).unwrap_or(0.0);
        let d_max = net.landmark_site(lm).map_or(0.0, |x| x.1);
        let heading = net.vertex(source).map_or(0.0, |v| v.heading);
        overflights.push(Overflight {
            landmark: s.landmarks[lm as usize].name.clone(),
            heading_deg: compass_deg_from_heading(heading),
            quality,
            range_m: d_max * quality,
            leg_m,
        });
    }
    Ok(LandmarkRoute {
        weather: s.weather[w as usize].clone(),
        summary,
        edges,
        overflights,
        pruned: (pruned, between.len() as u32),
        online_start,
        goal_piece,
    })
}

/// The range `o` has left: its last overflight's `d_max·q` in the weather in force (the
/// stored direction nearest its heading), or the network's start range, less what it flew.
fn range_left(
    p: &CompactHostPlanner,
    net: &Network,
    s: &Scenario,
    o: &OnlineStart,
) -> Result<f32, LandmarkPlanError> {
    let l = net.landmark().ok_or(LandmarkPlanError::NotLandmark)?;
    let allowed = match &o.last_overflight {
        None => l.start_range_m,
        Some((name, compass_deg)) => {
            let index = s
                .landmarks
                .iter()
                .position(|m| &m.name == name)
                .ok_or_else(|| LandmarkPlanError::UnknownLandmark(name.clone()))?
                as u32;
            let off = |v: u32| {
                let deg = net
                    .vertex(v)
                    .map_or(0.0, |x| compass_deg_from_heading(x.heading));
                (deg as f64 - compass_deg)
                    .rem_euclid(360.0)
                    .min((compass_deg - deg as f64).rem_euclid(360.0))
            };
            let first = index * l.directions;
            let nearest = (first..first + l.directions)
                .min_by(|&a, &b| off(a).total_cmp(&off(b)))
                .ok_or(LandmarkPlanError::NotLandmark)?;
            p.overflight_range(nearest)
                .ok_or(LandmarkPlanError::NotLandmark)?
        }
    };
    let left = allowed - o.flown_m;
    if left.is_nan() || left < 0.0 {
        return Err(LandmarkPlanError::RangeSpent(o.flown_m, allowed));
    }
    Ok(left)
}

/// The route file of a landmark route: overflights, and every Hermite piece as its two line
/// elements (local metres and m/s) with the piece's parameter range, so an autopilot can
/// rebuild and sample it ([`skyroute::geometry::hermite::HermiteSegment::new`]); `legs` holds
/// each leg (the online start's piece, each edge, the online goal's piece) as a 50 m polyline for
/// `skyroute render`, `geometry` the route for GIS tools.
pub fn landmark_route_json(
    r: &LandmarkRoute,
    bytes: &[u8],
    frame: &LocalFrame,
    scenario_name: &str,
) -> Value {
    let net = Network::from_bytes(bytes).ok();
    // The legs: (edge, its pieces), the online start's piece first with no edge.
    let mut route_legs: Vec<(Option<u32>, Vec<HermiteSegment>)> = Vec::new();
    if let Some((_, piece)) = &r.online_start {
        route_legs.push((None, vec![*piece]));
    }
    if let Some(net) = &net {
        for &e in &r.edges {
            let pieces = (0..net.chain_piece_count(e))
                .filter_map(|k| net.chain_piece(e, k))
                .collect();
            route_legs.push((Some(e), pieces));
        }
    }
    if let Some(piece) = &r.goal_piece {
        route_legs.push((None, vec![*piece]));
    }
    // Leg names: the start, the overflown landmarks in order, the goal.
    let mut names = vec!["start".to_string()];
    names.extend(r.overflights.iter().map(|o| o.landmark.clone()));
    names.push("goal".to_string());
    let mut pieces = Vec::new();
    let mut line = Vec::new();
    let mut legs = Vec::new();
    for (i, (edge, segs)) in route_legs.iter().enumerate() {
        // For drawing (`skyroute render`): the pieces as a polyline through points 50 m
        // apart along the parameter; the exact curves are in `pieces`.
        let mut polyline: Vec<Value> = Vec::new();
        let mut last: Option<skyroute::Vec2> = None;
        for seg in segs {
            for q in sample(seg, 50.0) {
                if let Some(a) = last.filter(|a| a.distance(q) > 0.0) {
                    polyline.push(json!({"type": "line", "start": [a.x, a.y], "end": [q.x, q.y]}));
                }
                last = Some(q);
            }
            let mut piece = crate::route_json::hermite_piece_json(seg);
            piece["edge"] = json!(edge);
            pieces.push(piece);
            for q in sample(seg, 200.0).skip(usize::from(!line.is_empty())) {
                let (lon, lat) = frame.to_geo(q.x as f64, q.y as f64);
                line.push([lon, lat]);
            }
        }
        legs.push(json!({
            "from": names.get(i).cloned().unwrap_or_default(),
            "to": names.get(i + 1).cloned().unwrap_or_default(),
            "length_m": edge
                .and_then(|e| net.as_ref()?.edge_length(e))
                .unwrap_or_else(|| segs.iter().map(|s| s.length()).sum::<f32>()),
            "primitives": polyline,
        }));
    }
    let (lat0, lon0) = frame.origin();
    json!({
        "scenario": scenario_name,
        "mode": "landmark",
        "frame": {"origin_lat_deg": lat0, "origin_lon_deg": lon0, "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)"},
        "weather": r.weather,
        "length_m": r.summary.length,
        "network_edges": r.summary.network_edges,
        "pieces_count": r.summary.primitives,
        "work": crate::route_json::work_json(&r.summary.work),
        "navigability_pruned": {"edges": r.pruned.0, "of": r.pruned.1},
        "online_start": r.online_start.as_ref().map(|(range, piece)| json!({
            "range_left_m": range,
            "piece_length_m": piece.length(),
        })),
        "overflights": r.overflights.iter().map(|o| json!({
            "landmark": o.landmark,
            "heading_deg": o.heading_deg,
            "quality": o.quality,
            "range_m": o.range_m,
            "next_leg_m": o.leg_m,
        })).collect::<Vec<_>>(),
        "pieces": pieces,
        "legs": legs,
        "geometry": {"type": "LineString", "coordinates": line},
    })
}

/// Points of `seg` about `step` metres apart along its parameter, both ends included.
fn sample(seg: &HermiteSegment, step: f32) -> impl Iterator<Item = skyroute::Vec2> + '_ {
    let n = (seg.length() / step).ceil().max(1.0) as usize;
    (0..=n).filter_map(move |j| seg.position(seg.t_max() * j as f32 / n as f32))
}
