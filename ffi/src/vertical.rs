//! Three-dimensional roadmaps (Niendorf et al. in 3-D): the query's altitudes, and the
//! route's altitude along each of its lines and arcs.

use crate::status::plan_status;
use crate::{planner_mut, planner_ref, SrPlanner, SrStatus};

/// Three-dimensional roadmap: sets the start's and the goal's altitudes (metres, in the
/// network's datum) for the `sr_plan` calls that follow; a three-dimensional roadmap refuses a
/// query until they are set (`SR_STATUS_PLAN_ALTITUDES_NEEDED`). Any other network:
/// `SR_STATUS_PLAN_NOT_THREE_DIMENSIONAL`; a value that is not finite or beyond 100 km:
/// `SR_STATUS_PLAN_INVALID_ALTITUDE` (the previous setting is kept).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`.
#[no_mangle]
pub unsafe extern "C" fn sr_set_query_altitudes(
    planner: *mut SrPlanner,
    start_m: f32,
    goal_m: f32,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    match p.set_query_altitudes(start_m, goal_m) {
        Ok(()) => SrStatus::Ok,
        Err(e) => plan_status(&e),
    }
}

/// Three-dimensional roadmap: writes to `*altitude_m` the last route's altitude, metres,
/// `s_m` metres into its primitive `index` (the order of `sr_route_primitives`; `s_m` clamped
/// to the primitive, NaN as 0). The altitude follows the climb-early, descend-late profile the
/// route was checked with, which an autopilot must fly to keep the clearance over what the
/// route passes above; it is not the straight line between the primitive's ends.
/// `SR_STATUS_INVALID_ARGUMENT` for an index past the route;
/// `SR_STATUS_PLAN_NOT_THREE_DIMENSIONAL` on any other network. Work: O(route length).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `altitude_m` is NULL or points to a
/// writable float.
#[no_mangle]
pub unsafe extern "C" fn sr_route_altitude_at(
    planner: *const SrPlanner,
    index: usize,
    s_m: f32,
    altitude_m: *mut f32,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`.
    let Some(p) = (unsafe { planner_ref(planner) }) else {
        return SrStatus::NullPointer;
    };
    if altitude_m.is_null() {
        return SrStatus::NullPointer;
    }
    if !p.network().is_three_dimensional() {
        return SrStatus::PlanNotThreeDimensional;
    }
    match p.route_altitude_at(index, s_m) {
        Some(z) => {
            // SAFETY: `altitude_m` is non-null and the caller gives it writable.
            unsafe { altitude_m.write(z) };
            SrStatus::Ok
        }
        None => SrStatus::InvalidArgument,
    }
}
