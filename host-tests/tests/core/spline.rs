//! Curvature-bounded cubic spline smoothing (`skyroute::geometry::spline`) against independent
//! f64 references, never against earlier output of our own code:
//!
//! * **the corner table**: at random turn angles within the table and every grid ratio, the
//!   onboard bound is never below the largest curvature·s1 found by dense f64 sampling of the
//!   Bézier (evaluated here from its control points), and at most 1.35 times it (the slack is
//!   printed); the nodes are within the 1 % margin of the f64 value; `c` is non-decreasing in
//!   the turn angle on a 0.1° grid for every ratio;
//! * **the fit** on random polylines (turns near 0, near 180° and anywhere, segments from
//!   0.01 m to 20 km, random start headings, with and without a goal heading): every piece
//!   sampled densely in f64 has curvature at most `κ_max·(1 + 10⁻³)`; at every knot the
//!   position is equal, the unit tangent continuous within the f32 rounding of the pieces'
//!   points, the curvature 0 on both sides; the path starts at the start along its heading
//!   and ends at the goal (along its heading when given); every line lies on the coarse
//!   polyline or on a segment `clear` accepted; every corner's hull triangle was offered to
//!   `clear`; the counted work is within `fit_work_bound`, the calls to `clear` within
//!   `fit_clear_bound` (itself `2(n + 4) + 1`, worked out by hand);
//! * **`clear`**: a refused triangle gives `CornerBlocked` naming its corner, a refused segment
//!   `SegmentBlocked`; `out` is untouched on every error;
//! * **bad input** (NaN, infinities, empty waypoints, `κ_max` 0, negative or NaN, capacity 1,
//!   a corrupted table, thousands of points, repeated points, reversals) never panics;
//! * **pieces**: the length bounds contain the f64 length, the chord deviation bound holds.

use host_tests::{cases, reference, Rng};
use skyroute::geometry::spline::fit::LEAD_ROUNDS;
use skyroute::geometry::spline::table::{
    build_corner_table, corner_bound, table_angle, table_ratio, TABLE_LEN, TABLE_RATIOS,
};
use skyroute::geometry::spline::{
    fit, fit_clear_bound, fit_work_bound, FitError, FitInput, Piece, Vertex, TABLE_MAX_ANGLE,
};
use skyroute::geometry::{Pose, Vec2};

type V = [f64; 2];

fn v64(v: Vec2) -> V {
    [v.x as f64, v.y as f64]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}
fn cross(a: V, b: V) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn norm(a: V) -> f64 {
    (a[0] * a[0] + a[1] * a[1]).sqrt()
}

/// A cubic Bézier's first and second derivatives at `t`, f64, from its control points.
fn bez_d(p: &[V; 4], t: f64) -> (V, V) {
    let u = 1.0 - t;
    let mut d1 = [0.0; 2];
    let mut d2 = [0.0; 2];
    for k in 0..2 {
        d1[k] = 3.0
            * (u * u * (p[1][k] - p[0][k])
                + 2.0 * u * t * (p[2][k] - p[1][k])
                + t * t * (p[3][k] - p[2][k]));
        d2[k] = 6.0
            * (u * (p[2][k] - 2.0 * p[1][k] + p[0][k]) + t * (p[3][k] - 2.0 * p[2][k] + p[1][k]));
    }
    (d1, d2)
}
fn bez_point(p: &[V; 4], t: f64) -> V {
    let u = 1.0 - t;
    let w = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
    let mut r = [0.0; 2];
    for (k, pk) in p.iter().enumerate() {
        r[0] += w[k] * pk[0];
        r[1] += w[k] * pk[1];
    }
    r
}

/// `|x′y″ − y′x″| / (x′² + y′²)^{3/2}`.
fn curvature(p: &[V; 4], t: f64) -> f64 {
    let (d1, d2) = bez_d(p, t);
    let n = norm(d1);
    if n == 0.0 {
        return f64::INFINITY;
    }
    cross(d1, d2).abs() / (n * n * n)
}

/// Largest curvature over `n + 1` equally spaced parameters.
fn max_curvature(p: &[V; 4], n: usize) -> f64 {
    (0..=n)
        .map(|k| curvature(p, k as f64 / n as f64))
        .fold(0.0, f64::max)
}

/// True `c(θ, ρ)`: the corner piece A = (−1, 0), P = P = (0, 0), B = ρ·(cos θ, sin θ) has
/// s1 = 1, so its largest curvature is `c`. 20 000 samples, then a local refinement.
fn c_true(theta: f64, rho: f64) -> f64 {
    let p = [
        [-1.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [rho * theta.cos(), rho * theta.sin()],
    ];
    let n = 20_000;
    let (mut best, mut kb) = (0.0, 0usize);
    for k in 0..=n {
        let c = curvature(&p, k as f64 / n as f64);
        if c > best {
            best = c;
            kb = k;
        }
    }
    // Ternary refinement between the neighbouring samples.
    let (mut lo, mut hi) = (
        kb.saturating_sub(1) as f64 / n as f64,
        (kb + 1).min(n) as f64 / n as f64,
    );
    for _ in 0..60 {
        let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if curvature(&p, a) < curvature(&p, b) {
            lo = a;
        } else {
            hi = b;
        }
    }
    best.max(curvature(&p, 0.5 * (lo + hi)))
}

#[test]
fn table_never_below_sampled_curvature() {
    let table = build_corner_table();
    // Nodes within the margin.
    for i in (0..61).step_by(4) {
        for j in 0..TABLE_RATIOS {
            let (th, rho) = (
                table_angle(i).unwrap() as f64,
                table_ratio(j).unwrap() as f64,
            );
            let c = c_true(th, rho);
            let v = table[i * TABLE_RATIOS + j] as f64;
            assert!(
                v >= c && v <= c * 1.0101 + 1e-12,
                "node ({i}, {j}): {v} vs {c}"
            );
        }
    }
    let mut rng = Rng(0x5911_e001);
    let mut worst: f64 = 1.0;
    for _ in 0..cases(300, 3000) {
        let theta = rng.range(1e-3, TABLE_MAX_ANGLE as f64) as f32;
        let j = rng.below(TABLE_RATIOS as u64) as usize;
        let b = corner_bound(&table, theta, j).unwrap() as f64;
        let c = c_true(theta as f64, table_ratio(j).unwrap() as f64);
        assert!(
            b >= c,
            "θ {theta} ratio {j}: bound {b} below the sampled {c}"
        );
        worst = worst.max(b / c);
        assert!(b <= 1.35 * c, "θ {theta} ratio {j}: bound {b} vs {c}");
    }
    eprintln!("corner table: bound / sampled curvature at most {worst:.4}");
    // Outside the table.
    assert!(corner_bound(&table, TABLE_MAX_ANGLE * 1.001, 0).is_none());
    assert!(corner_bound(&table, f32::NAN, 0).is_none());
    assert!(corner_bound(&table, -0.1, 0).is_none());
    assert!(corner_bound(&table, 1.0, TABLE_RATIOS).is_none());
}

#[test]
fn c_is_monotone_in_the_turn_angle() {
    for j in 0..TABLE_RATIOS {
        let rho = table_ratio(j).unwrap() as f64;
        let mut prev = 0.0;
        let steps = cases(300, 1500);
        for k in 0..=steps {
            let th = TABLE_MAX_ANGLE as f64 * k as f64 / steps as f64;
            let c = c_true(th, rho);
            assert!(
                c >= prev * (1.0 - 1e-9),
                "ratio {rho}: c({th}) = {c} < {prev}"
            );
            prev = c;
        }
    }
}

// --------------------------------------------------------------------------------------------
// The fit.

struct Case {
    start: Pose,
    waypoints: Vec<Vec2>,
    goal: Vec2,
    goal_heading: Option<f32>,
    kappa: f32,
}

fn random_case(rng: &mut Rng) -> Case {
    let r = rng.log_range(20.0, 500.0);
    let n = rng.int(0, 10) as usize;
    let mut pts = vec![[rng.range(-2000.0, 2000.0), rng.range(-2000.0, 2000.0)]];
    let mut dir: f64 = rng.range(-3.2, 3.2);
    for _ in 0..=n {
        let turn = match rng.below(4) {
            0 => rng.range(-1e-3, 1e-3),
            1 => rng.sign() * (std::f64::consts::PI - rng.range(0.0, 2e-2)),
            _ => rng.range(-3.1, 3.1),
        };
        dir += turn;
        let len = if rng.chance(0.1) {
            rng.log_range(0.01, 5.0)
        } else {
            rng.log_range(5.0, 20_000.0)
        };
        let last = *pts.last().unwrap();
        pts.push([last[0] + len * dir.cos(), last[1] + len * dir.sin()]);
    }
    let f = |p: &[f64; 2]| Vec2::new(p[0] as f32, p[1] as f32);
    Case {
        start: Pose::new(
            pts[0][0] as f32,
            pts[0][1] as f32,
            rng.range(-3.2, 3.2) as f32,
        ),
        waypoints: pts[1..=n].iter().map(f).collect(),
        goal: f(&pts[n + 1]),
        goal_heading: rng.chance(0.5).then(|| rng.range(-3.2, 3.2) as f32),
        kappa: (1.0 / r) as f32,
    }
}

fn input(c: &Case) -> FitInput<'_> {
    FitInput {
        start: c.start,
        waypoints: &c.waypoints,
        goal: c.goal,
        goal_heading: c.goal_heading,
        kappa_max: c.kappa,
    }
}

fn angle_between(a: V, b: V) -> f64 {
    cross(a, b).atan2(a[0] * b[0] + a[1] * b[1]).abs()
}

/// The f64 tangent (not unit) at the start or end of a piece and the length that rounding of
/// its points is measured against.
fn end_tangent(p: &Piece, at_end: bool) -> (V, f64) {
    match *p {
        Piece::Line { a, b } => {
            let d = sub(v64(b), v64(a));
            (d, norm(d))
        }
        Piece::Cubic { p } => {
            let q = p.map(v64);
            let (d1, _) = bez_d(&q, if at_end { 1.0 } else { 0.0 });
            let leg = if at_end {
                norm(sub(q[3], q[2]))
            } else {
                norm(sub(q[1], q[0]))
            };
            (d1, leg)
        }
    }
}

/// The f32 rounding of the points, as an angle over a length `l`.
fn tangent_tol(mag: f64, l: f64) -> f64 {
    1e-5 + 8.0 * f32::EPSILON as f64 * mag / l
}

#[derive(Default)]
struct Record {
    segments: Vec<(Vec2, Vec2)>,
    triangles: Vec<[Vec2; 3]>,
}

fn check_fit(c: &Case, out: &[Piece], rec: &Record, work: u64) {
    let kappa = c.kappa as f64;
    let mut mag: f64 = 1.0;
    for p in c.waypoints.iter().chain([&c.start.position, &c.goal]) {
        mag = mag.max(p.x.abs() as f64).max(p.y.abs() as f64);
    }
    assert!(work <= fit_work_bound(c.waypoints.len()), "work {work}");
    let clears = (rec.segments.len() + rec.triangles.len()) as u64;
    assert!(
        clears <= fit_clear_bound(c.waypoints.len()),
        "{clears} clearance queries for {} waypoints",
        c.waypoints.len()
    );
    assert!(!out.is_empty());
    assert_eq!(out[0].start(), c.start.position);
    assert_eq!(out.last().unwrap().end(), c.goal);
    // Start and goal headings.
    let (t0, l0) = end_tangent(&out[0], false);
    let h0 = [c.start.heading.cos() as f64, c.start.heading.sin() as f64];
    assert!(
        angle_between(t0, h0) <= tangent_tol(mag, l0) + 1e-6,
        "start tangent"
    );
    if let Some(hg) = c.goal_heading {
        let (t1, l1) = end_tangent(out.last().unwrap(), true);
        let h = [hg.cos() as f64, hg.sin() as f64];
        assert!(
            angle_between(t1, h) <= tangent_tol(mag, l1) + 1e-6,
            "goal tangent"
        );
    }
    // Coarse polyline and accepted segments.
    let mut coarse: Vec<(V, V)> = Vec::new();
    let mut all = vec![c.start.position];
    all.extend(&c.waypoints);
    all.push(c.goal);
    for w in all.windows(2) {
        coarse.push((v64(w[0]), v64(w[1])));
    }
    for s in &rec.segments {
        coarse.push((v64(s.0), v64(s.1)));
    }
    let on_lines = |p: V| {
        coarse.iter().any(|(a, b)| {
            reference::dist_point_segment((p[0], p[1]), (a[0], a[1]), (b[0], b[1])) <= 1e-5 * mag
        })
    };
    for (k, piece) in out.iter().enumerate() {
        match *piece {
            Piece::Line { a, b } => {
                assert!(
                    on_lines(v64(a)) && on_lines(v64(b)),
                    "line {k} off the polyline"
                );
                // Both ends on one segment.
                let ok = coarse.iter().any(|(s, e)| {
                    [a, b].iter().all(|p| {
                        reference::dist_point_segment(
                            (p.x as f64, p.y as f64),
                            (s[0], s[1]),
                            (e[0], e[1]),
                        ) <= 1e-5 * mag
                    })
                });
                assert!(ok, "line {k} not on one segment");
            }
            Piece::Cubic { p } => {
                assert_eq!(p[1], p[2]);
                assert!(
                    rec.triangles.contains(&[p[0], p[1], p[3]]),
                    "cubic {k}: hull not offered"
                );
                let q = p.map(v64);
                let m = max_curvature(&q, 2000);
                assert!(
                    m <= kappa * (1.0 + 1e-3),
                    "cubic {k}: curvature {m} > {kappa}: {q:?} legs {} {} angle {} pieces {}",
                    norm(sub(q[1], q[0])),
                    norm(sub(q[3], q[2])),
                    angle_between(sub(q[1], q[0]), sub(q[3], q[2])).to_degrees(),
                    out.len()
                );
                for t in [0.0, 1.0] {
                    assert!(curvature(&q, t) <= kappa * 1e-3, "cubic {k}: end curvature");
                }
            }
        }
    }
    for (k, w) in out.windows(2).enumerate() {
        assert_eq!(w[0].end(), w[1].start(), "knot {k}: position");
        let (ta, la) = end_tangent(&w[0], true);
        let (tb, lb) = end_tangent(&w[1], false);
        let tol = tangent_tol(mag, la.min(lb));
        let err = angle_between(ta, tb);
        assert!(
            err <= tol,
            "knot {k}: tangent jump {err} > {tol} ({la}, {lb})"
        );
    }
}

fn run_fit(
    c: &Case,
    rec: &mut Record,
    out: &mut heapless::Vec<Piece, 256>,
) -> Result<skyroute::geometry::spline::FitSummary, FitError> {
    let table = build_corner_table();
    let mut clear = |pts: &[Vec2]| {
        match pts {
            [a, b] => rec.segments.push((*a, *b)),
            [a, b, c] => rec.triangles.push([*a, *b, *c]),
            _ => panic!("clear asked about {} points", pts.len()),
        }
        true
    };
    fit(&input(c), &table, &mut clear, out)
}

/// `fit_clear_bound` is its documented `2(n + 4) + 1`, worked out by hand: 9 with no waypoint,
/// 35 with 13, and saturated rather than wrapped for the largest count.
#[test]
fn the_clearance_query_bound_is_its_documented_count() {
    assert_eq!(fit_clear_bound(0), 9);
    assert_eq!(fit_clear_bound(13), 35);
    assert_eq!(fit_clear_bound(usize::MAX), u64::MAX);
}

#[test]
fn random_fits_are_flyable_and_continuous() {
    let mut rng = Rng(0x5911_e002);
    let (mut ok, mut errs, mut dropped, mut two) = (0, 0, 0, 0);
    let n = cases(400, 4000);
    for case in 0..n {
        let c = random_case(&mut rng);
        let mut rec = Record::default();
        let mut out = heapless::Vec::new();
        match run_fit(&c, &mut rec, &mut out) {
            Ok(s) => {
                ok += 1;
                dropped += s.dropped;
                two += (s.lead_in == 2) as usize;
                assert_eq!(s.pieces, out.len());
                check_fit(&c, &out, &rec, s.work);
                let _ = case;
            }
            Err(FitError::LeadInInfeasible | FitError::LeadOutInfeasible) => errs += 1,
            Err(e) => panic!("case {case}: {e:?}"),
        }
    }
    eprintln!("spline fits: {ok} ok ({dropped} waypoints dropped, {two} two-corner lead-ins), {errs} lead infeasible of {n}");
    // The rest are ends within a few turn radii at an adverse heading: they need a loop that
    // two corners of at most 150° each cannot fly.
    assert!(ok * 100 >= n * 85, "only {ok} of {n} fitted");
}

#[test]
fn refused_triangles_and_segments_are_named_and_out_is_untouched() {
    let table = build_corner_table();
    let mut rng = Rng(0x5911_e003);
    let sentinel = Piece::Line {
        a: Vec2::new(1.0, 2.0),
        b: Vec2::new(3.0, 4.0),
    };
    let (mut tri, mut seg) = (0, 0);
    for _ in 0..cases(200, 2000) {
        let c = random_case(&mut rng);
        let mut rec = Record::default();
        let mut out = heapless::Vec::new();
        let Ok(s) = run_fit(&c, &mut rec, &mut out) else {
            continue;
        };
        // The corner each cubic belongs to, from the summary and the waypoints' positions.
        let cubics: Vec<[Vec2; 4]> = out
            .iter()
            .filter_map(|p| {
                if let Piece::Cubic { p } = p {
                    Some(*p)
                } else {
                    None
                }
            })
            .collect();
        let k = rng.below(cubics.len() as u64) as usize;
        let p = cubics[k];
        let expect = match c.waypoints.iter().position(|w| *w == p[1]) {
            Some(i) => Vertex::Waypoint(i),
            None if k < s.lead_in => Vertex::LeadIn(k as u8),
            None => Vertex::LeadOut((k - (s.corners - s.lead_out)) as u8),
        };
        let refused = [p[0], p[1], p[3]];
        let mut out2: heapless::Vec<Piece, 256> = heapless::Vec::new();
        out2.push(sentinel).unwrap();
        let r = fit(
            &input(&c),
            &table,
            &mut |pts: &[Vec2]| pts != refused,
            &mut out2,
        );
        assert_eq!(r, Err(FitError::CornerBlocked { corner: expect }));
        assert_eq!(out2.as_slice(), &[sentinel]);
        tri += 1;
        // A refused new segment.
        if let Some(&(a, b)) = rec.segments.first() {
            let mut out3: heapless::Vec<Piece, 256> = heapless::Vec::new();
            out3.push(sentinel).unwrap();
            let r = fit(
                &input(&c),
                &table,
                &mut |pts: &[Vec2]| pts != [a, b],
                &mut out3,
            );
            assert!(matches!(r, Err(FitError::SegmentBlocked { .. })), "{r:?}");
            assert_eq!(out3.as_slice(), &[sentinel]);
            seg += 1;
        }
    }
    eprintln!("clear refusals: {tri} triangles, {seg} segments");
}

#[test]
fn bad_input_never_panics() {
    let table = build_corner_table();
    let base = Case {
        start: Pose::new(0.0, 0.0, 0.3),
        waypoints: vec![Vec2::new(1000.0, 0.0), Vec2::new(1000.0, 1000.0)],
        goal: Vec2::new(2000.0, 1500.0),
        goal_heading: Some(1.0),
        kappa: 0.01,
    };
    let sentinel = Piece::Line {
        a: Vec2::new(1.0, 2.0),
        b: Vec2::new(3.0, 4.0),
    };
    let run = |c: &Case, t: &[f32; TABLE_LEN]| {
        let mut out: heapless::Vec<Piece, 64> = heapless::Vec::new();
        out.push(sentinel).unwrap();
        let r = fit(&input(c), t, &mut |_: &[Vec2]| true, &mut out);
        if r.is_err() {
            assert_eq!(out.as_slice(), &[sentinel]);
        }
        r
    };
    assert!(run(&base, &table).is_ok());
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.start.position.x = bad;
        assert_eq!(run(&c, &table), Err(FitError::NonFinite));
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.start.heading = bad;
        assert_eq!(run(&c, &table), Err(FitError::NonFinite));
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.goal.y = bad;
        assert_eq!(run(&c, &table), Err(FitError::NonFinite));
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.goal_heading = Some(bad);
        assert_eq!(run(&c, &table), Err(FitError::NonFinite));
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.waypoints[1].x = bad;
        assert_eq!(run(&c, &table), Err(FitError::NonFinite));
        let mut c = Case {
            waypoints: base.waypoints.clone(),
            ..base
        };
        c.kappa = bad;
        assert_eq!(run(&c, &table), Err(FitError::BadCurvature));
        let mut t = table;
        t[100] = bad;
        assert_eq!(run(&base, &t), Err(FitError::BadTable));
    }
    for k in [0.0, -0.01, -0.0, f32::MIN_POSITIVE / 4.0] {
        let c = Case {
            waypoints: base.waypoints.clone(),
            kappa: k,
            ..base
        };
        let r = run(&c, &table);
        assert!(r.is_err() || k > 0.0, "{k}: {r:?}");
    }
    let c = Case {
        waypoints: vec![Vec2::new(2e7, 0.0)],
        ..base
    };
    assert_eq!(run(&c, &table), Err(FitError::OutOfRange));
    // Empty waypoints, with and without a goal heading.
    for gh in [None, Some(0.5)] {
        let c = Case {
            waypoints: vec![],
            goal_heading: gh,
            ..base
        };
        assert!(run(&c, &table).is_ok());
    }
    // Capacity 1.
    let mut out: heapless::Vec<Piece, 1> = heapless::Vec::new();
    out.push(sentinel).unwrap();
    let r = fit(&input(&base), &table, &mut |_: &[Vec2]| true, &mut out);
    assert_eq!(r, Err(FitError::RouteTooLong { capacity: 1 }));
    assert_eq!(out.as_slice(), &[sentinel]);
    // Repeated points, reversals, the goal on the start, huge and tiny curvatures.
    let mut rng = Rng(0x5911_e004);
    for _ in 0..cases(300, 3000) {
        let n = rng.int(0, 8) as usize;
        let mut pts = Vec::new();
        for _ in 0..n {
            let p = match rng.below(4) {
                0 => pts.last().copied().unwrap_or(Vec2::new(0.0, 0.0)),
                1 if pts.len() >= 2 => pts[pts.len() - 2],
                _ => Vec2::new(rng.range_f32(-500.0, 500.0), rng.range_f32(-500.0, 500.0)),
            };
            pts.push(p);
        }
        let c = Case {
            start: Pose::new(0.0, 0.0, rng.range_f32(-4.0, 4.0)),
            waypoints: pts,
            goal: if rng.chance(0.2) {
                Vec2::new(0.0, 0.0)
            } else {
                Vec2::new(rng.range_f32(-500.0, 500.0), 300.0)
            },
            goal_heading: rng.chance(0.5).then(|| rng.range_f32(-4.0, 4.0)),
            kappa: rng.log_range(1e-30, 1e30) as f32,
        };
        let mut rec = Record::default();
        let mut out = heapless::Vec::new();
        if let Ok(s) = run_fit(&c, &mut rec, &mut out) {
            assert!(s.work <= fit_work_bound(c.waypoints.len()));
            assert_eq!(out.last().unwrap().end(), c.goal);
        }
    }
}

#[test]
fn thousands_of_points_within_the_work_bound() {
    let table = build_corner_table();
    let mut rng = Rng(0x5911_e005);
    for _ in 0..cases(2, 10) {
        let n = 3000;
        let mut p = [0.0f64, 0.0];
        let mut dir: f64 = 0.0;
        let pts: Vec<Vec2> = (0..n)
            .map(|_| {
                dir += rng.range(-2.5, 2.5);
                let l = rng.log_range(1.0, 2000.0);
                p = [p[0] + l * dir.cos(), p[1] + l * dir.sin()];
                Vec2::new(p[0] as f32, p[1] as f32)
            })
            .collect();
        let c = Case {
            start: Pose::new(0.0, 0.0, 0.0),
            waypoints: pts,
            goal: Vec2::new(p[0] as f32 + 500.0, p[1] as f32),
            goal_heading: Some(0.0),
            kappa: 1.0 / 50.0,
        };
        let mut out: heapless::Vec<Piece, 8192> = heapless::Vec::new();
        let mut rec = Record::default();
        let r = fit(
            &input(&c),
            &table,
            &mut |pts: &[Vec2]| {
                match pts {
                    [a, b] => rec.segments.push((*a, *b)),
                    [a, b, c] => rec.triangles.push([*a, *b, *c]),
                    _ => {}
                }
                true
            },
            &mut out,
        );
        let s = r.expect("a long random walk fits");
        assert!(
            s.work <= fit_work_bound(n),
            "{} > {}",
            s.work,
            fit_work_bound(n)
        );
        check_fit(&c, &out, &rec, s.work);
        eprintln!(
            "3000 points: {} pieces, {} dropped, work {} of bound {} (LEAD_ROUNDS {LEAD_ROUNDS})",
            s.pieces,
            s.dropped,
            s.work,
            fit_work_bound(n)
        );
        // Too small a capacity.
        let mut small: heapless::Vec<Piece, 512> = heapless::Vec::new();
        assert_eq!(
            fit(&input(&c), &table, &mut |_: &[Vec2]| true, &mut small),
            Err(FitError::RouteTooLong { capacity: 512 })
        );
        assert!(small.is_empty());
    }
}

#[test]
fn piece_length_and_chords_against_f64() {
    let mut rng = Rng(0x5911_e006);
    for _ in 0..cases(200, 2000) {
        let pt =
            |rng: &mut Rng| Vec2::new(rng.range_f32(-100.0, 100.0), rng.range_f32(-100.0, 100.0));
        let (a, p, b) = (pt(&mut rng), pt(&mut rng), pt(&mut rng));
        let piece = Piece::Cubic { p: [a, p, p, b] };
        let q = [a, p, p, b].map(v64);
        // f64 length by 100 000 chords (error below 10⁻⁸ relative for these curves).
        let n = 100_000;
        let mut l = 0.0;
        for k in 0..n {
            l += norm(sub(
                bez_point(&q, (k + 1) as f64 / n as f64),
                bez_point(&q, k as f64 / n as f64),
            ));
        }
        let (lo, hi) = piece.length_bounds();
        let tol = 1e-5 * l + 1e-4;
        assert!(
            lo as f64 <= l + tol && l <= hi as f64 + tol,
            "{lo} {l} {hi}"
        );
        // Chord deviation.
        let tol_m = rng.log_range(1e-3, 10.0) as f32;
        let Some(m) = piece.chords_for_deviation(tol_m) else {
            continue;
        };
        let dev = piece.chord_deviation(m);
        assert!(dev <= tol_m * 1.0001);
        let pts: Vec<V> = piece.chord_points(m).map(v64).collect();
        assert_eq!(pts.len(), m as usize + 1);
        for k in 0..m as usize {
            for s in 1..20 {
                let t = (k as f64 + s as f64 / 20.0) / m as f64;
                let x = bez_point(&q, t);
                let d = reference::dist_point_segment(
                    (x[0], x[1]),
                    (pts[k][0], pts[k][1]),
                    (pts[k + 1][0], pts[k + 1][1]),
                );
                assert!(d <= dev as f64 + 1e-4, "deviation {d} > {dev}");
            }
        }
    }
}
