//! `skyroute::geo` against PROJ: the committed reference `host-tests/data/pyproj_tmerc.csv`
//! (written by `scripts/pyproj_tmerc_reference.py`) holds, for the frame origin of every shipped
//! scenario, 150 points within ±50 km with PROJ's `tmerc` projection, meridian convergence and
//! point scale. Run with `--nocapture` to see the largest differences.

use std::f64::consts::{FRAC_PI_2, PI};

use skyroute::geo::{GeoError, LocalFrame, MAX_EAST_WEST_M, WGS84_A, WGS84_F};
use skyroute::{Network, Pose, Vec2};

/// One reference point.
struct Row {
    scenarios: String,
    lat0: f64,
    lon0: f64,
    lon: f64,
    lat: f64,
    x: f64,
    y: f64,
    convergence_deg: f64,
    scale: f64,
}

fn reference() -> Vec<Row> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/pyproj_tmerc.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (python3 scripts/pyproj_tmerc_reference.py)",
            path.display()
        )
    });
    let rows: Vec<Row> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("scenarios,"))
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            assert_eq!(c.len(), 9, "{l}");
            let v = |i: usize| -> f64 { c[i].parse().unwrap_or_else(|e| panic!("{l}: {e}")) };
            Row {
                scenarios: c[0].to_owned(),
                lat0: v(1),
                lon0: v(2),
                lon: v(3),
                lat: v(4),
                x: v(5),
                y: v(6),
                convergence_deg: v(7),
                scale: v(8),
            }
        })
        .collect();
    assert!(rows.len() >= 1000, "{} reference points", rows.len());
    rows
}

/// The distance on the ground, metres, of a small latitude/longitude difference at `lat`
/// (principal radii of curvature of WGS-84).
fn ground_m(lat: f64, dlon_deg: f64, dlat_deg: f64) -> f64 {
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let s = lat.to_radians().sin();
    let w = (1.0 - e2 * s * s).sqrt();
    let nu = WGS84_A / w;
    let rho = WGS84_A * (1.0 - e2) / (w * w * w);
    (dlon_deg.to_radians() * nu * lat.to_radians().cos()).hypot(dlat_deg.to_radians() * rho)
}

/// `a` reduced to (−π, π].
fn wrap_pi(a: f64) -> f64 {
    let r = (a + PI).rem_euclid(2.0 * PI) - PI;
    if r <= -PI {
        r + 2.0 * PI
    } else {
        r
    }
}

#[test]
fn matches_proj_tmerc_within_50_km_of_every_scenario_origin() {
    let rows = reference();
    let (mut fwd, mut inv, mut f32_err, mut gamma, mut scale, mut heading) =
        (0f64, 0f64, 0f64, 0f64, 0f64, 0f64);
    let mut f32_excess = 0f64; // beyond the rounding of the f64 result to f32
    for r in &rows {
        let frame = LocalFrame::new(r.lat0, r.lon0).unwrap();
        let (x, y) = frame.to_local(r.lon, r.lat);
        fwd = fwd.max((x - r.x).hypot(y - r.y));
        let (lon, lat) = frame.to_geo(r.x, r.y);
        inv = inv.max(ground_m(r.lat, lon - r.lon, lat - r.lat));

        let p = frame.position(r.lon, r.lat).unwrap();
        let e = (p.x as f64 - r.x).hypot(p.y as f64 - r.y);
        f32_err = f32_err.max(e);
        // Each component is the f64 value rounded to nearest: within half a spacing of f32.
        let half_ulp = |v: f64| (v.abs().max(f32::MIN_POSITIVE as f64) * f32::EPSILON as f64) / 2.0;
        assert!((p.x as f64 - x).abs() <= half_ulp(x) && (p.y as f64 - y).abs() <= half_ulp(y));
        f32_excess = f32_excess.max(e - half_ulp(r.x).hypot(half_ulp(r.y)));

        gamma = gamma.max((frame.convergence_deg(r.lon, r.lat) - r.convergence_deg).abs());
        scale = scale.max((frame.scale_factor(r.lon, r.lat) - r.scale).abs());
        for compass in [0.0, 37.5, 90.0, 179.99, 211.0, 359.9, -45.0] {
            let h = frame.heading(r.lon, r.lat, compass).unwrap() as f64;
            // The exact planner heading: grid heading compass − γ (PROJ's γ), counter-clockwise
            // from x.
            let exact = FRAC_PI_2 - (compass - r.convergence_deg).to_radians();
            heading = heading.max(wrap_pi(h - exact).abs());
        }
    }
    eprintln!(
        "against PROJ over {} points within ±50 km of the scenario origins:\n  \
         f64 forward {fwd:.2e} m, f64 inverse {inv:.2e} m on the ground,\n  \
         f32 position {f32_err:.2e} m ({f32_excess:.1e} m beyond f32 rounding), \
         convergence {gamma:.1e}°, scale {scale:.1e}, f32 heading {heading:.2e} rad",
        rows.len()
    );
    // The bounds stated in `skyroute::geo`'s documentation.
    assert!(fwd <= 1e-8, "forward {fwd}");
    assert!(inv <= 1e-8, "inverse {inv}");
    assert!(
        f32_err <= 2.8e-3 && f32_excess <= 1e-8,
        "f32 {f32_err}, {f32_excess}"
    );
    assert!(gamma <= 1e-9, "convergence {gamma}");
    // PROJ's `get_factors` differentiates numerically: its scale is good to about 1e-10.
    assert!(scale <= 1e-10, "scale {scale}");
    assert!(heading <= 1e-6, "heading {heading}");
}

/// The reference's origins are the shipped scenarios' frame origins (so the measured bound
/// covers every shipped scenario, and a scenario added or moved needs a new reference).
#[test]
fn reference_covers_every_shipped_scenario() {
    let rows = reference();
    for name in host_tests::scenarios::all_scenario_names() {
        let s = host_tests::scenarios::scenario(&name);
        let (lat0, lon0) = s.local_frame().origin();
        let row = rows
            .iter()
            .find(|r| r.scenarios.split(';').any(|n| n == name))
            .unwrap_or_else(|| panic!("{name} has no reference points: regenerate the CSV"));
        assert!(
            (row.lat0 - lat0).abs() <= 1e-12 && (row.lon0 - lon0).abs() <= 1e-12,
            "{name}: origin ({lat0}, {lon0}), reference ({}, {})",
            row.lat0,
            row.lon0
        );
    }
}

/// The core's pose is the ground tool's (`skyroute_prep::local::local_pose`, which builds the
/// networks' start and goal poses), bit for bit, at every scenario endpoint with a heading.
#[test]
fn pose_is_the_ground_tools_pose() {
    let mut checked = 0;
    for name in host_tests::scenarios::all_scenario_names() {
        let s = host_tests::scenarios::scenario(&name);
        let frame = s.local_frame();
        for e in s
            .start
            .iter()
            .chain(s.goal.iter())
            .chain(s.waypoints.iter())
        {
            let Some(h) = e.heading_deg else { continue };
            let ground = skyroute_prep::local::local_pose(&frame, e.lon, e.lat, Some(h));
            let core = frame.core().pose(e.lon, e.lat, h).unwrap();
            assert_eq!(core, ground, "{name} {}", e.name);
            checked += 1;
        }
    }
    assert!(checked >= 11, "{checked}");
}

#[test]
fn network_frame_is_the_header_origin() {
    let w = host_tests::world::world(7, 2000.0, 400.0, 60.0, 0);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let frame = net.local_frame();
    assert_eq!(frame, LocalFrame::new(48.0, 11.6).unwrap());
    assert_eq!(frame.origin(), net.origin_deg());
    let p = frame.position(11.6, 48.0).unwrap();
    assert!(p.x.abs() < 1e-6 && p.y.abs() < 1e-6, "{p:?}");
}

#[test]
fn round_trips_positions_and_headings() {
    let frame = LocalFrame::new(48.2, 11.9).unwrap();
    for &(lon, lat, compass) in &[
        (11.9, 48.2, 0.0),
        (12.5, 48.5, 90.0),
        (11.3, 47.8, 271.5),
        (12.1, 47.9, -10.0),
    ] {
        let pose = frame.pose(lon, lat, compass).unwrap();
        let (lon2, lat2) = frame.lon_lat(pose.position).unwrap();
        // Within the f32 rounding of a position up to 60 km out (3.9 mm spacing).
        assert!(ground_m(lat, lon2 - lon, lat2 - lat) < 3e-3, "{lon} {lat}");
        let c = frame.compass_deg(&pose).unwrap();
        let d = (c - compass).rem_euclid(360.0);
        assert!(d.min(360.0 - d) < 1e-4, "{compass} -> {c}");
    }
    // Grid north is true north only on the origin's meridian: 40 km east at 48° N a heading of
    // true north points about 0.4° west of grid north.
    let (lon, lat) = frame.to_geo(40_000.0, 0.0);
    let h = frame.heading(lon, lat, 0.0).unwrap() as f64;
    let west_of_grid_north = (h - FRAC_PI_2).to_degrees();
    assert!(
        west_of_grid_north > 0.35 && west_of_grid_north < 0.45,
        "{west_of_grid_north}"
    );
}

#[test]
fn refuses_bad_input_by_name() {
    use GeoError::*;
    assert_eq!(LocalFrame::new(f64::NAN, 0.0), Err(NonFinite));
    assert_eq!(LocalFrame::new(0.0, f64::INFINITY), Err(NonFinite));
    assert_eq!(LocalFrame::new(90.5, 0.0), Err(Latitude));
    let frame = LocalFrame::new(48.2, 11.9).unwrap();
    assert_eq!(frame.position(f64::NAN, 48.0), Err(NonFinite));
    assert_eq!(frame.position(11.9, f64::NEG_INFINITY), Err(NonFinite));
    assert_eq!(frame.position(11.9, -90.01), Err(Latitude));
    assert_eq!(frame.position(180.5, 48.0), Err(Longitude));
    // Farther from the origin's meridian than the series is accurate for, or 90° away.
    assert_eq!(frame.position(11.9 + 60.0, 48.0), Err(OutOfFrame));
    assert_eq!(frame.position(11.9 - 95.0, 0.0), Err(OutOfFrame));
    assert!(frame.position(11.9 + 20.0, 48.0).is_ok());
    assert_eq!(frame.heading(11.9, 48.2, f64::NAN), Err(NonFinite));
    assert_eq!(frame.heading(11.9, 48.2, 361.0), Err(Heading));
    assert_eq!(frame.pose(11.9, 48.2, -400.0), Err(Heading));
    assert_eq!(frame.pose(200.0, 48.2, 0.0), Err(Longitude));
    assert!(frame.heading(11.9, 48.2, -360.0).is_ok());
    assert_eq!(frame.lon_lat(Vec2::new(f32::NAN, 0.0)), Err(NonFinite));
    assert_eq!(
        frame.lon_lat(Vec2::new(MAX_EAST_WEST_M as f32 * 1.01, 0.0)),
        Err(OutOfFrame)
    );
    // North of the pole (the origin is 5 350 km south of it).
    assert_eq!(frame.lon_lat(Vec2::new(0.0, 4.7e6)), Err(OutOfFrame));
    assert!(frame.lon_lat(Vec2::new(0.0, 4.6e6)).is_ok());
    assert_eq!(
        frame.compass_deg(&Pose::new(0.0, 0.0, f32::INFINITY)),
        Err(NonFinite)
    );
    // The f64 methods return non-finite values, not a panic, for points outside the domain.
    let (x, _) = frame.to_local(11.9 + 90.0, 0.0);
    assert!(!x.is_finite() || x.abs() > MAX_EAST_WEST_M);
}
