//! A three-dimensional roadmap's fixture: the query's altitudes, the pop-up's height, and the
//! host's altitudes along the route for the firmware to match. On a planar network: no
//! altitudes, a pop-up of unbounded height (a wall), and an altitude sum of 0.

use super::HostPlanner;
use skyroute::{Network, Vec2};
use std::fmt::Write as _;

/// The altitude of the vertex nearest to `p` (`None` in a planar network).
fn nearest_altitude(network: &Network<'_>, p: Vec2) -> Option<f32> {
    let nearest = (0..network.vertex_count())
        .filter_map(|v| Some((network.vertex(v)?.position.distance(p), v)))
        .min_by(|a, b| a.0.total_cmp(&b.0))?
        .1;
    network.vertex_altitude(nearest)
}

/// The query's altitudes: `given`, else each end at its nearest vertex's altitude; `None` in a
/// planar network.
pub fn query_altitudes(
    network: &Network<'_>,
    given: Option<(f32, f32)>,
    start: Vec2,
    goal: Vec2,
) -> Option<(f32, f32)> {
    if !network.is_three_dimensional() {
        return None;
    }
    given.or_else(|| {
        Some((
            nearest_altitude(network, start)?,
            nearest_altitude(network, goal)?,
        ))
    })
}

/// The pop-up's height: `given`, else the middle of the vertices' altitudes in a
/// three-dimensional roadmap (so that some edges fly over it and some do not); unbounded in a
/// planar network.
pub fn popup_height(network: &Network<'_>, given: Option<f32>) -> f32 {
    let altitudes = (0..network.vertex_count()).filter_map(|v| network.vertex_altitude(v));
    let (lo, hi) = altitudes.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), z| {
        (lo.min(z), hi.max(z))
    });
    match (given, lo <= hi) {
        (Some(h), _) => h,
        (None, true) => 0.5 * (lo + hi),
        (None, false) => f32::INFINITY,
    }
}

/// The sum over the last route's primitives of the altitude at each one's middle
/// (`Planner::route_altitude_at`), in route order, as the firmware sums it; 0 in the plane.
pub fn altitude_sum(planner: &HostPlanner<'_>) -> f32 {
    (0..planner.route().len())
        .filter_map(|k| {
            let half = 0.5 * planner.route()[k].length();
            planner.route_altitude_at(k, half)
        })
        .sum()
}

/// An `f32` constant's literal, `f32::INFINITY` included.
fn literal(x: f32) -> String {
    match x {
        f32::INFINITY => "f32::INFINITY".to_string(),
        _ => super::lit(x),
    }
}

/// The `query.rs` lines of the query's altitudes, the pop-up's height and the host's
/// altitude sum.
pub fn vertical_rs(w: &mut String, altitudes: Option<(f32, f32)>, height: f32, sum: f32) {
    let altitudes = altitudes.map_or("None".to_string(), |(s, g)| {
        format!("Some(({}, {}))", super::lit(s), super::lit(g))
    });
    let _ = writeln!(
        w,
        "/// Three-dimensional roadmap: the start's and goal's altitudes, metres (`None` in the \
         plane)."
    );
    let _ = writeln!(w, "pub const ALTITUDES: Option<(f32, f32)> = {altitudes};");
    let _ = writeln!(w, "/// The pop-up's top, metres (`f32::INFINITY`: a wall).");
    let _ = writeln!(w, "pub const POPUP_HEIGHT: f32 = {};", literal(height));
    let _ = writeln!(
        w,
        "/// The sum over the route's primitives of the altitude at each one's middle, as the \
         host computes it (0 in the plane)."
    );
    let _ = writeln!(
        w,
        "pub const EXPECTED_ALTITUDE_SUM: f32 = {};",
        super::lit(sum)
    );
}
