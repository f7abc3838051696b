//! The collision predicates of `skyroute::geometry::predicates` checked against independent
//! references, never against earlier output of our own code:
//!
//! * **distances** against dense sampling with rigorous bounds: one primitive is sampled (a
//!   point of a segment or of an arc, in f64) and the other side is the trivially correct f64
//!   point–segment closed form (clamped projection) or a single point. The sampled function is
//!   Lipschitz with constant L = the sampled primitive's length (per unit of the parameter), so
//!   the sampled minimum `hi` is an upper bound of the true minimum and `hi − L·gap/2` a lower
//!   bound; a branch-and-bound subdivision of the most promising intervals tightens `lo` to
//!   within a fraction of the f32 tolerance. The exact distance must lie in [lo − eps, hi + eps].
//! * **booleans** (`conflicts_with_circle`, `conflicts_with_polygon`) must agree whenever those
//!   bounds are clear of the threshold by eps (otherwise the case is counted as ambiguous);
//!   containment in a polygon is decided by an exact winding number.
//! * `segments_intersect` and `point_in_polygon` against exact integer arithmetic: every f32
//!   input here is a multiple of 2⁻⁴⁰ below 2¹³, so orientations are evaluated exactly in i128.
//!
//! eps is the f32 rounding allowance: ~1e-6 of the coordinates' magnitude, plus for arcs
//! 1.5e-5·r, which covers `ANGLE_TOLERANCE` (an angle up to 1e-5 rad before an arc's start
//! counts as on the arc, which can only make a distance smaller: the safe side) and the f32
//! evaluation of arc points.
//!
//! Every input is rounded to f32 first, and the references use exactly those values.

use std::cmp::Ordering;
use std::collections::{BTreeMap, BinaryHeap};
use std::f64::consts::{PI, TAU};
use std::time::Instant;

use skyroute::geometry::predicates::{
    arc_segment_distance, conflicts_with_circle, conflicts_with_polygon, point_arc_distance,
    point_in_polygon, point_segment_distance, segment_segment_distance, segments_intersect,
};
use skyroute::geometry::{Arc, Primitive, Segment, Vec2};

use host_tests::{cases, Rng};

// --------------------------------------------------------------------------------------------
// Inputs: f32 values on the 2⁻⁴⁰ grid (so that the exact integer references apply).

type P = (f64, f64);

/// Rounds to f32; magnitudes below 2⁻¹⁷ (not all on the 2⁻⁴⁰ grid) become 0.
fn snap(x: f64) -> f32 {
    let y = x as f32;
    if y.abs() < 1e-5 {
        0.0
    } else {
        assert!(
            y.abs() < 8192.0,
            "coordinate {y} out of the exact-arithmetic range"
        );
        y
    }
}

fn vec2(p: P) -> Vec2 {
    Vec2::new(snap(p.0), snap(p.1))
}

fn p64(v: Vec2) -> P {
    (v.x as f64, v.y as f64)
}

fn add(a: P, b: P) -> P {
    (a.0 + b.0, a.1 + b.1)
}

fn scale(a: P, k: f64) -> P {
    (a.0 * k, a.1 * k)
}

fn dist(a: P, b: P) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// The trivially correct f64 distance from `p` to the segment `a`–`b` (clamped projection):
/// the shared reference.
use host_tests::reference::dist_point_segment as pt_seg;

fn seg_ends(s: &Segment) -> (P, P) {
    (p64(s.start), p64(s.end))
}

/// A primitive as an f64 curve over t ∈ [0, 1], from the very f32 fields the crate sees.
#[derive(Clone, Copy, Debug)]
enum Curve {
    Seg(P, P),
    Arc { c: P, r: f64, a0: f64, sweep: f64 },
}

impl Curve {
    fn of(p: &Primitive) -> Curve {
        match p {
            Primitive::Line(s) => Curve::Seg(p64(s.start), p64(s.end)),
            Primitive::Arc(a) => Curve::Arc {
                c: p64(a.centre),
                r: a.radius as f64,
                a0: a.start_angle as f64,
                sweep: a.sweep as f64,
            },
        }
    }
    fn at(&self, t: f64) -> P {
        match *self {
            Curve::Seg(a, b) => (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)),
            Curve::Arc { c, r, a0, sweep } => {
                let (s, co) = (a0 + t * sweep).sin_cos();
                (c.0 + r * co, c.1 + r * s)
            }
        }
    }
    /// Length: the Lipschitz constant of t ↦ at(t).
    fn length(&self) -> f64 {
        match *self {
            Curve::Seg(a, b) => dist(a, b),
            Curve::Arc { r, sweep, .. } => r * sweep.abs(),
        }
    }
    fn radius(&self) -> f64 {
        match *self {
            Curve::Seg(..) => 0.0,
            Curve::Arc { r, .. } => r,
        }
    }
    /// Largest coordinate magnitude involved.
    fn coord_scale(&self) -> f64 {
        match *self {
            Curve::Seg(a, b) => a.0.abs().max(a.1.abs()).max(b.0.abs()).max(b.1.abs()),
            Curve::Arc { c, r, .. } => c.0.abs().max(c.1.abs()) + r,
        }
    }
}

// --------------------------------------------------------------------------------------------
// Rigorous bounds on a minimum by sampling (branch and bound over a Lipschitz function).

struct Interval {
    lb: f64,
    centre: f64,
    half: f64,
    value: f64,
}

impl PartialEq for Interval {
    fn eq(&self, o: &Self) -> bool {
        self.lb.total_cmp(&o.lb) == Ordering::Equal
    }
}
impl Eq for Interval {}
impl PartialOrd for Interval {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Interval {
    // BinaryHeap is a max-heap: the lowest lower bound must come out first.
    fn cmp(&self, o: &Self) -> Ordering {
        o.lb.total_cmp(&self.lb)
    }
}

/// Bounds (lo, hi) of min over t ∈ [0, 1] of `f`, where |f(t) − f(u)| ≤ lip·|t − u|: `hi` is
/// the smallest sampled value, `lo` the smallest of f(centre) − lip·half over the intervals
/// that tile [0, 1]. The interval with the lowest bound is split in three (its centre value
/// reused) until hi − lo ≤ `target` or the evaluation budget is spent.
fn min_bounds(f: &dyn Fn(f64) -> f64, lip: f64, target: f64) -> (f64, f64) {
    const START: usize = 48;
    const BUDGET: usize = 4000;
    let mut hi = f(0.0).min(f(1.0));
    let mut heap = BinaryHeap::with_capacity(BUDGET);
    let half = 0.5 / START as f64;
    for i in 0..START {
        let centre = (2 * i + 1) as f64 * half;
        let value = f(centre);
        hi = hi.min(value);
        heap.push(Interval {
            lb: value - lip * half,
            centre,
            half,
            value,
        });
    }
    let mut evals = START + 2;
    loop {
        let top = heap.pop().expect("intervals tile [0, 1]");
        if hi - top.lb <= target || evals >= BUDGET {
            return (top.lb.min(hi), hi);
        }
        let h = top.half / 3.0;
        for (centre, value) in [
            (top.centre - 2.0 * h, None),
            (top.centre, Some(top.value)),
            (top.centre + 2.0 * h, None),
        ] {
            let value = value.unwrap_or_else(|| {
                evals += 1;
                f(centre)
            });
            hi = hi.min(value);
            heap.push(Interval {
                lb: value - lip * h,
                centre,
                half: h,
                value,
            });
        }
    }
}

/// Bounds on the distance from curve `c` to whatever `f_point` measures (1-Lipschitz in the
/// point), refined to a quarter of `eps`.
fn curve_min(c: &Curve, eps: f64, f_point: &dyn Fn(P) -> f64) -> (f64, f64) {
    min_bounds(&|t| f_point(c.at(t)), c.length(), 0.25 * eps)
}

/// The f32 rounding allowance for a distance involving `curves` (see the top of the file).
fn eps_for(curves: &[&Curve], extra_scale: f64) -> f64 {
    let scale = curves
        .iter()
        .fold(extra_scale, |m, c| m.max(c.coord_scale() + c.length()));
    let r = curves.iter().fold(0.0f64, |m, c| m.max(c.radius()));
    1e-6 * scale + 1.5e-5 * r + 1e-6
}

// --------------------------------------------------------------------------------------------
// Exact integer arithmetic for the booleans.

/// `x`·2⁴⁰ as an integer (exact for the inputs made by `snap`).
fn fx(x: f32) -> i128 {
    let v = x as f64 * (1u64 << 40) as f64;
    assert!(v.fract() == 0.0, "{x} is not on the 2^-40 grid");
    v as i128
}

type I = (i128, i128);

fn iv(v: Vec2) -> I {
    (fx(v.x), fx(v.y))
}

/// Exact orientation of `c` relative to `a → b` (sign of the cross product).
fn orient(a: I, b: I, c: I) -> i128 {
    ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).signum()
}

/// Whether `p`, known to be collinear with `a`–`b`, lies within its bounding box.
fn within(a: I, b: I, p: I) -> bool {
    p.0 >= a.0.min(b.0) && p.0 <= a.0.max(b.0) && p.1 >= a.1.min(b.1) && p.1 <= a.1.max(b.1)
}

/// Exact: whether two segments share a point.
fn intersect_exact(s: &Segment, t: &Segment) -> bool {
    let (a, b, c, d) = (iv(s.start), iv(s.end), iv(t.start), iv(t.end));
    let (o1, o2, o3, o4) = (
        orient(c, d, a),
        orient(c, d, b),
        orient(a, b, c),
        orient(a, b, d),
    );
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within(c, d, a))
        || (o2 == 0 && within(c, d, b))
        || (o3 == 0 && within(a, b, c))
        || (o4 == 0 && within(a, b, d))
}

/// Exact winding number of `polygon` around `p` (Sunday's algorithm); `None` on the boundary.
fn winding_exact(p: Vec2, polygon: &[Vec2]) -> Option<i32> {
    let q = iv(p);
    let n = polygon.len();
    let mut wn = 0;
    for i in 0..n {
        let (a, b) = (iv(polygon[i]), iv(polygon[(i + 1) % n]));
        let o = orient(a, b, q);
        if o == 0 && within(a, b, q) {
            return None;
        }
        if a.1 <= q.1 {
            if b.1 > q.1 && o > 0 {
                wn += 1;
            }
        } else if b.1 <= q.1 && o < 0 {
            wn -= 1;
        }
    }
    Some(wn)
}

/// Exact: whether a polygon is simple (≥ 3 vertices, no zero-length edge, non-adjacent edges
/// disjoint).
fn simple_exact(polygon: &[Vec2]) -> bool {
    let n = polygon.len();
    let edge = |i: usize| Segment::new(polygon[i], polygon[(i + 1) % n]);
    n >= 3
        && (0..n).all(|i| polygon[i] != polygon[(i + 1) % n])
        && (0..n).all(|i| {
            (i + 1..n).all(|j| {
                j == i + 1 || (i == 0 && j == n - 1) || !intersect_exact(&edge(i), &edge(j))
            })
        })
}

// --------------------------------------------------------------------------------------------
// Case generators.

/// A point within ±`lim` of the origin, shifted by ±2000..3000 m now and then (large
/// coordinates).
fn base_point(rng: &mut Rng, lim: f64) -> P {
    let mut p = (rng.range(-lim, lim), rng.range(-lim, lim));
    if rng.below(8) == 0 {
        p = add(
            p,
            (
                rng.sign() * rng.range(2000.0, 3000.0),
                rng.sign() * rng.range(2000.0, 3000.0),
            ),
        );
    }
    p
}

/// A random offset: none, tiny, or up to `spread`.
fn offset(rng: &mut Rng, spread: f64) -> P {
    match rng.below(8) {
        0 => (0.0, 0.0),
        1 => scale(rng.unit_vector(), rng.log_range(1e-5, 1e-2)),
        _ => scale(rng.unit_vector(), rng.log_range(1e-4, spread)),
    }
}

/// A segment through (or near) `q`, of length 0.01..500 m (1 in 50 of zero length).
fn segment_near(rng: &mut Rng, q: P) -> Segment {
    let len = if rng.below(50) == 0 {
        0.0
    } else {
        rng.log_range(0.01, 500.0)
    };
    let dir = rng.unit_vector();
    let u = rng.range(-0.2, 1.2); // where q lies along it (outside now and then)
    let a = add(q, scale(dir, -u * len));
    let b = add(a, scale(dir, len));
    Segment::new(vec2(a), vec2(b))
}

fn random_segment(rng: &mut Rng) -> Segment {
    let q = base_point(rng, 800.0);
    segment_near(rng, q)
}

/// A random arc: radius 1..500 m, any start angle (also beyond ±π), sweeps of either sign from
/// tiny to nearly a full turn.
fn random_arc(rng: &mut Rng) -> Arc {
    let c = base_point(rng, 800.0);
    let r = rng.log_range(1.0, 500.0);
    let start = if rng.below(6) == 0 {
        rng.range(-3.0 * TAU, 3.0 * TAU)
    } else {
        rng.range(-PI, PI)
    };
    let sweep = rng.sign()
        * match rng.below(6) {
            0 => rng.log_range(1e-6, 1e-2),
            1 => TAU - rng.log_range(1e-6, 1e-2),
            _ => rng.range(0.0, TAU),
        };
    Arc {
        centre: vec2(c),
        radius: r as f32,
        start_angle: start as f32,
        sweep: sweep as f32,
    }
}

/// A point near the curve: on it, near it, near its full circle (outside the sweep), or near
/// the centre of an arc.
fn point_near(rng: &mut Rng, c: &Curve, spread: f64) -> P {
    let t = match rng.below(5) {
        0 => rng.range(-0.5, 1.5),
        1 => [0.0, 1.0][rng.below(2) as usize],
        _ => rng.unit(),
    };
    let base = match (c, rng.below(10)) {
        (Curve::Arc { c: centre, .. }, 0) => *centre,
        (
            Curve::Arc {
                c: centre,
                r,
                a0,
                sweep,
            },
            1,
        ) => {
            // The part of the circle outside the sweep.
            let a = a0 + sweep + rng.range(0.0, TAU - sweep.abs()) * sweep.signum();
            add(*centre, scale((a.cos(), a.sin()), *r))
        }
        _ => c.at(t),
    };
    add(base, offset(rng, spread))
}

/// A star-shaped (hence simple) polygon of 3..10 vertices about `q` with size `size`.
fn polygon_near(rng: &mut Rng, q: P, size: f64) -> Vec<Vec2> {
    loop {
        let n = 3 + rng.below(8) as usize;
        let mut angles: Vec<f64> = (0..n).map(|_| rng.range(0.0, TAU)).collect();
        angles.sort_by(f64::total_cmp);
        let rot = rng.range(-PI, PI);
        let poly: Vec<Vec2> = angles
            .iter()
            .map(|&a| {
                let r = size * rng.range(0.2, 1.0);
                vec2(add(q, scale(((a + rot).cos(), (a + rot).sin()), r)))
            })
            .collect();
        if simple_exact(&poly) {
            return poly;
        }
    }
}

fn clearance(rng: &mut Rng) -> f32 {
    if rng.below(4) == 0 {
        0.0
    } else {
        rng.log_range(1e-3, 50.0) as f32
    }
}

// --------------------------------------------------------------------------------------------
// Bookkeeping.

/// Statistics of one predicate's run, and its failures.
struct Report {
    name: &'static str,
    cases: usize,
    decisive: usize,
    ambiguous: usize,
    /// Worst (ours − hi) / eps and (lo − ours) / eps: how far outside the sampled bounds.
    worst_above: f64,
    worst_below: f64,
    /// Widest final bounds relative to eps (how sharp the reference was).
    worst_width: f64,
    failures: BTreeMap<String, Vec<String>>,
    t0: Instant,
}

impl Report {
    fn new(name: &'static str) -> Self {
        Report {
            name,
            cases: 0,
            decisive: 0,
            ambiguous: 0,
            worst_above: f64::NEG_INFINITY,
            worst_below: f64::NEG_INFINITY,
            worst_width: 0.0,
            failures: BTreeMap::new(),
            t0: Instant::now(),
        }
    }
    fn fail(&mut self, kind: &str, detail: String) {
        self.failures
            .entry(kind.to_string())
            .or_default()
            .push(detail);
    }
    /// Checks a distance against sampled bounds.
    fn distance(&mut self, ours: f32, (lo, hi): (f64, f64), eps: f64, what: impl Fn() -> String) {
        self.cases += 1;
        let ours = ours as f64;
        self.worst_above = self.worst_above.max((ours - hi) / eps);
        self.worst_below = self.worst_below.max((lo - ours) / eps);
        self.worst_width = self.worst_width.max((hi - lo) / eps);
        if !(ours >= lo - eps && ours <= hi + eps) {
            self.fail(
                "distance outside the sampled bounds",
                format!(
                    "ours {ours}, bounds [{lo}, {hi}], eps {eps:.3e}: {}",
                    what()
                ),
            );
        }
    }
    /// Checks a boolean `ours` = (min distance ≤ threshold) where the minimum lies in
    /// [lo, hi]; `beyond` is the expected answer when the minimum is clearly above.
    fn boolean(
        &mut self,
        ours: bool,
        (lo, hi): (f64, f64),
        threshold: f64,
        eps: f64,
        beyond: impl FnOnce() -> Option<bool>,
        what: impl Fn() -> String,
    ) {
        self.cases += 1;
        let expected = if hi <= threshold - eps {
            Some(true)
        } else if lo > threshold + eps {
            beyond()
        } else {
            None
        };
        match expected {
            None => self.ambiguous += 1,
            Some(e) => {
                self.decisive += 1;
                if e != ours {
                    self.fail(
                        if e {
                            "missed conflict"
                        } else {
                            "false conflict"
                        },
                        format!(
                            "ours {ours}, distance in [{lo}, {hi}], threshold {threshold}, \
                             eps {eps:.3e}: {}",
                            what()
                        ),
                    );
                }
            }
        }
    }
    fn failed(&self) -> bool {
        !self.failures.is_empty()
    }
    fn finish(&self, min_cases: usize) {
        if self.decisive + self.ambiguous > 0 {
            println!(
                "{}: {} cases ({} decisive, {} ambiguous: within eps of the threshold) \
                 in {:.2?}",
                self.name,
                self.cases,
                self.decisive,
                self.ambiguous,
                self.t0.elapsed()
            );
        } else {
            println!(
                "{}: {} cases in {:.2?}; worst (ours - hi)/eps {:.3}, (lo - ours)/eps {:.3}, \
                 widest reference bounds {:.3} eps",
                self.name,
                self.cases,
                self.t0.elapsed(),
                self.worst_above,
                self.worst_below,
                self.worst_width
            );
        }
        if !self.failures.is_empty() {
            let total: usize = self.failures.values().map(Vec::len).sum();
            let mut msg = format!("{}: {total} of {} cases fail:\n", self.name, self.cases);
            for (kind, v) in &self.failures {
                msg += &format!("  {} x {kind}, e.g.\n", v.len());
                for d in v.iter().take(4) {
                    msg += &format!("    {d}\n");
                }
            }
            panic!("{msg}");
        }
        assert!(
            self.cases >= min_cases,
            "{}: only {} cases",
            self.name,
            self.cases
        );
    }
}

/// The random cases per predicate: 10 000 in the fast tier, 100 000 in the full tier.
fn n_cases() -> usize {
    cases(10_000, 100_000)
}

// --------------------------------------------------------------------------------------------
// Distances.

fn check_point_segment(n: usize, seed: u64, f: &dyn Fn(Vec2, &Segment) -> f32) -> Report {
    let mut rng = Rng(seed);
    let mut rep = Report::new("point_segment_distance");
    for _ in 0..n {
        let s = random_segment(&mut rng);
        let c = Curve::of(&Primitive::Line(s));
        let p = vec2(point_near(&mut rng, &c, 200.0));
        let eps = eps_for(&[&c], p64(p).0.abs().max(p64(p).1.abs()));
        let b = curve_min(&c, eps, &|x| dist(x, p64(p)));
        rep.distance(f(p, &s), b, eps, || format!("{p:?} {s:?}"));
    }
    rep
}

#[test]
fn point_segment_distance_matches_sampling() {
    check_point_segment(n_cases(), 0xD157_0001, &point_segment_distance).finish(n_cases());
}

#[test]
fn segment_segment_distance_and_intersection_match_references() {
    let mut rng = Rng(0xD157_0002);
    let mut rep = Report::new("segment_segment_distance");
    let mut inter = Report::new("segments_intersect (exact i128)");
    let mut crossing = 0;
    for _ in 0..n_cases() {
        let s = random_segment(&mut rng);
        let cs = Curve::of(&Primitive::Line(s));
        let q = point_near(&mut rng, &cs, 50.0);
        let t = segment_near(&mut rng, q);
        let ct = Curve::of(&Primitive::Line(t));
        let eps = eps_for(&[&cs, &ct], 0.0);
        let (t0, t1) = seg_ends(&t);
        let b = curve_min(&cs, eps, &|x| pt_seg(x, t0, t1));
        let what = || format!("{s:?} {t:?}");
        rep.distance(segment_segment_distance(&s, &t), b, eps, what);
        // Exact intersection, and its consistency with the sampled distance.
        let exact = intersect_exact(&s, &t);
        crossing += exact as usize;
        inter.cases += 1;
        inter.decisive += 1;
        if segments_intersect(&s, &t) != exact || segments_intersect(&t, &s) != exact {
            inter.fail(
                "differs from exact arithmetic",
                format!("exact {exact}: {}", what()),
            );
        }
        if exact && b.0 > eps {
            inter.fail(
                "reference inconsistent",
                format!("exact true but lo {}: {}", b.0, what()),
            );
        }
    }
    println!("  ({crossing} of the pairs intersect)");
    rep.finish(n_cases());
    inter.finish(n_cases());
}

fn check_point_arc(n: usize, seed: u64, f: &dyn Fn(Vec2, &Arc) -> f32) -> Report {
    let mut rng = Rng(seed);
    let mut rep = Report::new("point_arc_distance");
    for _ in 0..n {
        let a = random_arc(&mut rng);
        let c = Curve::of(&Primitive::Arc(a));
        let p = vec2(point_near(&mut rng, &c, 200.0));
        let eps = eps_for(&[&c], p64(p).0.abs().max(p64(p).1.abs()));
        let b = curve_min(&c, eps, &|x| dist(x, p64(p)));
        rep.distance(f(p, &a), b, eps, || format!("{p:?} {a:?}"));
    }
    rep
}

#[test]
fn point_arc_distance_matches_sampling() {
    check_point_arc(n_cases(), 0xD157_0003, &point_arc_distance).finish(n_cases());
}

fn check_arc_segment(n: usize, seed: u64, f: &dyn Fn(&Arc, &Segment) -> f32) -> Report {
    let mut rng = Rng(seed);
    let mut rep = Report::new("arc_segment_distance");
    for _ in 0..n {
        let a = random_arc(&mut rng);
        let c = Curve::of(&Primitive::Arc(a));
        let q = point_near(&mut rng, &c, 50.0);
        let s = segment_near(&mut rng, q);
        let cs = Curve::of(&Primitive::Line(s));
        let eps = eps_for(&[&c, &cs], 0.0);
        let (s0, s1) = seg_ends(&s);
        let b = curve_min(&c, eps, &|x| pt_seg(x, s0, s1));
        rep.distance(f(&a, &s), b, eps, || format!("{a:?} {s:?}"));
    }
    rep
}

#[test]
fn arc_segment_distance_matches_sampling() {
    check_arc_segment(n_cases(), 0xD157_0004, &arc_segment_distance).finish(n_cases());
}

// --------------------------------------------------------------------------------------------
// Conflicts.

fn random_primitive(rng: &mut Rng, arc: bool) -> Primitive {
    if arc {
        Primitive::Arc(random_arc(rng))
    } else {
        Primitive::Line(random_segment(rng))
    }
}

#[test]
fn conflicts_with_circle_matches_sampling() {
    for (arc, seed) in [(false, 0xD157_0005u64), (true, 0xD157_0006)] {
        let mut rng = Rng(seed);
        let mut rep = Report::new(if arc {
            "conflicts_with_circle (arcs)"
        } else {
            "conflicts_with_circle (lines)"
        });
        for _ in 0..n_cases() {
            let prim = random_primitive(&mut rng, arc);
            let c = Curve::of(&prim);
            let radius = if rng.below(10) == 0 {
                0.0
            } else {
                rng.log_range(0.01, 100.0) as f32
            };
            let cl = clearance(&mut rng);
            // Place the disc so that its edge comes near the primitive.
            let q = point_near(&mut rng, &c, 50.0);
            let dir = rng.unit_vector();
            let centre = vec2(add(q, scale(dir, radius as f64 + cl as f64)));
            let eps = eps_for(&[&c], p64(centre).0.abs().max(p64(centre).1.abs()));
            let b = curve_min(&c, eps, &|x| dist(x, p64(centre)));
            let ours = conflicts_with_circle(&prim, centre, radius, cl);
            rep.boolean(
                ours,
                b,
                radius as f64 + cl as f64,
                eps,
                || Some(false),
                || format!("{prim:?} centre {centre:?} radius {radius} clearance {cl}"),
            );
        }
        rep.finish(n_cases());
    }
}

type PolygonCheck = dyn Fn(&Primitive, &[Vec2], f32) -> bool;

fn check_polygon(n: usize, seed: u64, arc: bool, f: &PolygonCheck) -> Report {
    let mut rng = Rng(seed);
    let mut rep = Report::new(if arc {
        "conflicts_with_polygon (arcs)"
    } else {
        "conflicts_with_polygon (lines)"
    });
    let mut inside = 0;
    for _ in 0..n {
        let prim = random_primitive(&mut rng, arc);
        let c = Curve::of(&prim);
        let q = point_near(&mut rng, &c, 50.0);
        let size = rng.log_range(0.5, 300.0);
        let poly = polygon_near(&mut rng, q, size);
        let cl = clearance(&mut rng);
        let edges: Vec<(P, P)> = (0..poly.len())
            .map(|i| (p64(poly[i]), p64(poly[(i + 1) % poly.len()])))
            .collect();
        let scale_p = edges
            .iter()
            .fold(0.0f64, |m, (a, _)| m.max(a.0.abs()).max(a.1.abs()));
        let eps = eps_for(&[&c], scale_p);
        let b = curve_min(&c, eps, &|x| {
            edges
                .iter()
                .map(|&(e0, e1)| pt_seg(x, e0, e1))
                .fold(f64::INFINITY, f64::min)
        });
        let ours = f(&prim, &poly, cl);
        // Clear of the boundary by more than the clearance: the primitive is wholly inside or
        // wholly outside, as its first point (exact winding number; that point is the f32 one
        // the crate uses, which is within eps of the curve).
        let beyond = || {
            let w = winding_exact(prim.start(), &poly).expect("not on the boundary");
            inside += (w != 0) as usize;
            Some(w != 0)
        };
        rep.boolean(ours, b, cl as f64, eps, beyond, || {
            format!("{prim:?} polygon {poly:?} clearance {cl}")
        });
    }
    println!("  ({inside} decisive cases with the primitive inside the polygon)");
    rep
}

#[test]
fn conflicts_with_polygon_matches_sampling() {
    for (arc, seed) in [(false, 0xD157_0007u64), (true, 0xD157_0008)] {
        check_polygon(n_cases(), seed, arc, &|p, poly, cl| {
            conflicts_with_polygon(p, poly, cl)
        })
        .finish(n_cases());
    }
}

#[test]
fn point_in_polygon_matches_exact_winding() {
    let mut rng = Rng(0xD157_0009);
    let mut rep = Report::new("point_in_polygon (exact winding number)");
    let mut inside = 0;
    for _ in 0..n_cases() {
        let q = base_point(&mut rng, 800.0);
        let size = rng.log_range(0.5, 300.0);
        let poly = polygon_near(&mut rng, q, size);
        // Near a vertex, near an edge, or anywhere around.
        let n = poly.len();
        let i = rng.below(n as u64) as usize;
        let (a, b) = (p64(poly[i]), p64(poly[(i + 1) % n]));
        let p = match rng.below(3) {
            0 => add(a, offset(&mut rng, 1.0)),
            1 => add(
                add(a, scale((b.0 - a.0, b.1 - a.1), rng.unit())),
                offset(&mut rng, 1.0),
            ),
            _ => add(q, scale(rng.unit_vector(), size * rng.range(0.0, 1.2))),
        };
        let p = vec2(p);
        let scale_p = poly
            .iter()
            .fold(0.0f64, |m, v| m.max(v.x.abs() as f64).max(v.y.abs() as f64));
        let eps = 1e-6 * scale_p + 1e-6;
        // Points closer to the boundary than f32 rounding "may go either way" (documented).
        let boundary = (0..n)
            .map(|k| pt_seg(p64(p), p64(poly[k]), p64(poly[(k + 1) % n])))
            .fold(f64::INFINITY, f64::min);
        rep.cases += 1;
        match winding_exact(p, &poly) {
            Some(w) if boundary > eps => {
                rep.decisive += 1;
                inside += (w != 0) as usize;
                if point_in_polygon(p, &poly[..]) != (w != 0) {
                    rep.fail(
                        "differs from the exact winding number",
                        format!("winding {w}, boundary {boundary:.3e}: {p:?} {poly:?}"),
                    );
                }
            }
            _ => rep.ambiguous += 1,
        }
    }
    println!("  ({inside} decisive points inside)");
    rep.finish(n_cases());
}

// --------------------------------------------------------------------------------------------
// Constructed tangencies and touching cases, with clearance 0 and > 0.

fn seg(a: (f32, f32), b: (f32, f32)) -> Segment {
    Segment::new(Vec2::new(a.0, a.1), Vec2::new(b.0, b.1))
}

/// Exactly representable cases whose answers are known without rounding.
#[test]
fn exact_touching_configurations() {
    // Collinear overlapping, collinear disjoint, touching at end points, T-junction, crossing
    // at a vertex, along an integer direction (3, 4) so that every point is exact.
    let k = |i: f32| (3.0 * i, 4.0 * i);
    let cases: [(Segment, Segment, bool, f32); 9] = [
        (
            seg((0.0, 0.0), (10.0, 0.0)),
            seg((5.0, 0.0), (15.0, 0.0)),
            true,
            0.0,
        ),
        (
            seg((0.0, 0.0), (10.0, 0.0)),
            seg((11.0, 0.0), (20.0, 0.0)),
            false,
            1.0,
        ),
        (
            seg((0.0, 0.0), (10.0, 0.0)),
            seg((10.0, 0.0), (10.0, 10.0)),
            true,
            0.0,
        ),
        (
            seg((0.0, 0.0), (10.0, 0.0)),
            seg((4.0, 0.0), (4.0, 7.0)),
            true,
            0.0,
        ),
        (
            seg((0.0, 0.0), (10.0, 0.0)),
            seg((4.0, 0.5), (4.0, 7.0)),
            false,
            0.5,
        ),
        (seg(k(0.0), k(10.0)), seg(k(3.0), k(25.0)), true, 0.0),
        (seg(k(0.0), k(10.0)), seg(k(11.0), k(25.0)), false, 5.0),
        (
            seg(k(-7.0), k(10.0)),
            seg(k(10.0), (30.0 + 4.0, 40.0 - 3.0)),
            true,
            0.0,
        ),
        (
            seg((1000.5, -2000.25), (1000.5, -2000.25)),
            seg((1000.5, -2000.25), (1010.0, -2000.25)),
            true,
            0.0,
        ),
    ];
    for (s, t, meets, d) in cases {
        assert_eq!(segments_intersect(&s, &t), meets, "{s:?} {t:?}");
        assert_eq!(segments_intersect(&t, &s), meets, "{t:?} {s:?}");
        assert_eq!(intersect_exact(&s, &t), meets, "reference: {s:?} {t:?}");
        assert_eq!(segment_segment_distance(&s, &t), d, "{s:?} {t:?}");
    }

    // A segment tangent to an arc at an interior point: the circle x² + y² = 100² and the line
    // y = 100 (tangent at 90°), arcs sweeping over 90° either way and one that stops short.
    let arc = |start: f32, sweep: f32| Arc {
        centre: Vec2::new(0.0, 0.0),
        radius: 100.0,
        start_angle: start,
        sweep,
    };
    let tangent = seg((-50.0, 100.0), (50.0, 100.0));
    for a in [arc(0.0, 3.0), arc(3.0, -3.0), arc(-1.0, 4.0)] {
        assert_eq!(arc_segment_distance(&a, &tangent), 0.0, "{a:?}");
        for cl in [0.0, 0.5] {
            let mut square = vec![Vec2::new(-50.0, 100.0), Vec2::new(50.0, 100.0)];
            square.extend([Vec2::new(50.0, 200.0), Vec2::new(-50.0, 200.0)]);
            assert!(
                conflicts_with_polygon(&Primitive::Arc(a), &square[..], cl),
                "{a:?} {cl}"
            );
        }
    }
    // Stopping 0.5 rad short of the tangent point: the distance is to the arc's end.
    let short = arc(0.0, 1.0);
    let d = arc_segment_distance(&short, &tangent);
    let end = (100.0 * 1.0f64.cos(), 100.0 * 1.0f64.sin());
    let want = pt_seg(end, (-50.0, 100.0), (50.0, 100.0));
    assert!((d as f64 - want).abs() < 1e-4, "{d} vs {want}");

    // An arc whose first point (angle 0: exact) lies on a segment, or is a segment's end point.
    let a = arc(0.0, 1.0);
    for s in [
        seg((100.0, -50.0), (100.0, 50.0)),
        seg((100.0, 0.0), (150.0, 20.0)),
        seg((130.0, -20.0), (100.0, 0.0)),
    ] {
        assert_eq!(arc_segment_distance(&a, &s), 0.0, "{s:?}");
        assert!(conflicts_with_polygon(
            &Primitive::Arc(a),
            &[s.start, s.end, Vec2::new(200.0, -100.0)][..],
            0.0
        ));
    }

    // Polygon edge exactly at the clearance distance (boundary included) and just beyond it.
    let line = Primitive::Line(seg((0.0, 0.0), (100.0, 0.0)));
    let above = |y: f32| {
        vec![
            Vec2::new(-10.0, y),
            Vec2::new(110.0, y),
            Vec2::new(50.0, y + 30.0),
        ]
    };
    assert!(conflicts_with_polygon(&line, &above(5.0)[..], 5.0));
    assert!(!conflicts_with_polygon(
        &line,
        &above(5.0)[..],
        f32::from_bits(5.0f32.to_bits() - 1)
    ));
    assert!(!conflicts_with_polygon(
        &line,
        &above(f32::from_bits(5.0f32.to_bits() + 1))[..],
        5.0
    ));
    // An edge along the line itself.
    assert!(conflicts_with_polygon(&line, &above(0.0)[..], 0.0));
    // The same for an arc: the circle of radius 100 about the origin, an edge along y = 105.
    let top = Primitive::Arc(arc(1.0, 1.0)); // passes through 90°
    let band = [
        Vec2::new(-20.0, 105.0),
        Vec2::new(20.0, 105.0),
        Vec2::new(0.0, 150.0),
    ];
    assert!(conflicts_with_polygon(&top, &band[..], 5.0));
    assert!(!conflicts_with_polygon(&top, &band[..], 4.99));
    // Discs: touching (distance == radius + clearance) counts, for lines and arcs.
    assert!(conflicts_with_circle(&line, Vec2::new(50.0, 7.0), 2.0, 5.0));
    assert!(!conflicts_with_circle(
        &line,
        Vec2::new(50.0, 7.0),
        2.0,
        4.99
    ));
    assert!(conflicts_with_circle(&line, Vec2::new(50.0, 7.0), 7.0, 0.0));
    assert!(conflicts_with_circle(&top, Vec2::new(0.0, 110.0), 4.0, 6.0));
    assert!(!conflicts_with_circle(
        &top,
        Vec2::new(0.0, 110.0),
        4.0,
        5.99
    ));
    // Wholly inside a polygon, far from its edges: a conflict at any clearance.
    let big = [
        Vec2::new(-500.0, -500.0),
        Vec2::new(500.0, -500.0),
        Vec2::new(500.0, 500.0),
        Vec2::new(-500.0, 500.0),
    ];
    assert!(conflicts_with_polygon(&line, &big[..], 0.0));
    assert!(conflicts_with_polygon(&top, &big[..], 0.0));
}

/// Tangencies in general position (rotated, off-origin, f32-rounded): the distance must be 0
/// up to eps, a conflict at any clearance ≥ eps, and the sampled references must agree.
#[test]
fn rounded_tangencies() {
    let mut rng = Rng(0xD157_000A);
    let mut rep = Report::new("tangencies in general position");
    let n = cases(2_000, 20_000);
    for i in 0..n {
        let a = random_arc(&mut rng);
        let c = Curve::of(&Primitive::Arc(a));
        let (centre, r, a0, sweep) = match c {
            Curve::Arc { c, r, a0, sweep } => (c, r, a0, sweep),
            Curve::Seg(..) => unreachable!(),
        };
        // The touching point: interior to the arc, or one of its ends.
        let t = match i % 3 {
            0 => rng.range(0.05, 0.95),
            1 => 0.0,
            _ => 1.0,
        };
        let ang = a0 + t * sweep;
        let touch = add(centre, scale((ang.cos(), ang.sin()), r));
        let tangent_dir = (-ang.sin(), ang.cos());
        let s = match i % 2 {
            // Tangent line through the point, extending both ways.
            0 => {
                let (u, v) = (rng.log_range(0.1, 200.0), rng.log_range(0.1, 200.0));
                Segment::new(
                    vec2(add(touch, scale(tangent_dir, -u))),
                    vec2(add(touch, scale(tangent_dir, v))),
                )
            }
            // A segment ending at the point, coming from outside the circle.
            _ => {
                let out = scale((ang.cos(), ang.sin()), 1.0);
                let dir = add(out, scale(tangent_dir, rng.range(-1.0, 1.0)));
                Segment::new(
                    vec2(touch),
                    vec2(add(touch, scale(dir, rng.log_range(0.1, 200.0)))),
                )
            }
        };
        let cs = Curve::of(&Primitive::Line(s));
        let eps = eps_for(&[&c, &cs], 0.0);
        let (s0, s1) = seg_ends(&s);
        let b = curve_min(&c, eps, &|x| pt_seg(x, s0, s1));
        let what = || format!("{a:?} {s:?}");
        rep.distance(arc_segment_distance(&a, &s), b, eps, what);
        if b.1 > 2.0 * eps {
            rep.fail(
                "construction",
                format!("sampled distance {} is not ~0: {}", b.1, what()),
            );
        }
        // Any clearance of at least eps: a conflict with a polygon having that edge.
        let cl = [eps as f32 * 2.0, rng.log_range(0.01, 10.0) as f32][i % 2];
        let tri = [
            s.start,
            s.end,
            vec2(add(s1, scale((ang.cos(), ang.sin()), 50.0))),
        ];
        if simple_exact(&tri) && !conflicts_with_polygon(&Primitive::Arc(a), &tri[..], cl) {
            rep.fail("missed conflict", format!("clearance {cl}: {}", what()));
        }
    }
    rep.finish(n);
}

// --------------------------------------------------------------------------------------------
// The harness can fail: plausible wrong implementations are caught.

#[test]
fn harness_rejects_wrong_predicates() {
    let n = 5_000;
    // Distance to the infinite line instead of the segment.
    let line = |p: Vec2, s: &Segment| {
        let d = s.end - s.start;
        if d.norm() > 0.0 {
            (d.cross(p - s.start) / d.norm()).abs()
        } else {
            p.distance(s.start)
        }
    };
    assert!(
        check_point_segment(n, 1, &line).failed(),
        "line distance not caught"
    );
    // Distance to the full circle, ignoring the sweep.
    let circle = |p: Vec2, a: &Arc| ((p - a.centre).norm() - a.radius).abs();
    assert!(
        check_point_arc(n, 2, &circle).failed(),
        "full circle not caught"
    );
    // End points only, no interior critical pair and no intersection test.
    let ends_only = |a: &Arc, s: &Segment| {
        point_arc_distance(s.start, a)
            .min(point_arc_distance(s.end, a))
            .min(point_segment_distance(a.start(), s))
            .min(point_segment_distance(a.end(), s))
    };
    assert!(
        check_arc_segment(n, 3, &ends_only).failed(),
        "end points only not caught"
    );
    // Off by a hundredth of the tolerance's worth of metres: 1 mm too far everywhere.
    let far = |a: &Arc, s: &Segment| arc_segment_distance(a, s) + 1e-2;
    assert!(check_arc_segment(n, 4, &far).failed(), "+1 cm not caught");
    // Boundary distance only, no containment test.
    let no_inside = |p: &Primitive, poly: &[Vec2], cl: f32| {
        (0..poly.len()).any(|i| {
            let e = Segment::new(poly[i], poly[(i + 1) % poly.len()]);
            skyroute::geometry::predicates::primitive_segment_distance(p, &e) <= cl
        })
    };
    assert!(
        check_polygon(n, 5, true, &no_inside).failed(),
        "missing containment not caught"
    );
    // Clearance compared strictly (boundary excluded) is only caught by the exact cases; a
    // clearance ignored altogether is caught here.
    let no_clearance =
        |p: &Primitive, poly: &[Vec2], _cl: f32| conflicts_with_polygon(p, poly, 0.0);
    assert!(
        check_polygon(n, 6, false, &no_clearance).failed(),
        "ignored clearance not caught"
    );
}

/// Segments meeting exactly — collinear overlaps and gaps, T-junctions, shared end points — and
/// the same moved by one grid step, all exactly on the f32 grid at coordinates up to ±3000 m:
/// `segments_intersect` must equal exact integer arithmetic every time, and
/// `segment_segment_distance` must be 0 when they meet (and within f32 rounding of the f64
/// distance when they do not).
#[test]
fn touching_segments_on_the_grid() {
    let mut rng = Rng(0xD157_000B);
    let mut rep = Report::new("segments_intersect, exact touching on the grid");
    let mut meets = 0;
    for i in 0..cases(5_000, 50_000) {
        // A grid step g ≥ 2⁻¹¹: every multiple of it below 2²⁴·g ≥ 8192 m is an f32.
        let g = 2f64.powi(-11 + rng.below(12) as i32);
        let on_grid = |x: f64| (x / g).round() * g;
        let a = (
            on_grid(rng.range(-2000.0, 2000.0)),
            on_grid(rng.range(-2000.0, 2000.0)),
        );
        let lim = (200.0 / g).min(1000.0);
        let (dp, dq) = (rng.range(-lim, lim).round(), rng.range(-lim, lim).round());
        if dp == 0.0 && dq == 0.0 {
            continue;
        }
        let m = |k: f64| (a.0 + k * dp * g, a.1 + k * dq * g);
        let pick = |rng: &mut Rng| rng.range(-5.0, 5.0).round();
        let (m1, m2, m3, m4) = (
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
        );
        let perp = scale((-dq * g, dp * g), rng.range(1.0, 5.0).round());
        let nudge = match rng.below(3) {
            0 => (0.0, 0.0),
            1 => (g, 0.0),
            _ => (0.0, -g),
        };
        let s = Segment::new(vec2(m(m1)), vec2(m(m2)));
        let t = match i % 3 {
            0 => Segment::new(vec2(add(m(m3), nudge)), vec2(m(m4))), // collinear (or nearly)
            1 => Segment::new(vec2(add(m(m3), nudge)), vec2(add(m(m3), perp))), // T-junction
            _ => Segment::new(vec2(add(m(m2), nudge)), vec2(add(m(m2), perp))), // shared end
        };
        let exact = intersect_exact(&s, &t);
        meets += exact as usize;
        rep.cases += 1;
        rep.decisive += 1;
        let what = || format!("exact {exact}: {s:?} {t:?}");
        if segments_intersect(&s, &t) != exact || segments_intersect(&t, &s) != exact {
            rep.fail("segments_intersect differs from exact arithmetic", what());
        }
        // Meeting: exactly 0. Apart: the f64 distance (for disjoint segments the least of the
        // four end-point-to-segment distances) to within f32 rounding, which at these
        // coordinates can be all of it.
        let d = segment_segment_distance(&s, &t) as f64;
        let ((s0, s1), (t0, t1)) = (seg_ends(&s), seg_ends(&t));
        let want = if exact {
            0.0
        } else {
            pt_seg(s0, t0, t1)
                .min(pt_seg(s1, t0, t1))
                .min(pt_seg(t0, s0, s1))
                .min(pt_seg(t1, s0, s1))
        };
        let eps = 1e-6 * 3000.0 + 1e-6;
        if (exact && d != 0.0) || (d - want).abs() > eps {
            rep.fail(
                "segment_segment_distance",
                format!("{d} vs {want}: {}", what()),
            );
        }
    }
    println!("  ({meets} of them meet)");
    rep.finish(cases(4_000, 40_000));
}
