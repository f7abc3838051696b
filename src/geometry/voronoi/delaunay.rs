//! Incremental Delaunay triangulation of quantised sites in fixed storage (Bowyer–Watson
//! insertion with ghost triangles).
//!
//! ## Representation
//! Triangles are vertex triples in counter-clockwise order. The vertex [`GHOST`] stands for the
//! point at infinity: the ghost triangle `(x, y, ∞)` (in any rotation) is the outside of the hull
//! edge `x → y`, whose finite neighbour `(y, x, z)` lies to the right of `x → y`. With ghosts
//! every triangle has three neighbours, and `n ≥ 3` sites not all collinear have exactly
//! `2n − 2` triangles (Euler's formula on the sphere: `V = n + 1`, `E = 3n − 3`, `F = 2n − 2`).
//! `nb[t][i]` is the triangle across the edge opposite vertex `i` of `t`. The live triangles
//! occupy slots `0 .. nt` without gaps.
//!
//! ## Insertion
//! A new site `p` *conflicts* with a finite triangle when it lies strictly inside its
//! circumcircle (in-circle > 0), and with a ghost triangle `(x, y, ∞)` when it lies strictly on
//! the outer side of `x → y`, or on the line `xy` strictly between `x` and `y` (Shewchuk's
//! lecture notes on Delaunay refinement; CGAL's infinite vertex). The conflicting triangles form
//! a cavity that is star-shaped from `p`; they are replaced by the triangles joining `p` to the
//! cavity's boundary edges (`k` triangles become `k + 2`). Conflicts are found by scanning every
//! triangle, so an insertion costs `O(n)` work without any point-location structure, and the
//! whole construction `O(n²)` ([`delaunay_work_bound`]).
//!
//! Until three sites are not collinear there is no triangle: the sites are kept sorted
//! lexicographically, which for collinear points is their order along the line. The first site
//! off the line starts the triangulation with the triangle of the line's two extreme sites and
//! itself, and the sites between them are inserted into it.

use super::exact::{incircle, orient, quantise, strictly_between, Q};
use super::{Vec2, VoronoiError, UNITS_PER_M};

/// The vertex at infinity of a ghost triangle.
pub(super) const GHOST: u32 = u32::MAX;

/// "No entry" in the scratch maps.
const NONE: u32 = u32::MAX;

/// The Delaunay triangulation of up to `N` sites, with `T` triangle slots (finite and ghost).
///
/// `T ≥ 2N` is checked at compile time: `n ≥ 3` sites not all collinear have `2n − 2`
/// triangles including ghosts. `N` is at most 65 534 (graph edges name sites in `u16`).
/// Memory: about `16N + 41T` bytes; no allocation, usable in a `static` (see [`Self::new`]).
#[derive(Clone, Debug)]
pub struct Delaunay<const N: usize, const T: usize> {
    /// Quantised sites in insertion order; `sites[..n]` are live.
    sites: [Q; N],
    /// Number of sites.
    n: usize,
    /// While there is no triangle: the site indices `line[..n]` sorted lexicographically.
    line: [u32; N],
    /// Triangle vertices, counter-clockwise; [`GHOST`] for the vertex at infinity.
    tri: [[u32; 3]; T],
    /// `nb[t][i]`: the triangle across the edge opposite `tri[t][i]`.
    nb: [[u32; 3]; T],
    /// Number of live triangles (slots `0 .. nt`).
    nt: usize,
    /// Insertion scratch: whether a triangle conflicts with the new site (all false between
    /// insertions).
    mark: [bool; T],
    /// Insertion scratch: the cavity's boundary edges `(u, v, outside triangle, new slot)`.
    boundary: [[u32; 4]; T],
    /// Insertion scratch: for a site, the boundary edge starting at it.
    first: [u32; N],
    /// Insertion scratch: the boundary edge starting at the ghost vertex.
    ghost_first: u32,
    /// Work since [`Self::clear`].
    work: u64,
}

/// The documented worst case of [`Delaunay::work`] after `n` calls of [`Delaunay::insert`]
/// (successful or not) since [`Delaunay::clear`]: `21n² + 10n + 8` (saturating).
///
/// Counted units: a duplicate comparison, a lexicographic comparison, a triangle visit, a
/// predicate evaluation. A call with `m` sites already present costs:
/// * the duplicate scan: at most `m`;
/// * while all sites are collinear: one orientation and at most `m` comparisons;
/// * a triangulated insertion with `s` sites present (`2s − 2` triangles): the scan visits
///   every triangle and evaluates at most 2 predicates for it, `3(2s − 2)`; the `3k` edges of
///   the `k ≤ 2s − 2` cavity triangles are examined, `3(2s − 2)`; each of the `k + 2 ≤ 2s`
///   boundary edges costs one orientation and one cycle check, and each new triangle two
///   linking visits, `4·2s`: in all at most `20s − 12`, so a call costs at most `21m`;
/// * the transition from collinear to triangulated (once: the triangulation never returns to
///   collinear before [`Delaunay::clear`]) with `m` collinear sites: one orientation, the
///   first 4 triangles (5), and the re-insertion of the `m − 2` inner sites with
///   `s = 3 .. m` sites present: `Σ (20s − 12) ≤ 10m² + 10m`.
///
/// The `j`-th call (`j = 0 .. n − 1`, `m ≤ j`) costs at most `21j + 1` besides the transition,
/// `Σ ≤ 10.5n² + n`; the transition adds at most `10n² + 10n + 6` (`m < n`). The total is below
/// `21n² + 10n + 8`. A refused call costs no more than an accepted one.
pub fn delaunay_work_bound(n: u64) -> u64 {
    n.saturating_mul(n)
        .saturating_mul(21)
        .saturating_add(n.saturating_mul(10))
        .saturating_add(8)
}

impl<const N: usize, const T: usize> Default for Delaunay<N, T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const T: usize> Delaunay<N, T> {
    /// Compile-time check of the capacities: `T ≥ 2N` (the triangulation of `N` sites has at
    /// most `2N − 2` triangles including ghosts) and `N ≤ 65 534` (sites are `u16` in the
    /// graph, `u16::MAX` meaning none).
    const CAPACITIES_OK: () = {
        assert!(T >= 2 * N, "Delaunay<N, T> needs T >= 2 * N triangle slots");
        assert!(N <= 65_534, "Delaunay<N, T> holds at most 65 534 sites");
    };

    /// An empty triangulation (all zeros), usable in a `static`.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITIES_OK;
        Self {
            sites: [[0; 2]; N],
            n: 0,
            line: [0; N],
            tri: [[0; 3]; T],
            nb: [[0; 3]; T],
            nt: 0,
            mark: [false; T],
            boundary: [[0; 4]; T],
            first: [0; N],
            // Scratch, stale until an insertion writes it (readers check): 0 keeps `new`
            // all zero bytes, so a `static` lands in `.bss` and costs no flash.
            ghost_first: 0,
            work: 0,
        }
    }

    /// Removes every site and resets the work counter.
    pub fn clear(&mut self) {
        self.n = 0;
        self.nt = 0;
        self.work = 0;
        self.mark = [false; T];
    }

    /// Number of sites.
    pub fn site_count(&self) -> usize {
        self.n
    }

    /// Site `i` as quantised, metres (rounded to f32), or `None` past the last site.
    pub fn site(&self, i: u32) -> Option<Vec2> {
        let q = self.q(i).filter(|_| (i as usize) < self.n)?;
        Some(Vec2::new(
            q[0] as f32 / UNITS_PER_M,
            q[1] as f32 / UNITS_PER_M,
        ))
    }

    /// Work since [`Self::clear`]: duplicate and lexicographic comparisons, predicate
    /// evaluations and triangle visits. At most [`delaunay_work_bound`] of the number of
    /// [`Self::insert`] calls.
    pub fn work(&self) -> u64 {
        self.work
    }

    /// Inserts `site` (quantised to [`super::SITE_QUANTUM_M`]) and returns its index.
    ///
    /// Refuses a non-finite site ([`VoronoiError::NonFinite`]), a coordinate beyond
    /// [`super::MAX_SITE_COORDINATE_M`] ([`VoronoiError::OutOfRange`]), a site on the grid point
    /// of an earlier one ([`VoronoiError::DuplicateSite`]) and a full structure
    /// ([`VoronoiError::TooManySites`], [`VoronoiError::TooManyTriangles`]); every refusal
    /// leaves the triangulation unchanged.
    pub fn insert(&mut self, site: Vec2) -> Result<u32, VoronoiError> {
        let q = quantise(site)?;
        let index = self.n;
        if index >= N {
            return Err(VoronoiError::TooManySites { capacity: N });
        }
        let count = index + 1;
        if count >= 3 && 2 * count - 2 > T {
            return Err(VoronoiError::TooManyTriangles { capacity: T });
        }
        let existing = self.sites.iter().take(index).position(|s| *s == q);
        // One comparison per site looked at.
        self.tick(existing.map_or(index, |i| i + 1) as u64);
        if let Some(i) = existing {
            return Err(VoronoiError::DuplicateSite {
                index: index as u32,
                existing: i as u32,
            });
        }
        // Slot `index` is not live until `n` is raised, so writing it changes nothing visible.
        if let Some(slot) = self.sites.get_mut(index) {
            *slot = q;
        }
        if self.nt == 0 {
            self.insert_untriangulated(index as u32)?;
        } else {
            self.insert_point(index as u32)?;
        }
        self.n = count;
        Ok(index as u32)
    }

    /// Replaces every site by `sites` (used when a site is removed): all of them are checked
    /// first (finite, in range, no duplicate, within capacity), so a refusal leaves the previous
    /// triangulation intact; then the structure is cleared and the sites inserted in order.
    pub fn rebuild(&mut self, sites: &[Vec2]) -> Result<(), VoronoiError> {
        if sites.len() > N {
            return Err(VoronoiError::TooManySites { capacity: N });
        }
        for (i, s) in sites.iter().enumerate() {
            let q = quantise(*s)?;
            for (j, earlier) in sites.iter().take(i).enumerate() {
                if quantise(*earlier).ok() == Some(q) {
                    return Err(VoronoiError::DuplicateSite {
                        index: i as u32,
                        existing: j as u32,
                    });
                }
            }
        }
        self.clear();
        for s in sites {
            self.insert(*s)?;
        }
        Ok(())
    }

    /// Adds `k` to the work counter.
    fn tick(&mut self, k: u64) {
        self.work = self.work.saturating_add(k);
    }

    /// The quantised site `i` (any slot, live or not).
    pub(super) fn q(&self, i: u32) -> Option<Q> {
        self.sites.get(i as usize).copied()
    }

    /// Number of live triangles.
    pub(super) fn triangle_count(&self) -> usize {
        self.nt
    }

    /// The vertices of triangle `t` ([`GHOST`] for all three past the end).
    pub(super) fn triangle(&self, t: usize) -> [u32; 3] {
        self.tri.get(t).copied().unwrap_or([GHOST; 3])
    }

    /// The neighbours of triangle `t`.
    pub(super) fn neighbours(&self, t: usize) -> [u32; 3] {
        self.nb.get(t).copied().unwrap_or([NONE; 3])
    }

    /// The sites in lexicographic order while there is no triangle (all collinear).
    pub(super) fn line_order(&self) -> &[u32] {
        self.line.get(..self.n).unwrap_or(&[])
    }

    /// Inserts site `pi` while there is no triangle: either it is collinear with the sites so
    /// far (sorted into `line`) or it starts the triangulation.
    fn insert_untriangulated(&mut self, pi: u32) -> Result<(), VoronoiError> {
        let m = self.n;
        let p = self.q(pi).ok_or(VoronoiError::Inconsistent)?;
        if m >= 2 {
            let a = self.line.first().copied().unwrap_or(0);
            let z = self.line.get(m - 1).copied().unwrap_or(0);
            let (qa, qz) = match (self.q(a), self.q(z)) {
                (Some(qa), Some(qz)) => (qa, qz),
                _ => return Err(VoronoiError::Inconsistent),
            };
            self.tick(1);
            let o = orient(qa, qz, p);
            if o != 0 {
                return self.start_triangulation(pi, o > 0);
            }
        }
        // Lexicographic order is the order along the line.
        let found = (0..m).find(|&i| {
            let s = self.line.get(i).copied().unwrap_or(0);
            self.q(s).is_some_and(|qs| qs > p)
        });
        // One comparison per site looked at.
        self.tick(found.map_or(m, |i| i + 1) as u64);
        let pos = found.unwrap_or(m);
        if m >= N {
            return Err(VoronoiError::Inconsistent);
        }
        // Shifted up by one, element by element (`copy_within` checks its ranges by panicking).
        for k in (pos..m).rev() {
            let moved = self.line.get(k).copied().unwrap_or(0);
            if let Some(slot) = self.line.get_mut(k + 1) {
                *slot = moved;
            }
        }
        if let Some(slot) = self.line.get_mut(pos) {
            *slot = pi;
        }
        Ok(())
    }

    /// Starts the triangulation with the line's extreme sites and `pi` (off the line; `left`
    /// when it lies to the left of first → last), then inserts the line's inner sites. On a
    /// failure the triangles are dropped, which restores the collinear state (`line` is not
    /// touched).
    fn start_triangulation(&mut self, pi: u32, left: bool) -> Result<(), VoronoiError> {
        let m = self.n;
        let a = self.line.first().copied().unwrap_or(0);
        let z = self.line.get(m - 1).copied().unwrap_or(0);
        let (b, c) = if left { (z, pi) } else { (pi, z) };
        if T < 4 {
            return Err(VoronoiError::TooManyTriangles { capacity: T });
        }
        // Triangle 0 = (a, b, c) counter-clockwise; ghosts 1 = (b, a, ∞), 2 = (c, b, ∞),
        // 3 = (a, c, ∞), each across the edge of triangle 0 it names and beside the two
        // other ghosts.
        let tris = [[a, b, c], [b, a, GHOST], [c, b, GHOST], [a, c, GHOST]];
        let nbs = [[2, 3, 1], [3, 2, 0], [1, 3, 0], [2, 1, 0]];
        for (t, (v, n)) in tris.iter().zip(nbs.iter()).enumerate() {
            if let (Some(tv), Some(tn)) = (self.tri.get_mut(t), self.nb.get_mut(t)) {
                *tv = *v;
                *tn = *n;
            }
        }
        self.nt = 4;
        self.tick(5);
        for i in 1..m.saturating_sub(1) {
            let s = self.line.get(i).copied().unwrap_or(0);
            if let Err(e) = self.insert_point(s) {
                self.nt = 0;
                return Err(e);
            }
        }
        Ok(())
    }

    /// Whether site `p` conflicts with triangle `t` (counts the predicates).
    fn conflicts(&mut self, t: usize, p: Q) -> bool {
        let [a, b, c] = self.triangle(t);
        let hull_edge = if c == GHOST {
            Some((a, b))
        } else if a == GHOST {
            Some((b, c))
        } else if b == GHOST {
            Some((c, a))
        } else {
            None
        };
        match hull_edge {
            Some((x, y)) => {
                let (Some(qx), Some(qy)) = (self.q(x), self.q(y)) else {
                    return false;
                };
                self.tick(1);
                let o = orient(qx, qy, p);
                if o == 0 {
                    self.tick(1);
                }
                o > 0 || (o == 0 && strictly_between(qx, qy, p))
            }
            None => {
                let (Some(qa), Some(qb), Some(qc)) = (self.q(a), self.q(b), self.q(c)) else {
                    return false;
                };
                self.tick(1);
                incircle(qa, qb, qc, p) > 0
            }
        }
    }

    /// Bowyer–Watson insertion of site `pi` into the triangulation. Everything is checked
    /// before the first triangle changes: a refusal leaves the triangulation as it was.
    fn insert_point(&mut self, pi: u32) -> Result<(), VoronoiError> {
        let p = self.q(pi).ok_or(VoronoiError::Inconsistent)?;
        let nt = self.nt;
        if nt + 2 > T {
            return Err(VoronoiError::TooManyTriangles { capacity: T });
        }
        let mut k = 0usize;
        for t in 0..nt {
            self.tick(1);
            let c = self.conflicts(t, p);
            if let Some(m) = self.mark.get_mut(t) {
                *m = c;
            }
            k += usize::from(c);
        }
        let result = self.collect_boundary(p, k);
        match result {
            Ok(b) => {
                self.replace_cavity(pi, k, b);
                Ok(())
            }
            Err(e) => {
                self.mark = [false; T];
                Err(e)
            }
        }
    }

    /// Collects the cavity's boundary edges into `boundary` with their new slots, and the map
    /// `first` from a boundary vertex to the edge starting there; checks that the boundary is a
    /// simple cycle of `k + 2` edges each seeing `p` on its left. Returns the edge count.
    fn collect_boundary(&mut self, p: Q, k: usize) -> Result<usize, VoronoiError> {
        let nt = self.nt;
        if k == 0 {
            return Err(VoronoiError::Inconsistent);
        }
        let mut b = 0usize;
        for t in 0..nt {
            if !self.mark.get(t).copied().unwrap_or(false) {
                continue;
            }
            let (v, n) = (self.triangle(t), self.neighbours(t));
            for i in 0..3 {
                self.tick(1);
                let o = n[i];
                if self.mark.get(o as usize).copied().unwrap_or(true) {
                    continue;
                }
                let (x, y) = (v[(i + 1) % 3], v[(i + 2) % 3]);
                if x != GHOST && y != GHOST {
                    self.tick(1);
                    let ok = matches!((self.q(x), self.q(y)), (Some(qx), Some(qy)) if orient(qx, qy, p) > 0);
                    if !ok {
                        return Err(VoronoiError::Inconsistent);
                    }
                }
                let slot = self.boundary.get_mut(b).ok_or(VoronoiError::Inconsistent)?;
                *slot = [x, y, o, NONE];
                b += 1;
            }
        }
        if b != k + 2 {
            return Err(VoronoiError::Inconsistent);
        }
        // New slots: the cavity's own slots in order, then the two past the end.
        let mut j = 0usize;
        for t in 0..nt {
            if self.mark.get(t).copied().unwrap_or(false) {
                if let Some(e) = self.boundary.get_mut(j) {
                    e[3] = t as u32;
                }
                j += 1;
            }
        }
        for (extra, e) in self.boundary.iter_mut().take(b).skip(k).enumerate() {
            e[3] = (nt + extra) as u32;
        }
        // The map vertex → boundary edge starting there (the ghost vertex: `ghost_first`).
        for j in 0..b {
            let x = self.boundary.get(j).map_or(NONE, |e| e[0]);
            self.set_first(x, j as u32);
        }
        // A simple cycle: every edge's start maps back to it, every edge's end starts one.
        for j in 0..b {
            self.tick(1);
            let [x, y, _, _] = self.boundary.get(j).copied().unwrap_or([NONE; 4]);
            let fx = self.first_of(x);
            let fy = self.first_of(y);
            let y_starts = self.boundary.get(fy as usize).is_some_and(|e| e[0] == y);
            if fx != j as u32 || (fy as usize) >= b || !y_starts {
                return Err(VoronoiError::Inconsistent);
            }
        }
        Ok(b)
    }

    /// Records that boundary edge `j` starts at vertex `x`.
    fn set_first(&mut self, x: u32, j: u32) {
        if x == GHOST {
            self.ghost_first = j;
        } else if let Some(f) = self.first.get_mut(x as usize) {
            *f = j;
        }
    }

    /// The boundary edge recorded as starting at vertex `x` (possibly stale: callers check).
    fn first_of(&self, x: u32) -> u32 {
        if x == GHOST {
            self.ghost_first
        } else {
            self.first.get(x as usize).copied().unwrap_or(NONE)
        }
    }

    /// Replaces the cavity (the marked triangles) by the `b` triangles joining site `pi` to the
    /// boundary edges collected by [`Self::collect_boundary`], and links them: boundary edge
    /// `(u, v)` becomes triangle `(u, v, p)`, whose neighbour across `uv` is the outside
    /// triangle, across `vp` the new triangle of the edge starting at `v`, and across `pu` the
    /// new triangle of the edge ending at `u`.
    fn replace_cavity(&mut self, pi: u32, k: usize, b: usize) {
        for j in 0..b {
            self.tick(1);
            let [u, v, o, s] = self.boundary.get(j).copied().unwrap_or([NONE; 4]);
            let s = s as usize;
            if let (Some(tv), Some(tn), Some(m)) = (
                self.tri.get_mut(s),
                self.nb.get_mut(s),
                self.mark.get_mut(s),
            ) {
                *tv = [u, v, pi];
                tn[2] = o;
                *m = false;
            }
            // The outside triangle holds the edge as v → u; point it at the new triangle.
            let ov = self.triangle(o as usize);
            if let Some(on) = self.nb.get_mut(o as usize) {
                for i in 0..3 {
                    if ov[(i + 1) % 3] == v && ov[(i + 2) % 3] == u {
                        on[i] = s as u32;
                    }
                }
            }
        }
        for j in 0..b {
            self.tick(1);
            let [_, v, _, s] = self.boundary.get(j).copied().unwrap_or([NONE; 4]);
            let next = self.first_of(v);
            let ns = self.boundary.get(next as usize).map_or(NONE, |e| e[3]);
            if let Some(tn) = self.nb.get_mut(s as usize) {
                tn[0] = ns;
            }
            if let Some(tn) = self.nb.get_mut(ns as usize) {
                tn[1] = s;
            }
        }
        self.nt += b - k;
    }
}
