//! Checks of a static route: continuity (it starts at the start and ends at the goal, its
//! times increase), the speed and acceleration of its pieces, and that every straight piece
//! (not only its ends) keeps the clearance from every disc and no-fly zone. A discretised
//! planner can cut a corner between two checked points (the paper's known issue with the
//! MILP's point-wise avoidance); the worst such intrusion is reported.

use super::{Problem, Pt, StaticRoute};

/// The distance from `p` to the segment `a`–`b`.
pub fn point_segment_distance(p: Pt, a: Pt, b: Pt) -> f64 {
    let ab = b.minus(a);
    let len2 = ab.dot(ab);
    if len2 <= 0.0 {
        return p.dist(a);
    }
    let t = (p.minus(a).dot(ab) / len2).clamp(0.0, 1.0);
    p.dist(a.plus(ab.scale(t)))
}

/// Whether the segments `a`–`b` and `c`–`d` cross or touch.
pub fn segments_intersect(a: Pt, b: Pt, c: Pt, d: Pt) -> bool {
    let o = |p: Pt, q: Pt, r: Pt| q.minus(p).cross(r.minus(p));
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: Pt, q: Pt, r: Pt| point_segment_distance(r, p, q) <= 1e-9;
    on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d)
}

/// Whether `p` lies inside the polygon `ring` (even-odd rule).
pub fn point_in_polygon(p: Pt, ring: &[Pt]) -> bool {
    let mut inside = false;
    let n = ring.len();
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// The distance from the segment `a`–`b` to the polygon `ring` (0 when it enters it).
pub fn segment_polygon_distance(a: Pt, b: Pt, ring: &[Pt]) -> f64 {
    if point_in_polygon(a, ring) {
        return 0.0;
    }
    let n = ring.len();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (c, d) = (ring[i], ring[(i + 1) % n]);
        if segments_intersect(a, b, c, d) {
            return 0.0;
        }
        best = best
            .min(point_segment_distance(c, a, b))
            .min(point_segment_distance(a, c, d))
            .min(point_segment_distance(b, c, d));
    }
    best
}

/// How far the segment `a`–`b` intrudes into the problem's keep-out areas widened by
/// `clearance`: the largest `clearance − distance` (or `radius + clearance − distance` for a
/// disc) over the areas, with the area's name; `None` when there are no areas.
pub fn segment_intrusion(problem: &Problem, clearance: f64, a: Pt, b: Pt) -> Option<(f64, String)> {
    let discs = problem.discs.iter().map(|d| {
        let depth = d.radius + clearance - point_segment_distance(d.centre, a, b);
        (depth, d.name.clone())
    });
    let zones = problem.zones.iter().map(|z| {
        let depth = clearance - segment_polygon_distance(a, b, &z.ring);
        (depth, z.name.clone())
    });
    discs.chain(zones).max_by(|x, y| x.0.total_cmp(&y.0))
}

/// What [`check_route`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteCheck {
    /// Distance of the first point from the start plus that of the last from the goal, m.
    pub end_gap_m: f64,
    /// Whether the times strictly increase along the points.
    pub times_increase: bool,
    /// The fastest piece's speed (length / duration), m/s.
    pub max_speed: f64,
    /// The slowest piece's speed, m/s.
    pub min_speed: f64,
    /// The largest change of velocity between consecutive pieces divided by the mean of their
    /// durations, m/s² (0 for a route of one piece).
    pub max_accel: f64,
    /// The worst intrusion of a piece into a keep-out area widened by the clearance, metres
    /// (≤ 0: every piece keeps the clearance), with the piece's index and the area's name.
    pub worst_intrusion: Option<(f64, usize, String)>,
}

impl RouteCheck {
    /// Whether the route is continuous, within `v_max`·(1 + tol) and `a_max`·(1 + tol), and
    /// keeps the clearance (intrusion ≤ `tol_m`).
    pub fn ok(&self, v_max: f64, a_max: f64, tol: f64, tol_m: f64) -> bool {
        self.end_gap_m <= tol_m
            && self.times_increase
            && self.max_speed <= v_max * (1.0 + tol)
            && self.max_accel <= a_max * (1.0 + tol)
            && self.worst_intrusion.as_ref().is_none_or(|w| w.0 <= tol_m)
    }
}

/// Checks `route` against `problem`: ends, times, speeds, accelerations and every piece's
/// clearance.
pub fn check_route(problem: &Problem, route: &StaticRoute) -> RouteCheck {
    let pts = &route.points;
    let end_gap_m = match (pts.first(), pts.last()) {
        (Some(a), Some(b)) => a.dist(problem.start) + b.dist(problem.goal),
        _ => f64::INFINITY,
    };
    let times_increase =
        route.times.len() == pts.len() && route.times.windows(2).all(|w| w[1] > w[0]);
    let mut velocities = Vec::new();
    let (mut max_speed, mut min_speed) = (0.0f64, f64::INFINITY);
    let mut worst: Option<(f64, usize, String)> = None;
    for (i, w) in pts.windows(2).enumerate() {
        let dt = route
            .times
            .get(i + 1)
            .zip(route.times.get(i))
            .map_or(0.0, |(b, a)| b - a);
        let v = w[1].minus(w[0]).scale(1.0 / dt.max(1e-12));
        max_speed = max_speed.max(v.norm());
        min_speed = min_speed.min(v.norm());
        velocities.push((v, dt));
        if let Some((depth, name)) = segment_intrusion(problem, problem.clearance, w[0], w[1]) {
            if worst.as_ref().is_none_or(|x| depth > x.0) {
                worst = Some((depth, i, name));
            }
        }
    }
    let max_accel = velocities
        .windows(2)
        .map(|w| w[1].0.minus(w[0].0).norm() / (0.5 * (w[0].1 + w[1].1)).max(1e-12))
        .fold(0.0, f64::max);
    RouteCheck {
        end_gap_m,
        times_increase,
        max_speed,
        min_speed: if min_speed.is_finite() {
            min_speed
        } else {
            0.0
        },
        max_accel,
        worst_intrusion: worst,
    }
}
