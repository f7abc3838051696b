//! How a waypoint without a heading gets one. By default the mission planner keeps 36 copies of
//! the waypoint, one per heading, and the dynamic programme over the stages takes the copy on
//! the cheapest chain ([`FreeHeadingRule::Cheapest`], `crate::mission`). Niendorf et al. fix the
//! heading first, as the one with the most clear out-edges
//! ([`FreeHeadingRule::MostClearOutEdges`]): a heading from which many Dubins paths into the
//! roadmap are free keeps alternatives when a pop-up later blocks some of them. Counting
//! out-edges alone can pick a heading the waypoint cannot be reached with (beside a zone, the
//! heading away from it has the most ways out and no way in), so only headings with at least
//! one clear in-edge are candidates.

use skyroute::geometry::DubinsPath;
use skyroute::network::write::ObstacleSpec;
use skyroute::{Network, Pose, Vec2};

/// How a waypoint without a heading gets one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FreeHeadingRule {
    /// Jointly with the whole mission: the cheapest chain over every heading copy (the default).
    #[default]
    Cheapest,
    /// The paper's: the heading with the most clear out-edges, fixed before the legs are planned.
    MostClearOutEdges,
}

/// Of `headings`, the one whose pose at `position` has the most clear out-edges, among those with
/// at least one clear in-edge: shortest Dubins paths (the network's turn radius) to (out) and
/// from (in) the network's vertices within `radius_m` that keep the network's clearance from
/// every one of `obstacles`. Ties go to the earlier heading. Returns the heading and its
/// out-edge count (`(headings[0], 0)` when no heading has both).
pub fn most_clear_out_edges(
    net: &Network<'_>,
    obstacles: &[ObstacleSpec],
    position: Vec2,
    headings: &[f32],
    radius_m: f32,
) -> (f32, usize) {
    let clearance = net.clearance();
    let near: Vec<Pose> = (0..net.vertex_count())
        .filter_map(|v| net.vertex(v))
        .filter(|p| p.position.distance(position) <= radius_m)
        .collect();
    let clear = |path: &DubinsPath| {
        path.primitives().into_iter().flatten().all(|prim| {
            obstacles
                .iter()
                .all(|o| !crate::roadmap::primitive_conflicts(&prim, o, clearance))
        })
    };
    let mut best = (headings.first().copied().unwrap_or(0.0), 0);
    let r = net.turn_radius();
    for &heading in headings {
        let at = Pose { position, heading };
        let reachable = near
            .iter()
            .filter_map(|from| DubinsPath::shortest(from, &at, r))
            .any(|path| clear(&path));
        if !reachable {
            continue;
        }
        let count = near
            .iter()
            .filter_map(|to| DubinsPath::shortest(&at, to, r))
            .filter(|path| clear(path))
            .count();
        if count > best.1 {
            best = (heading, count);
        }
    }
    best
}
