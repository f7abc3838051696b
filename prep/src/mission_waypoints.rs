//! Waypoints for autopilots that fly straight lines between waypoints (PX4, ArduPilot), chosen
//! from a route of lines and arcs (`docs/AUTOPILOTS.md`).
//!
//! Every primitive's ends are waypoints (an arc's tangent points, a line's ends, a Voronoi
//! route's chord ends), and every arc is cut into `n` equal pieces whose chord's sagitta
//! `r (1 - cos(Δ/2))` is at most half the tolerance, with `Δ` at most 90°. Between two
//! consecutive waypoints the route is then either a line (the polyline follows it exactly) or
//! one arc piece (the polyline's cross-track error is exactly its sagitta), so the polyline's
//! deviation from the route is known exactly.
//!
//! An autopilot accepts a waypoint within its acceptance radius `A` and turns onto the next
//! segment early. Idealised as the circle tangent to both segments at distance `A` from the
//! corner, a turn of `θ` misses the corner by `A tan(θ/4)` towards the inside of the turn. Each
//! waypoint's acceptance radius (MAVLink `NAV_WAYPOINT` param2) is chosen so that this cut is at
//! most the other half of the tolerance, and at most half of either adjacent segment (so the
//! early turn ends before the segment's midpoint, where the idealisation holds).

use skyroute::{Primitive, Vec2};

/// The largest tolerance, metres: the polyline and the corner cuts together stay within it.
pub const MAX_TOLERANCE_M: f64 = 10.0;

/// The smallest tolerance, metres (a clearance of 0 still gets a finite number of waypoints).
pub const MIN_TOLERANCE_M: f64 = 0.5;

/// The largest acceptance radius written, metres (ArduPlane stores it in one byte).
pub const MAX_ACCEPTANCE_M: f64 = 255.0;

/// The largest arc per piece, radians: a piece never turns by more than 90°.
const MAX_PIECE_SWEEP: f64 = std::f64::consts::FRAC_PI_2;

/// Waypoints closer than this to the previous one are merged into it, metres.
const MERGE_M: f64 = 0.01;

/// The tolerance for a scenario's clearance: `min(clearance / 2, 10 m)`, at least 0.5 m (10 m
/// when the scenario states no clearance). The route keeps the clearance from the zones; the
/// autopilot's flown polyline may take at most half of it.
pub fn tolerance_m(clearance_m: Option<f64>) -> f64 {
    clearance_m
        .map_or(MAX_TOLERANCE_M, |c| (c / 2.0).min(MAX_TOLERANCE_M))
        .max(MIN_TOLERANCE_M)
}

/// The number of equal pieces an arc of `radius` and `sweep` (radians, either sign) is cut into
/// so that each piece's sagitta is at most `max_sagitta` and each turns by at most 90°.
pub fn arc_pieces(radius: f64, sweep: f64, max_sagitta: f64) -> usize {
    let ratio = (max_sagitta / radius).clamp(0.0, 1.0);
    let per_piece = (2.0 * (1.0 - ratio).acos()).min(MAX_PIECE_SWEEP);
    if per_piece <= 0.0 {
        return 1;
    }
    ((sweep.abs() / per_piece).ceil() as usize).max(1)
}

/// The sagitta of a chord of an arc of `radius` spanning `sweep` radians: the largest distance
/// between the chord and the arc, `r (1 - cos(sweep / 2))`.
pub fn sagitta(radius: f64, sweep: f64) -> f64 {
    radius * (1.0 - (sweep.abs() / 2.0).cos())
}

/// The miss distance at a corner of turn `theta` (radians) when the turn starts at distance
/// `acceptance` before it: `acceptance * tan(theta / 4)`.
pub fn corner_cut(acceptance: f64, theta: f64) -> f64 {
    acceptance * (theta.abs() / 4.0).tan()
}

/// A waypoint of a mission, in the route's local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct MissionWaypoint {
    /// Position, metres.
    pub position: (f64, f64),
    /// The name of the route's endpoint here (start, waypoint or goal), if it is one.
    pub name: Option<String>,
    /// Acceptance radius, whole metres, at least 1 (MAVLink `NAV_WAYPOINT` param2).
    pub acceptance_m: f64,
    /// The turn at this waypoint between the segments in and out, radians (0 at the ends).
    pub turn_rad: f64,
}

/// The waypoints of a route and the figures of how closely they follow it.
#[derive(Clone, Debug, PartialEq)]
pub struct WaypointPlan {
    /// The waypoints, start first, goal last.
    pub waypoints: Vec<MissionWaypoint>,
    /// The tolerance, metres ([`tolerance_m`]).
    pub tolerance_m: f64,
    /// The largest cross-track error of the polyline through the waypoints against the route,
    /// metres (the largest sagitta of an arc piece, or gap between primitives).
    pub polyline_error_m: f64,
    /// The largest corner cut at the waypoints' acceptance radii, metres ([`corner_cut`]).
    pub corner_cut_m: f64,
}

/// A leg of a route to choose waypoints on: its endpoints' names and its primitives.
pub struct LegPrimitives<'a> {
    /// The endpoint the leg leaves.
    pub from: &'a str,
    /// The endpoint the leg reaches.
    pub to: &'a str,
    /// Its lines and arcs, in order.
    pub primitives: &'a [Primitive],
}

fn xy(v: Vec2) -> (f64, f64) {
    (v.x as f64, v.y as f64)
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// The points of one primitive after its start: a line's end, or an arc's piece ends; and the
/// largest sagitta among its pieces.
fn primitive_points(p: &Primitive, max_sagitta: f64) -> (Vec<(f64, f64)>, f64) {
    match p {
        Primitive::Line(s) => (vec![xy(s.end)], 0.0),
        Primitive::Arc(a) => {
            let (r, sweep) = (a.radius as f64, a.sweep as f64);
            let n = arc_pieces(r, sweep, max_sagitta);
            let (cx, cy) = xy(a.centre);
            let points = (1..=n)
                .map(|k| {
                    let t = a.start_angle as f64 + sweep * k as f64 / n as f64;
                    (cx + r * t.cos(), cy + r * t.sin())
                })
                .collect();
            (points, sagitta(r, sweep / n as f64))
        }
    }
}

/// Appends `p` unless it coincides with the last point; a name given to a merged point is kept.
fn push_point(out: &mut Vec<MissionWaypoint>, p: (f64, f64), name: Option<&str>) {
    if let Some(last) = out.last_mut() {
        if dist(last.position, p) < MERGE_M {
            if let Some(n) = name {
                last.name = Some(n.to_string());
            }
            return;
        }
    }
    out.push(MissionWaypoint {
        position: p,
        name: name.map(str::to_string),
        acceptance_m: 1.0,
        turn_rad: 0.0,
    });
}

/// The waypoints along `legs` for a scenario clearance of `clearance_m`.
pub fn choose_waypoints(legs: &[LegPrimitives], clearance_m: Option<f64>) -> WaypointPlan {
    let tolerance = tolerance_m(clearance_m);
    let half = tolerance / 2.0;
    let mut out: Vec<MissionWaypoint> = Vec::new();
    let mut polyline_error: f64 = 0.0;
    for leg in legs {
        let Some(first) = leg.primitives.first() else {
            continue;
        };
        let start = xy(first.pose_at(0.0).position);
        if let Some(last) = out.last() {
            polyline_error = polyline_error.max(dist(last.position, start));
        }
        push_point(&mut out, start, Some(leg.from));
        for (k, p) in leg.primitives.iter().enumerate() {
            let begin = xy(p.pose_at(0.0).position);
            if let Some(last) = out.last() {
                // Consecutive primitives meet to within the f32 rounding of the route file.
                polyline_error = polyline_error.max(dist(last.position, begin));
            }
            let (points, s) = primitive_points(p, half);
            polyline_error = polyline_error.max(s);
            let count = points.len();
            for (i, q) in points.into_iter().enumerate() {
                let is_end = k + 1 == leg.primitives.len() && i + 1 == count;
                push_point(&mut out, q, is_end.then_some(leg.to));
            }
        }
    }
    let corner = assign_acceptance(&mut out, half);
    WaypointPlan {
        waypoints: out,
        tolerance_m: tolerance,
        polyline_error_m: polyline_error,
        corner_cut_m: corner,
    }
}

/// Sets each waypoint's turn and acceptance radius (the corner cut at most `budget`); returns
/// the largest corner cut.
fn assign_acceptance(w: &mut [MissionWaypoint], budget: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..w.len() {
        let here = w[i].position;
        let before = i.checked_sub(1).map(|j| w[j].position);
        let after = w.get(i + 1).map(|n| n.position);
        let mut limit = MAX_ACCEPTANCE_M;
        for p in before.iter().chain(after.iter()) {
            limit = limit.min(dist(here, *p) / 2.0);
        }
        let theta = match (before, after) {
            (Some(a), Some(b)) => {
                let (u, v) = ((here.0 - a.0, here.1 - a.1), (b.0 - here.0, b.1 - here.1));
                (u.0 * v.1 - u.1 * v.0).abs().atan2(u.0 * v.0 + u.1 * v.1)
            }
            _ => 0.0,
        };
        let quarter = (theta / 4.0).tan();
        if quarter > 0.0 {
            limit = limit.min(budget / quarter);
        }
        let acceptance = limit.floor().max(1.0);
        w[i].turn_rad = theta;
        w[i].acceptance_m = acceptance;
        worst = worst.max(corner_cut(acceptance, theta));
    }
    worst
}

/// The distance from `p` to a primitive, metres: to the nearest point of a line segment, or of
/// an arc (its circle where `p`'s direction from the centre lies within the sweep, else the
/// nearer end).
pub fn distance_to_primitive(p: (f64, f64), prim: &Primitive) -> f64 {
    match prim {
        Primitive::Line(s) => {
            let (a, b) = (xy(s.start), xy(s.end));
            let d = (b.0 - a.0, b.1 - a.1);
            let len2 = d.0 * d.0 + d.1 * d.1;
            let t = if len2 > 0.0 {
                (((p.0 - a.0) * d.0 + (p.1 - a.1) * d.1) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            dist(p, (a.0 + t * d.0, a.1 + t * d.1))
        }
        Primitive::Arc(a) => {
            let c = xy(a.centre);
            let (start, sweep) = (a.start_angle as f64, a.sweep as f64);
            let angle = (p.1 - c.1).atan2(p.0 - c.0);
            let tau = std::f64::consts::TAU;
            // How far along the sweep's direction `angle` lies from the start, in [0, 2π).
            let along = ((angle - start) * sweep.signum()).rem_euclid(tau);
            if along <= sweep.abs() {
                (dist(p, c) - a.radius as f64).abs()
            } else {
                let end = start + sweep;
                let r = a.radius as f64;
                let ends = [
                    (c.0 + r * start.cos(), c.1 + r * start.sin()),
                    (c.0 + r * end.cos(), c.1 + r * end.sin()),
                ];
                dist(p, ends[0]).min(dist(p, ends[1]))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyroute::{Arc, Segment};

    #[test]
    fn the_tolerance_is_half_the_clearance_within_its_bounds() {
        assert_eq!(tolerance_m(Some(7.0)), 3.5);
        assert_eq!(tolerance_m(Some(50.0)), 10.0);
        assert_eq!(tolerance_m(Some(0.0)), MIN_TOLERANCE_M);
        assert_eq!(tolerance_m(None), 10.0);
    }

    #[test]
    fn arc_pieces_keep_the_sagitta_and_no_fewer_would() {
        for &(r, sweep, s) in &[(64.0, 3.0, 1.75), (300.0, 1.2, 5.0), (64.0, -6.0, 0.25)] {
            let n = arc_pieces(r, sweep, s);
            assert!(sagitta(r, sweep / n as f64) <= s + 1e-12, "{r} {sweep} {s}");
            if n > 1 && sweep.abs() / (n - 1) as f64 <= MAX_PIECE_SWEEP {
                assert!(
                    sagitta(r, sweep / (n - 1) as f64) > s,
                    "{n} is not the least"
                );
            }
        }
    }

    #[test]
    fn an_arc_route_gets_tangent_points_and_bounded_corner_cuts() {
        let line = Primitive::Line(Segment::new(Vec2::new(0.0, 0.0), Vec2::new(100.0, 0.0)));
        let arc = Primitive::Arc(Arc {
            centre: Vec2::new(100.0, 64.0),
            radius: 64.0,
            start_angle: -std::f32::consts::FRAC_PI_2,
            sweep: std::f32::consts::PI,
        });
        let prims = [line, arc];
        let legs = [LegPrimitives {
            from: "S",
            to: "G",
            primitives: &prims,
        }];
        let plan = choose_waypoints(&legs, Some(7.0));
        let w = &plan.waypoints;
        assert_eq!(w.first().unwrap().name.as_deref(), Some("S"));
        assert_eq!(w.last().unwrap().name.as_deref(), Some("G"));
        // π of arc at r = 64 m with a sagitta of at most 1.75 m: 2 acos(1 - 1.75/64) = 26.8°.
        assert_eq!(w.len(), 2 + arc_pieces(64.0, std::f64::consts::PI, 1.75));
        assert!(plan.polyline_error_m <= 1.75 && plan.corner_cut_m <= 1.75 + 1e-9);
        for p in w {
            let d = prims
                .iter()
                .map(|q| distance_to_primitive(p.position, q))
                .fold(f64::INFINITY, f64::min);
            assert!(d < 1e-3, "{p:?} is {d} m off the route");
            assert!(p.acceptance_m >= 1.0 && p.acceptance_m.fract() == 0.0);
        }
    }
}
