//! Latitude and longitude in and out: `sr_geo_to_local` and `sr_local_to_geo`, through the
//! loaded network's local frame (the core's `LocalFrame`: the transverse Mercator the ground
//! tool built the network in, with the meridian convergence applied to headings).

use crate::{planner_ref, SrPlanner, SrStatus};
use skyroute::{GeoError, Pose, Vec2};

/// A pose in the network's local frame: metres east (`x`) and north (`y`) of its origin, the
/// heading in radians counter-clockwise from east (as `sr_query` takes them).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrPose {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
    /// Radians counter-clockwise from east (grid east), in (−π, π].
    pub heading: f32,
}

/// A pose on the WGS-84 ellipsoid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrGeoPose {
    /// Longitude, degrees east, in [−180, 180).
    pub lon_deg: f64,
    /// Latitude, degrees north.
    pub lat_deg: f64,
    /// Compass heading: degrees clockwise from true north, in [0, 360).
    pub compass_deg: f64,
}

/// The status for a `GeoError`.
pub fn geo_status(e: &GeoError) -> SrStatus {
    match e {
        GeoError::NonFinite => SrStatus::GeoNonFinite,
        GeoError::Latitude => SrStatus::GeoLatitude,
        GeoError::Longitude => SrStatus::GeoLongitude,
        GeoError::Heading => SrStatus::GeoHeading,
        GeoError::OutOfFrame => SrStatus::GeoOutOfFrame,
    }
}

/// Converts a position (degrees) and compass heading (degrees clockwise from true north, in
/// [−360, 360]) to the loaded network's local frame and writes it to `*pose`, ready for an
/// `sr_query`. Refused with `SR_STATUS_NO_NETWORK` before a network is loaded, and with an
/// `SR_STATUS_GEO_…` status for a non-finite or out-of-range value or a point outside the
/// frame's valid region (`*pose` is then not written).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `pose` is NULL or points to a writable
/// `sr_pose`.
#[no_mangle]
pub unsafe extern "C" fn sr_geo_to_local(
    planner: *const SrPlanner,
    lon_deg: f64,
    lat_deg: f64,
    compass_deg: f64,
    pose: *mut SrPose,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`.
    let Some(p) = (unsafe { planner_ref(planner) }) else {
        return SrStatus::NullPointer;
    };
    if pose.is_null() {
        return SrStatus::NullPointer;
    }
    if p.network().byte_len() == 0 {
        return SrStatus::NoNetwork;
    }
    match p
        .network()
        .local_frame()
        .pose(lon_deg, lat_deg, compass_deg)
    {
        Ok(local) => {
            let out = SrPose {
                x: local.position.x,
                y: local.position.y,
                heading: local.heading,
            };
            // SAFETY: `pose` is non-null and the caller gives it writable.
            unsafe { pose.write(out) };
            SrStatus::Ok
        }
        Err(e) => geo_status(&e),
    }
}

/// Converts a pose of the loaded network's local frame (a route's point, an arrival heading) to
/// longitude, latitude and compass heading and writes it to `*geo`. Refused as
/// `sr_geo_to_local` refuses (`*geo` is then not written).
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `geo` is NULL or points to a writable
/// `sr_geo_pose`.
#[no_mangle]
pub unsafe extern "C" fn sr_local_to_geo(
    planner: *const SrPlanner,
    x: f32,
    y: f32,
    heading: f32,
    geo: *mut SrGeoPose,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`.
    let Some(p) = (unsafe { planner_ref(planner) }) else {
        return SrStatus::NullPointer;
    };
    if geo.is_null() {
        return SrStatus::NullPointer;
    }
    if p.network().byte_len() == 0 {
        return SrStatus::NoNetwork;
    }
    let frame = p.network().local_frame();
    let pose = Pose {
        position: Vec2::new(x, y),
        heading,
    };
    let converted = frame
        .lon_lat(pose.position)
        .and_then(|(lon, lat)| Ok((lon, lat, frame.compass_deg(&pose)?)));
    match converted {
        Ok((lon_deg, lat_deg, compass_deg)) => {
            // SAFETY: `geo` is non-null and the caller gives it writable.
            unsafe {
                geo.write(SrGeoPose {
                    lon_deg,
                    lat_deg,
                    compass_deg,
                })
            };
            SrStatus::Ok
        }
        Err(e) => geo_status(&e),
    }
}
