//! The risk model against a direct f64 evaluation written here from the formulas: the
//! ellipsoid's projected area against a numerical shadow (the largest extent of the ellipsoid
//! in each direction of the projection plane), the detection probability against eq. 7 in its
//! unscaled form with `c₂ = R_½^{−4c₁}`, and a route's survival, time and fuel figures against
//! f64 sampling of its lines and arcs.

use skyroute::geometry::{Arc, Segment};
use skyroute::planner::risk::{
    alternative, detection_at, detection_probability, projected_area, route_figures, time_factor,
    Airframe, AlternativeRisk, RadarModel, RiskParams, RouteFigures,
};
use skyroute::{Pose, Primitive, Vec2};

fn params() -> RiskParams {
    RiskParams {
        radar: RadarModel {
            range_max_m: 50_000.0,
            half_range_m: 8_000.0,
            c1: 2.0,
            altitude_m: 1_000.0,
        },
        airframe: Airframe {
            half_length_m: 1.5,
            half_span_m: 2.5,
            half_height_m: 0.25,
            k: 0.1,
        },
        dt_s: 1.0,
        speed_mps: 50.0,
        kill_per_step: 0.0002,
        max_turn_rate: 0.3,
    }
}

/// The shadow's area by integration: the support function h(θ) of the ellipsoid's projection
/// onto the plane ⟂ d, area = ½∮(h² − h′²) dθ, with h(u) = sqrt(uᵀ diag(a², b², c²) u).
fn shadow_area(a: f64, b: f64, c: f64, d: [f64; 3]) -> f64 {
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let d = [d[0] / n, d[1] / n, d[2] / n];
    let helper = if d[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |x: [f64; 3], y: [f64; 3]| {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    };
    let e1 = cross(d, helper);
    let m = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
    let e1 = [e1[0] / m, e1[1] / m, e1[2] / m];
    let e2 = cross(d, e1);
    let h = |t: f64| {
        let u = [0, 1, 2].map(|i| t.cos() * e1[i] + t.sin() * e2[i]);
        (a * a * u[0] * u[0] + b * b * u[1] * u[1] + c * c * u[2] * u[2]).sqrt()
    };
    // Polygon through the boundary points h(θ)u + h′(θ)u⊥ (the shadow is convex).
    let n = 20_000;
    let mut pts = Vec::with_capacity(n);
    for i in 0..n {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        let dt = 1e-6;
        let hp = (h(t + dt) - h(t - dt)) / (2.0 * dt);
        let (ux, uy) = (t.cos(), t.sin());
        pts.push((h(t) * ux - hp * uy, h(t) * uy + hp * ux));
    }
    let mut area = 0.0;
    for i in 0..n {
        let (p, q) = (pts[i], pts[(i + 1) % n]);
        area += p.0 * q.1 - q.0 * p.1;
    }
    area.abs() / 2.0
}

#[test]
fn projected_area_is_the_ellipsoid_shadow() {
    let f = params().airframe;
    let dirs: [[f64; 3]; 6] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.6, -0.7, 0.2],
        [-0.3, 0.2, -0.9],
        [0.99, 0.05, -0.124],
    ];
    for d in dirs {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let unit = [d[0] / n, d[1] / n, d[2] / n].map(|x| x as f32);
        let got = projected_area(&f, unit) as f64;
        let want = shadow_area(1.5, 2.5, 0.25, d);
        assert!(
            (got - want).abs() <= 1e-4 * want,
            "direction {d:?}: {got} against the shadow's {want}"
        );
    }
}

#[test]
fn detection_probability_is_eq_7() {
    let radar = params().radar;
    let c2 = 8_000f64.powf(-4.0 * 2.0);
    for &sigma in &[0.01f64, 0.3, 1.0, 4.0] {
        for i in 0..=120 {
            let r = 500.0 * i as f64;
            let want = if r > 50_000.0 {
                0.0
            } else {
                1.0 / (1.0 + c2 * (r.powi(4) / sigma).powf(2.0))
            };
            let got = detection_probability(&radar, sigma as f32, r as f32) as f64;
            assert!(
                (got - want).abs() <= 1e-5 + 1e-4 * want,
                "σ {sigma}, R {r}: {got} against {want}"
            );
        }
    }
    let half = detection_probability(&radar, 1.0, 8_000.0);
    assert!((half - 0.5).abs() < 1e-6, "P_t(R_½, 1 m²) = {half}");
    assert_eq!(detection_probability(&radar, 1.0, 50_001.0), 0.0);
    // R_max itself is within range: eq. 7's value there, not 0.
    let at_max = detection_probability(&radar, 1.0, 50_000.0) as f64;
    let want = 1.0 / (1.0 + 8_000f64.powf(-8.0) * 50_000f64.powi(8));
    assert!(
        (at_max - want).abs() < 1e-3 * want,
        "P_t(R_max) = {at_max}, want {want}"
    );
}

/// f64 figures of a route: samples at the middle of M equal steps, the same model.
fn reference(p: &RiskParams, route: &[Primitive], known: &[Vec2], popup: Vec2) -> [f64; 4] {
    let pose = |s: f64| -> (f64, f64, f64) {
        let mut base = 0.0;
        for (i, q) in route.iter().enumerate() {
            let len = q.length() as f64;
            if s <= base + len || i + 1 == route.len() {
                let t = s - base;
                return match q {
                    Primitive::Line(l) => {
                        let (dx, dy) = ((l.end.x - l.start.x) as f64, (l.end.y - l.start.y) as f64);
                        let n = dx.hypot(dy);
                        (
                            l.start.x as f64 + dx * t / n,
                            l.start.y as f64 + dy * t / n,
                            dy.atan2(dx),
                        )
                    }
                    Primitive::Arc(a) => {
                        let sign = a.sweep.signum() as f64;
                        let ang = a.start_angle as f64 + sign * t / a.radius as f64;
                        (
                            a.centre.x as f64 + a.radius as f64 * ang.cos(),
                            a.centre.y as f64 + a.radius as f64 * ang.sin(),
                            ang + sign * std::f64::consts::FRAC_PI_2,
                        )
                    }
                };
            }
            base += len;
        }
        (0.0, 0.0, 0.0)
    };
    let (a, b, c, k) = (1.5f64, 2.5f64, 0.25f64, 0.1f64);
    let h = p.radar.altitude_m as f64;
    let pt = |x: f64, y: f64, psi: f64, r: Vec2| {
        let (dx, dy) = (r.x as f64 - x, r.y as f64 - y);
        let range = (dx * dx + dy * dy + h * h).sqrt();
        if range > 50_000.0 {
            return 0.0;
        }
        let d = [
            (dx * psi.cos() + dy * psi.sin()) / range,
            (-dx * psi.sin() + dy * psi.cos()) / range,
            -h / range,
        ];
        let s = std::f64::consts::PI
            * a
            * b
            * c
            * ((d[0] / a).powi(2) + (d[1] / b).powi(2) + (d[2] / c).powi(2)).sqrt();
        let sigma = k * s;
        1.0 / (1.0 + 8_000f64.powf(-8.0) * (range.powi(4) / sigma).powi(2))
    };
    let length: f64 = route.iter().map(|q| q.length() as f64).sum();
    let (speed, dt) = (p.speed_mps as f64, p.dt_s as f64);
    let m = (length / (speed * dt)).ceil().max(1.0) as usize;
    let (mut sk, mut sp, mut turn, mut prev) = (1.0, 1.0, 0.0, None::<f64>);
    for i in 0..m {
        let (x, y, psi) = pose((i as f64 + 0.5) * length / m as f64);
        let unseen: f64 = known.iter().map(|&r| 1.0 - pt(x, y, psi, r)).product();
        sk *= 1.0 - 0.0002 * (1.0 - unseen);
        sp *= 1.0 - 0.0002 * pt(x, y, psi, popup);
        if let Some(q) = prev {
            let mut d = psi - q;
            while d > std::f64::consts::PI {
                d -= std::f64::consts::TAU;
            }
            while d < -std::f64::consts::PI {
                d += std::f64::consts::TAU;
            }
            turn += d.abs();
        }
        prev = Some(psi);
    }
    let fuel = turn / ((m - 1) as f64 * 0.3 * (length / m as f64 / speed));
    [m as f64, sk, sp, fuel]
}

#[test]
fn route_figures_match_a_direct_f64_evaluation() {
    // Δt = 1 s as in the paper, and a longer step (50 m and 125 m per step at 50 m/s).
    for dt_s in [1.0, 2.5] {
        route_figures_match_at(RiskParams { dt_s, ..params() });
    }
    assert_eq!(time_factor(100, 100), 0.0);
    assert!((time_factor(65, 100) - 0.35).abs() < 1e-6);
}

/// `route_figures` of a three-piece route among three radars and a pop-up against the f64
/// reference, at the parameters `p`.
fn route_figures_match_at(p: RiskParams) {
    let r = 166.67f32;
    let route = [
        Primitive::Line(Segment {
            start: Vec2::new(-20_000.0, 0.0),
            end: Vec2::new(0.0, 0.0),
        }),
        Primitive::Arc(Arc {
            centre: Vec2::new(0.0, r),
            radius: r,
            start_angle: -std::f32::consts::FRAC_PI_2,
            sweep: 1.2,
        }),
        Primitive::Line(Segment {
            start: Vec2::new(r * 1.2f32.sin(), r - r * 1.2f32.cos()),
            end: Vec2::new(
                r * 1.2f32.sin() + 15_000.0 * 1.2f32.cos(),
                r - r * 1.2f32.cos() + 15_000.0 * 1.2f32.sin(),
            ),
        }),
    ];
    let known = [
        Vec2::new(-12_000.0, 3_000.0),
        Vec2::new(-4_000.0, -5_000.0),
        Vec2::new(6_000.0, 2_000.0),
    ];
    let popup = Vec2::new(2_000.0, 9_000.0);
    let got = route_figures(&p, &route, &known, Some(popup));
    let want = reference(&p, &route, &known, popup);
    let dt = p.dt_s;
    assert_eq!(got.steps as f64, want[0], "steps at Δt {dt} s");
    // T = M·Δt (eq. 28).
    let t = got.time_s(&p) as f64;
    assert!(
        (t - want[0] * dt as f64).abs() < 1e-3,
        "T at Δt {dt} s: {t}"
    );
    for (name, g, w) in [
        ("survival_known", got.survival_known as f64, want[1]),
        ("survival_popup", got.survival_popup as f64, want[2]),
        ("fuel", got.fuel as f64, want[3]),
    ] {
        assert!(
            (g - w).abs() <= 2e-4 * w.max(1e-3) + 1e-6,
            "{name} at Δt {dt} s: {g} against {w}"
        );
    }
    assert!(
        want[1] < 0.99 && want[2] < 0.999,
        "the radars see the route: {want:?}"
    );
    // The risk from the two stored figures, against the total probability over the pop-up.
    let ar = AlternativeRisk {
        survival_known: got.survival_known,
        survival_popup: got.survival_popup,
    };
    for pa in [0.0, 0.2, 0.5, 0.8, 1.0] {
        let want = 1.0 - want[1] * ((1.0 - pa) + pa * want[2]);
        assert!((ar.risk(pa as f32) as f64 - want).abs() < 1e-5, "P_A {pa}");
    }
}

#[test]
fn bad_parameters_and_empty_routes_never_panic() {
    let mut p = params();
    p.kill_per_step = 1.5;
    assert_eq!(p.validate().unwrap_err().field, "kill_per_step");
    let f = route_figures(&p, &[], &[Vec2::new(0.0, 0.0)], None);
    assert_eq!((f.steps, f.survival_known, f.fuel), (0, 1.0, 0.0));
    let ar = AlternativeRisk {
        survival_known: f32::NAN,
        survival_popup: 0.5,
    };
    assert!((0.0..=1.0).contains(&ar.risk(f32::NAN)));
}

#[test]
fn every_bad_parameter_is_named_by_its_field() {
    type Field = fn(&mut RiskParams) -> &mut f32;
    let positive: [(&str, Field); 10] = [
        ("radar.range_max_m", |p| &mut p.radar.range_max_m),
        ("radar.half_range_m", |p| &mut p.radar.half_range_m),
        ("radar.c1", |p| &mut p.radar.c1),
        ("airframe.half_length_m", |p| &mut p.airframe.half_length_m),
        ("airframe.half_span_m", |p| &mut p.airframe.half_span_m),
        ("airframe.half_height_m", |p| &mut p.airframe.half_height_m),
        ("airframe.k", |p| &mut p.airframe.k),
        ("dt_s", |p| &mut p.dt_s),
        ("speed_mps", |p| &mut p.speed_mps),
        ("max_turn_rate", |p| &mut p.max_turn_rate),
    ];
    assert_eq!(params().validate(), Ok(()));
    let refused = |field: &str, set: Field, values: &[f32]| {
        for &v in values {
            let mut p = params();
            *set(&mut p) = v;
            assert_eq!(
                p.validate().map_err(|e| e.field),
                Err(field),
                "{field} = {v}"
            );
            // Parameters that do not validate give the figures of no route.
            let line = Primitive::Line(Segment {
                start: Vec2::new(0.0, 0.0),
                end: Vec2::new(1_000.0, 0.0),
            });
            let f = route_figures(&p, &[line], &[Vec2::new(0.0, 0.0)], None);
            assert_eq!((f.steps, f.survival_known, f.fuel), (0, 1.0, 0.0));
        }
    };
    for (field, set) in positive {
        refused(field, set, &[0.0, -1.0, f32::NAN, f32::INFINITY]);
        let mut p = params();
        *set(&mut p) = 1e-3;
        assert_eq!(p.validate(), Ok(()), "{field} = 1e-3");
    }
    refused(
        "radar.altitude_m",
        |p| &mut p.radar.altitude_m,
        &[-1e-3, f32::NAN, f32::INFINITY],
    );
    refused(
        "kill_per_step",
        |p| &mut p.kill_per_step,
        &[-1e-3, 1.001, f32::NAN],
    );
    for (altitude, kill) in [(0.0, 0.0), (0.0, 1.0)] {
        let mut p = params();
        p.radar.altitude_m = altitude;
        p.kill_per_step = kill;
        assert_eq!(p.validate(), Ok(()), "altitude {altitude}, p_k {kill}");
    }
    assert_eq!(params().step_m(), 50.0);
}

#[test]
fn the_edges_of_the_model_have_their_documented_figures() {
    let p = params();
    // Straight above the radar: the range is the altitude, the line of sight the body's −z,
    // so the aircraft shows its plan view, π·a·b.
    let above = Pose {
        position: Vec2::new(300.0, -200.0),
        heading: 0.7,
    };
    let sigma = 0.1 * std::f32::consts::PI * 1.5 * 2.5;
    let want = detection_probability(&p.radar, sigma, 1_000.0);
    let got = detection_at(&p, &above, above.position);
    assert!(
        (got - want).abs() < 1e-6 && got > 0.0,
        "{got} against {want}"
    );
    // On the radar in the plane: detected surely.
    let mut planar = p;
    planar.radar.altitude_m = 0.0;
    assert_eq!(detection_at(&planar, &above, above.position), 1.0);

    // The appearance probability: clamped to [0, 1], NaN taken as 1; a NaN survival is risk 1.
    let ar = AlternativeRisk {
        survival_known: 0.9,
        survival_popup: 0.5,
    };
    assert!((ar.risk(0.0) - 0.1).abs() < 1e-6 && (ar.risk(1.0) - 0.55).abs() < 1e-6);
    assert_eq!(ar.risk(-3.0), ar.risk(0.0));
    assert_eq!(ar.risk(7.0), ar.risk(1.0));
    assert_eq!(ar.risk(f32::NAN), ar.risk(1.0));
    let nan = AlternativeRisk {
        survival_known: f32::NAN,
        survival_popup: 0.5,
    };
    assert_eq!(nan.risk(0.3), 1.0);
    let above_one = AlternativeRisk {
        survival_known: 1.5,
        survival_popup: 1.0,
    };
    assert_eq!(above_one.risk(0.5), 0.0);

    // The decision's figures of an alternative.
    let figures = RouteFigures {
        steps: 80,
        survival_known: 0.9,
        survival_popup: 0.5,
        fuel: 0.25,
    };
    assert_eq!(figures.time_s(&p), 80.0);
    let a = alternative(&figures, 60, 1.0);
    assert!(
        (a.risk - 0.55).abs() < 1e-6 && a.time == 0.25 && a.fuel == 0.25,
        "{a:?}"
    );
    assert_eq!(time_factor(60, 0), 0.0);

    // Without a pop-up its survival is 1; a route of one step has no turn effort; a route of
    // no length has no steps.
    let short = Primitive::Arc(Arc {
        centre: Vec2::new(0.0, 100.0),
        radius: 100.0,
        start_angle: -std::f32::consts::FRAC_PI_2,
        sweep: 0.4,
    });
    let f = route_figures(&p, &[short], &[Vec2::new(0.0, 0.0)], None);
    assert_eq!((f.steps, f.survival_popup, f.fuel), (1, 1.0, 0.0));
    assert!(f.survival_known < 1.0, "the radar below sees the step");
    let point = Primitive::Line(Segment {
        start: Vec2::new(5.0, 5.0),
        end: Vec2::new(5.0, 5.0),
    });
    let f = route_figures(
        &p,
        &[point],
        &[Vec2::new(0.0, 0.0)],
        Some(Vec2::new(0.0, 0.0)),
    );
    assert_eq!(
        (f.steps, f.survival_known, f.survival_popup, f.fuel),
        (0, 1.0, 1.0, 0.0)
    );
}
