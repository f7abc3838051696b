//! Static planners of Ruz et al. for the nominal route: the MILP on linearised point-mass
//! dynamics (eqs 1–6, obstacles eqs 4–5, piecewise-linear detection eqs 13–18, objective
//! μ₁·t + μ₂·D eq. 37; [`milp`], behind the `milp` feature) and A* with an inertia term
//! (eqs 19–21; [`astar`]). Both plan in the scenario's local frame (the network's, metres) from
//! the scenario's start to its goal, avoiding the threat discs (and no-fly polygons) widened by
//! the clearance, and both routes are polylines checked by [`check`] and scored by the core's
//! risk model ([`score`]: R_K = 1 − P_S,known, as `alternatives` scores routes). `docs/RUZ.md`
//! (*Static planners*) states the formulation and every parameter.

pub mod astar;
pub mod check;
pub mod cli;
pub mod detection;
#[cfg(feature = "milp")]
pub mod milp;

use crate::frame::LocalFrame;
use crate::local::{local, local_heading};
use crate::scenario::Scenario;
use skyroute::geometry::Segment;
use skyroute::planner::risk::{route_figures, RiskParams};
use skyroute::{Primitive, Vec2};

/// A point or vector in the local frame, metres (or m/s), f64.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pt {
    /// East.
    pub x: f64,
    /// North.
    pub y: f64,
}

impl Pt {
    /// The point `(x, y)`.
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
    /// `self − o`.
    pub fn minus(self, o: Pt) -> Pt {
        Pt::new(self.x - o.x, self.y - o.y)
    }
    /// `self + o`.
    pub fn plus(self, o: Pt) -> Pt {
        Pt::new(self.x + o.x, self.y + o.y)
    }
    /// `self · k`.
    pub fn scale(self, k: f64) -> Pt {
        Pt::new(self.x * k, self.y * k)
    }
    /// Dot product.
    pub fn dot(self, o: Pt) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// Cross product (z component).
    pub fn cross(self, o: Pt) -> f64 {
        self.x * o.y - self.y * o.x
    }
    /// Euclidean norm.
    pub fn norm(self) -> f64 {
        self.x.hypot(self.y)
    }
    /// Distance to `o`.
    pub fn dist(self, o: Pt) -> f64 {
        self.minus(o).norm()
    }
    /// As the core's f32 vector.
    pub fn vec2(self) -> Vec2 {
        Vec2::new(self.x as f32, self.y as f32)
    }
    /// From the core's f32 vector.
    pub fn of(v: Vec2) -> Pt {
        Pt::new(v.x as f64, v.y as f64)
    }
}

/// The unit vector at polar angle `2π·k/sides + offset` (the outward normals of a regular
/// polygon's sides).
pub fn direction(k: usize, sides: usize, offset: f64) -> Pt {
    let a = std::f64::consts::TAU * k as f64 / sides as f64 + offset;
    Pt::new(a.cos(), a.sin())
}

/// A circular keep-out area: a threat disc or a pop-up disc.
#[derive(Clone, Debug, PartialEq)]
pub struct Disc {
    /// What it is, e.g. `threat "T3"`.
    pub name: String,
    /// Centre, local metres.
    pub centre: Pt,
    /// Radius, metres, without the clearance.
    pub radius: f64,
}

/// A no-fly polygon in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    /// What it is, e.g. `no-fly zone "B1"`.
    pub name: String,
    /// Its ring, local metres, without the closing duplicate.
    pub ring: Vec<Pt>,
}

/// What the static planners plan: ends, keep-out areas, radars and the vehicle's bounds.
#[derive(Clone, Debug)]
pub struct Problem {
    /// The start, local metres.
    pub start: Pt,
    /// The velocity at the start: the start's heading at the nominal speed, m/s.
    pub start_velocity: Pt,
    /// The goal (any arrival heading).
    pub goal: Pt,
    /// Circular keep-out areas (the threat discs, and the pop-up discs asked for).
    pub discs: Vec<Disc>,
    /// No-fly polygons.
    pub zones: Vec<Zone>,
    /// The clearance every route keeps from discs and zones, metres.
    pub clearance: f64,
    /// The known radars (the scenario's threats' centres), local metres.
    pub radars: Vec<Pt>,
    /// v_max, m/s.
    pub v_max: f64,
    /// v_nominal, m/s (the risk model's speed).
    pub v_nominal: f64,
    /// a_max: the largest acceleration, m/s² (the vehicle's lateral limit).
    pub a_max: f64,
    /// The risk model's parameters (`crate::ruz::risk_params`).
    pub params: RiskParams,
}

/// The problem of the scenario's start → goal in `frame`, with the threat discs and the
/// pop-ups whose indices `popups` lists as keep-out discs.
pub fn problem(s: &Scenario, frame: &LocalFrame, popups: &[usize]) -> Result<Problem, String> {
    let start = s.start.as_ref().ok_or("the scenario has no start")?;
    let goal = s.goal.as_ref().ok_or("the scenario has no goal")?;
    if !s.waypoints.is_empty() {
        return Err("the static planners fly start → goal; the scenario has waypoints".into());
    }
    let heading = start.heading_deg.map_or(0.0, |h| {
        local_heading(frame, start.lon, start.lat, h) as f64
    });
    let v_nominal = s.vehicle.v_nominal_mps;
    let mut discs: Vec<Disc> = s
        .threats
        .iter()
        .map(|t| Disc {
            name: format!("threat {:?}", t.name),
            centre: Pt::of(local(frame, t.lon, t.lat)),
            radius: t.radius_m,
        })
        .collect();
    discs.extend(
        popups
            .iter()
            .filter_map(|&i| s.popups.get(i))
            .map(|p| Disc {
                name: format!("pop-up {:?}", p.name),
                centre: Pt::of(local(frame, p.lon, p.lat)),
                radius: p.radius_m,
            }),
    );
    // A zone's holes are left out: the static planners keep out of the whole exterior ring,
    // which is conservative (a hole is reachable only through the zone around it).
    let zones = s
        .no_fly
        .iter()
        .map(|z| Zone {
            name: format!("no-fly zone {:?}", z.name),
            ring: z
                .ring
                .iter()
                .map(|&(lon, lat)| Pt::of(local(frame, lon, lat)))
                .collect(),
        })
        .collect();
    Ok(Problem {
        start: Pt::of(local(frame, start.lon, start.lat)),
        start_velocity: Pt::new(heading.cos(), heading.sin()).scale(v_nominal),
        goal: Pt::of(local(frame, goal.lon, goal.lat)),
        discs,
        zones,
        clearance: s.planner.clearance_m.unwrap_or(0.0),
        radars: s
            .threats
            .iter()
            .map(|t| Pt::of(local(frame, t.lon, t.lat)))
            .collect(),
        v_max: s.vehicle.v_max_mps,
        v_nominal,
        a_max: s.vehicle.a_lat_max_mps2,
        params: super::risk_params(s),
    })
}

/// A planned route: points start → goal and the time at each, seconds from the start.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StaticRoute {
    /// The points, local metres; the route flies straight between consecutive ones.
    pub points: Vec<Pt>,
    /// The time at each point, seconds (same length as `points`).
    pub times: Vec<f64>,
}

impl StaticRoute {
    /// The route's length, metres.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| w[0].dist(w[1])).sum()
    }
    /// Its flight time on its own schedule, seconds.
    pub fn time(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }
    /// Its straight pieces as the core's primitives (zero-length pieces left out).
    pub fn primitives(&self) -> Vec<Primitive> {
        self.points
            .windows(2)
            .filter(|w| w[0].dist(w[1]) > 1e-6)
            .map(|w| Primitive::Line(Segment::new(w[0].vec2(), w[1].vec2())))
            .collect()
    }
}

/// A route's figures by the risk model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Score {
    /// Length, metres.
    pub length_m: f64,
    /// M, the risk model's steps (T = M·Δt at the nominal speed).
    pub steps: u32,
    /// R_K = 1 − P_S,known: the mission kill probability from the known radars.
    pub risk_known: f64,
}

/// Scores `route` (lines and arcs) against the known `radars` with `params`, as
/// `crate::ruz::alternatives` scores the network planner's routes (no pop-up radar).
pub fn score(params: &RiskParams, route: &[Primitive], radars: &[Pt]) -> Score {
    let known: Vec<Vec2> = radars.iter().map(|r| r.vec2()).collect();
    let f = route_figures(params, route, &known, None);
    Score {
        length_m: route.iter().map(|p| p.length() as f64).sum(),
        steps: f.steps,
        risk_known: (1.0 - f.survival_known as f64).clamp(0.0, 1.0),
    }
}
