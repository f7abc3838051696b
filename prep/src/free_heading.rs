//! How a waypoint without a heading gets one. By default the mission planner keeps 36 copies of
//! the waypoint, one per heading, and the dynamic programme over the stages takes the copy on
//! the cheapest chain ([`FreeHeadingRule::Cheapest`], `crate::mission`). Niendorf et al. fix the
//! heading first, as the one with the most clear out-edges
//! ([`FreeHeadingRule::MostClearOutEdges`]): a heading from which many Dubins paths into the
//! roadmap are free keeps alternatives when a pop-up later blocks some of them. Counting
//! out-edges alone can pick a heading the waypoint cannot be reached with (beside a zone, the
//! heading away from it has the most ways out and no way in), so only headings with at least
//! one clear in-edge are candidates. On a three-dimensional roadmap each path flies between the
//! waypoint's altitude and the vertex's, and is clear when it keeps the clearance from every
//! obstacle and pop-up below its height (`crate::roadmap::vertical`).

use crate::roadmap::vertical::VerticalInput;
use crate::roadmap::{CollisionCheck, ObstacleIndex};
use skyroute::geometry::vertical::VerticalProfile;
use skyroute::geometry::DubinsPath;
use skyroute::network::write::ObstacleSpec;
use skyroute::{Network, Pose, Vec2};

/// What the paths from and to a free waypoint must keep the network's clearance from.
pub struct Surroundings<'a> {
    /// The scenario's obstacles and the pop-ups, in the frame.
    pub obstacles: &'a [ObstacleSpec],
    /// On a three-dimensional roadmap: the heights of `obstacles` (with the vertical limits)
    /// and the waypoint's altitude; `None` in the plane, where every obstacle is a wall.
    pub vertical: Option<(&'a VerticalInput, f32)>,
}

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
/// the `surroundings`. Ties go to the earlier heading. Returns the heading and its out-edge
/// count (`(headings[0], 0)` when no heading has both).
pub fn most_clear_out_edges(
    net: &Network<'_>,
    surroundings: &Surroundings,
    position: Vec2,
    headings: &[f32],
    radius_m: f32,
) -> (f32, usize) {
    let clearance = net.clearance();
    // Each vertex within the radius, with its altitude on a three-dimensional roadmap.
    let near: Vec<(Pose, f32)> = (0..net.vertex_count())
        .filter_map(|v| Some((net.vertex(v)?, net.vertex_altitude(v).unwrap_or(f32::NAN))))
        .filter(|(p, _)| p.position.distance(position) <= radius_m)
        .collect();
    let index = ObstacleIndex::new(surroundings.obstacles);
    // Whether `path`, flown from altitude `from` to `to`, is clear.
    let clear = |path: &DubinsPath, (from, to): (f32, f32)| match surroundings.vertical {
        None => path.primitives().into_iter().flatten().all(|prim| {
            let (lo, hi) = prim.bounding_box();
            index
                .near_indexed(lo, hi, clearance)
                .all(|(_, o)| !crate::roadmap::primitive_conflicts(&prim, o, clearance))
        }),
        Some((vertical, _)) => VerticalProfile::new(from, to, path.length(), &vertical.limits)
            .is_some_and(|p| {
                vertical.path_is_clear(&index, path, &p, clearance, CollisionCheck::Exact)
            }),
    };
    let z = surroundings.vertical.map_or(f32::NAN, |(_, z)| z);
    let mut best = (headings.first().copied().unwrap_or(0.0), 0);
    let r = net.turn_radius();
    for &heading in headings {
        let at = Pose { position, heading };
        let reachable = near.iter().any(|(from, zv)| {
            DubinsPath::shortest(from, &at, r).is_some_and(|path| clear(&path, (*zv, z)))
        });
        if !reachable {
            continue;
        }
        let count = near
            .iter()
            .filter(|(to, zv)| {
                DubinsPath::shortest(&at, to, r).is_some_and(|path| clear(&path, (z, *zv)))
            })
            .count();
        if count > best.1 {
            best = (heading, count);
        }
    }
    best
}
