//! The exposure of Judd & McLain's three-point rule (`skyroute::planner::segment_exposure`)
//! against the integral it approximates, ∫₀ᴸ Σ_j (r_j/d_j(s))⁴ ds, computed here in f64 by
//! adaptive Simpson quadrature: within 2 % for segments whose sites are at least three
//! lengths away (the midpoint rule's error on a convex integrand), and the two directions of its error near a site that `docs/THREATS.md`
//! states — over-estimated when the middle sample sits at the near pass, under-estimated when
//! the pass falls between samples.

use host_tests::rng::Rng;
use skyroute::planner::{segment_exposure, Threat, ThreatOrigin};
use skyroute::Vec2;

/// (r/d)⁴ summed over the threats at `p`, with the planner's floor d ≥ 0.01·r.
fn density(p: (f64, f64), threats: &[Threat]) -> f64 {
    threats
        .iter()
        .map(|t| {
            let r = t.radius as f64;
            let d = ((p.0 - t.position.x as f64).powi(2) + (p.1 - t.position.y as f64).powi(2))
                .sqrt()
                .max(0.01 * r);
            (r / d).powi(4)
        })
        .sum()
}

/// A panel of the adaptive Simpson rule: its ends and midpoint with their values, and the
/// panel's Simpson estimate.
#[derive(Clone, Copy)]
struct Panel {
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
}

/// ∫ of `f` over the panel by adaptive Simpson to relative tolerance `tol` (Richardson
/// corrected), at most `depth` halvings deep.
fn refine(f: &dyn Fn(f64) -> f64, p: Panel, tol: f64, depth: u32) -> f64 {
    let m = 0.5 * (p.a + p.b);
    let (flm, frm) = (f(0.5 * (p.a + m)), f(0.5 * (m + p.b)));
    let left = (m - p.a) / 6.0 * (p.fa + 4.0 * flm + p.fm);
    let right = (p.b - m) / 6.0 * (p.fm + 4.0 * frm + p.fb);
    if depth == 0 || (left + right - p.whole).abs() <= 15.0 * tol * (left + right).abs() {
        return left + right + (left + right - p.whole) / 15.0;
    }
    let l = Panel {
        a: p.a,
        b: m,
        fa: p.fa,
        fm: flm,
        fb: p.fm,
        whole: left,
    };
    let r = Panel {
        a: m,
        b: p.b,
        fa: p.fm,
        fm: frm,
        fb: p.fb,
        whole: right,
    };
    refine(f, l, tol, depth - 1) + refine(f, r, tol, depth - 1)
}

/// ∫ of `f` over [a, b] by adaptive Simpson to relative tolerance `tol`.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    let (fa, fb, fm) = (f(a), f(b), f(0.5 * (a + b)));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    refine(
        f,
        Panel {
            a,
            b,
            fa,
            fm,
            fb,
            whole,
        },
        tol,
        48,
    )
}

/// The integral along `a → b`, f64.
fn integral(a: Vec2, b: Vec2, threats: &[Threat]) -> f64 {
    let (ax, ay, bx, by) = (a.x as f64, a.y as f64, b.x as f64, b.y as f64);
    let l = ((bx - ax).powi(2) + (by - ay).powi(2)).sqrt();
    let f = |s: f64| density((ax + s / l * (bx - ax), ay + s / l * (by - ay)), threats);
    simpson(&f, 0.0, l, 1e-10)
}

fn threat(x: f32, y: f32, r: f32) -> Threat {
    Threat {
        position: Vec2::new(x, y),
        radius: r,
        origin: ThreatOrigin::Network(0),
    }
}

#[test]
fn the_rule_matches_the_integral_far_from_every_site() {
    let mut rng = Rng(71);
    let mut worst: f64 = 0.0;
    for _ in 0..host_tests::cases(500, 5000) {
        let l = rng.range(10.0, 20_000.0) as f32;
        let a = Vec2::new(rng.range(-5e4, 5e4) as f32, rng.range(-5e4, 5e4) as f32);
        let (ux, uy) = rng.unit_vector();
        let b = a + Vec2::new(ux as f32, uy as f32) * l;
        // Sites at least 3 lengths from the segment's midpoint.
        let threats: Vec<Threat> = (0..1 + rng.below(5))
            .map(|_| {
                let (vx, vy) = rng.unit_vector();
                let d = rng.range(3.0, 20.0) * l as f64;
                let m = (a + b) * 0.5;
                threat(
                    m.x + (vx * d) as f32,
                    m.y + (vy * d) as f32,
                    rng.range(500.0, 5000.0) as f32,
                )
            })
            .collect();
        let rule = segment_exposure(a, b, &threats).0 as f64;
        let exact = integral(a, b, &threats);
        let rel = (rule - exact).abs() / exact;
        worst = worst.max(rel);
        assert!(
            rel <= 0.02,
            "far segment: rule {rule}, integral {exact} ({:.3} %)",
            100.0 * rel
        );
    }
    println!(
        "three-point rule, sites ≥ 3 lengths away: worst relative error {:.4} %",
        100.0 * worst
    );
}

/// The rule over the integral for one site at perpendicular distance `h` from the line of a
/// segment of length `l` whose closest point lies at fraction `at` along it.
fn ratio(l: f32, h: f32, at: f32) -> f64 {
    let t = [threat(at * l, h, 1000.0)];
    let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(l, 0.0));
    segment_exposure(a, b, &t).0 as f64 / integral(a, b, &t)
}

#[test]
fn near_a_site_the_rule_errs_in_the_directions_the_docs_state() {
    let l = 6000.0;
    // The middle sample at the near pass (h = L/60): over-estimated.
    let over = ratio(l, l / 60.0, 0.5);
    assert!(
        over > 1.5,
        "middle sample at the pass: rule/integral {over}"
    );
    // The pass halfway between the L/6 and L/2 samples (at L/3): under-estimated.
    let under = ratio(l, l / 60.0, 1.0 / 3.0);
    assert!(under < 0.5, "pass between samples: rule/integral {under}");
    // A table for the docs: rule/integral by h/L and where the pass falls.
    for h in [0.01f32, 0.05, 0.1, 0.25, 0.5, 1.0] {
        let row: Vec<String> = [0.0f32, 1.0 / 6.0, 1.0 / 3.0, 0.5]
            .iter()
            .map(|&at| format!("{:8.3}", ratio(l, h * l, at)))
            .collect();
        println!("h/L {h:5.2}: pass at 0, L/6, L/3, L/2 -> {}", row.join(" "));
    }
}

/// A sample closer to a site than 1 % of its reference distance counts at that floor: on the
/// site, or 0.5 m from a site of r = 100 m, it weighs (1/0.01)⁴ = 10⁸ per metre; 2 m from it,
/// (100/2)⁴. The rule evaluates three terms per threat.
#[test]
fn a_sample_at_a_site_weighs_the_floor_and_each_threat_costs_three_terms() {
    let l = 600.0f32;
    let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(l, 0.0));
    // The middle sample at x = 300 m; the other two at 100 m and 500 m, 200 m from the site.
    for (offset, weight) in [(0.0f32, 1e8f64), (0.5, 1e8), (2.0, 50f64.powi(4))] {
        let t = [threat(300.0, offset, 100.0)];
        let (j, terms) = segment_exposure(a, b, &t);
        let side = (100.0 / (200.0f64.powi(2) + (offset as f64).powi(2)).sqrt()).powi(4);
        let expected = l as f64 / 3.0 * (weight + 2.0 * side);
        assert!(
            (j as f64 - expected).abs() <= 1e-5 * expected,
            "site {offset} m off the middle sample: {j}, expected {expected}"
        );
        assert_eq!(terms, 3);
    }
    let far: Vec<Threat> = (0..5)
        .map(|i| threat(1e5, 1e4 * i as f32, 1000.0))
        .collect();
    for n in 0..=far.len() {
        assert_eq!(
            segment_exposure(a, b, &far[..n]).1,
            3 * n as u64,
            "{n} threats"
        );
    }
}
