//! `geometry::grid` traversals against independent `f64` references, on random grids and
//! primitives (seeded splitmix64).
//!
//! Two references per case, both over the grid's closed cells:
//! * **sampled**: the primitive sampled every ≤ cell/50, each sample adding the cells that contain
//!   it (both or all four on a grid line or corner); for `widen > 0` also every cell near the
//!   primitive whose boundary, sampled every cell/50, has a point within `widen` of the primitive
//!   (exact `f64` point-to-segment / point-to-arc distances). Every cell it lists is touched.
//! * **exact**: every cell whose closed square lies within `widen` of the primitive, by a closed
//!   form `f64` rectangle-to-primitive distance (rectangle edges against the segment or arc:
//!   end points, the foot of the perpendicular from the arc's centre, and line–circle crossings).
//!
//! Asserted for every case: the traversal visits every cell of both references (the hard
//! requirement), each cell at most once, returns the number of visits, stays within the
//! documented distance slack and count bound, and (segments) visits rows and columns in the
//! direction of travel. The sampled reference must lie within the exact one (a check of the
//! references themselves). Extra cells (visited, farther than `widen`) and timings are printed
//! (`cargo test -p host-tests --test grid_traversal -- --nocapture`).

use skyroute::geometry::grid::{
    arc_cells, primitive_cells, segment_cells, CellGrid, GridError, SLACK_ULPS,
};
use skyroute::{Arc, Primitive, Segment, Vec2};
use std::collections::HashSet;
use std::f64::consts::{PI, TAU};
use std::time::Instant;

// ------------------------------------------------------------------------------------------------

use host_tests::{cases, reference, Rng};

// ------------------------------------------------------------------------------------------------
// f64 reference geometry

#[derive(Clone, Copy, Debug)]
struct P {
    x: f64,
    y: f64,
}

fn p(x: f64, y: f64) -> P {
    P { x, y }
}

fn sub(a: P, b: P) -> P {
    p(a.x - b.x, a.y - b.y)
}

fn dist(a: P, b: P) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

fn cross(a: P, b: P) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The shared f64 reference (`host_tests::reference`) on this file's points.
fn point_segment(q: P, a: P, b: P) -> f64 {
    reference::dist_point_segment((q.x, q.y), (a.x, a.y), (b.x, b.y))
}

#[derive(Clone, Copy, Debug)]
struct RArc {
    c: P,
    r: f64,
    a0: f64,
    sweep: f64,
}

impl RArc {
    fn at(&self, a: f64) -> P {
        p(self.c.x + self.r * a.cos(), self.c.y + self.r * a.sin())
    }
    fn start(&self) -> P {
        self.at(self.a0)
    }
    fn end(&self) -> P {
        self.at(self.a0 + self.sweep)
    }
    fn contains_angle(&self, a: f64) -> bool {
        if self.sweep.abs() >= TAU {
            return true;
        }
        let off = ((a - self.a0) * if self.sweep < 0.0 { -1.0 } else { 1.0 }).rem_euclid(TAU);
        off <= self.sweep.abs() || off >= TAU - 1e-15
    }
    fn point_dist(&self, q: P) -> f64 {
        let d = sub(q, self.c);
        let rho = d.x.hypot(d.y);
        let ends = dist(q, self.start()).min(dist(q, self.end()));
        if rho == 0.0 {
            return self.r.min(ends);
        }
        if self.contains_angle(d.y.atan2(d.x)) {
            (rho - self.r).abs().min(ends)
        } else {
            ends
        }
    }
    fn length(&self) -> f64 {
        self.r * self.sweep.abs().min(TAU)
    }
}

#[derive(Clone, Copy, Debug)]
enum Prim {
    Seg(P, P),
    Arc(RArc),
}

impl Prim {
    fn point_dist(&self, q: P) -> f64 {
        match self {
            Prim::Seg(a, b) => point_segment(q, *a, *b),
            Prim::Arc(arc) => arc.point_dist(q),
        }
    }
    fn length(&self) -> f64 {
        match self {
            Prim::Seg(a, b) => dist(*a, *b),
            Prim::Arc(arc) => arc.length(),
        }
    }
    fn sample(&self, n: usize) -> impl Iterator<Item = P> + '_ {
        (0..=n).map(move |i| {
            let t = i as f64 / n as f64;
            match self {
                Prim::Seg(a, b) => p(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)),
                Prim::Arc(arc) => {
                    let s = arc.sweep.clamp(-TAU, TAU);
                    if i == n {
                        arc.end()
                    } else {
                        arc.at(arc.a0 + t * s)
                    }
                }
            }
        })
    }
    /// Bounding box (an arc: its whole circle).
    fn bbox(&self) -> (P, P) {
        match self {
            Prim::Seg(a, b) => (p(a.x.min(b.x), a.y.min(b.y)), p(a.x.max(b.x), a.y.max(b.y))),
            Prim::Arc(arc) => (
                p(arc.c.x - arc.r, arc.c.y - arc.r),
                p(arc.c.x + arc.r, arc.c.y + arc.r),
            ),
        }
    }
}

/// Segments `ab` and `cd` intersect (touching counts).
fn segments_meet(a: P, b: P, c: P, d: P) -> bool {
    let o = |p0: P, p1: P, q: P| cross(sub(p1, p0), sub(q, p0));
    let (d1, d2) = (o(c, d, a), o(c, d, b));
    let (d3, d4) = (o(a, b, c), o(a, b, d));
    d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && {
        // collinear: boxes must overlap
        let bx = |u: P, v: P| (u.x.min(v.x), u.x.max(v.x), u.y.min(v.y), u.y.max(v.y));
        let (a0, a1, a2, a3) = bx(a, b);
        let (c0, c1, c2, c3) = bx(c, d);
        a0 <= c1 && c0 <= a1 && a2 <= c3 && c2 <= a3
    }
}

fn segment_segment(a: P, b: P, c: P, d: P) -> f64 {
    if segments_meet(a, b, c, d) {
        return 0.0;
    }
    point_segment(a, c, d)
        .min(point_segment(b, c, d))
        .min(point_segment(c, a, b))
        .min(point_segment(d, a, b))
}

fn segment_arc(a: P, b: P, arc: &RArc) -> f64 {
    let mut best = point_segment(arc.start(), a, b)
        .min(point_segment(arc.end(), a, b))
        .min(arc.point_dist(a))
        .min(arc.point_dist(b));
    let d = sub(b, a);
    let l2 = d.x * d.x + d.y * d.y;
    let ac = sub(a, arc.c);
    if l2 > 0.0 {
        let t = -(ac.x * d.x + ac.y * d.y) / l2;
        if (0.0..=1.0).contains(&t) {
            best = best.min(arc.point_dist(p(a.x + t * d.x, a.y + t * d.y)));
        }
        // Line–circle crossings on both.
        let bq = 2.0 * (ac.x * d.x + ac.y * d.y);
        let cq = ac.x * ac.x + ac.y * ac.y - arc.r * arc.r;
        let disc = bq * bq - 4.0 * l2 * cq;
        if disc >= 0.0 {
            for t in [
                (-bq - disc.sqrt()) / (2.0 * l2),
                (-bq + disc.sqrt()) / (2.0 * l2),
            ] {
                if (0.0..=1.0).contains(&t) {
                    let x = p(a.x + t * d.x, a.y + t * d.y);
                    let v = sub(x, arc.c);
                    if arc.contains_angle(v.y.atan2(v.x)) {
                        return 0.0;
                    }
                }
            }
        }
    }
    best
}

/// Exact distance between the closed rectangle `[lo, hi]` and the primitive.
fn rect_dist(lo: P, hi: P, prim: &Prim) -> f64 {
    let inside = |q: P| lo.x <= q.x && q.x <= hi.x && lo.y <= q.y && q.y <= hi.y;
    let corners = [lo, p(hi.x, lo.y), hi, p(lo.x, hi.y)];
    let edges = (0..4).map(|i| (corners[i], corners[(i + 1) % 4]));
    match prim {
        Prim::Seg(a, b) => {
            if inside(*a) || inside(*b) {
                return 0.0;
            }
            edges
                .map(|(c, d)| segment_segment(*a, *b, c, d))
                .fold(f64::INFINITY, f64::min)
        }
        Prim::Arc(arc) => {
            if inside(arc.start()) {
                return 0.0;
            }
            edges
                .map(|(c, d)| segment_arc(c, d, arc))
                .fold(f64::INFINITY, f64::min)
        }
    }
}

/// Distance between the rectangle's boundary, sampled every `step`, and the primitive.
fn rect_boundary_sampled(lo: P, hi: P, prim: &Prim, step: f64) -> f64 {
    let corners = [lo, p(hi.x, lo.y), hi, p(lo.x, hi.y)];
    let mut best = f64::INFINITY;
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        let n = (dist(a, b) / step).ceil().max(1.0) as usize;
        for j in 0..n {
            let t = j as f64 / n as f64;
            best = best.min(prim.point_dist(p(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))));
        }
    }
    best
}

// ------------------------------------------------------------------------------------------------
// Grid in f64

#[derive(Clone, Copy, Debug)]
struct G {
    ox: f64,
    oy: f64,
    cell: f64,
    cols: u32,
    rows: u32,
}

impl G {
    fn of(grid: &CellGrid) -> Self {
        G {
            ox: grid.origin.x as f64,
            oy: grid.origin.y as f64,
            cell: grid.cell as f64,
            cols: grid.cols,
            rows: grid.rows,
        }
    }
    fn rect(&self, c: u32, r: u32) -> (P, P) {
        let lo = p(
            self.ox + c as f64 * self.cell,
            self.oy + r as f64 * self.cell,
        );
        (lo, p(lo.x + self.cell, lo.y + self.cell))
    }
    /// Closed index range `[⌈lo⌉ − 1, ⌊hi⌋]` of grid-unit interval `[lo, hi]`, clipped.
    fn range(lo: f64, hi: f64, n: u32) -> Option<(u32, u32)> {
        let a = (lo.ceil() - 1.0).max(0.0);
        let b = hi.floor().min(n as f64 - 1.0);
        (a <= b).then_some((a as u32, b as u32))
    }
    /// Cells whose closed square holds `q` (within `tol` cells).
    fn cells_at(&self, q: P, tol: f64, out: &mut HashSet<(u32, u32)>) {
        let u = (q.x - self.ox) / self.cell;
        let v = (q.y - self.oy) / self.cell;
        if let (Some(cs), Some(rs)) = (
            G::range(u - tol, u + tol, self.cols),
            G::range(v - tol, v + tol, self.rows),
        ) {
            for r in rs.0..=rs.1 {
                for c in cs.0..=cs.1 {
                    out.insert((c, r));
                }
            }
        }
    }
    /// Cells overlapping the box `[lo, hi]` grown by `m` metres.
    fn candidates(&self, (lo, hi): (P, P), m: f64) -> Vec<(u32, u32)> {
        let cs = G::range(
            (lo.x - m - self.ox) / self.cell,
            (hi.x + m - self.ox) / self.cell,
            self.cols,
        );
        let rs = G::range(
            (lo.y - m - self.oy) / self.cell,
            (hi.y + m - self.oy) / self.cell,
            self.rows,
        );
        let mut v = Vec::new();
        if let (Some(cs), Some(rs)) = (cs, rs) {
            for r in rs.0..=rs.1 {
                for c in cs.0..=cs.1 {
                    v.push((c, r));
                }
            }
        }
        v
    }
}

// ------------------------------------------------------------------------------------------------
// Cases

#[derive(Clone, Copy, Debug)]
struct Case {
    grid: CellGrid,
    prim: Primitive,
    widen: f32,
    /// 0: general position; 1: built on exact ties (through grid corners, along grid lines,
    /// tangent to them, on an integer grid); 2: near-ties: the same constructions on a
    /// fractional grid, where f32 rounding of the inputs decides whether the tie holds, and
    /// tiny segments within 10⁻³ cells of a corner.
    class: usize,
}

fn random_grid(rng: &mut Rng, exact: bool) -> CellGrid {
    let cols = rng.int(1, 120) as u32;
    let rows = rng.int(1, 120) as u32;
    if exact {
        // Integer origin and cell: grid lines are exact in f32, so ties are real ties.
        let cell = rng.int(10, 100) as f32;
        let origin = Vec2::new(rng.int(-5000, 5000) as f32, rng.int(-5000, 5000) as f32);
        CellGrid::new(origin, cell, cols, rows)
    } else {
        let cell = rng.range(10.0, 100.0) as f32;
        let origin = Vec2::new(rng.range(-2e4, 2e4) as f32, rng.range(-2e4, 2e4) as f32);
        CellGrid::new(origin, cell, cols, rows)
    }
}

/// A world point at grid units `(u, v)`.
fn world(grid: &CellGrid, u: f64, v: f64) -> Vec2 {
    Vec2::new(
        (grid.origin.x as f64 + u * grid.cell as f64) as f32,
        (grid.origin.y as f64 + v * grid.cell as f64) as f32,
    )
}

/// A point in the grid's box grown by 20 % (grid units).
fn around(rng: &mut Rng, grid: &CellGrid) -> (f64, f64) {
    let (w, h) = (grid.cols as f64, grid.rows as f64);
    (
        rng.range(-0.2 * w - 1.0, 1.2 * w + 1.0),
        rng.range(-0.2 * h - 1.0, 1.2 * h + 1.0),
    )
}

fn random_widen(rng: &mut Rng, grid: &CellGrid, exact: bool) -> f32 {
    if rng.chance(0.5) {
        return 0.0;
    }
    let cells = if exact && rng.chance(0.5) {
        [0.5, 1.0, 1.5, 2.0][rng.below(4) as usize]
    } else {
        rng.log_range(1e-3, 3.0)
    };
    (cells * grid.cell as f64) as f32
}

fn random_segment_case(rng: &mut Rng) -> Case {
    // Kinds 2, 3, 6 on an exact grid (real ties), 7: kind 6 on a fractional grid (near-ties,
    // decided by f32 rounding of the inputs).
    let kind = rng.below(8);
    let exact = matches!(kind, 2 | 3 | 6) || (kind != 7 && rng.chance(0.3));
    let grid = random_grid(rng, exact);
    let (u0, v0) = around(rng, &grid);
    let (s, e) = match kind {
        // Random direction, length log-uniform 0.01 – 60 cells.
        0 | 1 => {
            let len = rng.log_range(0.01, 60.0);
            let a = rng.range(-PI, PI);
            ((u0, v0), (u0 + len * a.cos(), v0 + len * a.sin()))
        }
        // Zero length, anywhere or on a corner.
        2 => {
            let q = if rng.chance(0.5) {
                (u0.round(), v0.round())
            } else {
                (u0, v0)
            };
            (q, q)
        }
        // Axis-aligned, half of them on a grid line.
        3 => {
            let len = rng.log_range(0.01, 60.0) * if rng.chance(0.5) { 1.0 } else { -1.0 };
            let (u0, v0) = if rng.chance(0.5) {
                (u0.round(), v0.round())
            } else {
                (u0, v0)
            };
            if rng.chance(0.5) {
                ((u0, v0), (u0 + len, v0))
            } else {
                ((u0, v0), (u0, v0 + len))
            }
        }
        // Far outside to far outside, across the grid (clipping).
        4 => {
            let (w, h) = (grid.cols as f64, grid.rows as f64);
            let a = rng.range(-PI, PI);
            let (cu, cv) = (rng.range(0.0, w), rng.range(0.0, h));
            let far = 3.0 * (w + h);
            (
                (cu - far * a.cos(), cv - far * a.sin()),
                (cu + far * a.cos(), cv + far * a.sin()),
            )
        }
        // Tiny, next to a corner.
        5 => {
            let (cu, cv) = (u0.round(), v0.round());
            let a = rng.range(-PI, PI);
            let l = rng.log_range(1e-5, 1e-2);
            (
                (cu + rng.range(-1e-3, 1e-3), cv + rng.range(-1e-3, 1e-3)),
                (cu + l * a.cos(), cv + l * a.sin()),
            )
        }
        // Corner to corner along a lattice direction (exactly through every corner it passes).
        _ => {
            let (du, dv) = (rng.int(-3, 3) as f64, rng.int(-3, 3) as f64);
            let m = rng.int(1, 12) as f64;
            let q = (u0.round(), v0.round());
            (q, (q.0 + du * m, q.1 + dv * m))
        }
    };
    let seg = Segment::new(world(&grid, s.0, s.1), world(&grid, e.0, e.1));
    let widen = random_widen(rng, &grid, exact || kind == 7);
    Case {
        grid,
        prim: Primitive::Line(seg),
        widen,
        class: match kind {
            2 | 3 | 6 => 1,
            5 | 7 => 2,
            _ => 0,
        },
    }
}

fn random_arc_case(rng: &mut Rng) -> Case {
    // Kind 3: integer centre and radius on an exact grid (real ties); kind 4: the same on a
    // fractional grid (near-ties, decided by f32 rounding of the inputs).
    let kind = rng.below(5);
    let exact = kind == 3 || (kind != 4 && rng.chance(0.3));
    let grid = random_grid(rng, exact);
    let (u0, v0) = around(rng, &grid);
    let (centre, radius) = match kind {
        0 | 1 => (
            world(&grid, u0, v0),
            (rng.log_range(0.01, 40.0) * grid.cell as f64) as f32,
        ),
        2 => (world(&grid, u0, v0), 0.0),
        // Integer centre and radius (3-4-5 lattice points, tangent to grid lines).
        _ => (
            world(&grid, u0.round(), v0.round()),
            rng.int(1, 25) as f32 * grid.cell,
        ),
    };
    let start_angle = match rng.below(4) {
        0 => [0.0, 0.5, 1.0, 1.5, 2.0, -1.0][rng.below(6) as usize] * std::f32::consts::PI,
        _ => rng.range(-10.0, 10.0) as f32,
    };
    let mag = match rng.below(10) {
        0 => 0.0,
        1 => 1e-7,
        2 => 1e-4,
        3 => std::f32::consts::TAU - 1e-4,
        4 => std::f32::consts::TAU,
        5 => std::f32::consts::TAU + 0.3,
        6 => std::f32::consts::FRAC_PI_2,
        _ => rng.range(0.0, TAU + 0.5) as f32,
    };
    let sweep = if rng.chance(0.5) { mag } else { -mag };
    let widen = random_widen(rng, &grid, exact || kind == 4);
    Case {
        grid,
        prim: Primitive::Arc(Arc {
            centre,
            radius,
            start_angle,
            sweep,
        }),
        widen,
        class: kind.saturating_sub(2) as usize,
    }
}

fn reference_prim(prim: &Primitive) -> Prim {
    let q = |v: Vec2| p(v.x as f64, v.y as f64);
    match prim {
        Primitive::Line(s) => Prim::Seg(q(s.start), q(s.end)),
        Primitive::Arc(a) => Prim::Arc(RArc {
            c: q(a.centre),
            r: a.radius as f64,
            a0: a.start_angle as f64,
            sweep: a.sweep as f64,
        }),
    }
}

/// The documented slack, cells: 3δ, plus for arcs twice the angle error times (r + widen).
fn slack_cells(case: &Case) -> f64 {
    let g = G::of(&case.grid);
    let w = case.widen as f64 / g.cell;
    let u = |x: f32, o: f64| ((x as f64 - o) / g.cell).abs();
    let (m, extra) = match case.prim {
        Primitive::Line(s) => (
            u(s.start.x, g.ox)
                .max(u(s.start.y, g.oy))
                .max(u(s.end.x, g.ox))
                .max(u(s.end.y, g.oy))
                + w,
            0.0,
        ),
        Primitive::Arc(a) => {
            let r = a.radius as f64 / g.cell;
            let ea = 16.0
                * f32::EPSILON as f64
                * (a.start_angle.abs() as f64 + a.sweep.abs() as f64 + 8.0);
            (
                u(a.centre.x, g.ox).max(u(a.centre.y, g.oy)) + r + w,
                2.0 * ea * (r + w),
            )
        }
    };
    let delta = SLACK_ULPS as f64 * f32::EPSILON as f64 * (m + 1.0);
    3.0 * delta + extra
}

#[derive(Default, Debug)]
struct Stats {
    cases: u64,
    exact_cells: u64,
    visited: u64,
    extra: u64,
    extra_max_case: u64,
    sampled_missed_by_sampling: u64,
    clipped_cases: u64,
    ref_time_s: f64,
}

/// Runs one case against both references; panics with the case on a violation.
fn check(case: &Case, stats: &mut Stats) {
    let t0 = Instant::now();
    let g = G::of(&case.grid);
    let prim = reference_prim(&case.prim);
    let w = case.widen as f64;
    let tol = 1e-7; // cells: f64 noise in the references' tie decisions

    // Sampled reference.
    let mut sampled = HashSet::new();
    let step = g.cell / 50.0;
    let n = (prim.length() / step).ceil().max(1.0) as usize;
    for q in prim.sample(n) {
        g.cells_at(q, tol, &mut sampled);
    }
    let cands = g.candidates(prim.bbox(), w + g.cell);
    let near = |c: u32, r: u32| {
        let (lo, hi) = g.rect(c, r);
        let centre = p(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y));
        prim.point_dist(centre) <= w + g.cell * (0.5f64.sqrt() + 1e-6)
    };
    if w > 0.0 {
        for &(c, r) in &cands {
            if near(c, r) {
                let (lo, hi) = g.rect(c, r);
                if rect_boundary_sampled(lo, hi, &prim, step) <= w {
                    sampled.insert((c, r));
                }
            }
        }
    }
    // Exact reference.
    let mut exact = HashSet::new();
    for &(c, r) in &cands {
        if near(c, r) {
            let (lo, hi) = g.rect(c, r);
            if rect_dist(lo, hi, &prim) <= w + tol * g.cell {
                exact.insert((c, r));
            }
        }
    }
    stats.ref_time_s += t0.elapsed().as_secs_f64();

    // The traversal.
    let mut visited = HashSet::new();
    let mut order = Vec::new();
    let count = primitive_cells(&case.grid, &case.prim, case.widen, |c, r| {
        assert!(
            c < case.grid.cols && r < case.grid.rows,
            "{case:?}: ({c}, {r}) outside"
        );
        assert!(visited.insert((c, r)), "{case:?}: ({c}, {r}) visited twice");
        order.push((c, r));
        true
    })
    .unwrap_or_else(|e| panic!("{case:?}: {e}"));
    assert_eq!(count, visited.len() as u64, "{case:?}: count");

    for cell in exact.iter().chain(sampled.iter()) {
        assert!(
            visited.contains(cell),
            "{case:?}: missed {cell:?} (exact distance {}, widen {w})",
            {
                let (lo, hi) = g.rect(cell.0, cell.1);
                rect_dist(lo, hi, &prim)
            }
        );
    }
    for cell in &sampled {
        let (lo, hi) = g.rect(cell.0, cell.1);
        let d = rect_dist(lo, hi, &prim);
        assert!(
            d <= w + 2.0 * tol * g.cell, // cells_at's tolerance, on both axes
            "{case:?}: reference disagreement at {cell:?}: sampled within {w}, exact {d}"
        );
    }
    // Extra cells: within the documented slack.
    let slack = slack_cells(case) * g.cell + tol * g.cell;
    let mut extra = 0;
    for cell in &visited {
        if !exact.contains(cell) {
            extra += 1;
            let (lo, hi) = g.rect(cell.0, cell.1);
            let d = rect_dist(lo, hi, &prim);
            assert!(
                d <= w + slack,
                "{case:?}: visited {cell:?} at distance {d} > widen {w} + slack {slack}"
            );
        }
    }
    // Count bound: N ≤ 2(ρ + √2)L + π(ρ + √2)² (arcs: also ≤ π(r + ρ + √2)²), in cells.
    let rho = w / g.cell + slack_cells(case) + 2f64.sqrt();
    let l = prim.length() / g.cell;
    let mut bound = 2.0 * rho * l + PI * rho * rho;
    if let Prim::Arc(a) = prim {
        bound = bound.min(PI * (a.r / g.cell + rho).powi(2));
    }
    assert!(
        count as f64 <= bound + 1e-9,
        "{case:?}: {count} cells > bound {bound}"
    );
    // Segments: rows in the direction of travel, columns too within a row.
    if let Primitive::Line(s) = case.prim {
        let up = s.end.y >= s.start.y;
        let east = s.end.x >= s.start.x;
        for pair in order.windows(2) {
            let ((c0, r0), (c1, r1)) = (pair[0], pair[1]);
            assert!(
                r0 == r1 || (r1 > r0) == up,
                "{case:?}: row order {r0} → {r1}"
            );
            assert!(
                r0 != r1 || (c1 > c0) == east,
                "{case:?}: column order {c0} → {c1}"
            );
        }
    }

    stats.cases += 1;
    stats.exact_cells += exact.len() as u64;
    stats.visited += count;
    stats.extra += extra;
    if extra > stats.extra_max_case && std::env::var_os("GRID_DEBUG").is_some() {
        println!("extra {extra}: {case:?}");
    }
    stats.extra_max_case = stats.extra_max_case.max(extra);
    stats.sampled_missed_by_sampling += exact.difference(&sampled).count() as u64;
    let (lo, hi) = case.prim.bounding_box();
    let m = Vec2::new(case.widen, case.widen);
    if !case.grid.covers(lo - m, hi + m) {
        stats.clipped_cases += 1;
    }
}

fn report(name: &str, s: &Stats) {
    println!(
        "{name}: {} cases, {} exact cells, {} visited, {} extra ({:.3} %; at most {} in one case), \
         {} exact cells the sampling missed, {} cases clipped, references {:.1} s",
        s.cases,
        s.exact_cells,
        s.visited,
        s.extra,
        100.0 * s.extra as f64 / s.exact_cells.max(1) as f64,
        s.extra_max_case,
        s.sampled_missed_by_sampling,
        s.clipped_cases,
        s.ref_time_s,
    );
}

/// Times the traversal alone over all cases with a counting visitor.
fn time(name: &str, cases: &[Case]) {
    let t0 = Instant::now();
    let mut cells = 0u64;
    for case in cases {
        cells += primitive_cells(&case.grid, &case.prim, case.widen, |_, _| true).unwrap();
    }
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "{name}: traversal alone {:.1} ms for {} calls and {cells} cells: {:.0} ns/call, {:.1} ns/cell",
        dt * 1e3,
        cases.len(),
        dt * 1e9 / cases.len() as f64,
        dt * 1e9 / cells.max(1) as f64,
    );
}

fn run(name: &str, seed: u64, n: usize, gen: fn(&mut Rng) -> Case) {
    let mut rng = Rng(seed);
    let cases: Vec<Case> = (0..n).map(|_| gen(&mut rng)).collect();
    // By widen = 0 / > 0 and class (general position, exact ties, near-ties).
    let mut stats: [Stats; 6] = Default::default();
    for case in &cases {
        let bucket = (case.widen > 0.0) as usize * 3 + case.class;
        check(case, &mut stats[bucket]);
    }
    for (i, s) in stats.iter().enumerate() {
        let widen = if i >= 3 { "widen > 0" } else { "widen = 0" };
        let class = ["general", "exact ties", "near-ties"][i % 3];
        report(&format!("{name}, {widen}, {class}"), s);
    }
    time(name, &cases);
    assert!(stats.iter().all(|s| s.cases > n as u64 / 20));
}

#[test]
fn segments_visit_every_touched_cell() {
    run(
        "segments",
        0x5EED_0001,
        cases(10_000, 100_000),
        random_segment_case,
    );
}

#[test]
fn arcs_visit_every_touched_cell() {
    run("arcs", 0x5EED_0002, cases(10_000, 100_000), random_arc_case);
}

// ------------------------------------------------------------------------------------------------
// Small exact cases

fn collect(grid: &CellGrid, prim: Primitive, widen: f32) -> Vec<(u32, u32)> {
    let mut v = Vec::new();
    primitive_cells(grid, &prim, widen, |c, r| {
        v.push((c, r));
        true
    })
    .unwrap();
    v.sort_unstable();
    v
}

fn seg(x0: f32, y0: f32, x1: f32, y1: f32) -> Primitive {
    Primitive::Line(Segment::new(Vec2::new(x0, y0), Vec2::new(x1, y1)))
}

#[test]
fn ties_visit_every_cell_sharing_the_point_or_edge() {
    let grid = CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 10, 10);
    // Through the corner (20, 20): all four cells around it, plus the diagonal ones.
    assert_eq!(
        collect(&grid, seg(15.0, 15.0, 25.0, 25.0), 0.0),
        [(1, 1), (1, 2), (2, 1), (2, 2)]
    );
    // Along the grid line y = 30: the cells on both sides.
    assert_eq!(
        collect(&grid, seg(12.0, 30.0, 18.0, 30.0), 0.0),
        [(1, 2), (1, 3)]
    );
    // A point on a corner: four cells; inside a cell: one.
    assert_eq!(
        collect(&grid, seg(40.0, 40.0, 40.0, 40.0), 0.0),
        [(3, 3), (3, 4), (4, 3), (4, 4)]
    );
    assert_eq!(collect(&grid, seg(41.0, 41.0, 41.0, 41.0), 0.0), [(4, 4)]);
    // widen reaching exactly to a grid line touches the cell beyond it.
    assert_eq!(
        collect(&grid, seg(45.0, 45.0, 45.0, 45.0), 5.0),
        [
            (3, 3),
            (3, 4),
            (3, 5),
            (4, 3),
            (4, 4),
            (4, 5),
            (5, 3),
            (5, 4),
            (5, 5)
        ]
        .iter()
        .copied()
        // the disc of radius 5 about (45, 45) touches x = 40, 50 and y = 40, 50 only at
        // four points, the corners (40, 40) etc. are 7.07 away
        .filter(|&(c, r)| c == 4 || r == 4)
        .collect::<Vec<_>>()
    );
    // An arc whose ends lie on grid lines.
    let arc = Primitive::Arc(Arc {
        centre: Vec2::new(50.0, 50.0),
        radius: 15.0,
        start_angle: 0.0,
        sweep: std::f32::consts::FRAC_PI_2,
    });
    assert_eq!(
        collect(&grid, arc, 0.0),
        [(4, 6), (5, 6), (6, 4), (6, 5), (6, 6)]
    );
}

#[test]
fn clipping_to_the_grid() {
    let grid = CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 10, 10);
    // From far west to far east through row 5: the ten cells of the row.
    let row: Vec<_> = (0..10).map(|c| (c, 5)).collect();
    assert_eq!(collect(&grid, seg(-1e4, 55.0, 1e4, 55.0), 0.0), row);
    // Entirely outside, or touching the grid's edge from outside.
    assert!(collect(&grid, seg(-50.0, -5.0, 150.0, -5.0), 0.0).is_empty());
    assert_eq!(collect(&grid, seg(-50.0, 0.0, 5.0, 0.0), 0.0), [(0, 0)]);
    assert_eq!(collect(&grid, seg(-50.0, -5.0, 150.0, -5.0), 5.0).len(), 10);
    // A circle around the whole grid: nothing; one through its corner cells.
    let circle = |r: f32| {
        Primitive::Arc(Arc {
            centre: Vec2::new(50.0, 50.0),
            radius: r,
            start_angle: 0.3,
            sweep: 7.0,
        })
    };
    assert!(collect(&grid, circle(80.0), 0.0).is_empty());
    let cells = collect(&grid, circle(70.0), 0.0);
    assert!(!cells.is_empty() && cells.len() < 100);
    assert!(cells.contains(&(0, 0)) && cells.contains(&(9, 9)));
}

#[test]
fn early_stop() {
    let grid = CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 50, 50);
    let s = Segment::new(Vec2::new(1.0, 1.0), Vec2::new(480.0, 333.0));
    let all = segment_cells(&grid, &s, 7.0, |_, _| true).unwrap();
    let mut calls = 0;
    let n = segment_cells(&grid, &s, 7.0, |_, _| {
        calls += 1;
        calls < 5
    })
    .unwrap();
    assert!(all > 5);
    assert_eq!((n, calls), (5, 5));
    let a = Arc {
        centre: Vec2::new(250.0, 250.0),
        radius: 150.0,
        start_angle: 1.0,
        sweep: -4.0,
    };
    let mut calls = 0;
    let n = arc_cells(&grid, &a, 3.0, |_, _| {
        calls += 1;
        calls < 7
    })
    .unwrap();
    assert_eq!((n, calls), (7, 7));
}

#[test]
fn invalid_and_extreme_inputs_never_panic() {
    let specials = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        -1.0,
        1e-30,
        1e17,
        -1e17,
        1e30,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        1.0,
        123.4,
    ];
    let base_grid = CellGrid::new(Vec2::new(-100.0, -50.0), 10.0, 30, 20);
    let mut calls = 0u64;
    let mut ok = 0u64;
    for (i, &a) in specials.iter().enumerate() {
        for &b in &specials {
            // Grid fields.
            for g in [
                CellGrid::new(Vec2::new(a, b), 10.0, 30, 20),
                CellGrid::new(Vec2::new(0.0, 0.0), a, 30, 20),
                CellGrid::new(Vec2::new(a, 0.0), b, 1, 1),
                CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 0, 20),
                CellGrid::new(Vec2::new(0.0, 0.0), 10.0, u32::MAX, 2),
            ] {
                let s = Segment::new(Vec2::new(0.0, 0.0), Vec2::new(50.0, 30.0));
                let r = segment_cells(&g, &s, 1.0, |c, r| {
                    calls += 1;
                    c < g.cols && r < g.rows
                });
                ok += r.is_ok() as u64;
                if !(g.cell.is_finite() && g.cell > 0.0 && g.origin.is_finite()) || g.cols == 0 {
                    assert_eq!(r, Err(GridError::InvalidGrid));
                }
            }
            // Primitive fields and widen.
            let prims = [
                seg(a, b, 10.0, 10.0),
                seg(0.0, 0.0, a, b),
                seg(a, 5.0, -a, 5.0),
                Primitive::Arc(Arc {
                    centre: Vec2::new(a, b),
                    radius: 30.0,
                    start_angle: 0.0,
                    sweep: 1.0,
                }),
                Primitive::Arc(Arc {
                    centre: Vec2::new(0.0, 0.0),
                    radius: a,
                    start_angle: b,
                    sweep: 1.0,
                }),
                Primitive::Arc(Arc {
                    centre: Vec2::new(0.0, 0.0),
                    radius: 40.0,
                    start_angle: a,
                    sweep: b,
                }),
            ];
            for prim in prims {
                for widen in [0.0, 2.5, specials[(i + 3) % specials.len()]] {
                    let r = primitive_cells(&base_grid, &prim, widen, |c, r| {
                        calls += 1;
                        assert!(c < base_grid.cols && r < base_grid.rows);
                        true
                    });
                    if let Ok(n) = r {
                        ok += 1;
                        assert!(n <= 600);
                    }
                    if !widen.is_finite() || widen < 0.0 {
                        assert_eq!(r, Err(GridError::InvalidWiden));
                    }
                }
            }
        }
    }
    assert!(ok > 1000 && calls > 0, "{ok} {calls}");

    // NaN anywhere in the primitive is an error, never an empty Ok.
    let g = base_grid;
    assert_eq!(
        segment_cells(
            &g,
            &Segment::new(Vec2::new(f32::NAN, 0.0), Vec2::new(1.0, 1.0)),
            0.0,
            |_, _| true
        ),
        Err(GridError::NonFinite)
    );
    let arc = |centre: Vec2, radius: f32, start_angle: f32, sweep: f32| Arc {
        centre,
        radius,
        start_angle,
        sweep,
    };
    for a in [
        arc(Vec2::new(0.0, f32::NAN), 1.0, 0.0, 1.0),
        arc(Vec2::new(0.0, 0.0), f32::INFINITY, 0.0, 1.0),
        arc(Vec2::new(0.0, 0.0), 1.0, f32::NAN, 1.0),
        arc(Vec2::new(0.0, 0.0), 1.0, 0.0, f32::NEG_INFINITY),
    ] {
        assert_eq!(
            arc_cells(&g, &a, 0.0, |_, _| true),
            Err(GridError::NonFinite)
        );
    }
    assert_eq!(
        arc_cells(
            &g,
            &arc(Vec2::new(0.0, 0.0), -1.0, 0.0, 1.0),
            0.0,
            |_, _| true
        ),
        Err(GridError::NegativeRadius)
    );
    assert_eq!(
        segment_cells(
            &g,
            &Segment::new(Vec2::new(f32::MAX, 0.0), Vec2::new(1.0, 1.0)),
            0.0,
            |_, _| true
        ),
        Err(GridError::OutOfRange)
    );

    // Huge but accepted coordinates: conservative (the slack grows with them), still every
    // touched cell, never more than the grid.
    let s = Segment::new(Vec2::new(-1e17, 5.0), Vec2::new(1e17, 5.0));
    let mut cells = HashSet::new();
    let n = segment_cells(&g, &s, 0.0, |c, r| {
        cells.insert((c, r));
        true
    })
    .unwrap();
    assert!(n <= 600 && cells.len() as u64 == n);
    assert!((0..30).all(|c| cells.contains(&(c, 5))));
    // A start angle of 1e30 rad: the angle is meaningless at f32 precision, so the whole circle.
    let a = arc(Vec2::new(50.0, 50.0), 40.0, 1e30, 0.5);
    let mut cells = HashSet::new();
    arc_cells(&g, &a, 0.0, |c, r| {
        cells.insert((c, r));
        true
    })
    .unwrap();
    // East, west, north and south points of the circle (centre (15, 10) cells, radius 4).
    for cell in [(19, 10), (10, 10), (15, 14), (15, 5)] {
        assert!(cells.contains(&cell), "{cell:?}");
    }
}
