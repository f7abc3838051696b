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

/// The fillet against its closed form: a turn through `θ` on radius `r` is tangent to both
/// directions at `r·tan(θ/2)` from the node (the tangent-length formula of a circular curve),
/// computed here in f64.
#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::format;

    const R: f32 = 120.0;

    /// Left and right turns of 0.05 to 3.1 rad, entered on eight headings.
    #[test]
    fn a_turns_cut_angle_direction_and_saving_are_the_tangent_lengths() {
        for k in 0..8 {
            let heading = -3.0 + 0.77 * k as f32;
            let u_in = Vec2::from_angle(heading);
            for step in 0..63 {
                let theta = 0.05 + 0.049 * step as f32;
                for (turn, sign) in [(Turn::Left, 1.0), (Turn::Right, -1.0)] {
                    let u_out = Vec2::from_angle(heading + sign * theta);
                    let f = Fillet::new(u_in, u_out, R);
                    let cut = R as f64 * (theta as f64 / 2.0).tan();
                    let at = format!("heading {heading}, θ {theta}, {turn:?}");
                    assert!(
                        (f.cut as f64 - cut).abs() <= 1e-4 * cut.max(1.0),
                        "{at}: cut {}",
                        f.cut
                    );
                    assert!((f.angle - theta).abs() <= 1e-5, "{at}: angle {}", f.angle);
                    assert_eq!(f.turn, turn, "{at}");
                    let saving = R as f64 * theta as f64 - 2.0 * cut;
                    assert!(
                        (f.saving(R) as f64 - saving).abs() <= 1e-3 * cut.max(1.0),
                        "{at}"
                    );
                }
            }
        }
    }

    /// The arc starts `cut` before the node on the way in, with the incoming heading, sweeps
    /// `θ`, and ends `cut` after it on the way out, with the outgoing heading.
    #[test]
    fn the_arc_runs_from_tangent_point_to_tangent_point() {
        let node = Vec2::new(250.0, -40.0);
        for (heading, theta) in [(0.3f32, 1.2f32), (-2.0, -0.4), (2.9, 2.5), (1.0, -3.0)] {
            let u_in = Vec2::from_angle(heading);
            let u_out = Vec2::from_angle(heading + theta);
            let f = Fillet::new(u_in, u_out, R);
            let arc = f.arc(node, u_in, R).expect("a turn has an arc");
            let entry = node - u_in * f.cut;
            let exit = node + u_out * f.cut;
            // `1 + dot` loses f32 digits near a reversal (θ = 3: cut 1.7 km): 10⁻⁵ of the cut.
            let tolerance = 1e-3 + 1e-5 * f.cut;
            assert!(arc.start().distance(entry) < tolerance, "θ {theta}");
            assert!(arc.end().distance(exit) < tolerance, "θ {theta}");
            assert!((arc.length() - R * theta.abs()).abs() < 1e-3, "θ {theta}");
            let (first, last) = (arc.pose_at(0.0), arc.pose_at(arc.length()));
            assert!(crate::geometry::wrap_to_pi(first.heading - heading).abs() < 1e-5);
            assert!(crate::geometry::wrap_to_pi(last.heading - heading - theta).abs() < 1e-4);
            assert_eq!(arc.turn(), f.turn);
        }
    }

    /// A straight pass has no arc and costs nothing; a zero radius has no arc either.
    #[test]
    fn a_straight_pass_or_a_zero_radius_has_no_arc() {
        let u = Vec2::from_angle(0.7);
        let f = Fillet::new(u, u, R);
        assert_eq!((f.cut, f.angle, f.saving(R)), (0.0, 0.0, 0.0));
        assert!(f.arc(Vec2::new(1.0, 2.0), u, R).is_none());
        let bend = Fillet::new(u, Vec2::from_angle(1.7), R);
        assert!(bend.arc(Vec2::new(1.0, 2.0), u, 0.0).is_none());
        assert!(bend.arc(Vec2::new(1.0, 2.0), u, R).is_some());
    }

    /// A reversal, or a turn within 10⁻³ rad of one, has no room: an infinite cut and no arc.
    /// Nor has a turn so near one that `1 + cos θ ≤ 10⁻⁶` (within about 1.41·10⁻³ rad of π:
    /// 1.2·10⁻³ short), nor directions a rounding short of unit length that point back
    /// (1 + dot > 0 while the angle is π), nor directions longer than unit whose `1 + dot` is
    /// not positive. A turn 2·10⁻³ short of π has a finite cut.
    #[test]
    fn a_reversal_has_no_room_to_turn() {
        let u_in = Vec2::from_angle(0.4);
        for delta in [0.0f32, 2e-4, 9e-4, 1.2e-3] {
            let f = Fillet::new(u_in, Vec2::from_angle(0.4 + PI - delta), R);
            assert_eq!(f.cut, f32::INFINITY, "{delta} short of π");
            assert!(f.arc(Vec2::new(0.0, 0.0), u_in, R).is_none());
        }
        let tight = Fillet::new(u_in, Vec2::from_angle(0.4 + PI - 2e-3), R);
        assert!(
            tight.cut.is_finite() && tight.cut > 1e5,
            "cut {}",
            tight.cut
        );
        let short = Fillet::new(Vec2::new(0.999, 0.0), Vec2::new(-1.0, 0.0), R);
        assert_eq!(short.cut, f32::INFINITY);
        let long = Fillet::new(Vec2::new(1.01, 0.0), Vec2::from_angle(PI - 0.01), R);
        assert_eq!(long.cut, f32::INFINITY);
    }

    /// Within 1 mm of a node, plus 10⁻⁶ of its coordinates' magnitudes for their rounding.
    #[test]
    fn on_node_is_within_a_millimetre_and_the_rounding() {
        let origin = Vec2::new(0.0, 0.0);
        assert!(on_node(Vec2::new(0.0009, 0.0), origin));
        assert!(!on_node(Vec2::new(0.0011, 0.0), origin));
        assert!(!on_node(Vec2::new(0.0, -0.0011), origin));
        let far = Vec2::new(-6.0e4, 4.0e4); // 0.1 m of rounding slack
        assert!(on_node(far + Vec2::new(0.0, 0.09), far));
        assert!(!on_node(far + Vec2::new(0.0, 0.11), far));
    }
}
