//! The Voronoi diagram as a graph clipped to the mission box: what the planner searches.
//!
//! * A Delaunay edge between two finite triangles is the Voronoi edge between their
//!   circumcentres. Triangles with the same circumcircle (an exactly zero in-circle determinant
//!   across their common edge) are merged first, so cocircular sites give one vertex and no
//!   zero-length edge.
//! * A hull edge `x → y` of a finite triangle is the Voronoi ray from that triangle's
//!   circumcentre along the edge's outward normal.
//! * With no finite triangle (at most two sites, or all collinear) the Voronoi edges are the
//!   perpendicular bisectors of consecutive sites along the line: whole, parallel lines.
//!
//! Each piece is clipped to the box (Liang & Barsky 1984, parametric clipping in f64) and
//! dropped when it misses it; a clipped end is snapped onto the box side it crosses. The box's
//! border is then split at every vertex lying on it (clip points, corners, circumcentres exactly
//! on a side) into border edges, so the graph is connected and runs around every threat.
//! Vertices are shared by exact f32 position.

use super::delaunay::{Delaunay, GHOST};
use super::exact::{circumcentre, incircle, metres, Q};
use super::{Vec2, VoronoiError};
use heapless::Vec;

/// The site index of a border edge when there are no sites at all.
pub const NO_SITE: u16 = u16::MAX;

/// "No graph vertex" (a circumcentre outside the box).
const NO_VERTEX: u16 = u16::MAX;

/// The mission box, metres: the graph is the Voronoi diagram clipped to it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Bounds {
    /// South-west corner.
    pub min: Vec2,
    /// North-east corner (strictly above `min` on both axes).
    pub max: Vec2,
}

/// An edge of the graph: vertex indices into [`VoronoiGraph::vertices`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GraphEdge {
    /// One end.
    pub a: u16,
    /// The other end.
    pub b: u16,
    /// The two sites the edge separates (equidistant from both, farther from every other); for
    /// a border edge the site whose cell it bounds, twice ([`NO_SITE`] with no sites).
    pub sites: [u16; 2],
    /// Whether the edge is a piece of the box's border.
    pub border: bool,
}

/// The clipped Voronoi graph: at most `VV` vertices and `EE` edges.
#[derive(Clone, Debug, Default)]
pub struct VoronoiGraph<const VV: usize, const EE: usize> {
    vertices: Vec<Vec2, VV>,
    edges: Vec<GraphEdge, EE>,
    /// Steps counted by the [`Delaunay::graph`] call that built it.
    work: u64,
}

/// Upper bound on the vertices of the graph of `n` sites: `8n + 4`.
///
/// Argument: `n ≥ 3` sites have at most `2n − 5` finite Delaunay triangles (`2n − 2 − h`, hull
/// size `h ≥ 3`), hence at most `2n` circumcentres; at most `3n − 6` Delaunay edges (`n − 1`
/// bisectors when collinear), hence at most `3n` Voronoi pieces with at most 2 clip points
/// each, `6n`; and 4 corners. Fewer than 3 sites: at most 1 bisector, 2 clip points, 4 corners.
pub const fn graph_vertex_bound(n: usize) -> usize {
    n.saturating_mul(8).saturating_add(4)
}

/// Upper bound on the edges of the graph of `n` sites: `11n + 4`.
///
/// Argument: at most `3n` Voronoi pieces (see [`graph_vertex_bound`]) give one edge each; the
/// border is a cycle through the vertices lying on it, at most all `8n + 4` of them, with one
/// edge per vertex.
pub const fn graph_edge_bound(n: usize) -> usize {
    n.saturating_mul(11).saturating_add(4)
}

/// The documented worst case of [`VoronoiGraph::work`] for the graph of `n` sites (saturating).
///
/// Counted units: a vertex compared in the scan that shares vertices, an edge added, a
/// triangle visited, a neighbour examined (with its in-circle test), a union–find step, a
/// piece, a bisector, a vertex or a site scanned on the border. With `t ≤ 2n` triangles
/// (ghosts included), `V ≤` [`graph_vertex_bound`]`(n)` vertices at any time and a find of at
/// most `t` steps (each moves to a distinct ancestor):
/// * the cocircular groups: per triangle 1, per neighbour 1 and two finds, `t(4 + 6t)`;
/// * the circumcentres: per triangle 1, a find and a vertex scan, `t(1 + t + V)`;
/// * the pieces: per triangle 1 and a find, per neighbour 1, a find and a piece (1, two vertex
///   scans and an edge: `2 + 2V`), `t(10 + 4t + 6V)`;
/// * with no triangle, the bisectors of at most `n − 1` consecutive pairs, each 1 and a piece,
///   `n(3 + 2V)`;
/// * the border: its 4 corners' scans, and per side at most `V` steps, each scanning every
///   vertex and every site and adding an edge, `4V + 4V(V + n + 1)`.
///
/// The total is below `t(15 + 11t + 7V) + n(3 + 2V) + 4V(V + n + 2)`.
pub const fn graph_work_bound(n: usize) -> u64 {
    let v = graph_vertex_bound(n) as u64;
    let n = n as u64;
    let t = n.saturating_mul(2);
    let triangles = t.saturating_mul(
        15u64
            .saturating_add(t.saturating_mul(11))
            .saturating_add(v.saturating_mul(7)),
    );
    let bisectors = n.saturating_mul(v.saturating_mul(2).saturating_add(3));
    let border = v
        .saturating_mul(4)
        .saturating_mul(v.saturating_add(n).saturating_add(2));
    triangles.saturating_add(bisectors).saturating_add(border)
}

impl<const VV: usize, const EE: usize> VoronoiGraph<VV, EE> {
    /// An empty graph.
    pub const fn new() -> Self {
        Self {
            vertices: Vec::new(),
            edges: Vec::new(),
            work: 0,
        }
    }

    /// The vertices, metres (inside the box).
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// The edges.
    pub fn edges(&self) -> &[GraphEdge] {
        &self.edges
    }

    /// The steps [`Delaunay::graph`] counted building this graph: at most
    /// [`graph_work_bound`] of the site count.
    pub fn work(&self) -> u64 {
        self.work
    }

    /// Adds `k` to the work counter.
    fn tick(&mut self, k: u64) {
        self.work = self.work.saturating_add(k);
    }

    /// The vertex at exactly `p`, added if new. Counts each vertex compared.
    fn vertex(&mut self, p: Vec2) -> Result<u16, VoronoiError> {
        let found = self.vertices.iter().position(|v| *v == p);
        self.tick(found.map_or(self.vertices.len(), |i| i + 1) as u64);
        if let Some(i) = found {
            return Ok(i as u16);
        }
        let i = self.vertices.len();
        if i >= usize::from(NO_VERTEX) {
            return Err(VoronoiError::GraphFull);
        }
        self.vertices.push(p).map_err(|_| VoronoiError::GraphFull)?;
        Ok(i as u16)
    }

    /// Adds the edge `a`–`b` unless it has zero length. Counts 1.
    fn edge(&mut self, a: u16, b: u16, sites: [u16; 2], border: bool) -> Result<(), VoronoiError> {
        self.tick(1);
        if a == b {
            return Ok(());
        }
        let e = GraphEdge {
            a,
            b,
            sites,
            border,
        };
        self.edges.push(e).map_err(|_| VoronoiError::GraphFull)
    }
}

/// A side of the box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Left,
    Right,
    Bottom,
    Top,
}

type P = (f64, f64);

/// The validated box, with its f64 copy.
struct Box64 {
    b: Bounds,
    min: P,
    max: P,
}

impl Box64 {
    fn new(b: &Bounds) -> Result<Self, VoronoiError> {
        let ok = b.min.is_finite() && b.max.is_finite() && b.min.x < b.max.x && b.min.y < b.max.y;
        if !ok {
            return Err(VoronoiError::InvalidBounds);
        }
        Ok(Self {
            b: *b,
            min: (f64::from(b.min.x), f64::from(b.min.y)),
            max: (f64::from(b.max.x), f64::from(b.max.y)),
        })
    }

    /// Whether `p` is in the closed box (false for NaN).
    fn contains(&self, p: P) -> bool {
        p.0 >= self.min.0 && p.0 <= self.max.0 && p.1 >= self.min.1 && p.1 <= self.max.1
    }

    /// `p` (in the box) rounded to f32 and clamped into the box.
    fn to_f32(&self, p: P) -> Vec2 {
        Vec2::new(
            // max-then-min rather than `clamp`, which panics on a box with min > max.
            (p.0 as f32).max(self.b.min.x).min(self.b.max.x),
            (p.1 as f32).max(self.b.min.y).min(self.b.max.y),
        )
    }

    /// `p` snapped onto `side`: that coordinate set to the side's, the other clamped.
    fn snap(&self, p: P, side: Side) -> Vec2 {
        let v = self.to_f32(p);
        match side {
            Side::Left => Vec2::new(self.b.min.x, v.y),
            Side::Right => Vec2::new(self.b.max.x, v.y),
            Side::Bottom => Vec2::new(v.x, self.b.min.y),
            Side::Top => Vec2::new(v.x, self.b.max.y),
        }
    }

    /// A side `p` lies beyond, or else the nearest side (for a clipped end that rounding put
    /// back inside the box).
    fn side_of(&self, p: P) -> Side {
        let gaps = [
            (p.0 - self.min.0, Side::Left),
            (self.max.0 - p.0, Side::Right),
            (p.1 - self.min.1, Side::Bottom),
            (self.max.1 - p.1, Side::Top),
        ];
        let mut best = gaps[0];
        for g in gaps {
            if g.0 < best.0 {
                best = g;
            }
        }
        best.1
    }

    /// Liang–Barsky: the parameter range of `p0 + t·d`, `t ∈ [t_lo, t_hi]`, inside the box,
    /// with the side that bounds each end when it is clipped; `None` when it misses the box.
    /// Each constraint `p·t ≤ q` is one side (`p = −dx, q = x0 − xmin` for the left side, …).
    fn clip(&self, p0: P, d: P, t_lo: f64, t_hi: f64) -> Option<Clipped> {
        let mut c = Clipped {
            t_enter: t_lo,
            enter: None,
            t_exit: t_hi,
            exit: None,
        };
        let constraints = [
            (-d.0, p0.0 - self.min.0, Side::Left),
            (d.0, self.max.0 - p0.0, Side::Right),
            (-d.1, p0.1 - self.min.1, Side::Bottom),
            (d.1, self.max.1 - p0.1, Side::Top),
        ];
        for (p, q, side) in constraints {
            if !(p.is_finite() && q.is_finite()) {
                return None;
            }
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
                continue;
            }
            let r = q / p;
            if p < 0.0 {
                if r > c.t_enter {
                    c.t_enter = r;
                    c.enter = Some(side);
                }
            } else if r < c.t_exit {
                c.t_exit = r;
                c.exit = Some(side);
            }
        }
        let ok = c.t_enter < c.t_exit && c.t_enter.is_finite() && c.t_exit.is_finite();
        ok.then_some(c)
    }
}

/// A clipped parameter range.
struct Clipped {
    t_enter: f64,
    enter: Option<Side>,
    t_exit: f64,
    exit: Option<Side>,
}

/// A Voronoi piece: `p0 + t·d`, `t ∈ [t_lo, t_hi]`; `v0` / `v1` are the graph vertices of the
/// ends when they are circumcentres inside the box (never clipped there).
struct Piece {
    p0: P,
    d: P,
    t_lo: f64,
    t_hi: f64,
    v0: Option<u16>,
    v1: Option<u16>,
    sites: [u16; 2],
}

/// Clips `piece` to the box and adds it to `out` (nothing when it misses the box).
fn add_piece<const VV: usize, const EE: usize>(
    out: &mut VoronoiGraph<VV, EE>,
    bx: &Box64,
    piece: &Piece,
) -> Result<(), VoronoiError> {
    out.tick(1);
    if let (Some(a), Some(b)) = (piece.v0, piece.v1) {
        return out.edge(a, b, piece.sites, false);
    }
    let Some(c) = bx.clip(piece.p0, piece.d, piece.t_lo, piece.t_hi) else {
        return Ok(());
    };
    let at = |t: f64| (piece.p0.0 + t * piece.d.0, piece.p0.1 + t * piece.d.1);
    let a = match piece.v0 {
        Some(a) => a,
        None => {
            let p = at(c.t_enter);
            out.vertex(bx.snap(p, c.enter.unwrap_or_else(|| bx.side_of(p))))?
        }
    };
    let b = match piece.v1 {
        Some(b) => b,
        None => {
            let p = at(c.t_exit);
            out.vertex(bx.snap(p, c.exit.unwrap_or_else(|| bx.side_of(p))))?
        }
    };
    out.edge(a, b, piece.sites, false)
}

/// Union–find root of `x` with path halving (at most `parent.len()` steps, each counted in
/// `work`).
fn find(parent: &mut [u32], x: u32, work: &mut u64) -> u32 {
    let mut x = x;
    for _ in 0..parent.len() {
        *work = work.saturating_add(1);
        let p = parent.get(x as usize).copied().unwrap_or(x);
        if p == x {
            break;
        }
        let gp = parent.get(p as usize).copied().unwrap_or(p);
        if let Some(slot) = parent.get_mut(x as usize) {
            *slot = gp;
        }
        x = gp;
    }
    x
}

fn is_ghost(v: [u32; 3]) -> bool {
    v.contains(&GHOST)
}

fn site16(i: u32) -> u16 {
    u16::try_from(i).unwrap_or(NO_SITE)
}

impl<const N: usize, const T: usize> Delaunay<N, T> {
    /// The quantised vertices of a finite triangle.
    fn corners(&self, v: [u32; 3]) -> Option<[Q; 3]> {
        Some([self.q(v[0])?, self.q(v[1])?, self.q(v[2])?])
    }

    /// The circumcentre of triangle `t`, metres (`None` for a ghost).
    fn centre(&self, t: usize) -> Option<P> {
        let [a, b, c] = self.corners(self.triangle(t))?;
        let p = circumcentre(a, b, c);
        (p.0.is_finite() && p.1.is_finite()).then_some(p)
    }

    /// Union–find over the finite triangles: neighbours with the same circumcircle (the
    /// in-circle determinant of one triangle and the far vertex of the other exactly zero)
    /// share a root. Counts each triangle, each neighbour and each find step in `work`.
    fn cocircular_groups(&self, parent: &mut [u32; T], work: &mut u64) {
        for t in 0..self.triangle_count() {
            *work = work.saturating_add(1);
            let v = self.triangle(t);
            let Some(qv) = self.corners(v) else { continue };
            for o in self.neighbours(t) {
                *work = work.saturating_add(1);
                let ov = self.triangle(o as usize);
                if (o as usize) <= t || is_ghost(ov) {
                    continue;
                }
                let far = ov.iter().copied().find(|x| !v.contains(x));
                let Some(qd) = far.and_then(|x| self.q(x)) else {
                    continue;
                };
                if incircle(qv[0], qv[1], qv[2], qd) == 0 {
                    let (rt, ro) = (find(parent, t as u32, work), find(parent, o, work));
                    if let Some(slot) = parent.get_mut(ro as usize) {
                        *slot = rt;
                    }
                }
            }
        }
    }

    /// The Voronoi vertices: one circumcentre per group of Delaunay triangles with the same
    /// circumcircle, metres, unclipped (none when all sites are collinear). Uses `4T` bytes of
    /// stack.
    pub fn voronoi_vertices<const VV: usize>(
        &self,
        out: &mut Vec<Vec2, VV>,
    ) -> Result<(), VoronoiError> {
        out.clear();
        let mut parent: [u32; T] = core::array::from_fn(|i| i as u32);
        // This query is not part of a counted rebuild, so its steps are counted and dropped.
        let mut work = 0;
        self.cocircular_groups(&mut parent, &mut work);
        for t in 0..self.triangle_count() {
            if find(&mut parent, t as u32, &mut work) as usize != t {
                continue;
            }
            if let Some(c) = self.centre(t) {
                let v = Vec2::new(c.0 as f32, c.1 as f32);
                out.push(v).map_err(|_| VoronoiError::GraphFull)?;
            }
        }
        Ok(())
    }

    /// The Voronoi diagram clipped to `bounds`, with the border split at every clip point and
    /// corner, into `out` (cleared first; left empty on an error).
    ///
    /// Refuses bounds that are not finite or not strictly ordered
    /// ([`VoronoiError::InvalidBounds`]) and a graph too small for the result
    /// ([`VoronoiError::GraphFull`]; capacities of [`graph_vertex_bound`] and
    /// [`graph_edge_bound`] of the site count always suffice). Uses `6T` bytes of stack; the
    /// cost is `O(V² + n·B)` for `V` vertices, `B` border edges and `n` sites (vertices are
    /// shared by a scan), counted in [`VoronoiGraph::work`] (at most [`graph_work_bound`]).
    pub fn graph<const VV: usize, const EE: usize>(
        &self,
        bounds: &Bounds,
        out: &mut VoronoiGraph<VV, EE>,
    ) -> Result<(), VoronoiError> {
        out.vertices.clear();
        out.edges.clear();
        out.work = 0;
        let result = Box64::new(bounds).and_then(|bx| {
            if self.triangle_count() == 0 {
                self.bisector_graph(&bx, out)?;
            } else {
                self.triangulated_graph(&bx, out)?;
            }
            self.border(&bx, out)
        });
        if result.is_err() {
            out.vertices.clear();
            out.edges.clear();
        }
        result
    }

    /// No finite triangle: the bisectors of consecutive sites along their line.
    fn bisector_graph<const VV: usize, const EE: usize>(
        &self,
        bx: &Box64,
        out: &mut VoronoiGraph<VV, EE>,
    ) -> Result<(), VoronoiError> {
        for w in self.line_order().windows(2) {
            out.tick(1);
            let (a, b) = (w[0], w[1]);
            let (Some(qa), Some(qb)) = (self.q(a), self.q(b)) else {
                continue;
            };
            let (pa, pb) = (metres(qa), metres(qb));
            let piece = Piece {
                p0: ((pa.0 + pb.0) / 2.0, (pa.1 + pb.1) / 2.0),
                d: (-(pb.1 - pa.1), pb.0 - pa.0),
                t_lo: f64::NEG_INFINITY,
                t_hi: f64::INFINITY,
                v0: None,
                v1: None,
                sites: [site16(a), site16(b)],
            };
            add_piece(out, bx, &piece)?;
        }
        Ok(())
    }

    /// Finite Voronoi edges between circumcentres of neighbouring triangles (cocircular groups
    /// merged) and rays across the hull edges.
    fn triangulated_graph<const VV: usize, const EE: usize>(
        &self,
        bx: &Box64,
        out: &mut VoronoiGraph<VV, EE>,
    ) -> Result<(), VoronoiError> {
        let nt = self.triangle_count();
        let mut parent: [u32; T] = core::array::from_fn(|i| i as u32);
        let mut work = 0;
        self.cocircular_groups(&mut parent, &mut work);
        out.tick(work);
        let mut vid = [NO_VERTEX; T];
        for t in 0..nt {
            let mut work = 1;
            let root = find(&mut parent, t as u32, &mut work);
            out.tick(work);
            if root as usize != t {
                continue;
            }
            if let Some(c) = self.centre(t).filter(|c| bx.contains(*c)) {
                let v = out.vertex(bx.to_f32(c))?;
                if let Some(slot) = vid.get_mut(t) {
                    *slot = v;
                }
            }
        }
        let vertex_of = |r: u32| vid.get(r as usize).copied().filter(|v| *v != NO_VERTEX);
        for t in 0..nt {
            out.tick(1);
            let v = self.triangle(t);
            if is_ghost(v) {
                continue;
            }
            let mut work = 0;
            let rt = find(&mut parent, t as u32, &mut work);
            out.tick(work);
            let Some(ct) = self.centre(rt as usize) else {
                continue;
            };
            for (i, o) in self.neighbours(t).into_iter().enumerate() {
                out.tick(1);
                let (x, y) = (v[(i + 1) % 3], v[(i + 2) % 3]);
                let sites = [site16(x), site16(y)];
                if is_ghost(self.triangle(o as usize)) {
                    // Hull edge x → y with the interior on its left: the ray goes right.
                    let (Some(qx), Some(qy)) = (self.q(x), self.q(y)) else {
                        continue;
                    };
                    let (px, py) = (metres(qx), metres(qy));
                    let piece = Piece {
                        p0: ct,
                        d: (py.1 - px.1, -(py.0 - px.0)),
                        t_lo: 0.0,
                        t_hi: f64::INFINITY,
                        v0: vertex_of(rt),
                        v1: None,
                        sites,
                    };
                    add_piece(out, bx, &piece)?;
                    continue;
                }
                let mut work = 0;
                let ro = find(&mut parent, o, &mut work);
                out.tick(work);
                if (o as usize) <= t || ro == rt {
                    continue;
                }
                let Some(co) = self.centre(ro as usize) else {
                    continue;
                };
                // Start from the end inside the box, if any, so it is never clipped.
                let (p0, v0, p1, v1) = match (vertex_of(rt), vertex_of(ro)) {
                    (None, Some(vo)) => (co, Some(vo), ct, None),
                    (vt, vo) => (ct, vt, co, vo),
                };
                let piece = Piece {
                    p0,
                    d: (p1.0 - p0.0, p1.1 - p0.1),
                    t_lo: 0.0,
                    t_hi: 1.0,
                    v0,
                    v1,
                    sites,
                };
                add_piece(out, bx, &piece)?;
            }
        }
        Ok(())
    }

    /// The site nearest to `p` (f64), or [`NO_SITE`]: a scan of every site.
    fn nearest_site(&self, p: P) -> u16 {
        let mut best = (f64::INFINITY, NO_SITE);
        for i in 0..self.site_count() {
            let Some(q) = self.q(i as u32) else { continue };
            let s = metres(q);
            let d = (s.0 - p.0) * (s.0 - p.0) + (s.1 - p.1) * (s.1 - p.1);
            if d < best.0 {
                best = (d, site16(i as u32));
            }
        }
        best.1
    }

    /// The border: the 4 corners and every vertex exactly on a side, joined in order along
    /// each side (counter-clockwise from the south-west corner).
    fn border<const VV: usize, const EE: usize>(
        &self,
        bx: &Box64,
        out: &mut VoronoiGraph<VV, EE>,
    ) -> Result<(), VoronoiError> {
        let (lo, hi) = (bx.b.min, bx.b.max);
        let corners = [
            out.vertex(Vec2::new(lo.x, lo.y))?,
            out.vertex(Vec2::new(hi.x, lo.y))?,
            out.vertex(Vec2::new(hi.x, hi.y))?,
            out.vertex(Vec2::new(lo.x, hi.y))?,
        ];
        // (side, start corner, end corner)
        let sides = [
            (Side::Bottom, corners[0], corners[1]),
            (Side::Right, corners[1], corners[2]),
            (Side::Top, corners[2], corners[3]),
            (Side::Left, corners[3], corners[0]),
        ];
        let in_x = |v: Vec2| v.x >= lo.x && v.x <= hi.x;
        let in_y = |v: Vec2| v.y >= lo.y && v.y <= hi.y;
        for (side, start, end) in sides {
            // The position along the side, increasing counter-clockwise.
            let along = |v: Vec2| match side {
                Side::Bottom => v.x,
                Side::Right => v.y,
                Side::Top => -v.x,
                Side::Left => -v.y,
            };
            let on = |v: Vec2| match side {
                Side::Bottom => v.y == lo.y && in_x(v),
                Side::Top => v.y == hi.y && in_x(v),
                Side::Left => v.x == lo.x && in_y(v),
                Side::Right => v.x == hi.x && in_y(v),
            };
            let (mut cur, last) = (start, end);
            for _ in 0..out.vertices.len() {
                // The scan of every vertex, and of every site for the edge's site.
                out.tick((out.vertices.len() + self.site_count()) as u64);
                let here = out.vertices.get(usize::from(cur)).copied().unwrap_or(lo);
                let mut next: Option<(f32, u16)> = None;
                for (i, w) in out.vertices.iter().enumerate() {
                    let a = along(*w);
                    if on(*w) && a > along(here) && next.is_none_or(|(b, _)| a < b) {
                        next = Some((a, i as u16));
                    }
                }
                let Some((_, nx)) = next else { break };
                let there = out.vertices.get(usize::from(nx)).copied().unwrap_or(lo);
                let mid = (
                    (f64::from(here.x) + f64::from(there.x)) / 2.0,
                    (f64::from(here.y) + f64::from(there.y)) / 2.0,
                );
                let s = self.nearest_site(mid);
                out.edge(cur, nx, [s, s], true)?;
                cur = nx;
                if cur == last {
                    break;
                }
            }
        }
        Ok(())
    }
}
