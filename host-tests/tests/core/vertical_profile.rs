//! The vertical profile of Niendorf et al.'s aircraft (`skyroute::geometry::vertical`) against
//! independent references:
//!
//! * the **limits themselves**: sampled in f32, every profile starts and ends at its altitudes
//!   and at rest, never changes direction, and keeps its gradient within `v_c / v` and its
//!   second differences within `a_z / v²`;
//! * a **linear programme** (`scripts/vertical_reference.py`, SciPy's HiGHS): the largest
//!   rest-to-rest climb over an edge, and the highest altitude any monotone move reaches at a
//!   quarter, half and three quarters of it. The LP's moves are flyable (piecewise-constant
//!   acceleration), so ours must reach at least as high, and at most the discretisation gap
//!   higher;
//! * an **f64 profile** written from the definitions (below) and a bisection on it: the span
//!   below a ceiling must cover every point the f64 profile flies below it;
//! * **sampling in 3-D**: a Dubins edge flown with its profile past a cylinder of finite height,
//!   sampled every few centimetres, against the exact check of the path cut to that span.

use std::f64::consts::PI;

use skyroute::geometry::predicates::conflicts_with_circle;
use skyroute::geometry::vertical::{
    pieces_within, VerticalLimits, VerticalProfile, CEILING_MARGIN, CEILING_MARGIN_M, SPAN_MARGIN,
    SPAN_MARGIN_M,
};
use skyroute::geometry::{DubinsPath, Pose, Primitive, Vec2};

use host_tests::reference::vertical_altitude as altitude_f64;
use host_tests::{cases, Rng};

fn random_limits(rng: &mut Rng) -> VerticalLimits {
    VerticalLimits {
        airspeed: rng.range_f32(10.0, 60.0),
        climb_rate: rng.range_f32(1.0, 15.0),
        vertical_accel: rng.range_f32(1.0, 30.0),
    }
}

/// A random feasible profile: altitudes up to 400 m, a length from 1 m to 5 km, a move of up
/// to the largest climb (either way, sometimes level).
fn random_profile(rng: &mut Rng) -> (VerticalProfile, VerticalLimits) {
    loop {
        let limits = random_limits(rng);
        let length = rng.log_range(1.0, 5000.0) as f32;
        let from = rng.range_f32(0.0, 400.0);
        let to = if rng.chance(0.1) {
            from
        } else {
            from + (rng.sign() * rng.unit()) as f32 * limits.max_climb(length)
        };
        if let Some(p) = VerticalProfile::new(from, to, length, &limits) {
            return (p, limits);
        }
    }
}

#[test]
fn profiles_keep_the_vertical_limits_and_start_and_end_at_rest() {
    let mut rng = Rng(0x5EED_0001);
    for case in 0..cases(2_000, 20_000) {
        let (p, limits) = random_profile(&mut rng);
        let (g, k) = (limits.gradient() as f64, limits.curvature() as f64);
        let z = |s: f64| p.altitude_at(s as f32) as f64;
        // f32 rounding of an altitude: a few ulp of the largest altitude.
        let noise = 4.0 * f32::EPSILON as f64 * p.from.abs().max(p.to.abs()).max(1.0) as f64;
        let length = p.length as f64;
        let ctx = format!("case {case}: {p:?}, {limits:?}");
        assert!((z(0.0) - p.from as f64).abs() <= noise, "start ({ctx})");
        assert!((z(length) - p.to as f64).abs() <= noise, "end ({ctx})");
        // A step at which the curvature bound stands well above the rounding.
        let h = ((1e4 * noise / k).sqrt()).min(length / 8.0);
        if h <= 0.0 {
            continue;
        }
        let sign = if p.to >= p.from { 1.0 } else { -1.0 };
        let steps = (length / h).floor() as usize;
        for i in 0..steps {
            let s = i as f64 * h;
            let step = z(s + h) - z(s);
            assert!(sign * step >= -noise, "direction at {s} ({ctx})");
            assert!(
                step.abs() <= g * h * (1.0 + 1e-4) + 2.0 * noise,
                "gradient at {s} ({ctx})"
            );
            if i > 0 {
                let second = z(s + h) - 2.0 * z(s) + z(s - h);
                assert!(
                    second.abs() <= k * h * h * (1.0 + 1e-3) + 4.0 * noise,
                    "curvature at {s}: {second} against {} ({ctx})",
                    k * h * h
                );
            }
        }
        // At rest at both ends: from rest, the altitude moves at most k h²/2 in h.
        assert!((z(h) - z(0.0)).abs() <= 0.5 * k * h * h * (1.0 + 1e-3) + 2.0 * noise);
        assert!((z(length) - z(length - h)).abs() <= 0.5 * k * h * h * (1.0 + 1e-3) + 2.0 * noise);
    }
}

#[test]
fn a_move_beyond_the_largest_climb_or_a_bad_input_is_refused() {
    let mut rng = Rng(0x5EED_0002);
    for _ in 0..cases(2_000, 20_000) {
        let limits = random_limits(&mut rng);
        let length = rng.log_range(1.0, 5000.0) as f32;
        let max = limits.max_climb(length);
        // From 0 the move is exactly representable; from higher up it rounds to an ulp of the
        // altitude, and is only asserted feasible when the rounded move is still within.
        for from in [0.0, rng.range_f32(0.0, 400.0)] {
            for sign in [1.0, -1.0] {
                let within = from + sign * max * (1.0 - 1e-4);
                let beyond = from + sign * (max * (1.0 + 1e-3) + 1e-3);
                if ((within - from) as f64).abs() <= max as f64 * (1.0 - 1e-5) {
                    assert!(VerticalProfile::new(from, within, length, &limits).is_some());
                }
                assert!(VerticalProfile::new(from, beyond, length, &limits).is_none());
            }
        }
    }
    let limits = VerticalLimits::niendorf(20.0);
    for (from, to, length) in [
        (f32::NAN, 0.0, 100.0),
        (0.0, f32::INFINITY, 100.0),
        (0.0, 0.0, -1.0),
        (0.0, 0.0, f32::NAN),
        (0.0, 1.0, 0.0),
        (0.0, 1e30, 1e30),
    ] {
        assert!(VerticalProfile::new(from, to, length, &limits).is_none());
    }
    assert!(VerticalProfile::new(5.0, 5.0, 0.0, &limits).is_some());
    for limits in host_tests::damage::bad_vertical_limits(limits) {
        assert!(!limits.is_valid());
        assert_eq!(limits.max_climb(100.0), 0.0);
        assert!(VerticalProfile::new(0.0, 0.0, 100.0, &limits).is_none());
    }
}

fn lp_csv() -> Option<String> {
    let path = match std::env::var_os("SKYROUTE_VERTICAL_LP_CSV") {
        Some(p) => std::path::PathBuf::from(p),
        None => std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../target/reference/vertical_lp.csv"),
    };
    // The fast tier may run without the CSV (it says so); the full tier needs it.
    if !path.exists() && !host_tests::full_tier() {
        host_tests::tier::skipped(
            "vertical_profile (LP reference)",
            &format!(
                "no LP reference at {}; generate it with `python3 scripts/vertical_reference.py`",
                path.display()
            ),
        );
        return None;
    }
    Some(std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read the LP reference {} ({e}); generate it with \
             `python3 scripts/vertical_reference.py` (needs scipy and numpy)",
            path.display()
        )
    }))
}

/// Ours against the LP: at least the LP's value (less f32 rounding), at most the gap a
/// discretisation of `steps` steps can leave (a rate error of `a_z dt` over the whole time, and
/// a position error of `v_c dt`).
#[test]
fn the_largest_climb_and_the_highest_profile_match_the_linear_programme() {
    let Some(text) = lp_csv() else { return };
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("v,vc,az,length,steps,max_climb,climb,z1,z2,z3")
    );
    let mut rows = 0;
    for line in lines.filter(|l| !l.is_empty()) {
        let f: Vec<f64> = line
            .split(',')
            .map(|x| x.parse().expect("number"))
            .collect();
        let (v, vc, az, length, steps) = (f[0], f[1], f[2], f[3], f[4]);
        let limits = VerticalLimits {
            airspeed: v as f32,
            climb_rate: vc as f32,
            vertical_accel: az as f32,
        };
        let dt = length / v / steps;
        let gap = vc * dt + az * dt * (length / v);
        let rounding = |x: f64| 1e-5 * (1.0 + x.abs());
        let ours = limits.max_climb(length as f32) as f64;
        assert!(
            ours >= f[5] - rounding(f[5]),
            "max climb {ours} < LP {} ({line})",
            f[5]
        );
        assert!(
            ours <= f[5] + gap,
            "max climb {ours} > LP {} + {gap} ({line})",
            f[5]
        );
        let climb = f[6] as f32;
        let up = VerticalProfile::new(0.0, climb, length as f32, &limits).expect("feasible");
        let down = VerticalProfile::new(climb, 0.0, length as f32, &limits).expect("feasible");
        for j in 1..=3 {
            let s = (j as f64 * length / 4.0) as f32;
            let lp = f[6 + j];
            for (ours, what) in [
                (up.altitude_at(s) as f64, "climb"),
                // A descent is a climb flown backwards: its highest at s is the climb's at L − s.
                (down.altitude_at(length as f32 - s) as f64, "descent"),
            ] {
                assert!(
                    ours >= lp - rounding(lp),
                    "{what} at {j}/4: {ours} < LP {lp} ({line})"
                );
                assert!(
                    ours <= lp + gap,
                    "{what} at {j}/4: {ours} > LP {lp} + {gap} ({line})"
                );
            }
        }
        rows += 1;
    }
    assert!(rows >= 100, "only {rows} LP cases");
}

/// The f64 distance along the profile where it crosses `ceiling` (bisection on the monotone f64
/// profile); `None` when it never does.
fn crossing_f64(p: &VerticalProfile, limits: &VerticalLimits, ceiling: f64) -> Option<f64> {
    let z = |s: f64| altitude_f64(p, limits, s);
    let length = p.length as f64;
    let (low, high) = (z(0.0).min(z(length)), z(0.0).max(z(length)));
    if ceiling <= low || ceiling > high {
        return None;
    }
    let climbing = p.to > p.from;
    let (mut a, mut b) = (0.0, length);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (z(m) < ceiling) == climbing {
            a = m;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}

#[test]
fn the_span_below_a_ceiling_covers_every_point_flown_below_it_and_little_more() {
    let mut rng = Rng(0x5EED_0003);
    for case in 0..cases(5_000, 50_000) {
        let (p, limits) = random_profile(&mut rng);
        let (low, high) = (p.from.min(p.to), p.from.max(p.to));
        // Ceilings over the whole move, near its ends (where the gradient is zero) and beyond.
        // Within a few f32 steps of either end, a rounding of the altitudes is a large error in
        // distance (the gradient is zero there).
        let ulps = |x: f32, n: i32| f32::from_bits((x.to_bits() as i32 + n) as u32);
        let ceiling = match rng.below(7) {
            0 => low - rng.range_f32(0.0, 1.0),
            1 => high + rng.range_f32(0.0, 1.0),
            2 => low + (high - low) * rng.unit_f32() * 1e-3,
            3 => high - (high - low) * rng.unit_f32() * 1e-3,
            4 => ulps(low, rng.int(-2, 8) as i32),
            5 => ulps(high, rng.int(-8, 2) as i32),
            _ => low + (high - low) * rng.unit_f32(),
        };
        let span = p.span_below(ceiling);
        let ctx = format!("case {case}: {p:?}, ceiling {ceiling}, span {span:?}");
        let length = p.length as f64;
        let z = |s: f64| altitude_f64(&p, &limits, s);
        // Safety: every point the f64 profile flies below the ceiling lies in the span.
        let below_at = |s: f64| z(s) < ceiling as f64;
        if below_at(0.0) || below_at(length) {
            let (a, b) = span.unwrap_or_else(|| panic!("no span ({ctx})"));
            let (a, b) = (a as f64, b as f64);
            match crossing_f64(&p, &limits, ceiling as f64) {
                None => assert!(a <= 0.0 && b >= length, "whole edge ({ctx})"),
                Some(x) if p.to > p.from => assert!(a <= 0.0 && b >= x, "climb ({ctx})"),
                Some(x) => assert!(a <= x && b >= length, "descent ({ctx})"),
            }
        }
        // Tightness: the span reaches no further than the crossing of the raised ceiling plus
        // the distance margin (and twice the rounding of that raise).
        if let Some((a, b)) = span {
            let scale = ceiling.abs().max(p.from.abs()).max(p.to.abs()) as f64;
            let raised = ceiling as f64
                + 2.0 * (CEILING_MARGIN as f64 * scale)
                + CEILING_MARGIN_M as f64 * 2.0;
            let margin = 2.0 * (SPAN_MARGIN as f64 * length + SPAN_MARGIN_M as f64);
            if p.to > p.from {
                let x = crossing_f64(&p, &limits, raised).unwrap_or(length);
                assert!(
                    (b as f64) <= x + margin,
                    "climb span too long ({ctx}, crossing {x})"
                );
            } else if p.to < p.from {
                let x = crossing_f64(&p, &limits, raised).unwrap_or(0.0);
                assert!(
                    (a as f64) >= x - margin,
                    "descent span too long ({ctx}, crossing {x})"
                );
            } else {
                assert!(
                    ceiling as f64 + 1e-2 > p.from as f64,
                    "level edge above ({ctx})"
                );
            }
        }
    }
}

fn random_path(rng: &mut Rng) -> DubinsPath {
    loop {
        let r = rng.range_f32(20.0, 200.0);
        let a = Pose::new(0.0, 0.0, rng.range(-PI, PI) as f32);
        let b = Pose::new(
            rng.range_f32(-800.0, 800.0),
            rng.range_f32(-800.0, 800.0),
            rng.range(-PI, PI) as f32,
        );
        if let Some(path) = DubinsPath::shortest(&a, &b, r) {
            return path;
        }
    }
}

fn position_f64(p: &Primitive, s: f64) -> (f64, f64) {
    match p {
        Primitive::Line(seg) => {
            let len = seg.length() as f64;
            let t = if len > 0.0 {
                (s / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (a, b) = (seg.start, seg.end);
            (
                a.x as f64 + (b.x - a.x) as f64 * t,
                a.y as f64 + (b.y - a.y) as f64 * t,
            )
        }
        Primitive::Arc(a) => {
            let sign = if a.sweep.is_sign_negative() {
                -1.0
            } else {
                1.0
            };
            let angle =
                a.start_angle as f64 + sign * s.clamp(0.0, a.length() as f64) / a.radius as f64;
            (
                a.centre.x as f64 + a.radius as f64 * angle.cos(),
                a.centre.y as f64 + a.radius as f64 * angle.sin(),
            )
        }
    }
}

#[test]
fn the_pieces_within_an_interval_fly_the_paths_own_points() {
    let mut rng = Rng(0x5EED_0004);
    for case in 0..cases(2_000, 20_000) {
        let path = random_path(&mut rng);
        let total = path.length();
        let (mut a, mut b) = (
            rng.range_f32(-50.0, total + 50.0),
            rng.range_f32(-50.0, total + 50.0),
        );
        if a > b {
            core::mem::swap(&mut a, &mut b);
        }
        let pieces: Vec<Primitive> = pieces_within(&path, a, b).into_iter().flatten().collect();
        let kept: f64 = pieces.iter().map(|p| p.length() as f64).sum();
        let expected = (b.min(total) - a.max(0.0)).max(0.0) as f64;
        let tol = 1e-4 * (1.0 + total as f64);
        assert!(
            (kept - expected).abs() <= tol,
            "case {case}: {kept} kept of {expected}"
        );
        // Each piece's points are the path's points at the same distance along it.
        let mut along = a.max(0.0) as f64;
        for piece in &pieces {
            for i in 0..=16 {
                let s = piece.length() as f64 * i as f64 / 16.0;
                let ours = position_f64(piece, s);
                let theirs = path.sample((along + s) as f32).position;
                let d = ((ours.0 - theirs.x as f64).powi(2) + (ours.1 - theirs.y as f64).powi(2))
                    .sqrt();
                assert!(
                    d <= 2e-3 * (1.0 + total as f64 / 1000.0),
                    "case {case}: {d} m off at {s}"
                );
            }
            along += piece.length() as f64;
        }
    }
}

/// A Dubins edge flown with its profile past a cylinder (centre, radius, top): sampled every
/// 5 cm in f64 against the exact check of the pieces flown below the top plus the clearance.
/// A sample inside the cylinder (with the clearance) must be a conflict; a conflict must have a
/// sample within 5 cm (horizontally) and 5 cm (vertically) of it.
#[test]
fn a_building_is_a_conflict_exactly_where_the_edge_flies_below_its_top() {
    let mut rng = Rng(0x5EED_0005);
    let (mut conflicts, mut clear) = (0, 0);
    for case in 0..cases(600, 6_000) {
        let path = random_path(&mut rng);
        let length = path.length();
        let limits = random_limits(&mut rng);
        let from = rng.range_f32(0.0, 200.0);
        let to = from + (rng.sign() * rng.unit()) as f32 * limits.max_climb(length);
        let Some(profile) = VerticalProfile::new(from, to, length, &limits) else {
            continue;
        };
        let at = path.sample(rng.range_f32(0.0, length)).position;
        let centre = at + Vec2::from_angle(rng.range_f32(-3.2, 3.2)) * rng.range_f32(0.0, 60.0);
        let radius = rng.range_f32(1.0, 40.0);
        let clearance = rng.range_f32(0.0, 10.0);
        let top = from.min(to) + (from - to).abs() * rng.range_f32(-0.2, 1.2);
        let exact = profile.span_below(top + clearance).is_some_and(|(a, b)| {
            pieces_within(&path, a, b)
                .into_iter()
                .flatten()
                .any(|p| conflicts_with_circle(&p, centre, radius, clearance))
        });
        let reach = (radius + clearance) as f64;
        let ceiling = (top + clearance) as f64;
        let (mut inside, mut near) = (false, false);
        let mut along = 0.0;
        for prim in path.primitives().into_iter().flatten() {
            let len = prim.length() as f64;
            let n = (len / 0.05).ceil() as usize;
            for i in 0..=n {
                let s = len * i as f64 / n.max(1) as f64;
                let (x, y) = position_f64(&prim, s);
                let d = ((x - centre.x as f64).powi(2) + (y - centre.y as f64).powi(2)).sqrt();
                let z = altitude_f64(&profile, &limits, along + s);
                inside |= d < reach - 1e-3 && z < ceiling - 1e-3;
                near |= d < reach + 0.05 && z < ceiling + 0.05;
            }
            along += len;
        }
        let ctx = format!("case {case}: {path:?} {profile:?} circle {centre:?} r {radius} top {top} c {clearance}");
        if inside {
            assert!(
                exact,
                "a sample flies inside but the check is clear ({ctx})"
            );
        }
        if exact {
            assert!(near, "a conflict with no sample near ({ctx})");
            conflicts += 1;
        } else {
            clear += 1;
        }
    }
    assert!(
        conflicts > 50 && clear > 50,
        "{conflicts} conflicts, {clear} clear"
    );
}
