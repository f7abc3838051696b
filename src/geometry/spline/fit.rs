//! The fit: coarse polyline in, lines and corner pieces out (see [`super`] for the method).
//!
//! ## The vertex list
//! The fit builds the list of vertices the smoothed path turns at, in one sweep with a stack:
//! start, lead-in corners, the waypoints that are kept, lead-out corners, goal. A waypoint is
//! pushed after the corner below it on the stack has been checked against it; a corner whose
//! legs do not fit ([`super::choose_legs`]) is popped (dropped: its neighbours are joined
//! directly) and the one below re-checked. A corner's legs depend only on its two neighbours
//! and on whether they are corners, so a corner below the top never needs re-checking unless
//! the top is popped. Each waypoint is pushed and popped at most once. The lead-in corners are
//! searched for against the vertex after them; when that vertex is popped they are searched
//! again. The lead-out corners are searched for against the last kept vertex; when no
//! waypoint is left, lead-out and lead-in are searched for against each other in turn (at
//! most [`LEAD_ROUNDS`] rounds) until the whole chain is feasible.
//!
//! The list is then checked once more corner by corner (the same computation, so the same
//! answer), every segment that is not a segment of the coarse polyline is offered to `clear`,
//! and every corner piece's hull triangle `A, P, B` too. Only then is `out` written.

use heapless::Vec as HVec;

use super::super::{trig, Pose, Vec2};
use super::table::{
    choose_legs, corner_bound, table_is_valid, CornerBound, Legs, RATIOS, RATIO_ONE,
    TABLE_MAX_ANGLE,
};
use super::{unit, Piece};

/// Growth factor of the lead-in scan: the candidates are `x0·1.25^k`.
pub const SCAN_FACTOR: f32 = 1.25;
/// Most candidates of the lead-in scan (`1.25⁶⁴ ≈ 1.6·10⁶`: from the smallest useful lead-in
/// to far beyond any useful one).
pub const SCAN_STEPS: u32 = 64;
/// Bisection steps after the scan (the bracket shrinks to `2⁻²⁰` of its width).
pub const BISECT_STEPS: u32 = 20;
/// Corner evaluations of one lead search: one single-corner search (one evaluation per
/// candidate) and two two-corner searches (two per candidate), each at most
/// `SCAN_STEPS + BISECT_STEPS` candidates.
pub const SEARCH_EVALS: u64 = 5 * (SCAN_STEPS as u64 + BISECT_STEPS as u64);
/// Most rounds of alternating lead-out and lead-in searches when no waypoint lies between
/// them ([`fit`]'s `lead_in_and_out`).
pub const LEAD_ROUNDS: u64 = 4;
/// Waypoints closer than this to the previous kept vertex are skipped (a zero-length segment
/// has no direction), relative to the coordinates' magnitude (plus 1 mm).
const DUPLICATE_REL: f32 = 1e-6;
/// The shortest leg, relative to the corner's coordinates' magnitude (`2⁻¹²`): shorter legs are
/// lengthened (both by the same factor, which lowers the curvature), so a leg is at least
/// 2000 f32 rounding units and its direction is kept to 5·10⁻⁴ rad.
const MIN_LEG_REL: f32 = 1.0 / 4096.0;
/// A line between two pieces shorter than this fraction of its segment is not emitted: the
/// next piece starts where the previous ended (a leg lengthened by at most 2·10⁻⁴ of itself).
const SNAP_REL: f32 = 1e-4;

/// What [`fit`] smooths.
#[derive(Clone, Copy, Debug)]
pub struct FitInput<'a> {
    /// The start pose: the path begins here along its heading.
    pub start: Pose,
    /// The coarse polyline's inner vertices, in order (clear of hard zones between
    /// consecutive points, and from the start to the first and the last to the goal).
    pub waypoints: &'a [Vec2],
    /// The goal position.
    pub goal: Vec2,
    /// The heading at the goal (radians counter-clockwise from east), if one is required.
    pub goal_heading: Option<f32>,
    /// The largest curvature the vehicle flies, 1/metres.
    pub kappa_max: f32,
}

/// A vertex of the smoothed path's vertex list, as named in results and errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Vertex {
    /// The start position.
    Start,
    /// Lead-in corner `k` (0 first flown).
    LeadIn(u8),
    /// Waypoint `i` of [`FitInput::waypoints`].
    Waypoint(usize),
    /// Lead-out corner `k` (0 first flown).
    LeadOut(u8),
    /// The goal position.
    Goal,
}

impl Vertex {
    /// Whether the path turns here (a corner piece): lead-in, waypoint and lead-out vertices.
    pub fn is_corner(self) -> bool {
        matches!(
            self,
            Vertex::LeadIn(_) | Vertex::Waypoint(_) | Vertex::LeadOut(_)
        )
    }
}

/// Why [`fit`] failed. `out` is unchanged in every case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FitError {
    /// A position, heading or waypoint is NaN or infinite.
    NonFinite,
    /// A coordinate exceeds [`crate::geometry::MAX_COORDINATE_M`].
    OutOfRange,
    /// `kappa_max` is not finite and positive.
    BadCurvature,
    /// The corner table has a non-finite or negative node, or a non-zero straight row.
    BadTable,
    /// The vertex list or the pieces exceed the capacity `R`.
    RouteTooLong {
        /// The capacity `R`.
        capacity: usize,
    },
    /// `clear` refused the hull triangle of this corner's piece.
    CornerBlocked {
        /// The corner.
        corner: Vertex,
    },
    /// `clear` refused a segment that is not on the coarse polyline: a lead-in or lead-out
    /// segment, or one joining the neighbours of dropped waypoints.
    SegmentBlocked {
        /// First end.
        from: Vertex,
        /// Last end.
        to: Vertex,
    },
    /// No lead-in from the start pose reaches the first vertex that must be kept (the goal or
    /// the lead-out) within the curvature bound.
    LeadInInfeasible,
    /// No lead-out reaches the goal heading within the curvature bound.
    LeadOutInfeasible,
}

/// What [`fit`] produced.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FitSummary {
    /// Pieces written to `out`.
    pub pieces: usize,
    /// Corner pieces among them.
    pub corners: usize,
    /// Waypoints dropped by the fallback (duplicates skipped are not counted).
    pub dropped: usize,
    /// Lead-in corners (1 or 2).
    pub lead_in: usize,
    /// Lead-out corners (0 without a goal heading, else 1 or 2).
    pub lead_out: usize,
    /// Sum of the pieces' [`Piece::length`] estimates, metres.
    pub length: f32,
    /// Corner evaluations done (each at most `TABLE_RATIOS + 1` table look-ups); at most
    /// [`fit_work_bound`].
    pub work: u64,
}

/// The most corner evaluations [`fit`] does for `waypoints` waypoints (`n`):
/// `(3n + 6 + 2·LEAD_ROUNDS)·SEARCH_EVALS + 5n + 12 + 4·LEAD_ROUNDS`. At most `2n + 3` lead-in searches (the first, one after
/// each waypoint the lead-in cannot reach, one after each waypoint popped) and `n + 2`
/// lead-out searches (one per popped waypoint, plus the last); when no waypoint is left
/// between lead-in and lead-out, at most `LEAD_ROUNDS` rounds of two searches and a check of
/// at most 4 corners; `2n + 1` checks in the sweep
/// (each pushes or pops a waypoint), `n + 1` at the goal and 2 per corner of the final list
/// (at most `n + 4` corners) when checking and writing it. `clear` is called at most
/// [`fit_clear_bound`] times.
pub fn fit_work_bound(waypoints: usize) -> u64 {
    let n = waypoints as u64;
    (3 * n + 6 + 2 * LEAD_ROUNDS)
        .saturating_mul(SEARCH_EVALS)
        .saturating_add(5 * n + 12 + 4 * LEAD_ROUNDS)
}

/// The most times [`fit`] calls `clear` for `waypoints` waypoints (`n`): `2(n + 4) + 1`. The
/// final list holds at most `n + 4` corners (`n` waypoints, 2 lead-in and 2 lead-out) between
/// the start and the goal, so at most `n + 5` segments are offered, and one hull triangle per
/// corner, `n + 4`.
pub fn fit_clear_bound(waypoints: usize) -> u64 {
    (waypoints as u64)
        .saturating_add(4)
        .saturating_mul(2)
        .saturating_add(1)
}

#[derive(Clone, Copy, Debug)]
struct Node {
    p: Vec2,
    tag: Vertex,
}

/// A corner's directions and legs.
#[derive(Clone, Copy)]
struct Corner {
    u1: Vec2,
    u2: Vec2,
    legs: Legs,
}

struct Ctx<'t, T: CornerBound> {
    table: &'t T,
    kappa: f32,
    work: u64,
}

impl<T: CornerBound> Ctx<'_, T> {
    /// The corner at `c` between `prev` and `next`: each neighbour that is a corner leaves it
    /// half of the segment between them, one that is not the whole segment.
    fn eval(&mut self, prev: Node, c: Node, next: Node) -> Option<Corner> {
        self.work += 1;
        let (d1, d2) = (c.p - prev.p, next.p - c.p);
        let (u1, u2) = (unit(d1)?, unit(d2)?);
        let theta = libm::atan2f(libm::fabsf(u1.cross(u2)), u1.dot(u2));
        let share = |v: Node| if v.tag.is_corner() { 0.5 } else { 1.0 };
        let (a1, a2) = (d1.norm() * share(prev), d2.norm() * share(next));
        let mag = magnitude(c.p);
        let legs = floor_legs(choose_legs(self.table, theta, a1, a2, self.kappa)?, mag);
        // The stored control points are rounded to f32 (each coordinate by at most ε·mag), which
        // turns each leg's direction by up to √2·ε·mag/s: the legs are chosen again for the
        // turn angle plus both legs' rounding, so the flown piece's angle is within the one
        // tabulated (this matters for small turns, whose legs are short).
        let delta = 3.0 * f32::EPSILON * mag / legs.s1.min(legs.s2);
        let legs = floor_legs(
            choose_legs(self.table, theta + delta, a1, a2, self.kappa)?,
            mag,
        );
        (legs.s1 <= a1 && legs.s2 <= a2).then_some(Corner { u1, u2, legs })
    }

    /// Whether every inner vertex of `chain` is a feasible corner.
    fn chain_ok(&mut self, chain: &[Node]) -> bool {
        triples(chain).all(|(a, b, c)| self.eval(a, b, c).is_some())
    }
}

/// The consecutive triples of `items` (`slice::windows(3)` without its run-time size check,
/// whose `expect` would otherwise stay in the firmware).
fn triples<T: Copy>(items: &[T]) -> impl Iterator<Item = (T, T, T)> + '_ {
    items
        .iter()
        .zip(items.iter().skip(1))
        .zip(items.iter().skip(2))
        .map(|((&a, &b), &c)| (a, b, c))
}

/// `legs` lengthened by a common factor (a scaled piece has a lower curvature) so that the
/// shorter is at least `MIN_LEG_REL·mag`.
fn floor_legs(legs: Legs, mag: f32) -> Legs {
    let f = (MIN_LEG_REL * mag / legs.s1.min(legs.s2)).max(1.0);
    Legs {
        s1: legs.s1 * f,
        s2: legs.s2 * f,
    }
}

/// The largest coordinate magnitude of `p`, at least 1 m.
fn magnitude(p: Vec2) -> f32 {
    libm::fabsf(p.x).max(libm::fabsf(p.y)).max(1.0)
}

/// `h` turned by `a` radians counter-clockwise.
fn rotate(h: Vec2, a: f32) -> Vec2 {
    let (s, c) = trig::sin_cos(a);
    Vec2::new(h.x * c - h.y * s, h.x * s + h.y * c)
}

/// The smallest `x` with `ok(x)` found by scanning `x0·SCAN_FACTOR^k` up to `upper`, then
/// bisecting between the last failing candidate (or 0) and the first passing one, keeping a
/// passing upper end: the result always passed `ok`.
fn smallest_feasible(x0: f32, upper: f32, mut ok: impl FnMut(f32) -> bool) -> Option<f32> {
    if !(x0 > 0.0 && x0.is_finite()) {
        return None;
    }
    let (mut lo, mut x) = (0.0f32, x0);
    for _ in 0..SCAN_STEPS {
        if !(x <= upper) {
            return None;
        }
        if ok(x) {
            let mut hi = x;
            for _ in 0..BISECT_STEPS {
                let mid = 0.5 * (lo + hi);
                if ok(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Some(hi);
        }
        lo = x;
        x *= SCAN_FACTOR;
    }
    None
}

/// Lead corners in flight order.
#[derive(Clone, Copy)]
struct Lead {
    nodes: [Node; 2],
    n: usize,
}

impl Lead {
    fn nodes(&self) -> &[Node] {
        self.nodes.get(..self.n).unwrap_or(&[])
    }
}

/// The lead corners joining the end `origin` (start or goal), left or entered along the unit
/// direction `h` pointing away from it, to `target`; `reverse` for the goal (the chain is
/// flown towards `origin`). Tries one corner `origin + d·h`, then two corners `origin + q·h`
/// and `origin + q·h + 2q·rotate(h, ψ)` with `ψ` half the turn towards `target` or half the
/// turn the other way round; `d` and `q` by [`smallest_feasible`] (see the module doc).
fn lead<T: CornerBound>(
    ctx: &mut Ctx<'_, T>,
    origin: Node,
    h: Vec2,
    target: Node,
    reverse: bool,
) -> Option<Lead> {
    let tag = |k: u8| {
        if reverse {
            Vertex::LeadOut(k)
        } else {
            Vertex::LeadIn(k)
        }
    };
    // The chain in flight order, from the outward list [origin, o0, (o1), target].
    let order = |o: &[Node]| -> ([Node; 4], usize) {
        let mut c = [origin; 4];
        let n = o.len() + 2;
        for (k, slot) in c.iter_mut().take(n).enumerate() {
            let v = match k {
                0 => origin,
                k if k == n - 1 => target,
                k => o.get(k - 1).copied().unwrap_or(origin),
            };
            *slot = v;
        }
        if reverse {
            if let Some(s) = c.get_mut(..n) {
                s.reverse();
            }
        }
        (c, n)
    };
    let rel = target.p - origin.p;
    let l = rel.norm();
    let turn = if l > 0.0 {
        libm::atan2f(h.cross(rel), h.dot(rel))
    } else {
        core::f32::consts::PI
    };
    let kappa = ctx.kappa;
    let c_max = corner_bound(ctx.table, TABLE_MAX_ANGLE, RATIO_ONE)? / kappa;
    // Beyond `x + √3|y| ≤ 3l` along `h` a single corner turns more than 150°.
    let upper = 3.0 * l + 4.0 * c_max;
    let theta0 = libm::fabsf(turn);
    if theta0 <= TABLE_MAX_ANGLE {
        let x0 = (0..RATIOS.len())
            .filter_map(|j| corner_bound(ctx.table, theta0, j))
            .fold(f32::INFINITY, f32::min)
            / kappa;
        let single = |d: f32| {
            [Node {
                p: origin.p + h * d,
                tag: tag(0),
            }]
        };
        let found = smallest_feasible(x0, upper, |d| {
            let (c, n) = order(&single(d));
            ctx.chain_ok(c.get(..n).unwrap_or(&[]))
        });
        if let Some(d) = found {
            let (c, _) = order(&single(d));
            return Some(Lead {
                nodes: [c[1], c[1]],
                n: 1,
            });
        }
    }
    let sign = if turn < 0.0 { -1.0 } else { 1.0 };
    for psi in [0.5 * turn, -sign * (core::f32::consts::PI - 0.5 * theta0)] {
        if !(libm::fabsf(psi) <= TABLE_MAX_ANGLE) {
            continue;
        }
        let m = rotate(h, psi);
        let double = |q: f32| {
            let a = origin.p + h * q;
            [
                Node { p: a, tag: tag(0) },
                Node {
                    p: a + m * (2.0 * q),
                    tag: tag(0),
                },
            ]
        };
        let x0 = corner_bound(ctx.table, libm::fabsf(psi), RATIO_ONE)? / kappa;
        let found = smallest_feasible(x0, upper, |q| {
            let (c, n) = order(&double(q));
            ctx.chain_ok(c.get(..n).unwrap_or(&[]))
        });
        if let Some(q) = found {
            let (c, _) = order(&double(q));
            let (mut a, mut b) = (c[1], c[2]);
            a.tag = tag(0);
            b.tag = tag(1);
            return Some(Lead {
                nodes: [a, b],
                n: 2,
            });
        }
    }
    None
}

fn push<const R: usize>(path: &mut HVec<Node, R>, v: Node) -> Result<(), FitError> {
    path.push(v)
        .map_err(|_| FitError::RouteTooLong { capacity: R })
}

fn pop_lead_in<const R: usize>(path: &mut HVec<Node, R>) {
    while matches!(
        path.last(),
        Some(Node {
            tag: Vertex::LeadIn(_),
            ..
        })
    ) {
        path.pop();
    }
}

/// Makes the top of `path` a feasible corner before `v` (popping waypoints that are not), or
/// places the lead-in when only the start is left. `Ok(false)`: `v` (a waypoint) cannot be
/// reached from the start and is dropped.
fn settle<T: CornerBound, const R: usize>(
    ctx: &mut Ctx<'_, T>,
    path: &mut HVec<Node, R>,
    v: Node,
    h0: Vec2,
    dropped: &mut usize,
) -> Result<bool, FitError> {
    // Each pass pops at least one vertex or returns; the start is never popped.
    while let Some(&top) = path.last() {
        match top.tag {
            Vertex::Start => {
                return match lead(ctx, top, h0, v, false) {
                    Some(l) => {
                        for &n in l.nodes() {
                            push(path, n)?;
                        }
                        Ok(true)
                    }
                    None if matches!(v.tag, Vertex::Waypoint(_)) => Ok(false),
                    None => Err(FitError::LeadInInfeasible),
                };
            }
            Vertex::LeadIn(_) => pop_lead_in(path),
            Vertex::Waypoint(_) => {
                let prev = path.len().checked_sub(2).and_then(|i| path.get(i).copied());
                if let Some(prev) = prev {
                    if ctx.eval(prev, top, v).is_some() {
                        return Ok(true);
                    }
                }
                path.pop();
                *dropped += 1;
            }
            Vertex::LeadOut(_) | Vertex::Goal => return Ok(true),
        }
    }
    Ok(false)
}

/// Lead-in and lead-out with no waypoint between them: the lead-out is searched against the
/// start (as if it were a corner), the lead-in against the lead-out, then the lead-out against
/// the last lead-in corner and so on, at most [`LEAD_ROUNDS`] rounds, until the whole chain is
/// feasible.
fn lead_in_and_out<T: CornerBound, const R: usize>(
    ctx: &mut Ctx<'_, T>,
    path: &mut HVec<Node, R>,
    start: Node,
    g: Node,
    hg: Vec2,
    h0: Vec2,
) -> Result<(), FitError> {
    let mut target = Node {
        p: start.p,
        tag: Vertex::LeadIn(0),
    };
    for _ in 0..LEAD_ROUNDS {
        let lo = lead(ctx, g, -hg, target, true).ok_or(FitError::LeadOutInfeasible)?;
        let first = *lo.nodes().first().ok_or(FitError::LeadOutInfeasible)?;
        let li = lead(ctx, start, h0, first, false).ok_or(FitError::LeadInInfeasible)?;
        let mut chain = [start; 6];
        let mut n = 1;
        for (slot, &v) in chain
            .iter_mut()
            .skip(1)
            .zip(li.nodes().iter().chain(lo.nodes()).chain([&g]))
        {
            *slot = v;
            n += 1;
        }
        if ctx.chain_ok(chain.get(..n).unwrap_or(&[])) {
            for &v in chain.get(1..n).unwrap_or(&[]) {
                push(path, v)?;
            }
            return Ok(());
        }
        target = *li.nodes().last().ok_or(FitError::LeadInInfeasible)?;
    }
    Err(FitError::LeadOutInfeasible)
}

/// Appends the lead-out corners and the goal (goal heading `hg`, unit direction of flight).
fn finish_with_heading<T: CornerBound, const R: usize>(
    ctx: &mut Ctx<'_, T>,
    path: &mut HVec<Node, R>,
    g: Node,
    hg: Vec2,
    h0: Vec2,
    dropped: &mut usize,
) -> Result<(), FitError> {
    while let Some(&top) = path.last() {
        match top.tag {
            Vertex::LeadIn(_) => pop_lead_in(path),
            Vertex::Start => return lead_in_and_out(ctx, path, top, g, hg, h0),
            Vertex::Waypoint(_) => {
                let prev = path.len().checked_sub(2).and_then(|i| path.get(i).copied());
                let found = lead(ctx, g, -hg, top, true);
                let ok = match (found, prev) {
                    (Some(lo), Some(prev)) => match lo.nodes().first() {
                        Some(&first) => ctx.eval(prev, top, first).map(|_| lo),
                        None => None,
                    },
                    _ => None,
                };
                match ok {
                    Some(lo) => {
                        for &n in lo.nodes() {
                            push(path, n)?;
                        }
                        return push(path, g);
                    }
                    None => {
                        path.pop();
                        *dropped += 1;
                    }
                }
            }
            Vertex::LeadOut(_) | Vertex::Goal => return Err(FitError::LeadOutInfeasible),
        }
    }
    Err(FitError::LeadOutInfeasible)
}

/// Checks the input and builds the vertex list.
fn build_path<T: CornerBound, const R: usize>(
    input: &FitInput,
    ctx: &mut Ctx<'_, T>,
    path: &mut HVec<Node, R>,
) -> Result<usize, FitError> {
    let h0 = input.start.direction();
    let mut dropped = 0;
    push(
        path,
        Node {
            p: input.start.position,
            tag: Vertex::Start,
        },
    )?;
    let near = |a: Vec2, b: Vec2| a.distance(b) <= DUPLICATE_REL * magnitude(a) + 1e-3;
    for (i, &w) in input.waypoints.iter().enumerate() {
        let v = Node {
            p: w,
            tag: Vertex::Waypoint(i),
        };
        if path.last().is_some_and(|t| near(t.p, w)) {
            continue;
        }
        if settle(ctx, path, v, h0, &mut dropped)? {
            push(path, v)?;
        } else {
            dropped += 1;
        }
    }
    // A last waypoint on the goal is the goal.
    let g = Node {
        p: input.goal,
        tag: Vertex::Goal,
    };
    if path
        .last()
        .is_some_and(|t| matches!(t.tag, Vertex::Waypoint(_)) && near(t.p, g.p))
    {
        path.pop();
    }
    match input.goal_heading {
        None => {
            if !settle(ctx, path, g, h0, &mut dropped)? {
                return Err(FitError::LeadInInfeasible);
            }
            push(path, g)?;
        }
        Some(hg) => finish_with_heading(ctx, path, g, Vec2::from_angle(hg), h0, &mut dropped)?,
    }
    Ok(dropped)
}

/// Whether `a → b` is a segment of the coarse polyline (start, waypoints, goal).
fn coarse(a: Vertex, b: Vertex, waypoints: usize) -> bool {
    match (a, b) {
        (Vertex::Start, Vertex::Waypoint(0)) => true,
        (Vertex::Waypoint(i), Vertex::Waypoint(j)) => j == i + 1,
        (Vertex::Waypoint(i), Vertex::Goal) => i + 1 == waypoints,
        (Vertex::Start, Vertex::Goal) => waypoints == 0,
        _ => false,
    }
}

fn infeasible(tag: Vertex) -> FitError {
    match tag {
        Vertex::LeadOut(_) => FitError::LeadOutInfeasible,
        _ => FitError::LeadInInfeasible,
    }
}

/// Calls `sink` with the pieces of the vertex list in order (the cubic's corner named).
fn emit<T: CornerBound>(
    ctx: &mut Ctx<'_, T>,
    path: &[Node],
    sink: &mut impl FnMut(Piece, Option<Vertex>) -> Result<(), FitError>,
) -> Result<(), FitError> {
    let (Some(first), Some(last)) = (path.first(), path.last()) else {
        return Ok(());
    };
    let mut cursor = first.p;
    let mut pending: Option<([Vec2; 4], Vertex)> = None;
    let snap = |a: Vec2, b: Vec2, seg: f32| {
        a.distance(b) <= SNAP_REL * seg + 4.0 * f32::EPSILON * magnitude(a)
    };
    for (prev, c, next) in triples(path) {
        let corner = ctx.eval(prev, c, next).ok_or(infeasible(c.tag))?;
        let mut a = c.p - corner.u1 * corner.legs.s1;
        let b = c.p + corner.u2 * corner.legs.s2;
        if let Some((q, tag)) = pending.take() {
            sink(Piece::Cubic { p: q }, Some(tag))?;
        }
        if snap(cursor, a, prev.p.distance(c.p)) {
            a = cursor;
        } else {
            sink(Piece::Line { a: cursor, b: a }, None)?;
        }
        pending = Some(([a, c.p, c.p, b], c.tag));
        cursor = b;
    }
    let seg = path
        .len()
        .checked_sub(2)
        .and_then(|i| path.get(i))
        .map_or(0.0, |p| p.p.distance(last.p));
    match pending.take() {
        Some((mut q, tag)) if snap(cursor, last.p, seg) => {
            q[3] = last.p;
            sink(Piece::Cubic { p: q }, Some(tag))
        }
        Some((q, tag)) => {
            sink(Piece::Cubic { p: q }, Some(tag))?;
            sink(
                Piece::Line {
                    a: cursor,
                    b: last.p,
                },
                None,
            )
        }
        None => sink(
            Piece::Line {
                a: cursor,
                b: last.p,
            },
            None,
        ),
    }
}

fn check_input(input: &FitInput, table: &impl CornerBound) -> Result<(), FitError> {
    let finite = input.start.is_finite()
        && input.goal.is_finite()
        && input.goal_heading.is_none_or(f32::is_finite)
        && input.waypoints.iter().all(|w| w.is_finite());
    if !finite {
        return Err(FitError::NonFinite);
    }
    let in_range = input.start.position.is_in_range()
        && input.goal.is_in_range()
        && input.waypoints.iter().all(|w| w.is_in_range());
    if !in_range {
        return Err(FitError::OutOfRange);
    }
    if !(input.kappa_max > 0.0 && input.kappa_max.is_finite()) {
        return Err(FitError::BadCurvature);
    }
    if !table_is_valid(table) {
        return Err(FitError::BadTable);
    }
    Ok(())
}

/// Smooths the coarse polyline `start → waypoints → goal` into lines and corner pieces with
/// curvature at most `kappa_max` (by `table`), beginning along the start heading and ending
/// along the goal heading when one is given (else along the last segment), and writes them to
/// `out` (cleared first). `clear(points)` is asked about each segment that is not on the coarse
/// polyline (2 points) and each corner piece's hull triangle `A, P, B` (3 points), and must say
/// whether it is clear of hard zones. The vertex list uses a stack buffer of `R` vertices
/// (16 bytes each on a 32-bit target). On any error `out` is unchanged. Never panics.
pub fn fit<const R: usize>(
    input: &FitInput,
    table: &impl CornerBound,
    clear: &mut impl FnMut(&[Vec2]) -> bool,
    out: &mut HVec<Piece, R>,
) -> Result<FitSummary, FitError> {
    check_input(input, table)?;
    let mut ctx = Ctx {
        table,
        kappa: input.kappa_max,
        work: 0,
    };
    let mut path: HVec<Node, R> = HVec::new();
    let dropped = build_path(input, &mut ctx, &mut path)?;
    let n = input.waypoints.len();
    for (a, b) in path.iter().zip(path.iter().skip(1)) {
        if !coarse(a.tag, b.tag, n) && !clear(&[a.p, b.p]) {
            return Err(FitError::SegmentBlocked {
                from: a.tag,
                to: b.tag,
            });
        }
    }
    let (mut pieces, mut corners, mut length) = (0usize, 0usize, 0.0f32);
    emit(&mut ctx, &path, &mut |piece, tag| {
        pieces += 1;
        length += piece.length();
        if let (Piece::Cubic { p }, Some(corner)) = (piece, tag) {
            corners += 1;
            if !clear(&[p[0], p[1], p[3]]) {
                return Err(FitError::CornerBlocked { corner });
            }
        }
        Ok(())
    })?;
    if pieces > R {
        return Err(FitError::RouteTooLong { capacity: R });
    }
    out.clear();
    emit(&mut ctx, &path, &mut |piece, _| {
        out.push(piece)
            .map_err(|_| FitError::RouteTooLong { capacity: R })
    })?;
    let count = |f: fn(Vertex) -> bool| path.iter().filter(|v| f(v.tag)).count();
    Ok(FitSummary {
        pieces,
        corners,
        dropped,
        lead_in: count(|t| matches!(t, Vertex::LeadIn(_))),
        lead_out: count(|t| matches!(t, Vertex::LeadOut(_))),
        length,
        work: ctx.work,
    })
}
