//! The rounding of one corner of a terrain route (the paper's 1-trajectory turn) and the
//! tolerance of a start or goal on a node.

use crate::geometry::{Arc, Pose, Turn, Vec2};
use core::f32::consts::PI;

/// A start or goal within this many metres of a node is on it: the start leaves the node along
/// its own heading (a link of length 0, whose first turn may cut at most this far), and a
/// free-heading goal is reached by arriving at the node (no turn).
pub(super) const ON_NODE_M: f32 = 1e-3;

/// Whether `p` is on node position `node` ([`ON_NODE_M`], plus the f32 rounding of their
/// coordinates).
pub(super) fn on_node(p: Vec2, node: Vec2) -> bool {
    p.distance(node) <= ON_NODE_M + 1e-6 * (libm::fabsf(node.x) + libm::fabsf(node.y))
}

/// The rounding of one corner.
#[derive(Clone, Copy, Debug)]
pub(super) struct Fillet {
    /// Distance from the node to each tangent point, `r·tan(θ/2)`.
    pub(super) cut: f32,
    /// Turn angle `θ`, radians in `[0, π]`.
    pub(super) angle: f32,
    /// Turn direction.
    pub(super) turn: Turn,
}

impl Fillet {
    /// The fillet of radius `r` between unit directions `u_in` and `u_out`.
    pub(super) fn new(u_in: Vec2, u_out: Vec2, r: f32) -> Self {
        let cross = u_in.cross(u_out);
        let dot = u_in.dot(u_out);
        let angle = libm::atan2f(libm::fabsf(cross), dot);
        // A (near) reversal has no room to turn: `1 + dot` near 0 would give a cut of 0 for
        // directions a rounding short of unit length, so turns within 10⁻³ rad of π are refused.
        let cut = if angle < PI - 1e-3 && 1.0 + dot > 1e-6 {
            r * libm::fabsf(cross) / (1.0 + dot)
        } else {
            f32::INFINITY
        };
        let turn = if cross >= 0.0 {
            Turn::Left
        } else {
            Turn::Right
        };
        Fillet { cut, angle, turn }
    }

    /// What the fillet changes in the length flown: `r·θ − 2c` (never positive).
    pub(super) fn saving(&self, r: f32) -> f32 {
        r * self.angle - 2.0 * self.cut
    }

    /// The arc at node `v` entered along `u_in`, or `None` for a straight pass.
    pub(super) fn arc(&self, v: Vec2, u_in: Vec2, r: f32) -> Option<Arc> {
        if !(self.angle * r > 0.0) || !self.cut.is_finite() {
            return None;
        }
        let entry = v - u_in * self.cut;
        let pose = Pose {
            position: entry,
            heading: u_in.angle(),
        };
        Some(Arc::from_pose(&pose, self.turn, r, self.angle))
    }
}
