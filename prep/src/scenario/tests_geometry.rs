//! The ring self-intersection sweep against the brute force that compares every pair of edges.

use super::geometry::first_self_intersection;

type P = (f64, f64);

/// The reference: every pair `(i, j)`, `i < j`, in order, with the same exact predicates
/// reached through one-segment rings (a ring of two edges folds iff they overlap).
fn brute_force(ring: &[P]) -> Option<(usize, usize, bool)> {
    let n = ring.len();
    let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let ((a, b), (c, d)) = (edge(i), edge(j));
            if adjacent {
                // The shared vertex s; the other two ends u and w.
                let (s, u, w) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                let cross = (u.0 - s.0) * (w.1 - s.1) - (u.1 - s.1) * (w.0 - s.0);
                let dot = (u.0 - s.0) * (w.0 - s.0) + (u.1 - s.1) * (w.1 - s.1);
                if cross == 0.0 && dot > 0.0 {
                    return Some((i, j, true));
                }
            } else if closed_segments_meet(a, b, c, d) {
                return Some((i, j, false));
            }
        }
    }
    None
}

/// Closed-segment intersection on small integer coordinates, where f64 arithmetic is exact.
fn closed_segments_meet(a: P, b: P, c: P, d: P) -> bool {
    let orient = |p: P, q: P, r: P| {
        let v = (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0);
        (v > 0.0) as i32 - (v < 0.0) as i32
    };
    let on = |p: P, q: P, r: P| {
        p.0.min(q.0) <= r.0 && r.0 <= p.0.max(q.0) && p.1.min(q.1) <= r.1 && r.1 <= p.1.max(q.1)
    };
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    (o1 * o2 < 0 && o3 * o4 < 0)
        || (o1 == 0 && on(a, b, c))
        || (o2 == 0 && on(a, b, d))
        || (o3 == 0 && on(c, d, a))
        || (o4 == 0 && on(c, d, b))
}

/// xorshift64*: a fixed, dependency-free stream of test rings.
struct Stream(u64);

impl Stream {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) % n
    }
}

#[test]
fn sweep_finds_the_brute_forces_first_pair_on_random_rings() {
    // Small integer grids make touching, collinear and folding edges common, the cases where a
    // sweep that skips a pair would differ.
    let mut rng = Stream(0x9E37_79B9_7F4A_7C15);
    let (mut simple, mut folds, mut meets) = (0, 0, 0);
    for _ in 0..20_000 {
        let n = 3 + rng.below(10) as usize;
        let side = 2 + rng.below(6);
        let mut ring: Vec<P> = Vec::with_capacity(n);
        while ring.len() < n {
            let p = (rng.below(side) as f64, rng.below(side) as f64);
            if ring.last() != Some(&p) && (ring.len() + 1 < n || ring.first() != Some(&p)) {
                ring.push(p);
            }
        }
        let expected = brute_force(&ring);
        assert_eq!(first_self_intersection(&ring), expected, "ring {ring:?}");
        match expected {
            None => simple += 1,
            Some((_, _, true)) => folds += 1,
            Some(_) => meets += 1,
        }
    }
    // Every outcome is exercised.
    assert!(
        simple > 500 && folds > 500 && meets > 500,
        "{simple} {folds} {meets}"
    );
}

#[test]
fn a_twenty_thousand_vertex_circle_is_simple_and_one_dent_is_found() {
    let n = 20_000;
    let mut ring: Vec<P> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            (11.6 + 0.01 * t.cos(), 48.0 + 0.01 * t.sin())
        })
        .collect();
    assert_eq!(first_self_intersection(&ring), None);
    // Vertex 7 500 pushed across the circle's centre: its two edges cross the far side.
    ring[7_500] = (11.6, 47.985);
    let found = first_self_intersection(&ring);
    assert_eq!(found, brute_force_around(&ring, 7_499));
}

/// The brute force restricted to pairs that include edge `i` or `i + 1` (the only edges a moved
/// vertex `i + 1` changes), which is the whole answer on a ring that was simple before.
fn brute_force_around(ring: &[P], i: usize) -> Option<(usize, usize, bool)> {
    let n = ring.len();
    let edge = |k: usize| (ring[k], ring[(k + 1) % n]);
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for moved in [i, i + 1] {
        for k in 0..n {
            let (lo, hi) = (moved.min(k), moved.max(k));
            if hi > lo + 1 && !(lo == 0 && hi == n - 1) {
                pairs.push((lo, hi));
            }
        }
    }
    pairs.sort_unstable();
    pairs.into_iter().find_map(|(lo, hi)| {
        let ((a, b), (c, d)) = (edge(lo), edge(hi));
        closed_segments_meet(a, b, c, d).then_some((lo, hi, false))
    })
}
