//! Pop-ups with heights on a three-dimensional roadmap (`Planner::add_popup_with_height`):
//! the lattice and low wall of `vertical_planning`, with pop-ups of random shape, place and
//! height. Every verdict is checked against an independent f64 sampling in 3-D: a point of a
//! path conflicts with a pop-up where it is within the clearance of the footprint
//! (`reference::dist_polygon`, or the distance to the centre for a disc) and below the
//! pop-up's height plus the clearance, at the altitude of the f64 profile from the
//! definitions (`reference::vertical_altitude`).

use super::drift_exit::checks_work;
use super::vertical_planning::{limits, network, query, random_query, Small, CLEARANCE};
use host_tests::reference::{dist_polygon, vertical_altitude, P};
use skyroute::geometry::vertical::VerticalProfile;
use skyroute::planner::{PlanError, Popup, PopupError, QueryField};
use skyroute::{DubinsPath, Vec2};

/// A pop-up and its height.
#[derive(Clone, Debug)]
struct TallPopup {
    shape: Popup,
    height: f32,
}

/// How far the f64 footprint of `popup` is from `p`, metres (0 inside).
fn footprint_distance(popup: &Popup, p: Vec2) -> f64 {
    let p = (p.x as f64, p.y as f64);
    match popup {
        Popup::Circle { centre, radius } => {
            let d = ((p.0 - centre.x as f64).powi(2) + (p.1 - centre.y as f64).powi(2)).sqrt();
            (d - *radius as f64).max(0.0)
        }
        Popup::Polygon(points) => {
            let poly: Vec<P> = points.iter().map(|q| (q.x as f64, q.y as f64)).collect();
            dist_polygon(p, &poly)
        }
    }
}

/// The least margins, metres, by which `path` flown on `profile` keeps out of the pop-up
/// grown by each of `grow` metres sideways and upwards (the clearance included), sampled
/// every 0.25 m: negative where a point is within `CLEARANCE + grow` of the footprint and
/// below `height + CLEARANCE + grow`; +∞ when no point comes that near the footprint.
fn margins<const N: usize>(
    path: &DubinsPath,
    profile: &VerticalProfile,
    popup: &TallPopup,
    grow: [f64; N],
) -> [f64; N] {
    let n = (4.0 * path.length() as f64).ceil().max(1.0) as usize;
    let mut least = [f64::INFINITY; N];
    let (side, top) = (CLEARANCE as f64, popup.height as f64 + CLEARANCE as f64);
    for i in 0..=n {
        let s = path.length() as f64 * i as f64 / n as f64;
        let d = footprint_distance(&popup.shape, path.sample(s as f32).position);
        let z = vertical_altitude(profile, &limits(), s);
        for (m, g) in least.iter_mut().zip(grow) {
            if d < side + g {
                *m = m.min(z - (top + g));
            }
        }
    }
    least
}

/// A random disc or quadrilateral 15–60 m across near the lattice's middle, 20–80 m tall
/// (the vertices fly at 30–50 m).
fn random_popup(rng: &mut host_tests::Rng) -> TallPopup {
    let c = Vec2::new(rng.range_f32(50.0, 550.0), rng.range_f32(50.0, 550.0));
    let r = rng.range_f32(15.0, 60.0);
    let shape = if rng.range_f32(0.0, 1.0) < 0.5 {
        Popup::Circle {
            centre: c,
            radius: r,
        }
    } else {
        let a = rng.range_f32(0.0, 1.5);
        let corners = (0..4).map(|k| {
            let t = a + k as f32 * core::f32::consts::FRAC_PI_2;
            let s = if k % 2 == 0 { r } else { 0.6 * r };
            c + Vec2::new(s * t.cos(), s * t.sin())
        });
        Popup::Polygon(corners.collect())
    };
    TallPopup {
        shape,
        height: rng.range_f32(20.0, 80.0),
    }
}

/// Each random pop-up blocks every edge the f64 sampling finds flying within the clearance
/// of it below its height plus the clearance, and no edge that keeps 0.5 m more than that
/// from it; a finite height leaves open edges a wall of the same footprint blocks.
#[test]
fn a_popup_blocks_exactly_the_edges_that_fly_below_its_top_near_it() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let net = *planner.network();
    let mut rng = host_tests::Rng(0x3D_0002);
    let (mut blocked, mut spared) = (0u32, 0u32);
    for case in 0..host_tests::cases(12, 200) {
        let popup = random_popup(&mut rng);
        let summary = planner
            .add_popup_with_height(popup.shape.clone(), popup.height)
            .unwrap();
        assert!(summary.predicate_tests as u64 <= planner.worst_case_popup_work());
        let mut wall = Small::new();
        wall.load(&solid).unwrap();
        wall.add_popup(popup.shape.clone()).unwrap();
        for e in 0..net.edge_count() {
            let (path, profile) = (net.edge_path(e).unwrap(), net.edge_profile(e).unwrap());
            let enabled = planner.is_edge_enabled(e);
            // Only edges that may come near the pop-up are sampled: every point of an edge
            // is within its length of its start.
            let reach = path.length() + CLEARANCE + 1.0;
            if footprint_distance(&popup.shape, path.start.position) > reach as f64 {
                assert!(enabled, "case {case}: edge {e} is far from {popup:?}");
                continue;
            }
            let [within, grown] = margins(&path, &profile, &popup, [0.0, 0.5]);
            if within < -1e-3 {
                assert!(!enabled, "case {case}: edge {e} flies into {popup:?}");
            }
            if grown > 0.0 {
                assert!(enabled, "case {case}: edge {e} keeps clear of {popup:?}");
            }
            assert!(wall.is_edge_enabled(e) <= enabled, "case {case}: edge {e}");
            blocked += !enabled as u32;
            spared += (enabled && !wall.is_edge_enabled(e)) as u32;
        }
        planner.remove_popup(summary.id).unwrap();
    }
    assert!(
        blocked >= 50 && spared >= 50,
        "{blocked} edges blocked, {spared} flown over"
    );
    eprintln!("{blocked} edges blocked, {spared} that a wall would block flown over");
}

/// Random queries with a random pop-up of each kind in place: every route, and every route
/// post-processing makes of it, keeps out of each pop-up below its height plus the clearance
/// (the links and shortcuts built in flight included); some fly over a pop-up where the
/// same footprint as a wall leaves a longer route or none.
#[test]
fn routes_keep_out_of_popups_below_their_tops_and_fly_over_low_ones() {
    let solid = network(true);
    let mut rng = host_tests::Rng(0x3D_0003);
    let (mut routed, mut shorter) = (0u32, 0u32);
    for case in 0..host_tests::cases(60, 600) {
        let popups = [random_popup(&mut rng), random_popup(&mut rng)];
        let (q, (sz, gz)) = random_query(&mut rng, (0.0, 600.0), (0.0, 600.0));
        let plan = |tall: bool| {
            let mut planner = Small::new();
            planner.load(&solid).unwrap();
            planner.set_query_altitudes(sz, gz).unwrap();
            for p in &popups {
                let height = if tall { f32::INFINITY } else { p.height };
                planner
                    .add_popup_with_height(p.shape.clone(), height)
                    .unwrap();
            }
            let summary = planner.plan(&q, u64::MAX).ok()?;
            assert!(summary.work.total() <= planner.worst_case_work());
            Some((planner, summary.exit.is_some()))
        };
        let Some((mut planner, exit)) = plan(false) else {
            continue;
        };
        routed += 1;
        let walls: Option<f32> =
            plan(true).map(|(p, _)| p.route_paths().iter().map(|p| p.length()).sum());
        for stage in ["searched", "post-processed"] {
            let paths = planner.route_paths().to_vec();
            // An exit, flown level, may be within the clearance of what it leaves.
            for (k, path) in paths.iter().enumerate().skip(exit as usize) {
                let profile = planner.route_profile(k).unwrap();
                for p in &popups {
                    let [m] = margins(path, &profile, p, [0.0]);
                    assert!(m >= -1e-3, "case {case} {stage} path {k}: {m} m into {p:?}");
                }
            }
            if stage == "searched" {
                // Not always shorter: the links try the nearest vertices first and keep the
                // first clear ones, so walls can make them try others that happen to be better.
                let length: f32 = paths.iter().map(|p| p.length()).sum();
                shorter += walls.is_none_or(|w| length < w - 1.0) as u32;
                planner.shortcut_best(u64::MAX).unwrap();
                planner.smooth_headings(9, u64::MAX).unwrap();
            }
        }
    }
    assert!(
        routed >= 20 && shorter >= 3,
        "{routed} routed, {shorter} shorter"
    );
    eprintln!("{routed} routed, {shorter} shorter than with walls or routed only without");
}

/// A start or goal over a pop-up's footprint is free above its height and inside it below;
/// a start below its top leaves by an exit, one above it needs none.
#[test]
fn an_end_above_a_popup_is_free_and_one_below_it_is_inside() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let centre = Vec2::new(150.0, 250.0);
    let disc = Popup::Circle {
        centre,
        radius: 40.0,
    };
    let id = planner.add_popup_with_height(disc, 40.0).unwrap().id;
    assert_eq!(planner.popup_height(id), Some(40.0));
    let (far, near) = (Vec2::new(500.0, 300.0), centre);
    // A goal on the top is outside the pop-up, but no link reaches it without flying within
    // the clearance of the top; one above it by more than the clearance is reached.
    planner.set_query_altitudes(30.0, 40.0).unwrap();
    assert_eq!(
        planner.plan(&query(far, near), u64::MAX),
        Err(PlanError::GoalUnconnected)
    );
    planner.set_query_altitudes(30.0, 50.0).unwrap();
    planner
        .plan(&query(far, near), u64::MAX)
        .expect("a goal above the pop-up");
    planner.set_query_altitudes(30.0, 39.9).unwrap();
    assert_eq!(
        planner.plan(&query(far, near), u64::MAX),
        Err(PlanError::InsidePopup {
            field: QueryField::Goal,
            popup: id
        })
    );
    planner.set_query_altitudes(50.0, 40.0).unwrap();
    let above = planner.plan(&query(near, far), u64::MAX).unwrap();
    assert_eq!(above.exit, None, "a start above the top by the clearance");
    planner.set_query_altitudes(40.0, 40.0).unwrap();
    let below = planner.plan(&query(near, far), u64::MAX).unwrap();
    assert!(
        below.exit.is_some(),
        "a start within the clearance of the top"
    );
    // A start above the top by the clearance: the start's region test counts the pop-up once
    // (its height compared), and the goal's free-space check once (its containment test).
    planner.set_query_altitudes(50.0, 40.0).unwrap();
    let with_popup = checks_work(&mut planner, near, 0.0, far);
    planner.remove_popup(id).unwrap();
    assert_eq!(with_popup - checks_work(&mut planner, near, 0.0, far), 2);
}

/// Heights are checked: NaN, not positive, finite beyond 10⁵ m, and finite on a planar
/// network are refused, and nothing is added; +∞ (a wall) is taken anywhere.
#[test]
fn popup_heights_are_checked() {
    let disc = Popup::Circle {
        centre: Vec2::new(150.0, 250.0),
        radius: 40.0,
    };
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    for h in [f32::NAN, 0.0, -5.0, 1.0001e5, f32::NEG_INFINITY] {
        let refused = planner.add_popup_with_height(disc.clone(), h);
        assert_eq!(refused, Err(PopupError::BadHeight), "height {h}");
    }
    assert_eq!(planner.popups().count(), 0);
    let planar = network(false);
    let mut flat = Small::new();
    flat.load(&planar).unwrap();
    assert_eq!(
        flat.add_popup_with_height(disc.clone(), 40.0),
        Err(PopupError::HeightNeedsAltitudes)
    );
    assert_eq!(flat.popups().count(), 0);
    let id = flat.add_popup_with_height(disc, f32::INFINITY).unwrap().id;
    assert_eq!(flat.popup_height(id), Some(f32::INFINITY));
    assert_eq!(flat.popup_height(id + 1), None);
}

/// The exit is flown level at the start's altitude, so a pop-up that altitude clears by the
/// clearance is no obstacle to it: from inside a tall pop-up at 40 m, the straight exit east
/// ends within the clearance of a low pop-up beside it whose top is at 30 m (the tall one's
/// 40 m radius, the clearance and the 1 m margin). With the low one's top at 38 m, which 40 m
/// does not clear by the clearance, that exit is not taken.
#[test]
fn a_level_exit_passes_over_a_popup_it_clears() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let tall = Popup::Circle {
        centre: Vec2::new(150.0, 250.0),
        radius: 40.0,
    };
    let low = Popup::Polygon(
        [
            (200.0, 200.0),
            (240.0, 200.0),
            (240.0, 300.0),
            (200.0, 300.0),
        ]
        .iter()
        .map(|&(x, y)| Vec2::new(x, y))
        .collect(),
    );
    planner.add_popup_with_height(tall, 60.0).unwrap();
    let id = planner.add_popup_with_height(low.clone(), 30.0).unwrap().id;
    let q = query(Vec2::new(150.0, 250.0), Vec2::new(500.0, 300.0));
    planner.set_query_altitudes(40.0, 40.0).unwrap();
    let summary = planner.plan(&q, u64::MAX).unwrap();
    let over = summary
        .exit
        .expect("the start is inside the tall pop-up")
        .length;
    assert!((over - (40.0 + CLEARANCE + 1.0)).abs() < 1e-2, "{over}");
    planner.remove_popup(id).unwrap();
    planner.add_popup_with_height(low, 38.0).unwrap();
    match planner.plan(&q, u64::MAX) {
        Ok(s) => assert!(s.exit.unwrap().length > over + 0.5, "{s:?}"),
        Err(e) => assert_eq!(e, PlanError::StartUnconnected),
    }
}
