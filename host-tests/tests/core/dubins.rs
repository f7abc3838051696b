//! Dubins paths checked against independent references, never against earlier output of our
//! own code:
//!
//! * **OMPL** (`ompl::base::DubinsStateSpace`, f64, forward distance), through the CSV written by
//!   `python3 scripts/ompl_dubins_reference.py` (≥ 100 000 pose pairs incl. degenerate families);
//! * a **brute force in f64** written here from the classical normalised closed forms of the six
//!   words (Shkel & Lumelsky 2001, as in Walker's `dubins.c`), both `acos` branches of RLR/LRL,
//!   every candidate accepted only if a numerical (RK4) integration of the unicycle with turn
//!   radius r lands on the goal pose; the shortest accepted candidate is the reference.
//!
//! **What "agree" means.** A reference length is exact for the given inputs (every case is made
//! of f32-representable numbers, so both sides see the same poses). Our planner works in f32
//! and has documented tolerances: a turn angle within `ANGLE_TOLERANCE` = 1e-5 rad below 2π
//! counts as 0, CSC circles within ±1e-5·(2r)² of touching in l² count as touching (a straight
//! of length 0), end circles within 1e-6·r count as coincident, and centres up to 4r·(1 + 1e-6)
//! apart still admit CCC words. The Dubins distance is discontinuous in the goal pose, so
//! within those tolerances of a discontinuity our path can be a whole loop (or a CCC detour)
//! *shorter* than the exact optimum. Hence, for the shortest path:
//! * |ours − reference| ≤ `length_tol` (f32 rounding): agreement;
//! * ours longer than that: **failure**, always;
//! * ours shorter than that: a **shortcut**, accepted only if proved legitimate: our word with
//!   our piece lengths, flown in f64 by the brute force's integrator (independent of our
//!   `end()`), lands on the goal within `end_tol` (≈ 5e-5·r, the sum of the tolerances above).
//!   Shortcuts are counted per family; the non-degenerate families must have (almost) none.
//!
//! For single words (`with_word`) the same, plus one documented allowance (`judge_word`): in
//! the geometries where a word is ill-conditioned in f32 (LSL/RSR with end circles < 0.01·r
//! apart, LSR/RSL within 0.01·r of touching, RLR/LRL within 0.01·r of 4r apart), a longer answer
//! is accepted if it lands on the goal (within `end_tol`) and is the shortest path of that word
//! to where it lands. Such answers are counted and reported; `shortest()`
//! gets no such allowance (it never needs it: the same paths are reachable through a
//! well-conditioned word).
//!
//! Excluded families: none. OMPL's own degenerate answers (it returns the straight-line distance
//! whenever the positions are within 1e-6·r and the headings within 1e-6 rad, whatever the
//! direction of the goal) are reported as rows where OMPL is shorter than the exact brute force;
//! every row is judged against the brute force, and a disagreement with OMPL must be explained
//! by it.
//!
//! Units: metres, radians counter-clockwise from east.

use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::time::Instant;

use skyroute::geometry::{DubinsPath, DubinsWord, Pose, Primitive};

use host_tests::{cases, Rng};

// --------------------------------------------------------------------------------------------
// Cases: two poses and a radius, all f32 (the brute force evaluates the very same numbers).

#[derive(Clone, Copy, Debug)]
struct Case {
    x0: f32,
    y0: f32,
    h0: f32,
    x1: f32,
    y1: f32,
    h1: f32,
    r: f32,
}

impl Case {
    /// Rounds each value to f32.
    fn new(v: [f64; 7]) -> Self {
        let f = |x: f64| x as f32;
        Case {
            x0: f(v[0]),
            y0: f(v[1]),
            h0: f(v[2]),
            x1: f(v[3]),
            y1: f(v[4]),
            h1: f(v[5]),
            r: f(v[6]),
        }
    }
    fn start(&self) -> Pose {
        Pose::new(self.x0, self.y0, self.h0)
    }
    fn goal(&self) -> Pose {
        Pose::new(self.x1, self.y1, self.h1)
    }
    fn start64(&self) -> [f64; 3] {
        [self.x0 as f64, self.y0 as f64, self.h0 as f64]
    }
    fn goal64(&self) -> [f64; 3] {
        [self.x1 as f64, self.y1 as f64, self.h1 as f64]
    }
    fn r64(&self) -> f64 {
        self.r as f64
    }
    /// Largest coordinate magnitude, for the f32 rounding allowance.
    fn coord_scale(&self) -> f64 {
        [self.x0, self.y0, self.x1, self.y1]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs() as f64))
    }
    fn shortest(&self) -> DubinsPath {
        DubinsPath::shortest(&self.start(), &self.goal(), self.r)
            .unwrap_or_else(|| panic!("no shortest path for {self:?}"))
    }
}

/// Smallest difference of two angles modulo 2π, in [0, π].
fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

// --------------------------------------------------------------------------------------------
// The f64 brute force.

/// Reduces to [0, 2π).
fn mod2pi(a: f64) -> f64 {
    let m = a.rem_euclid(TAU);
    if m >= TAU {
        0.0
    } else {
        m
    }
}

/// The turn of each piece of `word`: +1 left, −1 right, 0 straight (written out from the name
/// rather than taken from `DubinsWord::letters`, so a mislabelled word in the crate shows).
fn turns(word: DubinsWord) -> [i8; 3] {
    match word.name() {
        "LSL" => [1, 0, 1],
        "RSR" => [-1, 0, -1],
        "LSR" => [1, 0, -1],
        "RSL" => [-1, 0, 1],
        "RLR" => [-1, 1, -1],
        "LRL" => [1, -1, 1],
        other => panic!("unknown word {other}"),
    }
}

/// Candidate normalised piece lengths (t, p, q) of `word` (arcs: turn angles; straight:
/// length / r) for the normalised problem: start at the origin with heading `a`, goal at (d, 0)
/// with heading `b`. Classical closed forms; the square roots tolerate a rounding error below
/// zero and both `acos` branches of the CCC words are returned. Also the degenerate candidates
/// the closed forms cannot express (d = 0 makes their `atan2(0, 0)` arbitrary): no move, a
/// single arc, a single straight. The integration decides which candidates are paths at all.
fn closed_forms(word: DubinsWord, d: f64, a: f64, b: f64) -> Vec<[f64; 3]> {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let cab = (a - b).cos();
    let root = |p2: f64| {
        if p2 >= -1e-9 {
            Some(p2.max(0.0).sqrt())
        } else {
            None
        }
    };
    let mut out = Vec::new();
    match word.name() {
        "LSL" => {
            if let Some(p) = root(2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)) {
                let th = (cb - ca).atan2(d + sa - sb);
                out.push([mod2pi(th - a), p, mod2pi(b - th)]);
            }
        }
        "RSR" => {
            if let Some(p) = root(2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)) {
                let th = (ca - cb).atan2(d - sa + sb);
                out.push([mod2pi(a - th), p, mod2pi(th - b)]);
            }
        }
        "LSR" => {
            if let Some(p) = root(-2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)) {
                let th = (-ca - cb).atan2(d + sa + sb) - (-2.0f64).atan2(p);
                out.push([mod2pi(th - a), p, mod2pi(th - b)]);
            }
        }
        "RSL" => {
            if let Some(p) = root(-2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb)) {
                let th = (ca + cb).atan2(d - sa - sb) - 2.0f64.atan2(p);
                out.push([mod2pi(a - th), p, mod2pi(b - th)]);
            }
        }
        "RLR" => {
            let c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0;
            if c.abs() <= 1.0 + 1e-9 {
                let psi = c.clamp(-1.0, 1.0).acos();
                let th = (ca - cb).atan2(d - sa + sb);
                for p in [TAU - psi, psi] {
                    let t = mod2pi(a - th + 0.5 * p);
                    out.push([t, p, mod2pi(a - b - t + p)]);
                }
            }
        }
        "LRL" => {
            let c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0;
            if c.abs() <= 1.0 + 1e-9 {
                let psi = c.clamp(-1.0, 1.0).acos();
                let th = (cb - ca).atan2(d + sa - sb);
                for p in [TAU - psi, psi] {
                    let t = mod2pi(-a + th + 0.5 * p);
                    out.push([t, p, mod2pi(b - a - t + p)]);
                }
            }
        }
        other => panic!("unknown word {other}"),
    }
    let [k1, k2, k3] = turns(word);
    let turn_by = |k: i8| mod2pi(k as f64 * (b - a));
    out.push([0.0, 0.0, 0.0]);
    out.push([turn_by(k1), 0.0, 0.0]);
    out.push([0.0, 0.0, turn_by(k3)]);
    out.push([0.0, if k2 == 0 { d } else { turn_by(k2) }, 0.0]);
    out
}

/// Flies the unicycle `x' = cos θ, y' = sin θ, θ' = κ` (κ = turn / r per piece) from `start`
/// over pieces of the given lengths (metres) by classical RK4, ≤ 0.02 rad of turn per step.
/// (The right-hand side depends on θ only and θ' is constant, so k2 = k3; the unit vectors at
/// θ + h·κ/2 and θ + h·κ are advanced by a rotation instead of calling sin/cos every step.)
fn integrate(start: [f64; 3], turn: [i8; 3], lengths: [f64; 3], r: f64) -> [f64; 3] {
    let [mut x, mut y, mut th] = start;
    for i in 0..3 {
        let len = lengths[i];
        if len <= 0.0 {
            continue;
        }
        if turn[i] == 0 {
            // RK4 is exact for a constant heading.
            x += len * th.cos();
            y += len * th.sin();
            continue;
        }
        let k = turn[i] as f64 / r;
        let n = ((len / r) / 0.02).ceil().max(1.0) as usize;
        let h = len / n as f64;
        let (sh, ch) = (0.5 * h * k).sin_cos(); // rotation by half a step
        let (mut s, mut c) = th.sin_cos();
        for _ in 0..n {
            let (s2, c2) = (s * ch + c * sh, c * ch - s * sh);
            let (s4, c4) = (s2 * ch + c2 * sh, c2 * ch - s2 * sh);
            x += h / 6.0 * (c + 4.0 * c2 + c4);
            y += h / 6.0 * (s + 4.0 * s2 + s4);
            (s, c) = (s4, c4);
        }
        th += len * k;
    }
    [x, y, th]
}

/// Landing tolerance of the brute force's own integration: RK4 with 0.02-rad steps errs by
/// ~(0.02)⁴/2880 ≈ 6e-11 per metre of arc; f64 rounding of the coordinates adds ~1e-15 of
/// their magnitude. (Deliberately not relative to r: a straight is integrated exactly, and a
/// tolerance of 1e-8·r would let a straight "land" on a goal a few µrad off its line.)
fn brute_pos_tol(arc_len: f64, scale: f64) -> f64 {
    1e-9 * arc_len + 1e-12 * scale
}
const BRUTE_HEADING_TOL: f64 = 1e-9;

/// Every closed-form candidate from pose `s` to pose `g` (`[x, y, heading]`), as (length in
/// metres, word, piece lengths in metres), shortest first.
fn candidates(s: [f64; 3], g: [f64; 3], r: f64) -> Vec<(f64, DubinsWord, [f64; 3])> {
    let (dx, dy) = (g[0] - s[0], g[1] - s[1]);
    let th = dy.atan2(dx);
    let (d, a, b) = (dx.hypot(dy) / r, mod2pi(s[2] - th), mod2pi(g[2] - th));
    let mut out = Vec::with_capacity(40);
    for w in DubinsWord::ALL {
        for cand in closed_forms(w, d, a, b) {
            if cand.iter().all(|v| v.is_finite() && *v >= 0.0) {
                let lengths = cand.map(|v| v * r);
                out.push((lengths.iter().sum::<f64>(), w, lengths));
            }
        }
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

/// Whether flying `word` with piece `lengths` from `s` lands on `g`.
fn lands(s: [f64; 3], g: [f64; 3], r: f64, word: DubinsWord, lengths: [f64; 3]) -> bool {
    let t = turns(word);
    let e = integrate(s, t, lengths, r);
    let arc_len: f64 = (0..3).filter(|&i| t[i] != 0).map(|i| lengths[i]).sum();
    let scale = r + lengths.iter().sum::<f64>() + s[0].abs().max(s[1].abs());
    (e[0] - g[0]).hypot(e[1] - g[1]) <= brute_pos_tol(arc_len, scale)
        && angle_diff(e[2], g[2]) <= BRUTE_HEADING_TOL * (1.0 + s[2].abs() + g[2].abs())
}

/// The brute-force length of every word from `s` to `g` (index = `DubinsWord::code`): its
/// shortest candidate whose integrated flight lands on `g`; `None` when none does.
fn brute_all64(s: [f64; 3], g: [f64; 3], r: f64) -> [Option<f64>; 6] {
    let cands = candidates(s, g, r);
    DubinsWord::ALL.map(|w| {
        cands
            .iter()
            .filter(|c| c.1 == w)
            .find(|c| lands(s, g, r, w, c.2))
            .map(|c| c.0)
    })
}

fn brute_all(c: &Case) -> [Option<f64>; 6] {
    brute_all64(c.start64(), c.goal64(), c.r64())
}

/// The brute-force shortest path: the shortest candidate of any word that lands.
fn brute_shortest(c: &Case) -> (f64, DubinsWord) {
    let (s, g, r) = (c.start64(), c.goal64(), c.r64());
    candidates(s, g, r)
        .into_iter()
        .find(|x| lands(s, g, r, x.1, x.2))
        .map(|x| (x.0, x.1))
        // LSL and RSR exist for every pair of poses, so some candidate must land.
        .unwrap_or_else(|| panic!("brute force found no path for {c:?}"))
}

/// The shortest of the per-word lengths, and its word.
fn best_of(all: &[Option<f64>; 6], c: &Case) -> (f64, DubinsWord) {
    let mut best: Option<(f64, DubinsWord)> = None;
    for w in DubinsWord::ALL {
        if let Some(l) = all[w.code() as usize] {
            if best.is_none_or(|(b, _)| l < b) {
                best = Some((l, w));
            }
        }
    }
    best.unwrap_or_else(|| panic!("brute force found no path for {c:?}"))
}

// --------------------------------------------------------------------------------------------
// Tolerances for our f32 results.

/// Allowed |ours − reference| for a length, from f32 rounding alone: angles good to a few ulp
/// of 2π (a few 1e-7 rad, times r), coordinates of magnitude X rounded to 6e-8·X, lengths summed
/// in f32.
fn length_tol(c: &Case, reference: f64) -> f64 {
    4e-6 * c.r64() + 2e-6 * (reference + c.coord_scale()) + 1e-4
}

/// Allowed distance between our path's end and the goal (m), and heading error (rad): f32
/// rounding plus the documented tolerances (≤ 1e-5 rad of arc dropped per turn, circles within
/// ~1e-5·r of touching taken as touching, end circles within 1e-6·r taken as coincident, CCC
/// accepted up to 4r·(1 + 1e-6)), which together stay below 5e-5·r.
fn end_tol(c: &Case, length: f64) -> (f64, f64) {
    (
        5e-5 * c.r64() + 4e-6 * (length + c.coord_scale()) + 1e-4,
        1e-4,
    )
}

/// Checks that `p.end()` (our own flight of the path) is the case's goal pose.
fn check_end(c: &Case, p: &DubinsPath) -> Result<(f64, f64), String> {
    let e = p.end();
    let g = c.goal64();
    let pos_err = (e.position.x as f64 - g[0]).hypot(e.position.y as f64 - g[1]);
    let head_err = angle_diff(e.heading as f64, g[2]);
    let (pt, ht) = end_tol(c, p.length() as f64);
    if pos_err <= pt && head_err <= ht {
        Ok((pos_err, head_err))
    } else {
        Err(format!(
            "{} path {:?} (length {}) ends at {:?}: {pos_err:.3e} m / {head_err:.3e} rad from \
             the goal (allowed {pt:.3e} m / {ht:.1e} rad)",
            p.word.name(),
            p.lengths,
            p.length(),
            e
        ))
    }
}

/// Proves a shortcut legitimate (see the top of the file): our word and piece lengths, flown in
/// f64 by the brute force's integrator (not by our own `end()`), land on the goal within
/// `end_tol`.
fn verify_shortcut(c: &Case, p: &DubinsPath) -> Result<(), String> {
    let lengths = p.lengths.map(|l| l as f64);
    let e = integrate(c.start64(), turns(p.word), lengths, c.r64());
    let g = c.goal64();
    let pos_err = (e[0] - g[0]).hypot(e[1] - g[1]);
    let head_err = angle_diff(e[2], g[2]);
    let (pt, ht) = end_tol(c, p.length() as f64);
    if pos_err > pt || head_err > ht {
        return Err(format!(
            "{} path {:?} flown in f64 ends {pos_err:.3e} m / {head_err:.3e} rad from the goal \
             (allowed {pt:.3e} m / {ht:.1e} rad)",
            p.word.name(),
            p.lengths
        ));
    }
    Ok(())
}

/// How our length compares with a reference.
enum Verdict {
    Agree(f64),
    Shortcut,
    /// Single words only: see `judge_word`.
    Conditioned,
    Fail(String),
}

/// Judges our path against the exact `reference` length (see the top of the file).
fn judge(c: &Case, p: &DubinsPath, reference: f64) -> Verdict {
    let ours = p.length() as f64;
    let err = ours - reference;
    if err.abs() <= length_tol(c, reference) {
        return Verdict::Agree(err.abs());
    }
    if err < 0.0 {
        return match verify_shortcut(c, p) {
            Ok(()) => Verdict::Shortcut,
            Err(e) => Verdict::Fail(format!("shorter than the reference {reference}: {e}")),
        };
    }
    Verdict::Fail(format!(
        "{} path of length {ours} is longer than the reference {reference} (tolerance {:.3e})",
        p.word.name(),
        length_tol(c, reference)
    ))
}

/// Judges a single word (`with_word`) against the brute force's length for that word. As
/// `judge`, except that a *longer* answer is also accepted when it is provably exact for a goal
/// moved by no more than `end_tol`, in a geometry where the word is ill-conditioned in f32:
/// * LSL/RSR with end circles < 0.01·r apart (their tangent direction is that of a v of
///   rounding-noise size),
/// * LSR/RSL with circles within 0.01·r of touching (the straight is the square root of a
///   near-zero l², so its direction errs by up to ~5e-4 rad),
/// * RLR/LRL with circles within 0.01·r of 4r apart (γ = acos(d/4r) near 1) or < 0.01·r apart.
///
/// There an end arc that is exactly ~0 for the given goal can come out as a full turn, or a CCC
/// some 1e-4·r too long: the answer is the exact one for a goal moved by ~1e-7·r. "Provably":
/// our word and lengths flown in f64 land within `end_tol` of the goal (as every path must),
/// and the brute force finds no shorter path of that word to where they land. `shortest()`
/// gets no such allowance (the same paths are available there through a well-conditioned
/// word).
fn judge_word(c: &Case, p: &DubinsPath, reference: f64) -> Verdict {
    let verdict = judge(c, p, reference);
    let Verdict::Fail(why) = verdict else {
        return verdict;
    };
    if (p.length() as f64) < reference || !ill_conditioned(c, p.word) {
        return Verdict::Fail(why);
    }
    if let Err(e) = verify_shortcut(c, p) {
        return Verdict::Fail(format!("{why}; {e}"));
    }
    let lengths = p.lengths.map(|l| l as f64);
    let e = integrate(c.start64(), turns(p.word), lengths, c.r64());
    let ours = p.length() as f64;
    match brute_all64(c.start64(), e, c.r64())[p.word.code() as usize] {
        Some(b) if ours <= b + length_tol(c, b) => Verdict::Conditioned,
        b => Verdict::Fail(format!(
            "{why}; and not the shortest {} to where it lands ({b:?})",
            p.word.name()
        )),
    }
}

/// Whether the word's end circles are in one of the f32-ill-conditioned configurations listed
/// at `judge_word` (computed in f64 from the case, not from our code).
fn ill_conditioned(c: &Case, w: DubinsWord) -> bool {
    let [k1, _, k3] = turns(w);
    let r = c.r64();
    let centre = |p: [f64; 3], k: i8| {
        let k = k as f64;
        [p[0] - k * r * p[2].sin(), p[1] + k * r * p[2].cos()]
    };
    let (c1, c3) = (centre(c.start64(), k1), centre(c.goal64(), k3));
    let d = (c3[0] - c1[0]).hypot(c3[1] - c1[1]);
    let band = 0.01 * r;
    match w.name() {
        "LSL" | "RSR" => d <= band,
        "LSR" | "RSL" => (d - 2.0 * r).abs() <= band,
        _ => (d - 4.0 * r).abs() <= band || d <= band,
    }
}

/// Worst case of a statistic, with its description.
struct Worst {
    name: &'static str,
    value: f64,
    what: String,
}

impl Worst {
    fn new(name: &'static str) -> Self {
        Worst {
            name,
            value: 0.0,
            what: String::new(),
        }
    }
    fn see(&mut self, value: f64, what: impl FnOnce() -> String) {
        if value > self.value {
            self.value = value;
            self.what = what();
        }
    }
    fn report(&self) {
        println!("  worst {}: {:.3e}  {}", self.name, self.value, self.what);
    }
}

/// Failures grouped by kind, so that a report shows every kind, not just the first few cases.
#[derive(Default)]
struct Failures(BTreeMap<String, Vec<String>>);

impl Failures {
    fn add(&mut self, kind: impl Into<String>, detail: String) {
        self.0.entry(kind.into()).or_default().push(detail);
    }
    fn assert_none(&self, what: &str, n: usize) {
        if self.0.is_empty() {
            return;
        }
        let total: usize = self.0.values().map(Vec::len).sum();
        let mut msg = format!("{total} of {n} {what}:\n");
        for (kind, v) in &self.0 {
            msg += &format!("  {} x {kind}, e.g.\n", v.len());
            for d in v.iter().take(3) {
                msg += &format!("    {d}\n");
            }
        }
        panic!("{msg}");
    }
}

// --------------------------------------------------------------------------------------------
// Case families for the brute-force and property tests (the OMPL CSV has its own, generated in
// Python the same way).

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Family {
    Random,
    LargeCoordinates,
    Coincident,
    NearlyCoincident,
    OnTurningCircle,
    HeadingWrap,
    CentresNear2r,
    CentresNear4r,
}

impl Family {
    /// Families built on a discontinuity of the Dubins distance, where shortcuts are expected.
    fn degenerate(self) -> bool {
        !matches!(self, Family::Random | Family::LargeCoordinates)
    }
}

fn heading(rng: &mut Rng) -> f64 {
    let h = rng.range(-PI, PI);
    match rng.below(10) {
        7 => h.rem_euclid(TAU),
        8 => h + TAU * (rng.below(7) as f64 - 3.0),
        _ => h,
    }
}

fn gen_case(rng: &mut Rng, fam: Family) -> Case {
    let r = rng.log_range(10.0, 500.0);
    let mut x0 = rng.range(-500.0, 500.0);
    let mut y0 = rng.range(-500.0, 500.0);
    let ang = rng.range(-PI, PI);
    match fam {
        Family::Random | Family::LargeCoordinates => {
            if fam == Family::LargeCoordinates {
                x0 += rng.sign() * rng.range(2000.0, 5000.0);
                y0 += rng.sign() * rng.range(2000.0, 5000.0);
            }
            let dist = r * rng.log_range(0.01, 20.0);
            let (h0, h1) = (heading(rng), heading(rng));
            Case::new([
                x0,
                y0,
                h0,
                x0 + dist * ang.cos(),
                y0 + dist * ang.sin(),
                h1,
                r,
            ])
        }
        Family::Coincident => {
            let h0 = heading(rng);
            let h1 = match rng.below(3) {
                0 => heading(rng),
                1 => h0 + TAU * (rng.below(5) as f64 - 2.0),
                _ => h0,
            };
            Case::new([x0, y0, h0, x0, y0, h1, r])
        }
        Family::NearlyCoincident => {
            let dist = rng.log_range(1e-4, 1e-2);
            let h0 = heading(rng);
            let h1 = match rng.below(3) {
                0 => h0,
                1 => h0 + rng.sign() * rng.log_range(1e-6, 1e-2),
                _ => heading(rng),
            };
            Case::new([
                x0,
                y0,
                h0,
                x0 + dist * ang.cos(),
                y0 + dist * ang.sin(),
                h1,
                r,
            ])
        }
        Family::OnTurningCircle => {
            let theta = match rng.below(4) {
                0 | 1 => rng.range(0.0, TAU),
                2 => rng.log_range(1e-5, 1e-2),
                _ => TAU - rng.log_range(1e-5, 1e-2),
            };
            on_circle(rng, r, x0, y0, theta)
        }
        Family::HeadingWrap => {
            let e1 = rng.log_range(1e-7, 1e-2);
            let e2 = rng.log_range(1e-7, 1e-2);
            let (mut h0, mut h1) = match rng.below(5) {
                0 => (359.9f64.to_radians(), 0.1f64.to_radians()),
                1 => (PI - e1, -PI + e2),
                2 => (TAU - e1, e2),
                3 => (-e1, TAU - e2),
                _ => (PI, -PI),
            };
            if rng.below(2) == 0 {
                std::mem::swap(&mut h0, &mut h1);
            }
            let dist = r * rng.log_range(0.01, 20.0);
            // A quarter straight ahead of or behind the start.
            let dir = if rng.below(4) == 0 {
                h0 + PI * rng.below(2) as f64
            } else {
                ang
            };
            Case::new([
                x0,
                y0,
                h0,
                x0 + dist * dir.cos(),
                y0 + dist * dir.sin(),
                h1,
                r,
            ])
        }
        Family::CentresNear2r | Family::CentresNear4r => {
            let m = if fam == Family::CentresNear2r {
                2.0
            } else {
                4.0
            };
            let rel = if rng.below(4) == 0 {
                0.0
            } else {
                rng.sign() * rng.log_range(1e-7, 1e-2)
            };
            let (s0, s1) = (rng.sign(), rng.sign());
            let (h0, h1) = (heading(rng), heading(rng));
            let c0 = (x0 - s0 * r * h0.sin(), y0 + s0 * r * h0.cos());
            let dist = m * r * (1.0 + rel);
            let c1 = (c0.0 + dist * ang.cos(), c0.1 + dist * ang.sin());
            Case::new([
                x0,
                y0,
                h0,
                c1.0 + s1 * r * h1.sin(),
                c1.1 - s1 * r * h1.cos(),
                h1,
                r,
            ])
        }
    }
}

/// A goal on the start's left or right turning circle (random side), `theta` radians further
/// round, with the tangent heading of that turn.
fn on_circle(rng: &mut Rng, r: f64, x0: f64, y0: f64, theta: f64) -> Case {
    let h0 = rng.range(-PI, PI);
    let s = rng.sign();
    let (cx, cy) = (x0 - s * r * h0.sin(), y0 + s * r * h0.cos());
    let h1 = h0 + s * theta;
    Case::new([
        x0,
        y0,
        h0,
        cx + s * r * h1.sin(),
        cy - s * r * h1.cos(),
        h1,
        r,
    ])
}

const FAMILIES: [(Family, usize); 8] = [
    (Family::Random, 70_000),
    (Family::LargeCoordinates, 10_000),
    (Family::Coincident, 1_000),
    (Family::NearlyCoincident, 5_000),
    (Family::OnTurningCircle, 5_000),
    (Family::HeadingWrap, 5_000),
    (Family::CentresNear2r, 5_000),
    (Family::CentresNear4r, 5_000),
];

// --------------------------------------------------------------------------------------------
// 1. OMPL reference.

fn ompl_csv_path() -> std::path::PathBuf {
    match std::env::var_os("SKYROUTE_OMPL_CSV") {
        Some(p) => p.into(),
        None => std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../target/reference/ompl_dubins.csv"),
    }
}

#[test]
fn shortest_matches_ompl() {
    let t0 = Instant::now();
    let path = ompl_csv_path();
    // The fast tier may run without the CSV (it says so); the full tier needs it.
    if !path.exists() && !host_tests::full_tier() {
        host_tests::tier::skipped(
            "dubins::shortest_matches_ompl",
            &format!(
                "no OMPL reference at {}; generate it with `python3 scripts/ompl_dubins_reference.py`",
                path.display()
            ),
        );
        return;
    }
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read the OMPL reference {} ({e}). Generate it first with \
             `python3 scripts/ompl_dubins_reference.py` (needs the PyPI packages `ompl` and \
             `numpy`), or point SKYROUTE_OMPL_CSV at an existing file.",
            path.display()
        )
    });
    let mut lines = text.lines();
    assert_eq!(
        lines.next().map(str::trim),
        Some("x0,y0,h0,x1,y1,h1,r,ompl_length"),
        "unexpected header in {}",
        path.display()
    );

    let mut rows = 0usize;
    let mut agree = 0usize;
    let mut shortcuts = 0usize;
    let mut ompl_short: Vec<String> = Vec::new();
    let mut ompl_long: Vec<String> = Vec::new();
    let mut failures = Failures::default();
    let mut worst = Worst::new("|ours - OMPL| where they agree (m)");
    let mut worst_rel = Worst::new("|ours - OMPL| / tolerance");
    for (i, line) in lines.enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let row = i + 2;
        let v: Vec<f64> = line
            .split(',')
            .map(|s| s.parse::<f64>())
            .collect::<Result<_, _>>()
            .unwrap_or_else(|e| panic!("row {row}: {e}: {line}"));
        assert_eq!(v.len(), 8, "row {row}: {line}");
        rows += 1;
        // The script wrote f32 values; reading them as f64 and rounding to f32 is exact.
        let c = Case::new([v[0], v[1], v[2], v[3], v[4], v[5], v[6]]);
        let ompl = v[7];
        let Some(p) = DubinsPath::shortest(&c.start(), &c.goal(), c.r) else {
            failures.add("no path", format!("row {row}: {c:?}"));
            continue;
        };
        let ours = p.length() as f64;
        let (bf, bf_word) = brute_shortest(&c);

        // OMPL against the exact brute force (reported: OMPL has tolerances of its own).
        let ompl_exact = (ompl - bf).abs() <= length_tol(&c, bf);
        if !ompl_exact {
            let what = format!(
                "row {row}: OMPL {ompl}, brute force {bf} ({}); {c:?}",
                bf_word.name()
            );
            if ompl < bf {
                ompl_short.push(what);
            } else {
                ompl_long.push(what);
            }
        }
        // Ours against OMPL. A disagreement must be explained by the brute force: OMPL off
        // the exact answer, or ours a verified shortcut (judged next).
        let tol = length_tol(&c, ompl);
        if (ours - ompl).abs() <= tol {
            agree += 1;
            let what = || format!("(row {row}: ours {ours}, OMPL {ompl}; {c:?})");
            worst.see((ours - ompl).abs(), what);
            worst_rel.see((ours - ompl).abs() / tol, what);
        } else if ompl_exact && (ours - bf).abs() <= length_tol(&c, bf) {
            failures.add(
                "disagrees with OMPL although OMPL matches the brute force",
                format!("row {row}: ours {ours}, OMPL {ompl}, brute force {bf}; {c:?}"),
            );
        }
        // Ours against the exact brute force, whatever OMPL says.
        match judge(&c, &p, bf) {
            Verdict::Agree(_) => {}
            Verdict::Shortcut | Verdict::Conditioned => shortcuts += 1,
            Verdict::Fail(e) => failures.add(
                format!("ours {} vs brute force {}", p.word.name(), bf_word.name()),
                format!("row {row}: ours {ours}, OMPL {ompl}, brute force {bf}: {e}; {c:?}"),
            ),
        }
    }
    println!(
        "OMPL reference {}: {rows} rows, {:.2?}",
        path.display(),
        t0.elapsed()
    );
    println!("  agree with OMPL within f32 tolerance: {agree}");
    worst.report();
    worst_rel.report();
    println!("  verified shortcuts (shorter than exact, ending on the goal): {shortcuts}");
    println!(
        "  rows where OMPL is shorter than the exact brute force (its own tolerances): {}",
        ompl_short.len()
    );
    for s in ompl_short.iter().take(5) {
        println!("    {s}");
    }
    println!(
        "  rows where OMPL is longer than the exact brute force: {}",
        ompl_long.len()
    );
    for s in ompl_long.iter().take(10) {
        println!("    {s}");
    }
    assert!(rows >= 100_000, "only {rows} rows in {}", path.display());
    failures.assert_none("rows disagree", rows);
}

// --------------------------------------------------------------------------------------------
// 2. Brute force: the shortest path and every single word.

#[test]
fn shortest_and_each_word_match_brute_force() {
    let t0 = Instant::now();
    let mut rng = Rng(0x5EED_D0B1_0000_0001);
    let mut n = 0usize;
    let mut word_checks = 0usize;
    let mut shortcuts: BTreeMap<Family, usize> = BTreeMap::new();
    let mut word_shortcuts = 0usize;
    let mut worst_by_family: BTreeMap<Family, f64> = BTreeMap::new();
    let mut conditioned: BTreeMap<&str, usize> = BTreeMap::new();
    let mut worst_cond = Worst::new("with_word longer than brute force, ill-conditioned (m)");
    let mut worst_cond_land = Worst::new("landing error / r of those");
    let mut feasibility_edge = 0usize;
    let mut failures = Failures::default();
    let mut worst = Worst::new("|shortest - brute force| where they agree (m)");
    let mut worst_rel = Worst::new("|shortest - brute force| / tolerance");
    let mut worst_word = Worst::new("|with_word - brute force| where they agree (m)");
    for (fam, count) in FAMILIES {
        for _ in 0..cases(count / 10, count) {
            let c = gen_case(&mut rng, fam);
            n += 1;
            let all = brute_all(&c);
            let (bf, bf_word) = best_of(&all, &c);
            let p = c.shortest();
            match judge(&c, &p, bf) {
                Verdict::Agree(e) => {
                    worst.see(e, || format!("({fam:?}: brute force {bf}; {c:?})"));
                    worst_rel.see(e / length_tol(&c, bf), || format!("({fam:?})"));
                    let w = worst_by_family.entry(fam).or_insert(0.0f64);
                    *w = w.max(e / length_tol(&c, bf));
                }
                Verdict::Shortcut | Verdict::Conditioned => *shortcuts.entry(fam).or_default() += 1,
                Verdict::Fail(e) => failures.add(
                    format!(
                        "{fam:?}: shortest ({} vs {})",
                        p.word.name(),
                        bf_word.name()
                    ),
                    format!("{e}; {c:?}"),
                ),
            }
            for w in DubinsWord::ALL {
                let ours = DubinsPath::with_word(&c.start(), &c.goal(), c.r, w);
                word_checks += 1;
                match (ours, all[w.code() as usize]) {
                    (Some(p), Some(b)) => match judge_word(&c, &p, b) {
                        Verdict::Agree(e) => {
                            worst_word.see(e, || format!("({fam:?} {}; {c:?})", w.name()))
                        }
                        Verdict::Shortcut => word_shortcuts += 1,
                        Verdict::Conditioned => {
                            *conditioned.entry(w.name()).or_default() += 1;
                            let e = integrate(
                                c.start64(),
                                turns(w),
                                p.lengths.map(|l| l as f64),
                                c.r64(),
                            );
                            let g = c.goal64();
                            worst_cond_land.see((e[0] - g[0]).hypot(e[1] - g[1]) / c.r64(), || {
                                format!("({fam:?} {}; {c:?})", w.name())
                            });
                            worst_cond.see(p.length() as f64 - b, || {
                                format!("({fam:?} {}: brute force {b}; {c:?})", w.name())
                            });
                        }
                        Verdict::Fail(e) => failures.add(
                            format!("{fam:?}: with_word {}", w.name()),
                            format!("brute force {b}: {e}; {c:?}"),
                        ),
                    },
                    (None, None) => {}
                    // Feasibility differs: only legitimate at the edge of the word's domain
                    // (a CSC inner tangent at centres 2r apart, a CCC word at 4r), within our
                    // tolerance; if ours exists it must still land on the goal.
                    (ours, b) => {
                        let ok = match ours {
                            Some(p) => verify_shortcut(&c, &p).is_ok(),
                            None => near_domain_edge(&c, w),
                        };
                        if ok {
                            feasibility_edge += 1;
                        } else {
                            failures.add(
                                format!("{fam:?}: with_word {} feasibility", w.name()),
                                format!(
                                    "ours {:?}, brute force {b:?}; {c:?}",
                                    ours.map(|p| (p.lengths, verify_shortcut(&c, &p)))
                                ),
                            );
                        }
                    }
                }
            }
        }
    }
    println!(
        "brute force: {n} cases, {word_checks} single-word checks, {:.2?}",
        t0.elapsed()
    );
    worst.report();
    worst_rel.report();
    println!("  worst |shortest - brute force| / tolerance per family: {worst_by_family:.3?}");
    worst_word.report();
    println!("  verified shortcuts of the shortest path, per family: {shortcuts:?}");
    println!("  verified single-word shortcuts: {word_shortcuts}");
    println!(
        "  single words longer than exact in f32-ill-conditioned geometry, exact for where \
         they land: {conditioned:?}"
    );
    worst_cond.report();
    worst_cond_land.report();
    println!("  words feasible on one side only, at the edge of their domain: {feasibility_edge}");
    assert!(n >= cases(10_000, 100_000));
    failures.assert_none("cases disagree with the brute force", n);
    // Away from the degenerate families a shortcut needs an input within ~1e-5 of a
    // discontinuity: a few in 10^5 at most.
    let plain: usize = shortcuts
        .iter()
        .filter(|(f, _)| !f.degenerate())
        .map(|(_, k)| k)
        .sum();
    assert!(
        plain <= 5,
        "{plain} shortcuts in the non-degenerate families"
    );
}

/// Whether the centres of the word's first and last circles are within f32 tolerance of the
/// distance where the word appears or vanishes (2r for LSR/RSL, 4r for RLR/LRL).
fn near_domain_edge(c: &Case, w: DubinsWord) -> bool {
    let [k1, _, k3] = turns(w);
    let r = c.r64();
    let centre = |p: [f64; 3], k: i8| {
        let k = k as f64;
        [p[0] - k * r * p[2].sin(), p[1] + k * r * p[2].cos()]
    };
    let (c1, c3) = (centre(c.start64(), k1), centre(c.goal64(), k3));
    let d = (c3[0] - c1[0]).hypot(c3[1] - c1[1]);
    let edge = match w.name() {
        "LSR" | "RSL" => 2.0 * r,
        "RLR" | "LRL" => 4.0 * r,
        _ => return false,
    };
    (d - edge).abs() <= 2e-5 * r + 1e-6 * c.coord_scale()
}

// --------------------------------------------------------------------------------------------
// 3. Properties of the paths we return.

/// Checks the geometry of one path: it flies from the start to the goal, its primitives join
/// up in position and heading, their lengths add up to `length()`, and no arc is a near-full
/// turn unless the exact shortest path (`exact`) is at least that long.
fn check_properties(c: &Case, p: &DubinsPath, exact: f64) -> Result<(), String> {
    check_end(c, p)?;
    let len = p.length() as f64;
    // A coordinate of magnitude X is good to 6e-8·X: a straight's length and direction are
    // recomputed from its rounded end points.
    let coord_ulp = 1.2e-7 * (c.coord_scale() + len);
    let pos_tol = 4e-6 * c.r64() + 4.0 * coord_ulp + 1e-4;
    let prims: Vec<Primitive> = p.primitives().into_iter().flatten().collect();
    let sum: f64 = prims.iter().map(|q| q.length() as f64).sum();
    if (sum - len).abs() > 1e-6 * len + 4.0 * coord_ulp + 1e-6 {
        return Err(format!("primitive lengths sum to {sum}, length() is {len}"));
    }
    let head_tol = |q: &Primitive| match q {
        Primitive::Line(s) => 1e-4 + 4.0 * coord_ulp / s.length() as f64,
        Primitive::Arc(_) => 1e-4,
    };
    let mut at = c.start();
    let mut prev_tol: f64 = 1e-4;
    for (i, q) in prims.iter().enumerate() {
        let s = q.pose_at(0.0);
        let dp = s.position.distance(at.position) as f64;
        let dh = angle_diff(s.heading as f64, at.heading as f64);
        let ht = prev_tol.max(head_tol(q));
        if dp > pos_tol || dh > ht {
            return Err(format!(
                "{} piece {i} {q:?} starts {dp:.3e} m / {dh:.3e} rad away from where the \
                 previous one ends {at:?} (allowed {pos_tol:.3e} m / {ht:.3e} rad)",
                p.word.name()
            ));
        }
        if let Primitive::Arc(a) = q {
            let turn = a.sweep.abs() as f64;
            if turn >= TAU - 1e-3 && exact < a.length() as f64 - length_tol(c, exact) {
                return Err(format!(
                    "{} piece {i} is a spurious full turn ({turn} rad): the exact shortest \
                     path is {exact}",
                    p.word.name()
                ));
            }
        }
        at = q.pose_at(q.length());
        prev_tol = head_tol(q);
    }
    Ok(())
}

#[test]
fn paths_fly_from_start_to_goal() {
    let t0 = Instant::now();
    let mut rng = Rng(0x5EED_D0B1_0000_0002);
    let mut n = 0usize;
    let mut paths = 0usize;
    let mut failures = Failures::default();
    let mut worst_pos = Worst::new("end position error / allowed");
    let mut worst_pos_abs = Worst::new("end position error (m)");
    let mut worst_pos_r = Worst::new("end position error / r");
    let mut worst_head = Worst::new("end heading error (rad)");
    for (fam, count) in FAMILIES {
        for _ in 0..cases(count / 20, count / 2) {
            let c = gen_case(&mut rng, fam);
            n += 1;
            let exact = brute_shortest(&c).0;
            let shortest = c.shortest();
            let words = DubinsWord::ALL
                .iter()
                .filter_map(|&w| DubinsPath::with_word(&c.start(), &c.goal(), c.r, w));
            for (k, p) in std::iter::once(shortest).chain(words).enumerate() {
                paths += 1;
                // The near-full-turn rule is for the shortest path: a single word may need a
                // loop.
                let exact = if k == 0 { exact } else { f64::INFINITY };
                match check_properties(&c, &p, exact) {
                    Ok(()) => {
                        let (pe, he) = check_end(&c, &p).unwrap();
                        let allowed = end_tol(&c, p.length() as f64).0;
                        let what = || format!("({fam:?} {}; {c:?})", p.word.name());
                        worst_pos.see(pe / allowed, what);
                        worst_pos_abs.see(pe, what);
                        worst_pos_r.see(pe / c.r64(), what);
                        worst_head.see(he, what);
                    }
                    Err(e) => failures.add(
                        format!(
                            "{fam:?} {}{}",
                            p.word.name(),
                            if k == 0 { " shortest" } else { "" }
                        ),
                        format!("{e}; {c:?}"),
                    ),
                }
            }
        }
    }
    println!("properties: {n} cases, {paths} paths, {:.2?}", t0.elapsed());
    worst_pos.report();
    worst_pos_abs.report();
    worst_pos_r.report();
    worst_head.report();
    failures.assert_none("paths break a property", paths);
}

#[test]
fn goal_on_the_turning_circle_is_one_arc() {
    let mut rng = Rng(0x5EED_D0B1_0000_0003);
    let mut failures = Failures::default();
    let n = cases(2_000, 20_000);
    let mut shortcuts = 0;
    for i in 0..n {
        let r = rng.log_range(10.0, 500.0);
        let (x0, y0) = (rng.range(-500.0, 500.0), rng.range(-500.0, 500.0));
        // Tiny turns (the classic spurious-loop case), then anything up to a half turn.
        let theta = if i % 2 == 0 {
            rng.log_range(1e-5, 1e-1)
        } else {
            rng.range(1e-1, PI)
        };
        let c = on_circle(&mut rng, r, x0, y0, theta);
        // The arc of the rounded inputs: the turn between the two headings.
        let arc = c.r64() * angle_diff(c.h1 as f64, c.h0 as f64);
        let tol = length_tol(&c, arc);
        let p = c.shortest();
        let ours = p.length() as f64;
        let exact = brute_shortest(&c).0;
        // Rounding the goal to f32 moves it off the circle by up to ~3e-5 m, which for a tiny
        // turn can make the exact answer a loop: then ours must be a verified shortcut.
        match judge(&c, &p, exact) {
            Verdict::Fail(e) => failures.add("against the brute force", format!("{e}; {c:?}")),
            Verdict::Shortcut | Verdict::Conditioned => shortcuts += 1,
            Verdict::Agree(_) => {}
        }
        // Whatever the word, the pieces must all be that one arc: turns of the start's sense
        // about the start's centre (e.g. LRL with an empty middle arc is one arc), no straight.
        let turn = if (c.h1 as f64 - c.h0 as f64).rem_euclid(TAU) < PI {
            1.0
        } else {
            -1.0
        };
        let h0 = c.h0 as f64;
        let centre = (
            c.x0 as f64 - turn * c.r64() * h0.sin(),
            c.y0 as f64 + turn * c.r64() * h0.cos(),
        );
        let same_arc = p.primitives().iter().flatten().all(|q| match q {
            Primitive::Arc(a) => {
                (a.length() as f64) <= tol
                    || (a.sweep as f64 * turn >= 0.0
                        && (a.centre.x as f64 - centre.0).hypot(a.centre.y as f64 - centre.1)
                            <= 4e-6 * c.r64() + 1e-4)
            }
            Primitive::Line(s) => (s.length() as f64) <= tol,
        });
        if (ours - arc).abs() > tol || !same_arc {
            failures.add(
                "not the arc",
                format!(
                    "{} {:?} (length {ours}) instead of the arc {arc}: {c:?}",
                    p.word.name(),
                    p.lengths
                ),
            );
        } else if let Err(e) = check_properties(&c, &p, exact) {
            failures.add("properties", format!("{e}: {c:?}"));
        }
    }
    println!("goal on the turning circle: {n} cases, {shortcuts} verified shortcuts");
    failures.assert_none("goals on the turning circle", n);
}

#[test]
fn coincident_poses_give_zero_length() {
    let mut rng = Rng(0x5EED_D0B1_0000_0004);
    let mut failures = Failures::default();
    let n = cases(2_000, 20_000);
    let mut loops = 0;
    for i in 0..n {
        let r = rng.log_range(10.0, 500.0);
        let (x, y) = (rng.range(-5000.0, 5000.0), rng.range(-5000.0, 5000.0));
        let h = heading(&mut rng);
        if i % 2 == 0 {
            // The same pose: nothing to fly.
            let c = Case::new([x, y, h, x, y, h, r]);
            let p = c.shortest();
            if p.length() as f64 > 1e-4 {
                failures.add(
                    "same pose",
                    format!("{} {:?} for {c:?}", p.word.name(), p.lengths),
                );
            } else if let Err(e) = check_end(&c, &p) {
                failures.add("same pose, end", format!("{e}: {c:?}"));
            }
        } else {
            // The same heading written a whole number of turns apart. Rounded to f32 the two
            // differ by up to a few 1e-6 rad, and for the exact inputs a turn in place that
            // small is not flyable: the answer is ~0 within our tolerance or a loop, as the
            // brute force decides.
            let c = Case::new([x, y, h, x, y, h + TAU * (rng.below(5) as f64 - 2.0), r]);
            let p = c.shortest();
            let exact = brute_shortest(&c).0;
            match judge(&c, &p, exact) {
                Verdict::Fail(e) => failures.add("turns apart", format!("{e}; {c:?}")),
                _ if p.length() as f64 > 1e-4 => loops += 1,
                _ => {}
            }
            if let Err(e) = check_properties(&c, &p, exact) {
                failures.add("turns apart, properties", format!("{e}: {c:?}"));
            }
        }
    }
    println!(
        "coincident poses: {n} cases; headings a whole number of turns apart that gave a loop: \
         {loops}"
    );
    failures.assert_none("coincident poses", n);
}

/// A zero-length right arc used to come out of `primitives()` as a left turn (sweep −0.0), so
/// the pieces after it were flown on the wrong side. Words starting with R and a goal dead
/// ahead, or on the start's right turning circle, have a zero first arc.
#[test]
fn zero_length_right_arcs_keep_their_side() {
    let (x0, y0, h0, r) = (100.0f64, -40.0f64, 0.3f64, 50.0f64);
    let ahead = [x0 + 80.0 * h0.cos(), y0 + 80.0 * h0.sin()];
    let c = Case::new([x0, y0, h0, ahead[0], ahead[1], h0, r]);
    for word in [DubinsWord::Rsr, DubinsWord::Lsl] {
        let p = DubinsPath::with_word(&c.start(), &c.goal(), c.r, word).unwrap();
        assert!((p.length() - 80.0).abs() < 1e-3, "{p:?}");
        check_properties(&c, &p, 80.0).unwrap_or_else(|e| panic!("{e}"));
    }
    // Goal on the right turning circle, theta further round: RSR with a zero first arc.
    let (cx, cy) = (x0 + r * h0.sin(), y0 - r * h0.cos());
    for theta in [1e-3, 0.5, 1.0, 2.0, 3.0] {
        let h1 = h0 - theta;
        let c = Case::new([x0, y0, h0, cx - r * h1.sin(), cy + r * h1.cos(), h1, r]);
        let p = c.shortest();
        assert!((p.length() as f64 - r * theta).abs() < 1e-3, "{p:?}");
        check_properties(&c, &p, r * theta).unwrap_or_else(|e| panic!("{e}; {c:?}"));
    }
}

/// `DubinsPath::length_lower_bound` is below the length of every path of every word, in every
/// case family (the planner skips a goal link whose bound shows it cannot improve the route,
/// so a computed length under the bound could change a route). Prints the smallest margin,
/// relative to the radius, by which a length exceeds a positive bound.
#[test]
fn every_word_is_at_least_the_length_lower_bound() {
    let mut rng = Rng(0x5EED_D0B1_0000_0004);
    let mut failures = Failures::default();
    let mut n = 0usize;
    let (mut closest, mut at) = (f64::INFINITY, String::new());
    for (fam, count) in FAMILIES {
        for _ in 0..cases(count / 10, count) {
            let c = gen_case(&mut rng, fam);
            let (s, g) = (c.start(), c.goal());
            let bound = DubinsPath::length_lower_bound(s.position, g.position, c.r);
            for w in DubinsWord::ALL {
                let Some(p) = DubinsPath::with_word(&s, &g, c.r, w) else {
                    continue;
                };
                n += 1;
                let slack = (p.length() - bound) as f64 / c.r64();
                if bound > 0.0 && slack < closest {
                    (closest, at) = (slack, format!("({fam:?} {}; {c:?})", w.name()));
                }
                if p.length() < bound || p.length().is_nan() {
                    failures.add(
                        format!("{fam:?} {}", w.name()),
                        format!("length {} < bound {bound}; {c:?}", p.length()),
                    );
                }
            }
        }
    }
    println!("length lower bound: {n} paths; smallest (length - bound) / r: {closest:.3e} {at}");
    failures.assert_none("paths shorter than the lower bound", n);
}
