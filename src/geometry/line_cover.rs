//! Where a line comes within a distance of a shape: the parameter intervals of the line
//! `o + t·u` (`u` a unit vector) that lie in a disc, in a segment's capsule (the points within
//! `c` of the segment), or inside a polygon. The exit from a keep-out region is the end of the
//! union of these intervals that contains `t = 0`.

use super::predicates::PolygonView;
use super::Vec2;

/// The interval of `t` where `o + t·u` lies within `radius` of `q`: the roots of
/// `t² + 2bt + k = 0` with `b = (o − q)·u`, `k = |o − q|² − radius²` (`|u| = 1`).
pub fn disc_interval(o: Vec2, u: Vec2, q: Vec2, radius: f32) -> Option<(f32, f32)> {
    let w = o - q;
    let b = w.dot(u);
    let k = w.norm_sq() - radius * radius;
    let discriminant = b * b - k;
    if !(discriminant >= 0.0) {
        return None;
    }
    let s = libm::sqrtf(discriminant);
    Some((-b - s, -b + s))
}

/// The interval of `t` where `v0 + t·vu` lies in `[lo, hi]` (unbounded when `vu` is 0 and
/// `v0` is inside).
fn slab(v0: f32, vu: f32, lo: f32, hi: f32) -> Option<(f32, f32)> {
    if vu == 0.0 {
        return (lo <= v0 && v0 <= hi).then_some((f32::NEG_INFINITY, f32::INFINITY));
    }
    let (t1, t2) = ((lo - v0) / vu, (hi - v0) / vu);
    Some((t1.min(t2), t1.max(t2)))
}

/// The interval of `t` where `o + t·u` lies within `c` of the segment `a → b`. The capsule is
/// convex, so its trace on the line is one interval: the hull of the traces of its two end
/// discs and of its rectangle (the points whose projection falls on the segment and whose
/// distance from its line is at most `c`: two slabs, along and across the segment).
pub fn capsule_interval(o: Vec2, u: Vec2, a: Vec2, b: Vec2, c: f32) -> Option<(f32, f32)> {
    let mut hull: Option<(f32, f32)> = None;
    let mut join = |i: (f32, f32)| {
        hull = Some(hull.map_or(i, |h| (h.0.min(i.0), h.1.max(i.1))));
    };
    for q in [a, b] {
        if let Some(i) = disc_interval(o, u, q, c) {
            join(i);
        }
    }
    let d = b - a;
    let length = d.norm();
    if length > 0.0 {
        let along = d * (1.0 / length);
        let across = along.perp();
        let w = o - a;
        let rectangle = slab(w.dot(along), u.dot(along), 0.0, length).and_then(|s| {
            slab(w.dot(across), u.dot(across), -c, c)
                .map(|h| (s.0.max(h.0), s.1.min(h.1)))
                .filter(|r| r.0 <= r.1)
        });
        if let Some(i) = rectangle {
            join(i);
        }
    }
    hull
}

/// Calls `each` with the parameter of every crossing of the line `o + t·u` with an edge of
/// `polygon`, counting an edge whose ends lie on different sides of the line (an end on the
/// line counts as the left side, so a crossing at a vertex is counted once). Sorted and
/// paired, the crossings bound the intervals inside the polygon (even–odd rule). Returns
/// `false` if a vertex is unreadable.
pub fn for_each_crossing(
    o: Vec2,
    u: Vec2,
    polygon: &(impl PolygonView + ?Sized),
    mut each: impl FnMut(f32),
) -> bool {
    for i in 0..polygon.vertex_count() {
        let Some(edge) = polygon.edge(i) else {
            return false;
        };
        let (a, b) = (edge.start, edge.end);
        let (side_a, side_b) = (u.cross(a - o), u.cross(b - o));
        if (side_a >= 0.0) == (side_b >= 0.0) {
            continue;
        }
        // o + t·u = a + s·(b − a): t = ((a − o) × (b − a)) / (u × (b − a)).
        let d = b - a;
        let denominator = u.cross(d);
        if denominator != 0.0 {
            each((a - o).cross(d) / denominator);
        }
    }
    true
}
