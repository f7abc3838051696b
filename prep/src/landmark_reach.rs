//! Why a landmark scenario has no navigable route, when its numbers alone prove it.
//!
//! Every leg of a landmark route is at least as long as the straight line it spans, and after
//! an overflight of landmark `l` in weather `ω` no leg may be longer than
//! `d_max(l) · max_α q(l, α, ω)` (Babel: the range an overflight of the best quality allows);
//! the first leg is bounded by the start's `dist_m`. So a route needs a chain start → landmarks
//! → goal whose straight legs fit those ranges. When no such chain exists (a breadth-first
//! search over the landmarks), no network and no planner can find a route, and the search's
//! frontier is the proof.

use crate::frame::LocalFrame;
use crate::local::local;
use crate::scenario::Scenario;

/// `Some(proof)` when the straight-leg condition rules out every route in weather `w` (index
/// into the scenario's weathers); `None` when some chain of straight legs fits (the network
/// may still have none) or the scenario has no start or goal.
pub fn no_route_proof(s: &Scenario, w: usize, frame: &LocalFrame) -> Option<String> {
    let (start, goal) = (s.start.as_ref()?, s.goal.as_ref()?);
    let start_range = start.dist_m?;
    let at = |lon, lat| {
        let p = local(frame, lon, lat);
        (p.x as f64, p.y as f64)
    };
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let sites: Vec<(f64, f64)> = s.landmarks.iter().map(|l| at(l.lon, l.lat)).collect();
    let range: Vec<f64> = s
        .landmarks
        .iter()
        .map(|l| {
            let best = l
                .quality
                .get(w)
                .map_or(0.0, |r| r.1.iter().copied().fold(0.0, f64::max));
            l.d_max_m * best
        })
        .collect();
    let (from, to) = (at(start.lon, start.lat), at(goal.lon, goal.lat));
    if dist(from, to) <= start_range {
        return None;
    }
    let mut reached: Vec<bool> = sites
        .iter()
        .map(|&p| dist(from, p) <= start_range)
        .collect();
    if !reached.iter().any(|&r| r) {
        let nearest =
            (0..sites.len()).min_by(|&a, &b| dist(from, sites[a]).total_cmp(&dist(from, sites[b])));
        let tail = nearest.map_or(String::new(), |i| {
            format!(
                " (the nearest, {}, is {:.2} km away)",
                s.landmarks[i].name,
                dist(from, sites[i]) / 1000.0
            )
        });
        return Some(format!(
            "no landmark lies within the start's {:.2} km{tail}, and the goal is farther",
            start_range / 1000.0
        ));
    }
    let mut frontier: Vec<usize> = (0..sites.len()).filter(|&i| reached[i]).collect();
    while let Some(a) = frontier.pop() {
        if dist(sites[a], to) <= range[a] {
            return None;
        }
        for b in 0..sites.len() {
            if !reached[b] && dist(sites[a], sites[b]) <= range[a] {
                reached[b] = true;
                frontier.push(b);
            }
        }
    }
    let names: Vec<String> = (0..sites.len())
        .filter(|&i| reached[i])
        .map(|i| {
            format!(
                "{} (range {:.2} km, goal {:.2} km away)",
                s.landmarks[i].name,
                range[i] / 1000.0,
                dist(sites[i], to) / 1000.0
            )
        })
        .collect();
    Some(format!(
        "straight legs within range reach only {} from the start, and none of them has the goal \
         or a landmark outside this set within range; every flyable leg is at least as long as \
         its straight line",
        names.join(", ")
    ))
}
