//! Planning on a landmark network with the onboard core, as the aircraft would, on the host:
//! choose the weather, add pop-ups, plan the stored start to the stored goal, and describe the
//! route (overflights with their heading and the range they allow, Hermite pieces) for the
//! `skyroute plan` route file.

use crate::frame::LocalFrame;
use crate::mission::{CompactHostPlanner, LocalPopup};
use crate::scenario::Scenario;
use serde_json::{json, Value};
use skyroute::geometry::compass_deg_from_heading;
use skyroute::planner::{Goal, PlanError, Query, RouteSummary, Search};
use skyroute::{LoadError, Network, Planner, PopupError};
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
            Self::Plan(e) => write!(f, "no navigable route from the start to the goal: {e}"),
        }
    }
}

impl std::error::Error for LandmarkPlanError {}

/// Plans the network's start → goal in `weather` (a name of `s.weather`; `None`: the first) with
/// `popups` added.
pub fn plan_landmark(
    bytes: &[u8],
    s: &Scenario,
    weather: Option<&str>,
    popups: &[LocalPopup],
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
        p.add_popup(skyroute::Popup::Circle {
            centre: pop.centre,
            radius: pop.radius,
        })
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
    let start = net
        .vertex(l.start_vertex)
        .ok_or(LandmarkPlanError::NotLandmark)?;
    let goal = net
        .vertex(l.goal_vertex)
        .ok_or(LandmarkPlanError::NotLandmark)?;
    let query = Query {
        start,
        goal: Goal {
            position: goal.position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let summary = p
        .plan(&query, p.worst_case_work())
        .map_err(LandmarkPlanError::Plan)?;
    let edges = p.route_edges().to_vec();
    let mut overflights = Vec::new();
    for &e in &edges {
        let (Some(r), Some(source)) = (net.edge_record(e), net.edge_source(e)) else {
            continue;
        };
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
            leg_m: r.cost,
        });
    }
    Ok(LandmarkRoute {
        weather: s.weather[w as usize].clone(),
        summary,
        edges,
        overflights,
        pruned: (pruned, between.len() as u32),
    })
}

/// The route file of a landmark route: overflights, and every Hermite piece as its two line
/// elements (local metres and m/s) with the piece's parameter range, so an autopilot can
/// rebuild and sample it ([`skyroute::geometry::hermite::HermiteSegment::new`]); `legs` holds
/// each edge as a 50 m polyline for `skyroute render`, `geometry` the route for GIS tools.
pub fn landmark_route_json(
    r: &LandmarkRoute,
    bytes: &[u8],
    frame: &LocalFrame,
    scenario_name: &str,
) -> Value {
    let net = Network::from_bytes(bytes).ok();
    let mut pieces = Vec::new();
    let mut line = Vec::new();
    let mut legs = Vec::new();
    if let Some(net) = &net {
        // Leg names: the start, the overflown landmarks in order, the goal.
        let mut names = vec!["start".to_string()];
        names.extend(r.overflights.iter().map(|o| o.landmark.clone()));
        names.push("goal".to_string());
        for (i, &e) in r.edges.iter().enumerate() {
            // For drawing (`skyroute render`): the pieces as a polyline through points 50 m
            // apart along the parameter; the exact curves are in `pieces`.
            let mut polyline: Vec<Value> = Vec::new();
            let mut last: Option<skyroute::Vec2> = None;
            for k in 0..net.chain_piece_count(e) {
                let Some(seg) = net.chain_piece(e, k) else {
                    continue;
                };
                let n = (seg.length() / 50.0).ceil().max(1.0) as usize;
                for j in 0..=n {
                    let Some(q) = seg.position(seg.t_max() * j as f32 / n as f32) else {
                        continue;
                    };
                    if let Some(a) = last {
                        if a.distance(q) > 0.0 {
                            polyline.push(
                                json!({"type": "line", "start": [a.x, a.y], "end": [q.x, q.y]}),
                            );
                        }
                    }
                    last = Some(q);
                }
            }
            legs.push(json!({
                "from": names.get(i).cloned().unwrap_or_default(),
                "to": names.get(i + 1).cloned().unwrap_or_default(),
                "length_m": net.edge_length(e).unwrap_or(0.0),
                "primitives": polyline,
            }));
        }
        for &e in &r.edges {
            for k in 0..net.chain_piece_count(e) {
                let Some(seg) = net.chain_piece(e, k) else {
                    continue;
                };
                let mut piece = crate::route_json::hermite_piece_json(&seg);
                piece["edge"] = json!(e);
                pieces.push(piece);
                let n = (seg.length() / 200.0).ceil().max(1.0) as usize;
                for i in usize::from(!line.is_empty())..=n {
                    let Some(q) = seg.position(seg.t_max() * i as f32 / n as f32) else {
                        continue;
                    };
                    let (lon, lat) = frame.to_geo(q.x as f64, q.y as f64);
                    line.push([lon, lat]);
                }
            }
        }
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
