//! The independent f64 reference geometry the tests check routes and networks against.
//!
//! Written here from the textbook formulas, in f64, and never calling `skyroute`'s geometry:
//! a clamped projection for point–segment distances, the even–odd crossing rule for
//! containment, orientation signs for proper crossings, and the power basis for quintic
//! Hermite pieces. Points are `(x, y)` tuples in metres. Specialised references that only one
//! test needs (Dubins brute force, exact rational predicates, sampled grid traversals) stay in
//! that test's module, beside what they check.

use skyroute::geometry::hermite::HermiteSegment;
use skyroute::geometry::vertical::{VerticalLimits, VerticalProfile};
use skyroute::{Primitive, Vec2};

/// A point or vector in f64.
pub type P = (f64, f64);

/// Euclidean distance.
pub fn dist(a: P, b: P) -> f64 {
    (b.0 - a.0).hypot(b.1 - a.1)
}

/// Distance from `p` to the closed segment `a`–`b` (clamped projection; a point for `a == b`).
pub fn dist_point_segment(p: P, a: P, b: P) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p.0 - a.0 - t * dx).powi(2) + (p.1 - a.1 - t * dy).powi(2)).sqrt()
}

/// `(a − o) × (b − o)`: positive when `o → a → b` turns left.
pub fn cross(o: P, a: P, b: P) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// Whether the segments `ab` and `cd` cross properly (touching counts through the distance
/// test of the caller).
pub fn segments_cross(a: P, b: P, c: P, d: P) -> bool {
    let (d1, d2) = (cross(c, d, a), cross(c, d, b));
    let (d3, d4) = (cross(a, b, c), cross(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Distance between the closed segments `ab` and `cd` (0 if they cross).
pub fn dist_segment_segment(a: P, b: P, c: P, d: P) -> f64 {
    if segments_cross(a, b, c, d) {
        return 0.0;
    }
    dist_point_segment(a, c, d)
        .min(dist_point_segment(b, c, d))
        .min(dist_point_segment(c, a, b))
        .min(dist_point_segment(d, a, b))
}

/// Even–odd crossing test (points exactly on the boundary may go either way: they are within
/// any clearance ≥ 0 anyway).
pub fn inside(p: P, poly: &[P]) -> bool {
    let mut c = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) * (b.0 - a.0) / (b.1 - a.1) {
            c = !c;
        }
    }
    c
}

/// Distance from `p` to the polygon's area: 0 inside, else to the nearest boundary edge.
pub fn dist_polygon(p: P, poly: &[P]) -> f64 {
    if inside(p, poly) {
        return 0.0;
    }
    (0..poly.len())
        .map(|i| dist_point_segment(p, poly[i], poly[(i + 1) % poly.len()]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from the segment `ab` to the polygon's area: 0 if it enters it.
pub fn dist_segment_polygon(a: P, b: P, poly: &[P]) -> f64 {
    if inside(a, poly) || inside(b, poly) {
        return 0.0;
    }
    (0..poly.len())
        .map(|i| dist_segment_segment(a, b, poly[i], poly[(i + 1) % poly.len()]))
        .fold(f64::INFINITY, f64::min)
}

/// A quintic Hermite piece in f64 from its stored normalised coefficients
/// (`q(s) = Σ b_k s^k`, `s = t / T ∈ [0, 1]`).
pub struct Poly64 {
    /// The coefficients `b_0 … b_5`, f64.
    pub b: [P; 6],
    /// The piece's duration `T`, s.
    pub t: f64,
}

impl Poly64 {
    /// The piece's coefficients, widened to f64.
    pub fn new(seg: &HermiteSegment) -> Self {
        Self {
            b: seg
                .normalized_coefficients()
                .map(|v| (v.x as f64, v.y as f64)),
            t: seg.t_max() as f64,
        }
    }
    /// Position, velocity and acceleration (per second) at `s ∈ [0, 1]`.
    pub fn eval(&self, s: f64) -> (P, P, P) {
        let (mut p, mut v, mut a) = ((0.0, 0.0), (0.0, 0.0), (0.0, 0.0));
        for (k, bk) in self.b.iter().enumerate() {
            let kf = k as f64;
            let sk = s.powi(k as i32);
            p.0 += bk.0 * sk;
            p.1 += bk.1 * sk;
            if k >= 1 {
                let f = kf * s.powi(k as i32 - 1) / self.t;
                v.0 += bk.0 * f;
                v.1 += bk.1 * f;
            }
            if k >= 2 {
                let f = kf * (kf - 1.0) * s.powi(k as i32 - 2) / (self.t * self.t);
                a.0 += bk.0 * f;
                a.1 += bk.1 * f;
            }
        }
        (p, v, a)
    }
}

/// The polygons among `obstacles`, in f64 (circles left out).
pub fn obstacle_polygons(obstacles: &[skyroute::network::write::ObstacleSpec]) -> Vec<Vec<P>> {
    use skyroute::network::write::ObstacleSpec;
    obstacles
        .iter()
        .filter_map(|o| match o {
            ObstacleSpec::Polygon(pts) => {
                Some(pts.iter().map(|p| (p.x as f64, p.y as f64)).collect())
            }
            _ => None,
        })
        .collect()
}

/// The least f64 distance from `c` to the lines and arcs of `route`, sampled every 0.5 m
/// along each (the points are the route's own, from `Primitive::pose_at`: what is flown).
/// Sampling can only overstate the least distance, by at most the square of 0.25 m over
/// twice the distance.
pub fn route_distance(route: &[Primitive], c: Vec2) -> f64 {
    let mut least = f64::INFINITY;
    for q in route {
        let n = (2.0 * q.length() as f64).ceil().max(1.0) as usize;
        for i in 0..=n {
            let t = q.length() * i as f32 / n as f32;
            let at = q.pose_at(t).position;
            least = least.min((at.x as f64 - c.x as f64).hypot(at.y as f64 - c.y as f64));
        }
    }
    least
}

/// The altitude `s` metres along an edge with profile `p`, from the definitions in f64 (never
/// calling `skyroute`'s arithmetic): a rest-to-rest move of `d = |to − from|` in the least
/// distance, the gradient ramping at `k = a_z/v²` up to at most `g = v_c/v` and back; a climb
/// flown at once, a descent as late as it can be.
pub fn vertical_altitude(p: &VerticalProfile, limits: &VerticalLimits, s: f64) -> f64 {
    let v = limits.airspeed as f64;
    let (g, k) = (
        limits.climb_rate as f64 / v,
        limits.vertical_accel as f64 / (v * v),
    );
    let (from, to, length) = (p.from as f64, p.to as f64, p.length as f64);
    let d = (to - from).abs();
    let (ease, ramp) = if d >= g * g / k {
        (g / k, d / g + g / k)
    } else {
        ((d / k).sqrt(), 2.0 * (d / k).sqrt())
    };
    let start = if to >= from { 0.0 } else { length - ramp };
    let u = (s.clamp(0.0, length) - start).clamp(0.0, ramp);
    let moved = if u <= ease {
        0.5 * k * u * u
    } else if u >= ramp - ease {
        d - 0.5 * k * (ramp - u).powi(2)
    } else {
        0.5 * k * ease * ease + k * ease * (u - ease)
    };
    if to >= from {
        from + moved
    } else {
        from - moved
    }
}
