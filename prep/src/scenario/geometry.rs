//! Exact planar predicates on f64 coordinates (here: degrees of longitude and latitude).

/// `a + b` as `(s, e)` with `s + e == a + b` exactly (Knuth's TwoSum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a · b` as `(p, e)` with `p + e == a · b` exactly (barring underflow), by a fused multiply-add.
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Adds `b` to the non-overlapping expansion `e` (smallest component first), exactly
/// (Shewchuk's Grow-Expansion).
fn grow(e: &mut Vec<f64>, b: f64) {
    let mut q = b;
    let mut out = Vec::with_capacity(e.len() + 1);
    for &c in e.iter() {
        let (s, h) = two_sum(q, c);
        if h != 0.0 {
            out.push(h);
        }
        q = s;
    }
    if q != 0.0 {
        out.push(q);
    }
    *e = out;
}

/// The exact sign of `Σ sᵢ · (aᵢ − bᵢ) · (cᵢ − dᵢ)` with `sᵢ = ±1`.
fn exact_sign(terms: &[(f64, f64, f64, f64, f64)]) -> i32 {
    let mut e: Vec<f64> = Vec::with_capacity(4 * terms.len() * 2);
    for &(s, a, b, c, d) in terms {
        let (u1, u0) = two_sum(a, -b);
        let (v1, v0) = two_sum(c, -d);
        for x in [u1, u0] {
            for y in [v1, v0] {
                let (p, q) = two_prod(x, y);
                grow(&mut e, s * p);
                grow(&mut e, s * q);
            }
        }
    }
    match e.last() {
        Some(&x) if x > 0.0 => 1,
        Some(&x) if x < 0.0 => -1,
        _ => 0,
    }
}

type P = (f64, f64);

/// Exact sign of the orientation of `(a, b, c)`: +1 counter-clockwise, −1 clockwise, 0 collinear.
fn orient(a: P, b: P, c: P) -> i32 {
    exact_sign(&[(1.0, b.0, a.0, c.1, a.1), (-1.0, b.1, a.1, c.0, a.0)])
}

/// Exact sign of `(u − s) · (w − s)`.
fn dot_sign(s: P, u: P, w: P) -> i32 {
    exact_sign(&[(1.0, u.0, s.0, w.0, s.0), (1.0, u.1, s.1, w.1, s.1)])
}

/// Whether `p`, collinear with `a` and `b`, lies on the closed segment `ab`.
fn within(a: P, b: P, p: P) -> bool {
    a.0.min(b.0) <= p.0 && p.0 <= a.0.max(b.0) && a.1.min(b.1) <= p.1 && p.1 <= a.1.max(b.1)
}

/// Whether the closed segments `ab` and `cd` meet.
fn segments_meet(a: P, b: P, c: P, d: P) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within(a, b, c))
        || (o2 == 0 && within(a, b, d))
        || (o3 == 0 && within(c, d, a))
        || (o4 == 0 && within(c, d, b))
}

/// The first pair of edges `(i, j, overlap)` (smallest `i`, then smallest `j`) of the closed
/// ring (no repeated consecutive vertices) that meet other than at their shared vertex:
/// non-adjacent edges that touch or cross, or adjacent edges that fold back onto each other
/// (`overlap`).
///
/// Adjacent pairs are checked directly (n tests). Non-adjacent pairs go through a sort-and-sweep
/// on the edges' x-extents: the edges sorted by their least x, each compared only with the
/// earlier edges whose x-extent still reaches it and whose y-extent overlaps its own, and only
/// those pairs get the exact test. That is O(n log n + k) for k pairs of overlapping boxes: a
/// 20 000-vertex circle is checked in milliseconds, where comparing every pair took minutes.
pub(super) fn first_self_intersection(ring: &[P]) -> Option<(usize, usize, bool)> {
    let n = ring.len();
    let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
    let mut first: Option<(usize, usize, bool)> = None;
    let mut keep = |found: (usize, usize, bool)| {
        if first.is_none_or(|f| (found.0, found.1) < (f.0, f.1)) {
            first = Some(found);
        }
    };
    for i in 0..n.saturating_sub(1) {
        // Edges i and i + 1 share the vertex s; they overlap iff the other two ends lie on the
        // same ray from s.
        let (u, s) = edge(i);
        let (_, w) = edge(i + 1);
        if orient(u, s, w) == 0 && dot_sign(s, u, w) > 0 {
            keep((i, i + 1, true));
        }
    }
    if n > 2 {
        // Edges 0 and n − 1 share vertex 0.
        let ((s, u), (w, _)) = (edge(0), edge(n - 1));
        if orient(u, s, w) == 0 && dot_sign(s, u, w) > 0 {
            keep((0, n - 1, true));
        }
    }
    let edges: Vec<(P, P)> = (0..n).map(edge).collect();
    for_close_pairs(&edges, |lo, hi| {
        let adjacent = hi == lo + 1 || (lo == 0 && hi == n - 1);
        let ((a, b), (c, d)) = (edges[lo], edges[hi]);
        if !adjacent && segments_meet(a, b, c, d) {
            keep((lo, hi, false));
        }
    });
    first
}

/// Calls `visit(i, j)` (with `i < j`) for every pair of `edges` whose bounding boxes overlap:
/// a sort-and-sweep on the edges' x-extents, each edge compared only with the earlier edges
/// whose x-extent still reaches it, and passed on when the y-extents overlap too. O(n log n +
/// k) for k such pairs.
fn for_close_pairs(edges: &[(P, P)], mut visit: impl FnMut(usize, usize)) {
    let bounds = |i: usize| {
        let (a, b) = edges[i];
        (a.0.min(b.0), a.0.max(b.0), a.1.min(b.1), a.1.max(b.1))
    };
    let mut order: Vec<usize> = (0..edges.len()).collect();
    order.sort_by(|&i, &j| bounds(i).0.total_cmp(&bounds(j).0));
    let mut active: Vec<usize> = Vec::new();
    for &j in &order {
        let (x_min, _, y_min, y_max) = bounds(j);
        active.retain(|&i| bounds(i).1 >= x_min);
        for &i in &active {
            let (_, _, iy_min, iy_max) = bounds(i);
            if iy_max < y_min || y_max < iy_min {
                continue;
            }
            visit(i.min(j), i.max(j));
        }
        active.push(j);
    }
}

/// The first pair of rings `(a, b)`, `a < b` (smallest `a`, then smallest `b`), whose
/// boundaries meet: an edge of one touches or crosses an edge of the other. Each ring is closed
/// (its last vertex joins its first); meetings within one ring are not looked for here (see
/// [`first_self_intersection`]).
pub(super) fn first_rings_meeting(rings: &[&[P]]) -> Option<(usize, usize)> {
    let mut edges = Vec::new();
    let mut owner = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        for i in 0..ring.len() {
            edges.push((ring[i], ring[(i + 1) % ring.len()]));
            owner.push(r);
        }
    }
    let mut first: Option<(usize, usize)> = None;
    for_close_pairs(&edges, |i, j| {
        let (ra, rb) = (owner[i].min(owner[j]), owner[i].max(owner[j]));
        if ra == rb || first.is_some_and(|f| f <= (ra, rb)) {
            return;
        }
        let ((a, b), (c, d)) = (edges[i], edges[j]);
        if segments_meet(a, b, c, d) {
            first = Some((ra, rb));
        }
    });
    first
}

/// Whether `p` lies inside or on the boundary of the simple polygon `ring` (exact winding
/// number).
pub(super) fn point_in_ring(p: P, ring: &[P]) -> bool {
    let n = ring.len();
    let mut winding = 0i32;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let o = orient(a, b, p);
        if o == 0 && within(a, b, p) {
            return true;
        }
        if a.1 <= p.1 {
            if b.1 > p.1 && o > 0 {
                winding += 1;
            }
        } else if b.1 <= p.1 && o < 0 {
            winding -= 1;
        }
    }
    winding != 0
}

/// Whether `p` lies inside or on the boundary of the zone of exterior `ring` less `holes`: in
/// the ring, and not strictly inside any hole (a hole's boundary belongs to the zone).
pub(super) fn point_in_zone(p: P, ring: &[P], holes: &[Vec<P>]) -> bool {
    let on_boundary = |h: &[P]| {
        (0..h.len()).any(|i| {
            let (a, b) = (h[i], h[(i + 1) % h.len()]);
            orient(a, b, p) == 0 && within(a, b, p)
        })
    };
    point_in_ring(p, ring) && !holes.iter().any(|h| point_in_ring(p, h) && !on_boundary(h))
}

/// The convex hull of `points`, counter-clockwise, without collinear vertices (Andrew's
/// monotone chain with the exact orientation test).
pub(super) fn convex_hull(points: &[P]) -> Vec<P> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<P> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &P>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && orient(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_predicates() {
        // Collinear in exact arithmetic although naive f64 evaluation says otherwise.
        let a = (0.1, 0.1);
        let b = (0.2, 0.2);
        let c = (0.30000000000000004, 0.30000000000000004);
        assert_eq!(orient(a, b, c), 0);
        assert_eq!(orient((0.0, 0.0), (1.0, 0.0), (0.5, 1e-300)), 1);
        assert_eq!(orient((0.0, 0.0), (1.0, 0.0), (0.5, -1e-300)), -1);
        // Points that f64 rounding makes look collinear.
        let p = (0.5, 0.5);
        let q = (12.0, 12.0);
        let r = (24.0 + f64::EPSILON * 16.0, 24.0);
        assert_eq!(orient(p, q, r), -1);
        // Point in ring, exactly: one ulp east of the edge x = 11.1 is outside, on it inside.
        let ring = [(11.0, 48.0), (11.1, 48.0), (11.1, 48.1), (11.0, 48.1)];
        assert!(point_in_ring((11.1, 48.05), &ring));
        assert!(point_in_ring((11.099999999999998, 48.05), &ring));
        assert!(!point_in_ring((11.100000000000001, 48.05), &ring));
        assert!(point_in_ring((11.0, 48.0), &ring));
        assert!(!point_in_ring((10.9, 48.05), &ring));
        assert_eq!(
            convex_hull(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5)]).len(),
            4
        );
    }
}
