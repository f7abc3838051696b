//! Exact collision predicates with a clearance distance.
//!
//! Each test computes the closed-form minimum distance between two primitives and compares it
//! with the clearance; nothing is sampled. A primitive *conflicts* with an obstacle when some
//! point of it lies within `clearance` of the obstacle (boundary included) or inside it.
//!
//! Minimum distances are found from their critical points: for two sets the minimum is attained
//! either at an end point of one of them, or at a pair of interior points where the connecting
//! vector is normal to both (for a segment and an arc: the foot of the perpendicular from the
//! circle's centre), or at an intersection (distance 0). Each function evaluates exactly those
//! candidates, all of which are real distances between points of the two sets, so the minimum
//! over them is the exact minimum distance (up to f32 rounding).

use super::{Arc, Primitive, Segment, Vec2};

/// Orientation of `c` relative to the directed line `a → b`: positive when counter-clockwise.
/// Evaluated in f64, where the products of f32 differences are exact for coordinates of similar
/// magnitude, so the sign is reliable at touching configurations.
fn orient(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (ax, ay) = (a.x as f64, a.y as f64);
    let (bx, by) = (b.x as f64, b.y as f64);
    let (cx, cy) = (c.x as f64, c.y as f64);
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// Distance from point `p` to segment `s`.
pub fn point_segment_distance(p: Vec2, s: &Segment) -> f32 {
    let d = s.end - s.start;
    let len_sq = d.norm_sq();
    if len_sq <= 0.0 {
        return p.distance(s.start);
    }
    let t = ((p - s.start).dot(d) / len_sq).clamp(0.0, 1.0);
    p.distance(s.start + d * t)
}

/// Whether two segments share a point (touching counts).
pub fn segments_intersect(s: &Segment, t: &Segment) -> bool {
    let d1 = orient(t.start, t.end, s.start);
    let d2 = orient(t.start, t.end, s.end);
    let d3 = orient(s.start, s.end, t.start);
    let d4 = orient(s.start, s.end, t.end);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    // Collinear or touching cases: an end point lying on the other segment.
    let on = |a: Vec2, b: Vec2, p: Vec2, o: f64| {
        o == 0.0
            && p.x >= a.x.min(b.x)
            && p.x <= a.x.max(b.x)
            && p.y >= a.y.min(b.y)
            && p.y <= a.y.max(b.y)
    };
    on(t.start, t.end, s.start, d1)
        || on(t.start, t.end, s.end, d2)
        || on(s.start, s.end, t.start, d3)
        || on(s.start, s.end, t.end, d4)
}

/// Minimum distance between two segments (0 when they intersect).
pub fn segment_segment_distance(s: &Segment, t: &Segment) -> f32 {
    if segments_intersect(s, t) {
        return 0.0;
    }
    point_segment_distance(s.start, t)
        .min(point_segment_distance(s.end, t))
        .min(point_segment_distance(t.start, s))
        .min(point_segment_distance(t.end, s))
}

/// Distance from point `p` to arc `a`.
pub fn point_arc_distance(p: Vec2, a: &Arc) -> f32 {
    let rel = p - a.centre;
    if rel.norm_sq() > 0.0 && a.contains_angle(rel.angle()) {
        // The nearest point of the full circle lies on the arc.
        return libm::fabsf(rel.norm() - a.radius);
    }
    // Otherwise the distance to a circle point grows monotonically away from the radial
    // direction of p, so the nearest arc point is an end point (p at the centre: all are r).
    p.distance(a.start()).min(p.distance(a.end()))
}

/// Minimum distance between an arc and a segment (0 when they intersect).
pub fn arc_segment_distance(a: &Arc, s: &Segment) -> f32 {
    // End points of each against the other.
    let mut best = point_arc_distance(s.start, a)
        .min(point_arc_distance(s.end, a))
        .min(point_segment_distance(a.start(), s))
        .min(point_segment_distance(a.end(), s));
    let d = s.end - s.start;
    let len_sq = d.norm_sq();
    if len_sq <= 0.0 {
        return best;
    }
    // Interior critical pair: the foot f of the perpendicular from the centre onto the line.
    let t_foot = (a.centre - s.start).dot(d) / len_sq;
    let foot = s.start + d * t_foot;
    let h = foot.distance(a.centre); // distance from the centre to the line
    if h >= a.radius {
        // Line misses the circle: nearest circle point is radial towards the foot.
        if (0.0..=1.0).contains(&t_foot) && a.contains_angle((foot - a.centre).angle()) {
            best = best.min(h - a.radius);
        }
    }
    if h <= a.radius {
        // Line meets the circle at foot ± w·d̂: an intersection counts if on both pieces.
        let len = libm::sqrtf(len_sq);
        let w = libm::sqrtf((a.radius * a.radius - h * h).max(0.0));
        for sign in [-1.0f32, 1.0] {
            let t = t_foot + sign * w / len;
            if (0.0..=1.0).contains(&t) {
                let q = s.start + d * t;
                if a.contains_angle((q - a.centre).angle()) {
                    return 0.0;
                }
            }
        }
    }
    best
}

/// Minimum distance from a primitive to a point.
pub fn primitive_point_distance(p: &Primitive, q: Vec2) -> f32 {
    match p {
        Primitive::Line(s) => point_segment_distance(q, s),
        Primitive::Arc(a) => point_arc_distance(q, a),
    }
}

/// Minimum distance from a primitive to a segment.
pub fn primitive_segment_distance(p: &Primitive, s: &Segment) -> f32 {
    match p {
        Primitive::Line(l) => segment_segment_distance(l, s),
        Primitive::Arc(a) => arc_segment_distance(a, s),
    }
}

/// Whether a primitive comes within `clearance` of the disc with `centre` and `radius`
/// (segment–circle and arc–circle).
pub fn conflicts_with_circle(p: &Primitive, centre: Vec2, radius: f32, clearance: f32) -> bool {
    primitive_point_distance(p, centre) <= radius + clearance
}

/// Even–odd point-in-polygon test (points on the boundary may go either way; callers that need
/// the boundary use a distance test too, as [`conflicts_with_polygon`] does).
pub fn point_in_polygon(p: Vec2, polygon: &(impl PolygonView + ?Sized)) -> bool {
    let n = polygon.vertex_count();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (Some(a), Some(b)) = (polygon.vertex(i), polygon.vertex(j)) else {
            return false;
        };
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if p.x < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

/// Read access to a simple polygon's vertices (closed implicitly: the last joins the first).
pub trait PolygonView {
    /// Number of vertices.
    fn vertex_count(&self) -> usize;
    /// Vertex `i`, or `None` when out of range.
    fn vertex(&self, i: usize) -> Option<Vec2>;
    /// Edge `i` (from vertex `i` to vertex `i + 1`, wrapping), or `None` when out of range.
    fn edge(&self, i: usize) -> Option<Segment> {
        let n = self.vertex_count();
        if i >= n {
            return None;
        }
        Some(Segment::new(self.vertex(i)?, self.vertex((i + 1) % n)?))
    }
}

impl PolygonView for [Vec2] {
    fn vertex_count(&self) -> usize {
        self.len()
    }
    fn vertex(&self, i: usize) -> Option<Vec2> {
        self.get(i).copied()
    }
}

/// Whether a primitive comes within `clearance` of a simple polygon: some boundary edge is
/// within `clearance`, or the primitive lies inside. (A connected primitive that does not come
/// within `clearance ≥ 0` of the boundary is entirely inside or entirely outside, so testing one
/// of its points for containment decides the rest.)
pub fn conflicts_with_polygon(
    p: &Primitive,
    polygon: &(impl PolygonView + ?Sized),
    clearance: f32,
) -> bool {
    for i in 0..polygon.vertex_count() {
        match polygon.edge(i) {
            Some(e) if primitive_segment_distance(p, &e) <= clearance => return true,
            Some(_) => {}
            None => return true, // unreachable for a consistent view; fail safe
        }
    }
    point_in_polygon(p.start(), polygon)
}

/// Whether a polygon is simple: at least three vertices, all finite, no two non-adjacent edges
/// touching, no zero-length edge.
pub fn polygon_is_simple(polygon: &(impl PolygonView + ?Sized)) -> bool {
    let n = polygon.vertex_count();
    if n < 3 {
        return false;
    }
    for i in 0..n {
        let Some(e) = polygon.edge(i) else {
            return false;
        };
        if !e.start.is_finite() || e.length() <= 0.0 {
            return false;
        }
        for j in (i + 1)..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                continue;
            }
            let Some(f) = polygon.edge(j) else {
                return false;
            };
            if segments_intersect(&e, &f) {
                return false;
            }
        }
    }
    true
}
