//! The C API on a three-dimensional roadmap: the query's altitudes, the route's altitude
//! along each primitive (equal to the Rust API's, and at the query's altitudes at its ends),
//! pop-ups with heights, and each refusal on a planar network or for a bad value.

use skyroute::geometry::vertical::{VerticalLimits, VerticalProfile};
use skyroute::network::write::VerticalSpec;
use skyroute::network::write::{encode, encode_three_dimensional, EdgeSpec, NetworkSpec};
use skyroute::planner::{Goal, Planner, Query, Search};
use skyroute::{DubinsPath, Pose};
use skyroute_ffi::*;
use std::f32::consts::{FRAC_PI_2, PI};
use std::ptr::null_mut;

/// A 5 × 5 lattice 100 m apart, four headings per point, turn radius 30 m, vertex altitudes 30,
/// 40 or 50 m; edges between neighbours whose climb is flyable (three-dimensional) or all of
/// them (planar).
fn network(three_d: bool) -> Vec<u8> {
    let limits = VerticalLimits::niendorf(25.0);
    let mut vertices = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            for h in [0.0, FRAC_PI_2, PI, -FRAC_PI_2] {
                vertices.push(Pose::new(i as f32 * 100.0, j as f32 * 100.0, h));
            }
        }
    }
    let altitude = |p: &Pose| {
        let (i, j) = ((p.position.x / 100.0) as i32, (p.position.y / 100.0) as i32);
        30.0 + 10.0 * (i + j).rem_euclid(3) as f32
    };
    let mut edges = Vec::new();
    for (a, pa) in vertices.iter().enumerate() {
        for (b, pb) in vertices.iter().enumerate() {
            let d = pa.position.distance(pb.position);
            let Some(path) = DubinsPath::shortest(pa, pb, 30.0) else {
                continue;
            };
            let flyable =
                VerticalProfile::new(altitude(pa), altitude(pb), path.length(), &limits).is_some();
            if d > 0.0 && d <= 150.0 && (flyable || !three_d) {
                edges.push(EdgeSpec::dubins(a as u32, b as u32, &path));
            }
        }
    }
    let spec = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: 30.0,
        clearance_m: 5.0,
        vertices: vertices.clone(),
        edges,
        obstacles: Vec::new(),
        grid_cell_m: 60.0,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    if !three_d {
        return encode(&spec).unwrap();
    }
    let vertical = VerticalSpec {
        limits,
        altitudes: vertices.iter().map(altitude).collect(),
        heights: Vec::new(),
    };
    encode_three_dimensional(&spec, &vertical, None).unwrap()
}

/// Planner memory: 8-byte aligned, `SR_PLANNER_STORAGE_SIZE` bytes.
fn memory() -> Vec<u64> {
    vec![0u64; SR_PLANNER_STORAGE_SIZE / 8]
}

/// A planner in `mem` with `image` loaded.
fn loaded(mem: &mut [u64], image: &[u8]) -> *mut SrPlanner {
    let mut h = null_mut();
    // SAFETY: `mem` is writable, aligned and large enough; `image` outlives the planner's use.
    unsafe {
        assert_eq!(
            sr_planner_init(mem.as_mut_ptr().cast(), mem.len() * 8, &mut h),
            SrStatus::Ok
        );
        assert_eq!(sr_load(h, image.as_ptr(), image.len()), SrStatus::Ok);
    }
    h
}

fn query() -> SrQuery {
    SrQuery {
        start_x: 0.0,
        start_y: 100.0,
        start_heading: 0.0,
        goal_x: 400.0,
        goal_y: 300.0,
        goal_heading: 0.0,
        goal_has_heading: 1,
        search: SR_SEARCH_DIJKSTRA,
    }
}

#[test]
fn altitudes_along_the_route_match_the_rust_api() {
    let image = network(true);
    let mut mem = memory();
    let h = loaded(&mut mem, &image);
    let mut summary = SrRouteSummary::default();
    let (mut count, mut z) = (0usize, 0.0f32);
    // SAFETY: `h` is a loaded planner; every pointer points to a live value of its type.
    unsafe {
        assert_eq!(
            sr_plan(h, &query(), u64::MAX, &mut summary),
            SrStatus::PlanAltitudesNeeded
        );
        assert_eq!(
            sr_set_query_altitudes(h, f32::NAN, 50.0),
            SrStatus::PlanInvalidAltitude
        );
        assert_eq!(sr_set_query_altitudes(h, 30.0, 50.0), SrStatus::Ok);
        assert_eq!(sr_plan(h, &query(), u64::MAX, &mut summary), SrStatus::Ok);
        // A zero capacity asks for the count alone.
        sr_route_primitives(h, null_mut(), 0, &mut count);
    }
    assert!(count > 2);
    // The same query through the Rust API.
    let mut rust: Box<Planner<'_, 512, 8192, 4, 128>> = Box::new(Planner::new());
    rust.load(&image).unwrap();
    rust.set_query_altitudes(30.0, 50.0).unwrap();
    let q = Query {
        start: Pose::new(0.0, 100.0, 0.0),
        goal: Goal {
            position: skyroute::Vec2::new(400.0, 300.0),
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    };
    rust.plan(&q, u64::MAX).unwrap();
    assert_eq!(rust.route().len(), count);
    for k in 0..count {
        for s in [0.0, 10.0, 1e9] {
            // SAFETY: as above.
            assert_eq!(
                unsafe { sr_route_altitude_at(h, k, s, &mut z) },
                SrStatus::Ok
            );
            assert_eq!(
                Some(z),
                rust.route_altitude_at(k, s),
                "primitive {k} at {s}"
            );
        }
    }
    // SAFETY: as above.
    unsafe {
        assert_eq!(sr_route_altitude_at(h, 0, 0.0, &mut z), SrStatus::Ok);
        assert_eq!(z, 30.0);
        assert_eq!(
            sr_route_altitude_at(h, count - 1, f32::INFINITY, &mut z),
            SrStatus::Ok
        );
        assert_eq!(z, 50.0);
        assert_eq!(
            sr_route_altitude_at(h, count, 0.0, &mut z),
            SrStatus::InvalidArgument
        );
        assert_eq!(
            sr_route_altitude_at(h, 0, 0.0, null_mut()),
            SrStatus::NullPointer
        );
    }
}

#[test]
fn popups_take_heights_on_a_three_dimensional_roadmap_only() {
    let (solid, flat) = (network(true), network(false));
    let (mut mem, mut flat_mem) = (memory(), memory());
    let (h, f) = (loaded(&mut mem, &solid), loaded(&mut flat_mem, &flat));
    let (mut id, mut z) = (0u8, 0.0f32);
    let square = [150.0f32, 150.0, 250.0, 150.0, 250.0, 250.0, 150.0, 250.0];
    // SAFETY: `h` and `f` are loaded planners; every pointer points to a live value of its
    // type, arrays of the length given.
    unsafe {
        for bad in [f32::NAN, 0.0, -1.0, 2e5] {
            assert_eq!(
                sr_add_popup_circle_with_height(h, 200.0, 200.0, 30.0, bad, &mut id),
                SrStatus::PopupBadHeight,
                "{bad}"
            );
        }
        assert_eq!(
            sr_add_popup_circle_with_height(h, 200.0, 200.0, 30.0, 20.0, &mut id),
            SrStatus::Ok
        );
        assert_eq!(
            sr_add_popup_polygon_with_height(h, square.as_ptr(), 4, 45.0, &mut id),
            SrStatus::Ok
        );
        assert_eq!(id, 1);
        assert_eq!(
            sr_add_popup_circle_with_height(f, 200.0, 200.0, 30.0, 20.0, &mut id),
            SrStatus::PopupHeightNeedsAltitudes
        );
        assert_eq!(
            sr_add_popup_polygon_with_height(f, square.as_ptr(), 4, 45.0, &mut id),
            SrStatus::PopupHeightNeedsAltitudes
        );
        assert_eq!(
            sr_add_popup_circle_with_height(f, 200.0, 200.0, 30.0, f32::INFINITY, &mut id),
            SrStatus::Ok,
            "a wall on any network"
        );
        assert_eq!(
            sr_set_query_altitudes(f, 30.0, 30.0),
            SrStatus::PlanNotThreeDimensional
        );
        assert_eq!(
            sr_route_altitude_at(f, 0, 0.0, &mut z),
            SrStatus::PlanNotThreeDimensional
        );
        assert_eq!(
            sr_set_query_altitudes(null_mut(), 30.0, 30.0),
            SrStatus::NullPointer
        );
    }
}
