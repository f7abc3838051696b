//! Pop-up obstacles: add a circle or a polygon, remove one or all.

use crate::status::popup_status;
use crate::{planner_mut, planner_ref, SrPlanner, SrStatus, SR_MAX_POPUPS, SR_MAX_POPUP_VERTICES};
use skyroute::{Popup, Vec2};

/// The status of a core `add_popup`; on success writes the pop-up's id to `*id` unless `id`
/// is NULL.
///
/// # Safety
/// `id` is NULL or points to a writable byte.
unsafe fn added(
    result: Result<skyroute::PopupSummary, skyroute::PopupError>,
    id: *mut u8,
) -> SrStatus {
    match result {
        Ok(s) => {
            if !id.is_null() {
                // SAFETY: `id` is non-null and the caller gives it writable.
                unsafe { id.write(s.id) };
            }
            SrStatus::Ok
        }
        Err(e) => popup_status(&e),
    }
}

/// Adds a circular pop-up of `radius` metres about `(x, y)` and disables every edge that
/// comes within the network's clearance of it; writes its id (for `sr_remove_popup`) to
/// `*id` unless `id` is NULL. Work: at most `sr_worst_case_popup_work`. At most
/// `SR_MAX_POPUPS` are active at once (`SR_STATUS_POPUP_NO_FREE_SLOT`).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `id` is NULL or points to a writable
/// byte.
#[no_mangle]
pub unsafe extern "C" fn sr_add_popup_circle(
    planner: *mut SrPlanner,
    x: f32,
    y: f32,
    radius: f32,
    id: *mut u8,
) -> SrStatus {
    // SAFETY: the caller's guarantees are those of `sr_add_popup_circle_with_height`.
    unsafe { sr_add_popup_circle_with_height(planner, x, y, radius, f32::INFINITY, id) }
}

/// `sr_add_popup_circle` for a pop-up whose top is at `height_m` metres (the network's datum):
/// a three-dimensional roadmap flies over it where its altitude clears the top by the
/// clearance. `INFINITY` is a wall; a finite height on any other network is
/// `SR_STATUS_POPUP_HEIGHT_NEEDS_ALTITUDES`, and one that is NaN, not positive or beyond
/// 100 km `SR_STATUS_POPUP_BAD_HEIGHT`.
///
/// # Safety
/// As `sr_add_popup_circle`.
#[no_mangle]
pub unsafe extern "C" fn sr_add_popup_circle_with_height(
    planner: *mut SrPlanner,
    x: f32,
    y: f32,
    radius: f32,
    height_m: f32,
    id: *mut u8,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    let popup = Popup::Circle {
        centre: Vec2::new(x, y),
        radius,
    };
    // SAFETY: the caller gives `id` NULL or writable.
    unsafe { added(p.add_popup_with_height(popup, height_m), id) }
}

/// Adds a simple polygon pop-up of `n` vertices `(xy[2i], xy[2i + 1])`, metres, in either
/// order round it (3 ≤ `n` ≤ `SR_MAX_POPUP_VERTICES`; more: `SR_STATUS_INVALID_ARGUMENT`), as
/// `sr_add_popup_circle` does.
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `xy` is NULL or points to `2·n`
/// readable floats; `id` is NULL or points to a writable byte.
#[no_mangle]
pub unsafe extern "C" fn sr_add_popup_polygon(
    planner: *mut SrPlanner,
    xy: *const f32,
    n: usize,
    id: *mut u8,
) -> SrStatus {
    // SAFETY: the caller's guarantees are those of `sr_add_popup_polygon_with_height`.
    unsafe { sr_add_popup_polygon_with_height(planner, xy, n, f32::INFINITY, id) }
}

/// `sr_add_popup_polygon` for a pop-up whose top is at `height_m` metres, as
/// `sr_add_popup_circle_with_height` takes it.
///
/// # Safety
/// As `sr_add_popup_polygon`.
#[no_mangle]
pub unsafe extern "C" fn sr_add_popup_polygon_with_height(
    planner: *mut SrPlanner,
    xy: *const f32,
    n: usize,
    height_m: f32,
    id: *mut u8,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    if xy.is_null() {
        return SrStatus::NullPointer;
    }
    if n > SR_MAX_POPUP_VERTICES {
        return SrStatus::InvalidArgument;
    }
    // SAFETY: `xy` is non-null and points to `2·n` readable floats (n ≤ 16), as the caller
    // guarantees.
    let coords = unsafe { core::slice::from_raw_parts(xy, 2 * n) };
    let mut points = heapless::Vec::<Vec2, SR_MAX_POPUP_VERTICES>::new();
    for pair in coords.chunks_exact(2) {
        if let [x, y] = *pair {
            // Cannot fail: n ≤ SR_MAX_POPUP_VERTICES (checked above).
            let _ = points.push(Vec2::new(x, y));
        }
    }
    // SAFETY: the caller gives `id` NULL or writable.
    unsafe {
        added(
            p.add_popup_with_height(Popup::Polygon(points), height_m),
            id,
        )
    }
}

/// Removes pop-up `id` and re-enables the edges only it blocked
/// (`SR_STATUS_POPUP_UNKNOWN_ID` if no active pop-up has that id).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`.
#[no_mangle]
pub unsafe extern "C" fn sr_remove_popup(planner: *mut SrPlanner, id: u8) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    match p.remove_popup(id) {
        Ok(()) => SrStatus::Ok,
        Err(e) => popup_status(&e),
    }
}

/// Removes every active pop-up.
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`.
#[no_mangle]
pub unsafe extern "C" fn sr_remove_popups(planner: *mut SrPlanner) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    // At most SR_MAX_POPUPS are active.
    for _ in 0..SR_MAX_POPUPS {
        let Some(id) = p.popups().next().map(|(id, _)| id) else {
            break;
        };
        if let Err(e) = p.remove_popup(id) {
            return popup_status(&e);
        }
    }
    SrStatus::Ok
}

/// Writes the most work one `sr_add_popup_circle` or `sr_add_popup_polygon` can count on the
/// loaded network.
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `work` is NULL or points to a
/// writable integer.
#[no_mangle]
pub unsafe extern "C" fn sr_worst_case_popup_work(
    planner: *const SrPlanner,
    work: *mut u64,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`.
    let Some(p) = (unsafe { planner_ref(planner) }) else {
        return SrStatus::NullPointer;
    };
    if work.is_null() {
        return SrStatus::NullPointer;
    }
    // SAFETY: `work` is non-null and the caller gives it writable.
    unsafe { work.write(p.worst_case_popup_work()) };
    SrStatus::Ok
}
