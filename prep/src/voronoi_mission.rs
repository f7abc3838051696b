//! Planning a Voronoi mission — start → waypoints in order → goal — with the onboard core, leg
//! by leg as the aircraft would (each leg leaves where the last arrived, with its heading),
//! and the route file's JSON: the smoothed pieces, their line chords, and the route's
//! exposure both as the search costed it and as a dense integral along the flown pieces.

use crate::frame::LocalFrame;
use crate::local::{local, local_heading};
use crate::mission::LocalPopup;
use crate::route_json::{primitive_json, sampled_lon_lat, work_json};
use crate::scenario::Scenario;
use serde_json::{json, Value};
use skyroute::geometry::spline::Piece;
use skyroute::planner::{
    Goal, PlanError, Query, RouteSummary, Search, Threat, ThreatError, ThreatOrigin, VoronoiStorage,
};
use skyroute::{Planner, Pose, Primitive, Vec2};
use std::fmt;

/// The planner used for Voronoi missions on the host (its `V` holds the largest onboard
/// graph; `R` the chords of the longest route).
pub type VoronoiPlanner<'n> = Planner<'n, 1024, 1024, 16, 4096>;

/// Step of the dense exposure integral along the flown pieces, metres.
pub const EXPOSURE_STEP_M: f64 = 5.0;

/// A pop-up radar for `add_threat`: name, local position and reference distance.
#[derive(Clone, Debug)]
pub struct LocalThreat {
    /// Its name (`--threat` N).
    pub name: String,
    /// Position, metres.
    pub position: Vec2,
    /// Exposure reference distance, metres.
    pub radius: f32,
}

/// One planned leg.
#[derive(Clone, Debug)]
pub struct VoronoiLeg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// The core's summary.
    pub summary: RouteSummary,
    /// The smoothed pieces.
    pub pieces: Vec<Piece>,
    /// Their line chords (what [`Planner::route`] holds).
    pub chords: Vec<Primitive>,
    /// The coarse route: start, graph vertices, goal.
    pub coarse: Vec<Vec2>,
    /// The largest distance of a chord from its piece, metres.
    pub chord_deviation_m: f32,
    /// Exposure of the coarse route by the paper's three-point rule.
    pub coarse_exposure: f64,
    /// Exposure of the flown pieces, dense integral.
    pub flown_exposure: f64,
}

/// A planned Voronoi mission.
#[derive(Clone, Debug)]
pub struct VoronoiMission {
    /// The legs, in order.
    pub legs: Vec<VoronoiLeg>,
    /// The weight k used.
    pub threat_weight: f32,
    /// The threats in force (the network's and the pop-up ones).
    pub threats: Vec<Threat>,
}

/// Why a Voronoi mission could not be planned.
#[derive(Debug)]
pub enum VoronoiPlanError {
    /// The network would not load.
    Load(skyroute::LoadError),
    /// A pop-up obstacle was refused: (its name, why).
    Popup(String, skyroute::planner::PopupError),
    /// A pop-up threat or the weight was refused: (what, why).
    Threat(String, ThreatError),
    /// A leg has no route: (from, to, why).
    Leg(String, String, PlanError),
    /// The scenario lacks its start or goal.
    Missing(&'static str),
}

impl fmt::Display for VoronoiPlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VoronoiPlanError::Load(e) => write!(f, "network: {e}"),
            VoronoiPlanError::Popup(name, e) => write!(f, "pop-up {name}: {e}"),
            VoronoiPlanError::Threat(what, e) => write!(f, "{what}: {e}"),
            VoronoiPlanError::Leg(a, b, e) => write!(f, "leg {a} -> {b}: {e}"),
            VoronoiPlanError::Missing(what) => write!(f, "the scenario has no {what}"),
        }
    }
}

impl std::error::Error for VoronoiPlanError {}

impl VoronoiPlanError {
    /// Whether the error is bad input (exit 1) rather than the absence of a route (exit 3).
    pub fn is_bad_input(&self) -> bool {
        match self {
            VoronoiPlanError::Load(_)
            | VoronoiPlanError::Popup(..)
            | VoronoiPlanError::Threat(..)
            | VoronoiPlanError::Missing(_) => true,
            VoronoiPlanError::Leg(_, _, e) => !matches!(
                e,
                PlanError::NoRoute
                    | PlanError::StartUnconnected
                    | PlanError::GoalUnconnected
                    | PlanError::Smoothing { .. }
            ),
        }
    }
}

/// The dense exposure integral ∫ Σ_j (r_j/d_j(s))⁴ ds along `pieces`, in f64, by the
/// trapezoidal rule at steps of at most [`EXPOSURE_STEP_M`].
pub fn flown_exposure(pieces: &[Piece], threats: &[Threat]) -> f64 {
    let density = |p: Vec2| -> f64 {
        threats
            .iter()
            .map(|t| {
                let d = (p.distance(t.position) as f64).max(0.01 * t.radius as f64);
                (t.radius as f64 / d).powi(4)
            })
            .sum()
    };
    let mut total = 0.0;
    for piece in pieces {
        let n = ((piece.length() as f64 / EXPOSURE_STEP_M).ceil() as usize).clamp(1, 100_000);
        let mut prev = piece.point(0.0);
        let mut prev_density = density(prev);
        for i in 1..=n {
            let q = piece.point(i as f32 / n as f32);
            let dq = density(q);
            total += 0.5 * (prev_density + dq) * prev.distance(q) as f64;
            prev = q;
            prev_density = dq;
        }
    }
    total
}

/// Plans the scenario's mission on the Voronoi network `bytes`, with the pop-up obstacles
/// `popups` and pop-up radars `threats` added first and the weight `k` if given.
pub fn plan_voronoi_mission(
    bytes: &[u8],
    scenario: &Scenario,
    frame: &LocalFrame,
    popups: &[LocalPopup],
    threats: &[LocalThreat],
    k: Option<f32>,
) -> Result<VoronoiMission, VoronoiPlanError> {
    let mut storage = Box::new(VoronoiStorage::new());
    let mut p: Box<VoronoiPlanner> = Box::new(Planner::new());
    p.load_voronoi(bytes, &mut storage)
        .map_err(VoronoiPlanError::Load)?;
    if let Some(k) = k {
        p.set_threat_weight(k)
            .map_err(|e| VoronoiPlanError::Threat(format!("--threat-weight {k}"), e))?;
    }
    for pop in popups {
        pop.add_to(&mut p)
            .map_err(|e| VoronoiPlanError::Popup(pop.name.clone(), e))?;
    }
    for t in threats {
        p.add_threat(t.position, t.radius)
            .map_err(|e| VoronoiPlanError::Threat(format!("threat {}", t.name), e))?;
    }
    let goal = scenario
        .goal
        .as_ref()
        .ok_or(VoronoiPlanError::Missing("goal"))?;
    let s = scenario
        .start
        .as_ref()
        .ok_or(VoronoiPlanError::Missing("start"))?;
    let stops: Vec<(String, Vec2, Option<f32>)> = scenario
        .waypoints
        .iter()
        .chain(std::iter::once(goal))
        .map(|e| {
            (
                e.name.clone(),
                local(frame, e.lon, e.lat),
                e.heading_deg.map(|h| local_heading(frame, e.lon, e.lat, h)),
            )
        })
        .collect();
    let heading = s
        .heading_deg
        .map_or(0.0, |h| local_heading(frame, s.lon, s.lat, h));
    let mut at = Pose {
        position: local(frame, s.lon, s.lat),
        heading,
    };
    let mut from = s.name.clone();
    let mut legs = Vec::new();
    for (name, position, heading) in stops {
        let query = Query {
            start: at,
            goal: Goal { position, heading },
            search: Search::Dijkstra,
        };
        let summary = p
            .plan(&query, p.worst_case_work())
            .map_err(|e| VoronoiPlanError::Leg(from.clone(), name.clone(), e))?;
        let pieces = p.route_pieces().to_vec();
        let coarse: Vec<Vec2> = std::iter::once(at.position)
            .chain(p.route_paths().iter().map(|q| q.end().position))
            .collect();
        let coarse_exposure = coarse
            .windows(2)
            .map(|w| skyroute::planner::segment_exposure(w[0], w[1], p.threats()).0 as f64)
            .sum();
        legs.push(VoronoiLeg {
            from: from.clone(),
            to: name.clone(),
            summary,
            flown_exposure: flown_exposure(&pieces, p.threats()),
            pieces,
            chords: p.route().to_vec(),
            coarse,
            chord_deviation_m: p.chord_deviation().unwrap_or(0.0),
            coarse_exposure,
        });
        at = Pose {
            position,
            heading: summary.arrival_heading,
        };
        from = name;
    }
    Ok(VoronoiMission {
        legs,
        threat_weight: p.threat_weight().unwrap_or(0.0),
        threats: p.threats().to_vec(),
    })
}

/// A piece as JSON: `line` {start, end} or `cubic` {control points}, local metres.
pub fn piece_json(p: &Piece) -> Value {
    match p {
        Piece::Line { a, b } => json!({"type": "line", "start": [a.x, a.y], "end": [b.x, b.y]}),
        Piece::Cubic { p } => json!({
            "type": "cubic",
            "control_points": p.iter().map(|q| [q.x, q.y]).collect::<Vec<_>>(),
        }),
    }
}

/// The route file of a Voronoi mission.
pub fn voronoi_route_json(m: &VoronoiMission, frame: &LocalFrame, scenario_name: &str) -> Value {
    let all: Vec<Primitive> = m.legs.iter().flat_map(|l| l.chords.clone()).collect();
    let (lat0, lon0) = frame.origin();
    let length: f32 = m.legs.iter().map(|l| l.summary.length).sum();
    json!({
        "scenario": scenario_name,
        "mode": "voronoi",
        "frame": {"origin_lat_deg": lat0, "origin_lon_deg": lon0, "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)"},
        "length_m": length,
        "threat_weight": m.threat_weight,
        "exposure_flown": m.legs.iter().map(|l| l.flown_exposure).sum::<f64>(),
        "exposure_coarse_three_point": m.legs.iter().map(|l| l.coarse_exposure).sum::<f64>(),
        "threats": m.threats.iter().map(|t| json!({
            "centre": [t.position.x, t.position.y],
            "radius_m": t.radius,
            "origin": match t.origin {
                ThreatOrigin::Network(i) => format!("network {i}"),
                ThreatOrigin::Popped(id) => format!("in flight {id}"),
            },
        })).collect::<Vec<_>>(),
        "legs": m.legs.iter().map(|l| json!({
            "from": l.from,
            "to": l.to,
            "length_m": l.summary.length,
            "planned_length_m": l.summary.length,
            "network_edges": l.summary.network_edges,
            "arrival_heading_rad": l.summary.arrival_heading,
            "work": work_json(&l.summary.work),
            "exposure_flown": l.flown_exposure,
            "exposure_coarse_three_point": l.coarse_exposure,
            "chord_deviation_m": l.chord_deviation_m,
            "coarse": l.coarse.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            "pieces": l.pieces.iter().map(piece_json).collect::<Vec<_>>(),
            "primitives": l.chords.iter().map(primitive_json).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "geometry": {"type": "LineString", "coordinates": sampled_lon_lat(&all, frame, 5.0)},
    })
}
