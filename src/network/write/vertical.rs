//! The writer of a three-dimensional roadmap's vertical section (Niendorf et al.;
//! `docs/FORMAT.md`, vertical section).

use super::{push, WriteError};
use crate::geometry::vertical::VerticalLimits;
use crate::network::format::*;
use std::vec::Vec;

/// What makes a roadmap three-dimensional: the aircraft's vertical limits, an altitude per
/// vertex and a height per obstacle (`f32::INFINITY`: no altitude clears it).
#[derive(Clone, Debug, PartialEq)]
pub struct VerticalSpec {
    /// Airspeed, climb rate and vertical acceleration.
    pub limits: VerticalLimits,
    /// Altitude of each vertex, metres, in the spec's vertex order.
    pub altitudes: Vec<f32>,
    /// Height of each obstacle, metres, in the spec's obstacle order.
    pub heights: Vec<f32>,
}

/// Appends the section to `body`. The writer checks only that the tables match the vertex and
/// obstacle counts; the encoder then loads the image, which checks the values and that every
/// edge's climb is within the limits.
pub(super) fn write_vertical_section(
    body: &mut Vec<u8>,
    v: &VerticalSpec,
    vertices: usize,
    obstacles: usize,
) -> Result<(), WriteError> {
    if v.altitudes.len() != vertices {
        return Err(WriteError::BadVertical(
            "altitudes differ in number from the vertices",
        ));
    }
    if v.heights.len() != obstacles {
        return Err(WriteError::BadVertical(
            "heights differ in number from the obstacles",
        ));
    }
    push(
        body,
        &VerticalRecord {
            airspeed: v.limits.airspeed,
            climb_rate: v.limits.climb_rate,
            vertical_accel: v.limits.vertical_accel,
        },
    );
    for &z in v.altitudes.iter().chain(&v.heights) {
        push(body, &F32Record(z));
    }
    Ok(())
}
