//! Quintic Hermite segments (`skyroute::geometry::hermite`) against independent f64 references,
//! never against earlier output of our own code:
//!
//! * **boundary conditions** on random line-element pairs, in f32 through the API and in f64
//!   from the stored coefficients, to f32 rounding of the coefficients' magnitudes;
//! * **the 3 × 3 solve** against two f64 derivations: the textbook closed form (Biagiotti &
//!   Melchiorri) and Cramer's rule on the unscaled system in `t`;
//! * **length** against a dense f64 polyline (Richardson-extrapolated), and `L = v·T`;
//! * **a straight line** (`P1 = P0 + V0·T`, `V1 = V0`) comes out straight at constant speed;
//! * **flyability**: the conservative check against dense f64 sampling (step `T/20000`): it
//!   must never accept a segment that dense sampling finds violating; the over-conservatism is
//!   reported;
//! * **collision enclosure**: every dense curve point lies within `ε` of its chord, and the
//!   segment's polygon and circle tests never miss a conflict that dense sampling finds; the
//!   over-approximation is reported.
//!
//! The cases are drawn around the three Babel 2014 vehicles of `scenarios/babel-*.geojson`.

use std::time::Instant;

use rayon::prelude::*;
use skyroute::geometry::hermite::{
    FlyLimits, HermiteError, HermiteSegment, LineElement, Violation,
};
use skyroute::geometry::Vec2;

// The shared SplitMix64, case counts by tier, and f64 reference geometry.
use host_tests::{cases, reference, Rng};

// --------------------------------------------------------------------------------------------
// f64 helpers.

type V = [f64; 2];

fn v64(v: Vec2) -> V {
    [v.x as f64, v.y as f64]
}
fn f32v(v: V) -> Vec2 {
    Vec2::new(v[0] as f32, v[1] as f32)
}
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}
fn scale(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn cross(a: V, b: V) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}
fn dist(a: V, b: V) -> f64 {
    norm(sub(a, b))
}

/// f64 copies of the stored normalised coefficients.
fn b64(seg: &HermiteSegment) -> [V; 6] {
    seg.normalized_coefficients().map(v64)
}

/// `Σ b_k s^k` and its first two derivatives in s, in f64.
fn q(b: &[V; 6], s: f64) -> V {
    let mut acc = [0.0; 2];
    for k in (0..6).rev() {
        acc = add(scale(acc, s), b[k]);
    }
    acc
}
fn dq(b: &[V; 6], s: f64) -> V {
    let mut acc = [0.0; 2];
    for k in (1..6).rev() {
        acc = add(scale(acc, s), scale(b[k], k as f64));
    }
    acc
}
fn ddq(b: &[V; 6], s: f64) -> V {
    let mut acc = [0.0; 2];
    for k in (2..6).rev() {
        acc = add(scale(acc, s), scale(b[k], (k * (k - 1)) as f64));
    }
    acc
}

// The point–segment distance and containment are the shared f64 reference
// (`host_tests::reference`), on this file's `[f64; 2]` points.

fn point_segment_distance(p: V, a: V, b: V) -> f64 {
    reference::dist_point_segment((p[0], p[1]), (a[0], a[1]), (b[0], b[1]))
}

// --------------------------------------------------------------------------------------------
// Cases.

#[derive(Clone, Copy, Debug)]
struct Vehicle {
    v: f64,
    limits: FlyLimits,
}

/// Babel 2014 scenarios I, II, III (`scenarios/babel-*.geojson`).
const VEHICLES: [Vehicle; 3] = [
    Vehicle {
        v: 30.0,
        limits: FlyLimits {
            v_min: 25.0,
            v_max: 35.0,
            a_long_min: -3.0,
            a_long_max: 3.0,
            a_lat_max: 20.0,
        },
    },
    Vehicle {
        v: 100.0,
        limits: FlyLimits {
            v_min: 80.0,
            v_max: 125.0,
            a_long_min: -5.0,
            a_long_max: 5.0,
            a_lat_max: 40.0,
        },
    },
    Vehicle {
        v: 50.0,
        limits: FlyLimits {
            v_min: 40.0,
            v_max: 60.0,
            a_long_min: -4.0,
            a_long_max: 4.0,
            a_lat_max: 15.0,
        },
    },
];

#[derive(Clone, Copy, Debug)]
struct Case {
    start: LineElement,
    end: LineElement,
    vehicle: Vehicle,
}

/// A random pair: a Babel vehicle, a start anywhere in a 100 × 40 km frame, a distance of
/// 0.5–300 turn radii (v²/a_lat) in a random direction, and headings either uniform
/// (one case in three) or within ±60° or ±15° of the chord (flyable more often).
fn random_case(rng: &mut Rng) -> Case {
    let vehicle = VEHICLES[rng.below(3) as usize];
    let v = vehicle.v;
    let radius = v * v / vehicle.limits.a_lat_max as f64;
    let p0 = [
        rng.range(-50_000.0, 50_000.0),
        rng.range(-20_000.0, 20_000.0),
    ];
    let d = radius * rng.log_range(0.5, 300.0);
    let phi = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
    let p1 = add(p0, [d * phi.cos(), d * phi.sin()]);
    let spread = match rng.below(3) {
        0 => std::f64::consts::PI,
        1 => 60f64.to_radians(),
        _ => 15f64.to_radians(),
    };
    let h0 = phi + rng.range(-spread, spread);
    let h1 = phi + rng.range(-spread, spread);
    Case {
        start: LineElement::new(f32v(p0), f32v([v * h0.cos(), v * h0.sin()])),
        end: LineElement::new(f32v(p1), f32v([v * h1.cos(), v * h1.sin()])),
        vehicle,
    }
}

/// `n` successfully built random segments (and how many draws failed, by error).
fn segments(seed: u64, n: usize) -> (Vec<(Case, HermiteSegment)>, [usize; 6]) {
    let mut rng = Rng(seed);
    let mut out = Vec::with_capacity(n);
    let mut fails = [0usize; 6];
    while out.len() < n {
        let c = random_case(&mut rng);
        match HermiteSegment::new(&c.start, &c.end, c.vehicle.v as f32) {
            Ok(s) => out.push((c, s)),
            Err(e) => {
                fails[match e {
                    HermiteError::NonFinite => 0,
                    HermiteError::NonPositiveSpeed => 1,
                    HermiteError::CoincidentPositions => 2,
                    HermiteError::NoSolution => 3,
                    HermiteError::NoConvergence => 4,
                    HermiteError::SolveFailed => 5,
                }] += 1
            }
        }
    }
    (out, fails)
}

/// Magnitude scales of the coefficients: positions, `d/ds`, `d²/ds²` (in s units).
fn scales(b: &[V; 6]) -> (f64, f64, f64) {
    let pos = b[0][0].abs().max(b[0][1].abs()) + b[1..].iter().map(|c| norm(*c)).sum::<f64>();
    let vel = (1..6).map(|k| k as f64 * norm(b[k])).sum::<f64>();
    let acc = (2..6)
        .map(|k| (k * (k - 1)) as f64 * norm(b[k]))
        .sum::<f64>();
    (pos, vel, acc)
}

const EPS: f64 = f32::EPSILON as f64;

// --------------------------------------------------------------------------------------------

#[test]
fn boundary_conditions_hold_to_f32_rounding() {
    let t0 = Instant::now();
    let (segs, fails) = segments(1, cases(2_000, 20_000));
    let build = t0.elapsed();
    let (mut worst_api, mut worst_f64) = ([0.0f64; 3], [0.0f64; 3]);
    for (c, seg) in &segs {
        let b = b64(seg);
        let t = seg.t_max() as f64;
        let (sp, sv, sa) = scales(&b);
        let v0 = v64(c.start.velocity);
        let (p1, v1) = (v64(c.end.position), v64(c.end.velocity));

        // Start: position and acceleration exactly, velocity to a couple of roundings.
        let tm = seg.t_max();
        assert_eq!(seg.position(0.0), Some(c.start.position));
        assert_eq!(seg.acceleration(0.0), Some(Vec2::new(0.0, 0.0)));
        let ev = dist(v64(seg.velocity(0.0).unwrap()), v0);
        assert!(ev <= 4.0 * EPS * norm(v0), "{c:?}: v(0) off by {ev}");

        // End, through the API (f32): in units of ε times the terms' magnitudes.
        let e = [
            dist(v64(seg.position(tm).unwrap()), p1) / (EPS * sp),
            dist(v64(seg.velocity(tm).unwrap()), v1) / (EPS * sv / t),
            norm(v64(seg.acceleration(tm).unwrap())) / (EPS * sa / (t * t)),
        ];
        // End, in f64 from the stored f32 coefficients: the residual of the solve itself.
        let f = [
            dist(q(&b, 1.0), p1) / (EPS * sp),
            dist(scale(dq(&b, 1.0), 1.0 / t), v1) / (EPS * sv / t),
            norm(scale(ddq(&b, 1.0), 1.0 / (t * t))) / (EPS * sa / (t * t)),
        ];
        for i in 0..3 {
            assert!(
                e[i] <= 20.0,
                "{c:?}: API end condition {i} off by {} ε",
                e[i]
            );
            assert!(
                f[i] <= 20.0,
                "{c:?}: f64 end condition {i} off by {} ε",
                f[i]
            );
            worst_api[i] = worst_api[i].max(e[i]);
            worst_f64[i] = worst_f64[i].max(f[i]);
        }
        // The start element as reproduced.
        assert_eq!(seg.start().position, c.start.position);
    }
    println!(
        "boundary conditions: {} segments (built in {:.2?}; failed draws by error \
         [NonFinite, NonPositiveSpeed, Coincident, NoSolution, NoConvergence, SolveFailed]: \
         {fails:?})",
        segs.len(),
        build
    );
    println!(
        "  worst end error in ε·Σ|terms| (position, velocity, acceleration): API {:.2?}, \
         f64 from the coefficients {:.2?}; {:.2?}",
        worst_api,
        worst_f64,
        t0.elapsed()
    );
}

/// c3..c5 by the closed form of Biagiotti & Melchiorri (a quintic with given end positions,
/// velocities and accelerations, here both accelerations zero), in f64.
fn closed_form(p0: V, v0: V, p1: V, v1: V, t: f64) -> [V; 3] {
    let h = sub(p1, p0);
    let mut c = [[0.0; 2]; 3];
    for i in 0..2 {
        c[0][i] = (20.0 * h[i] - (8.0 * v1[i] + 12.0 * v0[i]) * t) / (2.0 * t.powi(3));
        c[1][i] = (-30.0 * h[i] + (14.0 * v1[i] + 16.0 * v0[i]) * t) / (2.0 * t.powi(4));
        c[2][i] = (12.0 * h[i] - 6.0 * (v1[i] + v0[i]) * t) / (2.0 * t.powi(5));
    }
    c
}

/// c3..c5 by Cramer's rule on the unscaled system in t (a second, independent derivation).
fn cramer(p0: V, v0: V, p1: V, v1: V, t: f64) -> [V; 3] {
    let m = [
        [t.powi(3), t.powi(4), t.powi(5)],
        [3.0 * t * t, 4.0 * t.powi(3), 5.0 * t.powi(4)],
        [6.0 * t, 12.0 * t * t, 20.0 * t.powi(3)],
    ];
    let det3 = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det3(&m);
    let mut c = [[0.0; 2]; 3];
    for i in 0..2 {
        let r = [p1[i] - p0[i] - v0[i] * t, v1[i] - v0[i], 0.0];
        for (k, ck) in c.iter_mut().enumerate() {
            let mut mk = m;
            for row in 0..3 {
                mk[row][k] = r[row];
            }
            ck[i] = det3(&mk) / d;
        }
    }
    c
}

#[test]
fn solve_matches_independent_f64_solutions() {
    let t0 = Instant::now();
    let (segs, _) = segments(2, cases(1_000, 10_000));
    let (mut worst, mut worst_refs) = (0.0f64, 0.0f64);
    for (c, seg) in &segs {
        let t = seg.t_max() as f64;
        let (p0, v0) = (v64(c.start.position), v64(c.start.velocity));
        let (p1, v1) = (v64(c.end.position), v64(c.end.velocity));
        let cf = closed_form(p0, v0, p1, v1, t);
        let cr = cramer(p0, v0, p1, v1, t);
        // Scale of the normalised unknowns b_k = c_k T^k: the right-hand side's size.
        let sc = norm(sub(p1, p0)) + (norm(v0) + norm(v1)) * t;
        let got = seg.coefficients().map(v64);
        let got_b = b64(seg);
        assert_eq!(got[0], p0);
        assert_eq!(got[2], [0.0, 0.0]);
        assert!(dist(got[1], v0) <= 4.0 * EPS * norm(v0));
        for k in 0..3 {
            let tk = t.powi(k as i32 + 3);
            let refs = dist(cf[k], cr[k]) * tk / sc;
            assert!(
                refs <= 1e-9,
                "{c:?}: the two f64 derivations disagree: {refs}"
            );
            worst_refs = worst_refs.max(refs);
            let e_b = dist(got_b[k + 3], scale(cf[k], tk)) / sc;
            let e_c = dist(got[k + 3], cf[k]) * tk / sc;
            // LU forward error: up to cond(M)·ε ≈ 524 · 1.2e-7 ≈ 6e-5 of the scale.
            assert!(
                e_b <= 6e-5 && e_c <= 6e-5,
                "{c:?}: c{} off by {e_b} / {e_c}",
                k + 3
            );
            worst = worst.max(e_b).max(e_c);
        }
    }
    println!(
        "3x3 solve vs f64 closed form: worst |Δb_k|/(|ΔP| + (|V0|+|V1|)T) = {worst:.2e} \
         ({:.1} ε); closed form vs Cramer {worst_refs:.1e}; {} segments, {:.2?}",
        worst / EPS,
        segs.len(),
        t0.elapsed()
    );
}

/// Length of the dense f64 polyline with `n` chords.
fn polyline_length(b: &[V; 6], n: usize) -> f64 {
    let mut prev = q(b, 0.0);
    let mut l = 0.0;
    for i in 1..=n {
        let p = q(b, i as f64 / n as f64);
        l += dist(p, prev);
        prev = p;
    }
    l
}

#[test]
fn length_matches_dense_polyline_and_equals_v_t() {
    let t0 = Instant::now();
    let (segs, _) = segments(3, cases(300, 3_000));
    let rows: Vec<(f64, f64, f64, f64)> = segs
        .par_iter()
        .map(|(c, seg)| {
            let b = b64(seg);
            // Chord sums converge like n⁻²: Richardson on (n, 2n) removes that term.
            let (l1, l2) = (polyline_length(&b, 20_000), polyline_length(&b, 40_000));
            let l_ref = l2 + (l2 - l1) / 3.0;
            let l = seg.length() as f64;
            let rel = (l - l_ref).abs() / l_ref;
            let vt = c.vehicle.v * seg.t_max() as f64;
            let rel_vt = (l_ref - vt).abs() / vt;
            let est = seg.length_error_estimate() as f64 / l_ref;
            let min_speed = (0..=1000)
                .map(|i| norm(dq(&b, i as f64 / 1000.0)) / seg.t_max() as f64)
                .fold(f64::INFINITY, f64::min);
            (rel, rel_vt, est, min_speed / c.vehicle.v)
        })
        .collect();
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    let mut beyond_estimate = 0;
    for (i, &(rel, rel_vt, est, min_speed)) in rows.iter().enumerate() {
        assert!(rel <= 1e-5, "{:?}: length off by {rel:e}", segs[i].0);
        assert!(rel_vt <= 1e-5, "{:?}: L − vT off by {rel_vt:e}", segs[i].0);
        // The estimate plus f32 rounding of the sum bounds the error.
        assert!(
            rel <= est + 2e-6,
            "{:?}: error {rel:e} > estimate {est:e}",
            segs[i].0
        );
        if rel > est {
            beyond_estimate += 1;
        }
        worst = (worst.0.max(rel), worst.1.max(rel_vt), worst.2.max(est));
        let _ = min_speed;
    }
    let near_cusp = rows.iter().filter(|r| r.3 < 0.1).count();
    let worst_cusp = rows
        .iter()
        .filter(|r| r.3 < 0.1)
        .map(|r| r.0)
        .fold(0.0, f64::max);
    println!(
        "length vs dense f64 polyline: worst relative error {:.2e} (near-cusp segments, min \
         speed < 0.1 v: {near_cusp}, worst {worst_cusp:.2e}); worst |L − vT|/vT {:.2e}; \
         worst relative estimate {:.2e}, error above estimate (within f32 rounding) in \
         {beyond_estimate} of {}; {:.2?}",
        worst.0,
        worst.1,
        worst.2,
        rows.len(),
        t0.elapsed()
    );
}

#[test]
fn straight_line_gives_the_straight_line_at_constant_speed() {
    // P1 = P0 + V0·T and V1 = V0, up to the f32 rounding of the inputs. The exact solution then
    // is the line: for inputs off it by d = P1 − P0 − V0·T (the rounding), the curve is
    // P0 + V0·t + d·h(t/T) with h = 10s³ − 15s⁴ + 6s⁵ (0 ≤ h ≤ 1, |h'| ≤ 1.875, |h''| ≤ 5.78),
    // so the tolerances are |d|-terms plus the rounding of the evaluation. Half the cases start
    // near the origin (small rounding), half anywhere in a 100 × 40 km frame.
    let t0 = Instant::now();
    let mut rng = Rng(4);
    let mut worst = [0.0f64; 5];
    let mut ratios = [0.0f64; 3];
    for i in 0..cases(200, 2_000) {
        let vehicle = VEHICLES[rng.below(3) as usize];
        let v = vehicle.v;
        let h = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
        let t_true = rng.log_range(1.0, 300.0);
        let p0 = if i % 2 == 0 {
            f32v([rng.range(-100.0, 100.0), rng.range(-100.0, 100.0)])
        } else {
            f32v([rng.range(-50e3, 50e3), rng.range(-20e3, 20e3)])
        };
        let v0 = f32v([v * h.cos(), v * h.sin()]);
        let p1 = f32v(add(v64(p0), scale(v64(v0), t_true)));
        let start = LineElement::new(p0, v0);
        let end = LineElement::new(p1, v0);
        let seg = HermiteSegment::new(&start, &end, v as f32).expect("a straight line");
        let (p0, v0, p1) = (v64(p0), v64(v0), v64(p1));
        let speed0 = norm(v0);
        // T: the chord at the nominal speed (the inputs' speed is v to f32 rounding).
        let t_exact = dist(p1, p0) / v;
        let t = seg.t_max() as f64;
        let et = (t - t_exact).abs() / t_exact;
        assert!(et <= 1e-6, "T {t} vs {t_exact}");
        // The inputs' inconsistency at the segment's T, and the rounding scales.
        let d = norm(sub(sub(p1, p0), scale(v0, t)));
        let big = p0[0].abs().max(p0[1].abs()) + p1[0].abs().max(p1[1].abs()) + speed0 * t;
        assert!(d <= 8.0 * EPS * big, "inputs off the line by {d} m");
        // What the f32 solve sees: d plus the rounding of P1 − P0 − V0·T.
        let d = d + 4.0 * EPS * (dist(p1, p0) + speed0 * t);
        let b = b64(&seg);
        let (sp, sv, sa) = scales(&b);
        let dir = scale(v0, 1.0 / speed0);
        let (mut off_line, mut speed_dev, mut lat) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..=100 {
            let tk = seg.t_max() * k as f32 / 100.0;
            let p = sub(v64(seg.position(tk).unwrap()), p0);
            off_line = off_line.max(cross(dir, p).abs());
            speed_dev = speed_dev.max((seg.speed(tk).unwrap() as f64 - speed0).abs());
            lat = lat.max(seg.lateral_acceleration(tk).unwrap() as f64);
        }
        let tol_off = d + 32.0 * EPS * sp;
        let tol_speed = 1.875 * d / t + 32.0 * EPS * sv / t;
        let tol_lat = 5.78 * d / (t * t) + 32.0 * EPS * sa / (t * t);
        assert!(
            off_line <= tol_off,
            "off the line by {off_line} m > {tol_off}"
        );
        assert!(
            speed_dev <= tol_speed,
            "speed off by {speed_dev} > {tol_speed}"
        );
        assert!(lat <= tol_lat, "lateral acceleration {lat} > {tol_lat}");
        let (lo, hi) = seg.speed_range();
        assert!(lo as f64 <= speed0 && hi as f64 >= speed0);
        assert_eq!(seg.check_flyable(&vehicle.limits), Ok(()));
        let rel = |x: f64, tol: f64| x / tol;
        ratios[0] = ratios[0].max(off_line / tol_off);
        ratios[1] = ratios[1].max(speed_dev / tol_speed);
        ratios[2] = ratios[2].max(lat / tol_lat);
        worst = [
            worst[0].max(et),
            worst[1].max(off_line / (speed0 * t)),
            worst[2].max(speed_dev / speed0),
            worst[3].max(lat),
            worst[4]
                .max(rel(off_line, tol_off))
                .max(rel(speed_dev, tol_speed))
                .max(rel(lat, tol_lat)),
        ];
    }
    println!(
        "straight line: worst relative |ΔT| {:.1e}, off-line distance / length {:.1e}, speed \
         deviation / speed {:.1e}, lateral acceleration {:.1e} m/s² (at most {:.2} of the \
         tolerances: {ratios:.2?} for off-line, speed, lateral; the lateral one is attained by \
         d·max|h''|/T² when the inputs' rounding d dominates); 2000 cases, {:.2?}",
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        worst[4],
        t0.elapsed()
    );
}

// --------------------------------------------------------------------------------------------
// Flyability.

/// Extremes over a dense f64 sampling (step T/n): min/max speed, min/max longitudinal,
/// max lateral acceleration.
fn dense_extremes(seg: &HermiteSegment, n: usize) -> [f64; 5] {
    let b = b64(seg);
    let t = seg.t_max() as f64;
    let mut e = [f64::INFINITY, 0.0, f64::INFINITY, f64::NEG_INFINITY, 0.0];
    for i in 0..=n {
        let s = i as f64 / n as f64;
        let v = scale(dq(&b, s), 1.0 / t);
        let a = scale(ddq(&b, s), 1.0 / (t * t));
        let sp = norm(v);
        e[0] = e[0].min(sp);
        e[1] = e[1].max(sp);
        if sp > 0.0 {
            let (al, at) = (dot(v, a) / sp, cross(v, a).abs() / sp);
            e[2] = e[2].min(al);
            e[3] = e[3].max(al);
            e[4] = e[4].max(at);
        }
    }
    e
}

fn violates(e: &[f64; 5], l: &FlyLimits) -> bool {
    e[0] < l.v_min as f64
        || e[1] > l.v_max as f64
        || e[2] < l.a_long_min as f64
        || e[3] > l.a_long_max as f64
        || e[4] > l.a_lat_max as f64
}

/// How far inside its limits the dense sampling keeps a segment, as the smallest relative
/// distance to a limit (limit ranges: v_max − v_min, a_long_max − a_long_min, a_lat_max).
fn slack(e: &[f64; 5], l: &FlyLimits) -> f64 {
    let dv = (l.v_max - l.v_min) as f64;
    let da = (l.a_long_max - l.a_long_min) as f64;
    [
        (e[0] - l.v_min as f64) / dv,
        (l.v_max as f64 - e[1]) / dv,
        (e[2] - l.a_long_min as f64) / da,
        (l.a_long_max as f64 - e[3]) / da,
        (l.a_lat_max as f64 - e[4]) / l.a_lat_max as f64,
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

#[test]
fn flyability_check_never_accepts_a_violating_segment() {
    let t0 = Instant::now();
    let (segs, _) = segments(5, cases(1_200, 12_000));
    // Half the cases with the vehicle's own limits; the other half with one limit moved to the
    // dense extreme ± a gap of 10⁻⁶…10⁻¹ of the limit's range (log-uniform, either side): the
    // hardest place for a sampled check, and a map of its over-conservatism against the gap.
    let rows: Vec<(bool, Result<(), Violation>, f64, std::time::Duration)> = segs
        .par_iter()
        .enumerate()
        .map(|(i, (c, seg))| {
            let e = dense_extremes(seg, 20_000);
            let mut l = c.vehicle.limits;
            if i % 2 == 1 {
                let mut rng = Rng(1000 + i as u64);
                let sign = if rng.below(2) == 0 { 1.0 } else { -1.0 };
                let gap = sign * rng.log_range(1e-6, 1e-1);
                let dv = (l.v_max - l.v_min) as f64;
                let da = (l.a_long_max - l.a_long_min) as f64;
                match rng.below(5) {
                    0 => l.v_min = (e[0] - gap * dv).max(1e-3) as f32,
                    1 => l.v_max = (e[1] + gap * dv) as f32,
                    2 => l.a_long_min = (e[2] - gap * da) as f32,
                    3 => l.a_long_max = (e[3] + gap * da) as f32,
                    _ => l.a_lat_max = (e[4] + gap * l.a_lat_max as f64).max(0.0) as f32,
                }
                if !l.is_valid() {
                    l = c.vehicle.limits;
                }
            }
            let t = Instant::now();
            let got = seg.check_flyable(&l);
            let dt = t.elapsed();
            (violates(&e, &l), got, slack(&e, &l), dt)
        })
        .collect();
    let (mut dense_ok, mut check_ok, mut over, mut over_unproven) = (0, 0, 0, 0);
    let mut by_limit = std::collections::BTreeMap::new();
    // Dense-accepted cases by their relative slack (smallest distance to a limit / its range),
    // and how many of them the check rejects.
    const BINS: [f64; 6] = [0.0, 1e-5, 1e-4, 1e-3, 1e-2, f64::INFINITY];
    let mut bins = [(0usize, 0usize); 5];
    let mut check_time = std::time::Duration::ZERO;
    for (i, (bad, got, sl, dt)) in rows.iter().enumerate() {
        check_time += *dt;
        if got.is_ok() {
            check_ok += 1;
            assert!(
                !bad,
                "accepted a segment that dense sampling finds violating: {:?}",
                segs[i]
            );
        }
        if !bad {
            dense_ok += 1;
            let k = (0..5).find(|&k| *sl < BINS[k + 1]).unwrap_or(4);
            bins[k].0 += 1;
            if let Err(v) = got {
                over += 1;
                bins[k].1 += 1;
                if let Violation::Unproven { limit, .. } = v {
                    over_unproven += 1;
                    *by_limit.entry(format!("{limit:?}")).or_insert(0usize) += 1;
                }
            }
        }
    }
    let mean_us = check_time.as_secs_f64() * 1e6 / rows.len() as f64;
    println!(
        "flyability: {} segments; dense sampling (step T/20000) accepts {dense_ok}, the check \
         accepts {check_ok} and never one that dense sampling rejects",
        rows.len()
    );
    println!(
        "  over-conservative: {over} of {dense_ok} dense-accepted ({:.2} %; {over_unproven} \
         unproven: {by_limit:?}; {} with a sample beyond a limit between dense samples); mean \
         check {mean_us:.1} µs; {:.2?}",
        100.0 * over as f64 / dense_ok.max(1) as f64,
        over - over_unproven,
        t0.elapsed()
    );
    for k in 0..5 {
        println!(
            "    slack in [{:.0e}, {:.0e}) of the limit range: {} of {} rejected ({:.1} %)",
            BINS[k],
            BINS[k + 1],
            bins[k].1,
            bins[k].0,
            100.0 * bins[k].1 as f64 / bins[k].0.max(1) as f64
        );
    }
    // With the unmodified limits only (the even cases):
    let (mut ok_v, mut over_v) = (0, 0);
    for (_, (bad, got, _, _)) in rows.iter().enumerate().filter(|(i, _)| i % 2 == 0) {
        if !bad {
            ok_v += 1;
            if got.is_err() {
                over_v += 1;
            }
        }
    }
    println!(
        "  with the vehicles' own limits: {over_v} of {ok_v} dense-accepted rejected ({:.2} %)",
        100.0 * over_v as f64 / ok_v.max(1) as f64
    );
}

// --------------------------------------------------------------------------------------------
// Collision enclosure.

/// A random simple (star-shaped) polygon around `centre` with radii in [r/3, r].
fn star_polygon(rng: &mut Rng, centre: V, r: f64) -> Vec<V> {
    let n = 3 + rng.below(10) as usize;
    let mut angles: Vec<f64> = (0..n)
        .map(|_| rng.range(0.0, std::f64::consts::TAU))
        .collect();
    angles.sort_by(f64::total_cmp);
    angles.dedup();
    angles
        .iter()
        .map(|&a| {
            let rr = rng.range(r / 3.0, r);
            v64(f32v(add(centre, [rr * a.cos(), rr * a.sin()])))
        })
        .collect()
}

#[test]
fn collision_enclosure_never_misses_a_conflict() {
    let t0 = Instant::now();
    let (segs, _) = segments(6, cases(300, 3_000));
    const DENSE: usize = 20_000;
    const PIECES: [usize; 3] = [8, 32, 128];
    // Per pieces: [circle conflicts found by dense, circle over-approx, polygon conflicts,
    // polygon over-approx, circle non-conflicts, polygon non-conflicts], plus max ε/length.
    let rows: Vec<([[usize; 6]; 3], [f64; 3])> = segs
        .par_iter()
        .enumerate()
        .map(|(i, (_, seg))| {
            let mut rng = Rng(7000 + i as u64);
            let b = b64(seg);
            let pts: Vec<V> = (0..=DENSE)
                .map(|k| q(&b, k as f64 / DENSE as f64))
                .collect();
            let mut counts = [[0usize; 6]; 3];
            let mut eps_rel = [0.0f64; 3];
            // The enclosure itself: every dense point within ε of its piece's chord.
            for (pi, &pieces) in PIECES.iter().enumerate() {
                let chords: Vec<_> = seg.polyline_bound(pieces).collect();
                assert_eq!(chords.len(), pieces);
                for (k, p) in pts.iter().enumerate() {
                    let s = k as f64 / DENSE as f64;
                    // Points on a shared end belong to both pieces; test the one(s) they fall in.
                    let j = ((s * pieces as f64) as usize).min(pieces - 1);
                    let c = &chords[j];
                    let d = point_segment_distance(*p, v64(c.chord.start), v64(c.chord.end));
                    assert!(
                        d <= c.epsilon as f64,
                        "point {k} off chord {j} by {d} > ε {}",
                        c.epsilon
                    );
                }
                eps_rel[pi] = chords.iter().map(|c| c.epsilon as f64).fold(0.0, f64::max)
                    / seg.length() as f64;
            }
            for _ in 0..8 {
                let clearance = if rng.below(2) == 0 {
                    50.0
                } else {
                    rng.range(0.0, 100.0)
                };
                let clearance = clearance as f32;
                let anchor = pts[rng.below(DENSE as u64 + 1) as usize];
                let a = rng.range(0.0, std::f64::consts::TAU);
                let size = rng.log_range(10.0, 2000.0);
                // Obstacle edge placed around the clearance distance from a curve point.
                let gap = clearance as f64 + rng.range(-0.1, 0.3) * size.min(200.0);
                // Circle.
                let radius = size as f32;
                let centre = f32v(add(
                    anchor,
                    [(size + gap) * a.cos(), (size + gap) * a.sin()],
                ));
                let dmin = pts
                    .iter()
                    .map(|p| dist(*p, v64(centre)) - radius as f64)
                    .fold(f64::INFINITY, f64::min);
                let dense_conflict = dmin <= clearance as f64;
                // Polygon.
                let pc = add(anchor, [(size + gap) * a.cos(), (size + gap) * a.sin()]);
                let poly64 = star_polygon(&mut rng, pc, size);
                let poly: Vec<Vec2> = poly64.iter().map(|p| f32v(*p)).collect();
                let poly_ref: Vec<reference::P> = poly64.iter().map(|v| (v[0], v[1])).collect();
                // (Points farther than the clearance from the polygon's box cannot conflict.)
                let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for v in &poly64 {
                    lo = [lo[0].min(v[0]), lo[1].min(v[1])];
                    hi = [hi[0].max(v[0]), hi[1].max(v[1])];
                }
                let c = clearance as f64;
                let dense_poly = pts.iter().any(|p| {
                    let near = p[0] >= lo[0] - c
                        && p[0] <= hi[0] + c
                        && p[1] >= lo[1] - c
                        && p[1] <= hi[1] + c;
                    let n = poly64.len();
                    near && (reference::inside((p[0], p[1]), &poly_ref)
                        || (0..n).any(|j| {
                            point_segment_distance(*p, poly64[j], poly64[(j + 1) % n]) <= c
                        }))
                });
                for (pi, &pieces) in PIECES.iter().enumerate() {
                    let got = seg.conflicts_with_circle(centre, radius, clearance, pieces);
                    assert!(
                        got || !dense_conflict,
                        "missed a circle conflict (dense {dmin} ≤ {clearance}), {pieces} pieces"
                    );
                    if dense_conflict {
                        counts[pi][0] += 1;
                    } else {
                        counts[pi][4] += 1;
                        if got {
                            counts[pi][1] += 1;
                        }
                    }
                    let got = seg.conflicts_with_polygon(&poly[..], clearance, pieces);
                    assert!(
                        got || !dense_poly,
                        "missed a polygon conflict, {pieces} pieces"
                    );
                    if dense_poly {
                        counts[pi][2] += 1;
                    } else {
                        counts[pi][5] += 1;
                        if got {
                            counts[pi][3] += 1;
                        }
                    }
                }
            }
            (counts, eps_rel)
        })
        .collect();
    println!(
        "collision enclosure: {} segments × 8 circles and 8 polygons",
        rows.len()
    );
    for (pi, pieces) in PIECES.iter().enumerate() {
        let mut tot = [0usize; 6];
        let mut eps: Vec<f64> = Vec::new();
        for (c, e) in &rows {
            for k in 0..6 {
                tot[k] += c[pi][k];
            }
            eps.push(e[pi]);
        }
        eps.sort_by(f64::total_cmp);
        println!(
            "  {pieces:>3} pieces: circles {} conflicts, {} of {} clear flagged ({:.1} %); \
             polygons {} conflicts, {} of {} clear flagged ({:.1} %); max ε/length median \
             {:.1e}, worst {:.1e}",
            tot[0],
            tot[1],
            tot[4],
            100.0 * tot[1] as f64 / tot[4].max(1) as f64,
            tot[2],
            tot[3],
            tot[5],
            100.0 * tot[3] as f64 / tot[5].max(1) as f64,
            eps[eps.len() / 2],
            eps[eps.len() - 1]
        );
    }
    println!("  {:.2?}", t0.elapsed());
}

// --------------------------------------------------------------------------------------------
// Errors and NaN.

#[test]
fn bad_inputs_give_errors_not_panics() {
    let p0 = Vec2::new(0.0, 0.0);
    let v0 = Vec2::new(30.0, 0.0);
    let p1 = Vec2::new(3000.0, 500.0);
    let good = (LineElement::new(p0, v0), LineElement::new(p1, v0));
    assert!(HermiteSegment::new(&good.0, &good.1, 30.0).is_ok());
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let variants = [
            LineElement::new(Vec2::new(bad, 0.0), v0),
            LineElement::new(Vec2::new(0.0, bad), v0),
            LineElement::new(p0, Vec2::new(bad, 0.0)),
            LineElement::new(p0, Vec2::new(0.0, bad)),
        ];
        for e in variants {
            assert_eq!(
                HermiteSegment::new(&e, &good.1, 30.0),
                Err(HermiteError::NonFinite)
            );
            assert_eq!(
                HermiteSegment::new(&good.0, &e, 30.0),
                Err(HermiteError::NonFinite)
            );
        }
        assert_eq!(
            HermiteSegment::new(&good.0, &good.1, bad),
            Err(HermiteError::NonFinite)
        );
    }
    // Overflowing distance.
    let far = LineElement::new(Vec2::new(3e38, 0.0), v0);
    let far2 = LineElement::new(Vec2::new(-3e38, 0.0), v0);
    assert_eq!(
        HermiteSegment::new(&far, &far2, 30.0),
        Err(HermiteError::NonFinite)
    );
    for v in [0.0, -0.0, -30.0] {
        assert_eq!(
            HermiteSegment::new(&good.0, &good.1, v),
            Err(HermiteError::NonPositiveSpeed)
        );
    }
    assert_eq!(
        HermiteSegment::new(&good.0, &LineElement::new(p0, -v0), 30.0),
        Err(HermiteError::CoincidentPositions)
    );
    // End velocities of 3v along a 1 m chord: every duration gives an average speed above v
    // (for large T the average speed tends to 3v·∫|1 − 30s²(1 − s)²| ds ≈ 1.76 v).
    let e = HermiteSegment::new(
        &LineElement::new(p0, Vec2::new(90.0, 0.0)),
        &LineElement::new(Vec2::new(1.0, 0.0), Vec2::new(90.0, 0.0)),
        30.0,
    );
    assert_eq!(e, Err(HermiteError::NoSolution));
    // A very slow nominal speed over a long way does not panic either way.
    let _ = HermiteSegment::new(&good.0, &good.1, 1e-30);
    let _ = HermiteSegment::new(&good.0, &good.1, 1e30);

    let seg = HermiteSegment::new(&good.0, &good.1, 30.0).unwrap();
    assert_eq!(seg.position(f32::NAN), None);
    assert_eq!(seg.velocity(f32::NAN), None);
    assert_eq!(seg.acceleration(f32::NAN), None);
    assert_eq!(seg.speed(f32::NAN), None);
    assert_eq!(seg.lateral_acceleration(f32::NAN), None);
    assert_eq!(seg.longitudinal_acceleration(f32::NAN), None);
    // Out of range clamps.
    assert_eq!(seg.position(-5.0), seg.position(0.0));
    assert_eq!(seg.position(f32::INFINITY), seg.position(seg.t_max()));
    let ok = VEHICLES[0].limits;
    for bad in [
        FlyLimits {
            v_min: f32::NAN,
            ..ok
        },
        FlyLimits { v_min: 0.0, ..ok },
        FlyLimits { v_max: 20.0, ..ok },
        FlyLimits {
            a_long_max: -4.0,
            ..ok
        },
        FlyLimits {
            a_lat_max: -1.0,
            ..ok
        },
        FlyLimits {
            a_lat_max: f32::INFINITY,
            ..ok
        },
    ] {
        assert_eq!(seg.check_flyable(&bad), Err(Violation::InvalidLimits));
    }
    let square = [
        Vec2::new(1e5, 1e5),
        Vec2::new(1e5 + 1.0, 1e5),
        Vec2::new(1e5 + 1.0, 1e5 + 1.0),
    ];
    assert!(!seg.conflicts_with_polygon(&square[..], 10.0, 16));
    assert!(seg.conflicts_with_polygon(&square[..], f32::NAN, 16));
    let nan_square = [square[0], Vec2::new(f32::NAN, 0.0), square[2]];
    assert!(seg.conflicts_with_polygon(&nan_square[..], 10.0, 16));
    assert!(!seg.conflicts_with_circle(Vec2::new(1e5, 1e5), 1.0, 10.0, 16));
    assert!(seg.conflicts_with_circle(Vec2::new(1e5, 1e5), f32::NAN, 10.0, 16));
    assert!(seg.conflicts_with_circle(Vec2::new(f32::NAN, 0.0), 1.0, 10.0, 16));
    assert_eq!(seg.polyline_bound(0).count(), 1);
    assert_eq!(seg.polyline_bound(usize::MAX).count(), 4096);
    // The bounding box holds the curve.
    let (lo, hi) = seg.bounding_box();
    for i in 0..=1000 {
        let p = seg.position(seg.t_max() * i as f32 / 1000.0).unwrap();
        assert!(p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y);
    }
}
