//! The C API's answers to misuse, called as C calls it: NULL for every pointer, memory too
//! small or misaligned, arrays too short, arguments out of their domain, a planner with no
//! network.

use skyroute_ffi::*;
use std::ptr::{null, null_mut};

/// Planner memory: 8-byte aligned, `SR_PLANNER_STORAGE_SIZE` bytes.
fn memory() -> Vec<u64> {
    vec![0u64; SR_PLANNER_STORAGE_SIZE / 8]
}

/// A planner in `mem`, with no network.
fn planner(mem: &mut [u64]) -> *mut SrPlanner {
    let mut h = null_mut();
    // SAFETY: `mem` is writable, aligned and large enough, and `h` is a writable handle.
    let status = unsafe { sr_planner_init(mem.as_mut_ptr().cast(), mem.len() * 8, &mut h) };
    assert_eq!(status, SrStatus::Ok);
    assert!(!h.is_null());
    h
}

#[test]
fn init_refuses_null_short_and_misaligned_memory() {
    let mut mem = memory();
    let bytes = mem.len() * 8;
    let base: *mut u8 = mem.as_mut_ptr().cast();
    let mut h = null_mut();
    // SAFETY: every pointer is NULL or into `mem`, with the length that remains of it.
    unsafe {
        assert_eq!(
            sr_planner_init(null_mut(), bytes, &mut h),
            SrStatus::NullPointer
        );
        assert_eq!(
            sr_planner_init(base.cast(), bytes, null_mut()),
            SrStatus::NullPointer
        );
        let size = sr_planner_size();
        assert_eq!(
            sr_planner_init(base.cast(), size - 1, &mut h),
            SrStatus::MemoryTooSmall
        );
        let odd = base.add(4).cast();
        assert_eq!(
            sr_planner_init(odd, bytes - 4, &mut h),
            SrStatus::MemoryMisaligned
        );
        assert!(h.is_null(), "no handle is written on an error");
        assert_eq!(sr_planner_init(base.cast(), size, &mut h), SrStatus::Ok);
    }
    assert_eq!(h.cast::<u8>(), base);
}

#[test]
fn every_call_refuses_a_null_planner_or_output() {
    let mut mem = memory();
    let h = planner(&mut mem);
    let (mut v, mut e, mut w, mut n, mut id) = (0u32, 0u32, 0u64, 0usize, 0u8);
    let mut summary = SrRouteSummary::default();
    let query = SrQuery {
        start_x: 0.0,
        start_y: 0.0,
        start_heading: 0.0,
        goal_x: 100.0,
        goal_y: 0.0,
        goal_heading: 0.0,
        goal_has_heading: 0,
        search: SR_SEARCH_DIJKSTRA,
    };
    let xy = [0.0f32, 0.0, 10.0, 0.0, 0.0, 10.0];
    let null_status = SrStatus::NullPointer;
    // SAFETY: every pointer is NULL or points to a live value of its type.
    unsafe {
        assert_eq!(sr_load(null_mut(), [0u8; 4].as_ptr(), 4), null_status);
        assert_eq!(sr_load(h, null(), 4), null_status);
        assert_eq!(sr_network_counts(null(), &mut v, &mut e), null_status);
        assert_eq!(sr_network_counts(h, null_mut(), &mut e), null_status);
        assert_eq!(sr_network_counts(h, &mut v, null_mut()), null_status);
        assert_eq!(sr_worst_case_work(null(), &mut w), null_status);
        assert_eq!(sr_worst_case_work(h, null_mut()), null_status);
        assert_eq!(sr_worst_case_popup_work(null(), &mut w), null_status);
        assert_eq!(sr_worst_case_popup_work(h, null_mut()), null_status);
        assert_eq!(sr_plan(null_mut(), &query, 1, &mut summary), null_status);
        assert_eq!(sr_plan(h, null(), 1, &mut summary), null_status);
        assert_eq!(sr_plan(h, &query, 1, null_mut()), null_status);
        let mut out = [SrPrimitive::default(); 1];
        assert_eq!(
            sr_route_primitives(null(), out.as_mut_ptr(), 1, &mut n),
            null_status
        );
        assert_eq!(sr_route_primitives(h, null_mut(), 1, &mut n), null_status);
        assert_eq!(
            sr_route_primitives(h, out.as_mut_ptr(), 1, null_mut()),
            null_status
        );
        assert_eq!(
            sr_add_popup_circle(null_mut(), 0.0, 0.0, 1.0, &mut id),
            null_status
        );
        assert_eq!(
            sr_add_popup_polygon(null_mut(), xy.as_ptr(), 3, &mut id),
            null_status
        );
        assert_eq!(sr_add_popup_polygon(h, null(), 3, &mut id), null_status);
        assert_eq!(sr_remove_popup(null_mut(), 0), null_status);
        assert_eq!(sr_remove_popups(null_mut()), null_status);
    }
}

#[test]
fn arguments_out_of_their_domain_are_refused() {
    let mut mem = memory();
    let h = planner(&mut mem);
    let mut id = 0xffu8;
    let xy = [0.0f32; 2 * (SR_MAX_POPUP_VERTICES + 1)];
    let line = [0.0f32, 0.0, 10.0, 0.0];
    let mut summary = SrRouteSummary::default();
    let query = SrQuery {
        start_x: 0.0,
        start_y: 0.0,
        start_heading: 0.0,
        goal_x: 100.0,
        goal_y: 0.0,
        goal_heading: 0.0,
        goal_has_heading: 0,
        search: 2,
    };
    // SAFETY: every pointer points to a live value of its type, arrays of the length given.
    unsafe {
        let too_many = SR_MAX_POPUP_VERTICES + 1;
        assert_eq!(
            sr_add_popup_polygon(h, xy.as_ptr(), too_many, &mut id),
            SrStatus::InvalidArgument
        );
        assert_eq!(
            sr_add_popup_polygon(h, line.as_ptr(), 2, &mut id),
            SrStatus::PopupNotSimple
        );
        assert_eq!(
            sr_add_popup_circle(h, f32::NAN, 0.0, 1.0, &mut id),
            SrStatus::PopupNonFinite
        );
        assert_eq!(id, 0xff, "no id is written on an error");
        assert_eq!(
            sr_plan(h, &query, 1, &mut summary),
            SrStatus::InvalidArgument
        );
        assert_eq!(sr_remove_popup(h, 3), SrStatus::PopupUnknownId);
        assert_eq!(sr_load(h, [0u8; 4].as_ptr(), 4), SrStatus::LoadTruncated);
    }
}

#[test]
fn a_planner_without_a_network_has_no_route_and_converts_no_position() {
    let mut mem = memory();
    let h = planner(&mut mem);
    let (mut v, mut e, mut n) = (9u32, 9u32, 9usize);
    let mut id = 0u8;
    // SAFETY: every pointer is NULL where allowed or points to a live value of its type.
    unsafe {
        assert_eq!(sr_network_counts(h, &mut v, &mut e), SrStatus::Ok);
        assert_eq!((v, e), (0, 0));
        assert_eq!(sr_route_primitives(h, null_mut(), 0, &mut n), SrStatus::Ok);
        assert_eq!(n, 0);
        // The pop-up slots work without a network; ids count from 0, and NULL takes no id.
        assert_eq!(sr_add_popup_circle(h, 0.0, 0.0, 5.0, &mut id), SrStatus::Ok);
        assert_eq!(id, 0);
        assert_eq!(
            sr_add_popup_circle(h, 50.0, 0.0, 5.0, null_mut()),
            SrStatus::Ok
        );
        assert_eq!(sr_remove_popups(h), SrStatus::Ok);
        assert_eq!(sr_remove_popup(h, 0), SrStatus::PopupUnknownId);
        // No frame to convert through: refused, and the outputs are not written.
        let mut pose = SrPose {
            x: 7.0,
            y: 7.0,
            heading: 7.0,
        };
        assert_eq!(
            sr_geo_to_local(h, 11.0, 48.0, 90.0, &mut pose),
            SrStatus::NoNetwork
        );
        assert_eq!(pose.x, 7.0);
        let mut geo = SrGeoPose::default();
        assert_eq!(
            sr_local_to_geo(h, 0.0, 0.0, 0.0, &mut geo),
            SrStatus::NoNetwork
        );
        assert_eq!(geo, SrGeoPose::default());
        assert_eq!(
            sr_geo_to_local(h, 11.0, 48.0, 90.0, null_mut()),
            SrStatus::NullPointer
        );
    }
}
