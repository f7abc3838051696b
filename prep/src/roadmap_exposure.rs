//! A ground-side planner for roadmap networks under the Voronoi mode's cost: Dijkstra over the
//! network's Dubins edges with edge cost k·L + (1 − k)·J, J the edge's exposure to the
//! scenario's threats by the three-point rule. The onboard roadmap planner does not weigh
//! exposure; this runs on the ground only, in f64, to compare the two modes under one cost.
//!
//! The exposure of a path of length L is (L/3)·Σ_j Σ_f (r_j/d_{f,j})⁴ with the distances d
//! taken at arc lengths L/6, L/2 and 5L/6 along the Dubins path (floored at 1 % of r_j), the
//! rule `skyroute::planner::segment_exposure` applies to straight segments. The threats are
//! the scenario's, each with its `radius_m` as the reference distance r_j; a roadmap network
//! was built with the same discs as hard obstacles, so its routes never enter them.
//!
//! Each leg's start and goal are joined by the shortest collision-free Dubins path (goal
//! heading free: a turn then a straight) to the network's vertices within the onboard
//! planner's connection radius, or, when none of those connects, to the 32 nearest vertices
//! however far. Connections and network edges that come within the network's clearance of a
//! pop-up (or a connection, of an obstacle) are left out. There is no post-processing (the
//! onboard mission shortens its routes afterwards; this does not).

use crate::frame::LocalFrame;
use crate::local::{local, local_heading};
use crate::mission::LocalPopup;
use crate::render::primitive_obstacle_distance;
use crate::route_json::{primitive_json, sampled_lon_lat};
use crate::scenario::Scenario;
use serde_json::{json, Value};
use skyroute::geometry::predicates::primitive_point_distance;
use skyroute::planner::{PlannerConfig, Threat};
use skyroute::{DubinsPath, Network, Pose, Primitive, Turn, Vec2};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// How many nearest vertices a leg's end is offered when none within the connection radius
/// connects.
pub const WIDE_CONNECTIONS: usize = 32;

/// Step of the dense exposure integral along the flown primitives, metres.
pub const FLOWN_STEP_M: f64 = 5.0;

/// A directed arc of the search graph.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GraphArc {
    /// Tail node.
    pub from: usize,
    /// Head node.
    pub to: usize,
    /// Cost (finite, ≥ 0).
    pub cost: f64,
}

/// The exposure density Σ_j (r_j/d_j)⁴ at `p`, the distance floored at 1 % of r_j.
pub fn exposure_density(p: Vec2, threats: &[Threat]) -> f64 {
    threats
        .iter()
        .map(|t| {
            let dx = p.x as f64 - t.position.x as f64;
            let dy = p.y as f64 - t.position.y as f64;
            let d = dx.hypot(dy).max(0.01 * t.radius as f64);
            (t.radius as f64 / d).powi(4)
        })
        .sum()
}

/// The exposure of a Dubins path by the three-point rule: (L/3)·Σ over the points at L/6, L/2
/// and 5L/6 of the density.
pub fn dubins_exposure(path: &DubinsPath, threats: &[Threat]) -> f64 {
    let l = path.length() as f64;
    [1.0 / 6.0, 0.5, 5.0 / 6.0]
        .iter()
        .map(|f| exposure_density(path.sample((l * f) as f32).position, threats))
        .sum::<f64>()
        * l
        / 3.0
}

/// The exposure along `prims` as a dense integral: the trapezoidal rule at steps of at most
/// [`FLOWN_STEP_M`].
pub fn primitives_flown_exposure(prims: &[Primitive], threats: &[Threat]) -> f64 {
    let mut total = 0.0;
    for p in prims {
        let len = p.length() as f64;
        let n = ((len / FLOWN_STEP_M).ceil() as usize).clamp(1, 1_000_000);
        let mut prev = exposure_density(p.start(), threats);
        for i in 1..=n {
            let q = exposure_density(
                p.pose_at((len * i as f64 / n as f64) as f32).position,
                threats,
            );
            total += 0.5 * (prev + q) * len / n as f64;
            prev = q;
        }
    }
    total
}

/// A node in the heap: its tentative cost, smallest first.
#[derive(PartialEq)]
struct Entry(f64, usize);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// Dijkstra over `n` nodes and `arcs` (costs ≥ 0) from `source` to `target`: the cheapest
/// cost and the arcs' indices along the route, or `None` when `target` is unreachable.
pub fn dijkstra(
    n: usize,
    arcs: &[GraphArc],
    source: usize,
    target: usize,
) -> Option<(f64, Vec<usize>)> {
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, a) in arcs.iter().enumerate() {
        out[a.from].push(i);
    }
    let mut dist = vec![f64::INFINITY; n];
    let mut via: Vec<Option<usize>> = vec![None; n];
    let mut heap = BinaryHeap::new();
    dist[source] = 0.0;
    heap.push(Entry(0.0, source));
    while let Some(Entry(d, u)) = heap.pop() {
        if d > dist[u] {
            continue;
        }
        if u == target {
            break;
        }
        for &i in &out[u] {
            let a = arcs[i];
            let nd = d + a.cost;
            if nd < dist[a.to] {
                dist[a.to] = nd;
                via[a.to] = Some(i);
                heap.push(Entry(nd, a.to));
            }
        }
    }
    if !dist[target].is_finite() {
        return None;
    }
    let mut path = Vec::new();
    let mut at = target;
    while let Some(i) = via[at] {
        path.push(i);
        at = arcs[i].from;
    }
    path.reverse();
    Some((dist[target], path))
}

/// One planned leg.
#[derive(Clone, Debug)]
pub struct GroundLeg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// Its lines and arcs.
    pub primitives: Vec<Primitive>,
    /// Length, metres.
    pub length_m: f64,
    /// Exposure by the three-point rule, summed over its Dubins paths (what the search costed).
    pub exposure_three_point: f64,
    /// Exposure of the flown primitives, dense integral.
    pub exposure_flown: f64,
    /// The network edges it uses.
    pub network_edges: usize,
    /// Heading on arrival, radians in the local frame.
    pub arrival_heading: f32,
    /// Whether an end needed the widened connection (the nearest vertices however far).
    pub widened: bool,
}

/// A mission planned on the ground under the exposure cost.
#[derive(Clone, Debug)]
pub struct GroundPlan {
    /// The legs, in order.
    pub legs: Vec<GroundLeg>,
    /// The weight k.
    pub threat_weight: f64,
    /// The threats the exposure was measured against.
    pub threats: Vec<Threat>,
    /// Network edges left out because they come within the clearance of a pop-up.
    pub blocked_edges: usize,
}

/// Why a ground plan failed: bad input, or no route.
#[derive(Debug)]
pub enum GroundPlanError {
    /// Bad input (the network, the scenario or the weight).
    BadInput(String),
    /// A leg has no route: the message names it.
    NoRoute(String),
}

impl std::fmt::Display for GroundPlanError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GroundPlanError::BadInput(m) | GroundPlanError::NoRoute(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for GroundPlanError {}

/// The network, its clearance, the pop-ups: what a path must keep away from.
struct Keepout<'a, 'n> {
    net: &'a Network<'n>,
    popups: &'a [LocalPopup],
    clearance: f64,
}

impl Keepout<'_, '_> {
    /// Whether `path` keeps the clearance from every pop-up, and, with `obstacles`, from every
    /// obstacle of the network.
    fn clear(&self, path: &DubinsPath, obstacles: bool) -> bool {
        let tol = 1e-3;
        path.primitives().iter().flatten().all(|p| {
            self.popups.iter().all(|c| {
                primitive_point_distance(p, c.centre) as f64
                    >= c.radius as f64 + self.clearance - tol
            }) && (!obstacles
                || (0..self.net.obstacle_count())
                    .filter_map(|i| self.net.obstacle(i))
                    .all(|(o, _)| primitive_obstacle_distance(p, &o) >= self.clearance - tol))
        })
    }

    /// Collision-free connections of `end` to the network's vertices (`towards`: from the end
    /// to a vertex, else from a vertex to the end): `(vertex, path)` pairs, and whether the
    /// connection radius had to be widened.
    fn connect(
        &self,
        end: Pose,
        heading_fixed: bool,
        towards: bool,
    ) -> (Vec<(usize, DubinsPath)>, bool) {
        let r = self.net.turn_radius();
        let mut near: Vec<(f64, usize, Pose)> = (0..self.net.vertex_count())
            .filter_map(|i| self.net.vertex(i).map(|v| (i as usize, v)))
            .map(|(i, v)| (v.position.distance(end.position) as f64, i, v))
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let path_to = |v: Pose| -> Option<DubinsPath> {
            if towards {
                return DubinsPath::shortest(&end, &v, r);
            }
            if heading_fixed {
                return DubinsPath::shortest(&v, &end, r);
            }
            [Turn::Left, Turn::Right]
                .into_iter()
                .filter_map(|t| DubinsPath::turn_then_straight(&v, r, end.position, t))
                .min_by(|a, b| a.length().total_cmp(&b.length()))
        };
        let radius = PlannerConfig::DEFAULT.connect_radius_m as f64;
        let connect = |cands: &[(f64, usize, Pose)]| -> Vec<(usize, DubinsPath)> {
            cands
                .iter()
                .filter_map(|&(_, i, v)| path_to(v).map(|p| (i, p)))
                .filter(|(_, p)| self.clear(p, true))
                .collect()
        };
        let within = near.iter().take_while(|c| c.0 <= radius).count();
        let found = connect(&near[..within]);
        if !found.is_empty() {
            return (found, false);
        }
        (connect(&near[..near.len().min(WIDE_CONNECTIONS)]), true)
    }
}

/// Plans start → waypoints in order → goal on the roadmap network `net` with edge cost
/// k·L + (1 − k)·exposure, avoiding `popups`.
pub fn plan_roadmap_exposure(
    net: &Network,
    scenario: &Scenario,
    frame: &LocalFrame,
    popups: &[LocalPopup],
    k: f64,
) -> Result<GroundPlan, GroundPlanError> {
    if !(0.0..=1.0).contains(&k) {
        return Err(GroundPlanError::BadInput(format!(
            "--threat-weight {k}: expected a weight in [0, 1]"
        )));
    }
    let threats = crate::local::local_threats(scenario, frame);
    let keep = Keepout {
        net,
        popups,
        clearance: net.clearance() as f64,
    };
    let cost = |p: &DubinsPath| k * p.length() as f64 + (1.0 - k) * dubins_exposure(p, &threats);
    // The network's edges: nodes 0..V; the leg's start is node V, its goal V + 1.
    let v = net.vertex_count() as usize;
    let mut arcs = Vec::new();
    let mut paths = Vec::new();
    let mut blocked_edges = 0;
    for i in 0..net.edge_count() {
        let (Some(e), Some(p)) = (net.edge(i), net.edge_path(i)) else {
            return Err(GroundPlanError::BadInput(format!(
                "edge {i} has no Dubins geometry: not a roadmap network"
            )));
        };
        if !keep.clear(&p, false) {
            blocked_edges += 1;
            continue;
        }
        arcs.push(GraphArc {
            from: e.source as usize,
            to: e.target as usize,
            cost: cost(&p),
        });
        paths.push(p);
    }
    let network_arcs = arcs.len();
    let start = scenario
        .start
        .as_ref()
        .ok_or_else(|| GroundPlanError::BadInput("the scenario has no start".into()))?;
    let goal = scenario
        .goal
        .as_ref()
        .ok_or_else(|| GroundPlanError::BadInput("the scenario has no goal".into()))?;
    let mut at = Pose {
        position: local(frame, start.lon, start.lat),
        heading: start
            .heading_deg
            .map_or(0.0, |h| local_heading(frame, start.lon, start.lat, h)),
    };
    let mut from = start.name.clone();
    let mut legs = Vec::new();
    for stop in scenario.waypoints.iter().chain(std::iter::once(goal)) {
        let heading = stop
            .heading_deg
            .map(|h| local_heading(frame, stop.lon, stop.lat, h));
        let end = Pose {
            position: local(frame, stop.lon, stop.lat),
            heading: heading.unwrap_or(0.0),
        };
        arcs.truncate(network_arcs);
        paths.truncate(network_arcs);
        let (outs, wide_s) = keep.connect(at, true, true);
        let (ins, wide_g) = keep.connect(end, heading.is_some(), false);
        for (i, p) in outs {
            arcs.push(GraphArc {
                from: v,
                to: i,
                cost: cost(&p),
            });
            paths.push(p);
        }
        for (i, p) in ins {
            arcs.push(GraphArc {
                from: i,
                to: v + 1,
                cost: cost(&p),
            });
            paths.push(p);
        }
        let Some((_, route)) = dijkstra(v + 2, &arcs, v, v + 1) else {
            return Err(GroundPlanError::NoRoute(format!(
                "leg {from} -> {}: no route through the network's edges clear of the pop-ups",
                stop.name
            )));
        };
        let leg_paths: Vec<&DubinsPath> = route.iter().map(|&i| &paths[i]).collect();
        let primitives: Vec<Primitive> = leg_paths
            .iter()
            .flat_map(|p| p.primitives().into_iter().flatten())
            .filter(|p| p.length() > 0.0)
            .collect();
        let arrival = leg_paths.last().map_or(at.heading, |p| p.end().heading);
        legs.push(GroundLeg {
            from: from.clone(),
            to: stop.name.clone(),
            length_m: leg_paths.iter().map(|p| p.length() as f64).sum(),
            exposure_three_point: leg_paths.iter().map(|p| dubins_exposure(p, &threats)).sum(),
            exposure_flown: primitives_flown_exposure(&primitives, &threats),
            network_edges: route.len().saturating_sub(2),
            arrival_heading: arrival,
            widened: wide_s || wide_g,
            primitives,
        });
        at = Pose {
            position: end.position,
            heading: arrival,
        };
        from = stop.name.clone();
    }
    Ok(GroundPlan {
        legs,
        threat_weight: k,
        threats,
        blocked_edges,
    })
}

/// The route file of a ground plan: the roadmap route file's members, plus the weight, the
/// exposures and the threats, marked as planned on the ground.
pub fn ground_route_json(m: &GroundPlan, frame: &LocalFrame, scenario_name: &str) -> Value {
    let all: Vec<Primitive> = m.legs.iter().flat_map(|l| l.primitives.clone()).collect();
    let (lat0, lon0) = frame.origin();
    json!({
        "scenario": scenario_name,
        "mode": "roadmap",
        "planner": "ground: Dijkstra over the roadmap's edges with cost k*L + (1 - k)*exposure (the onboard roadmap planner does not weigh exposure)",
        "frame": {"origin_lat_deg": lat0, "origin_lon_deg": lon0, "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)"},
        "length_m": m.legs.iter().map(|l| l.length_m).sum::<f64>(),
        "threat_weight": m.threat_weight,
        "exposure_flown": m.legs.iter().map(|l| l.exposure_flown).sum::<f64>(),
        "exposure_three_point": m.legs.iter().map(|l| l.exposure_three_point).sum::<f64>(),
        "blocked_edges": m.blocked_edges,
        "threats": m.threats.iter().enumerate().map(|(i, t)| json!({
            "centre": [t.position.x, t.position.y],
            "radius_m": t.radius,
            "origin": format!("scenario {i}"),
        })).collect::<Vec<_>>(),
        "legs": m.legs.iter().map(|l| json!({
            "from": l.from,
            "to": l.to,
            "length_m": l.length_m,
            "network_edges": l.network_edges,
            "arrival_heading_rad": l.arrival_heading,
            "widened_connection": l.widened,
            "exposure_flown": l.exposure_flown,
            "exposure_three_point": l.exposure_three_point,
            "primitives": l.primitives.iter().map(primitive_json).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "geometry": {"type": "LineString", "coordinates": sampled_lon_lat(&all, frame, 5.0)},
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyroute::planner::ThreatOrigin;

    /// Bellman–Ford: the cheapest cost from `source` to every node.
    fn bellman_ford(n: usize, arcs: &[GraphArc], source: usize) -> Vec<f64> {
        let mut d = vec![f64::INFINITY; n];
        d[source] = 0.0;
        for _ in 0..n {
            for a in arcs {
                if d[a.from] + a.cost < d[a.to] {
                    d[a.to] = d[a.from] + a.cost;
                }
            }
        }
        d
    }

    /// An independent exposure of a straight segment in f64 by the three-point rule.
    fn segment_exposure_f64(a: (f64, f64), b: (f64, f64), threats: &[(f64, f64, f64)]) -> f64 {
        let l = (b.0 - a.0).hypot(b.1 - a.1);
        let mut sum = 0.0;
        for f in [1.0 / 6.0, 0.5, 5.0 / 6.0] {
            let p = (a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f);
            for &(x, y, r) in threats {
                let d = (p.0 - x).hypot(p.1 - y).max(0.01 * r);
                sum += (r / d).powi(4);
            }
        }
        l / 3.0 * sum
    }

    #[test]
    fn dijkstra_matches_bellman_ford_on_a_small_roadmap_under_the_exposure_cost() {
        // A 4 x 4 grid of vertices 1 km apart, straight edges both ways between neighbours and
        // along the diagonals, two threats among them; the cost of each arc from the Dubins
        // line (heading along the edge) against the independent f64 rule.
        let threats_f64 = [(1200.0, 1300.0, 600.0), (2100.0, 800.0, 400.0)];
        let threats: Vec<Threat> = threats_f64
            .iter()
            .map(|&(x, y, r)| Threat {
                position: Vec2::new(x as f32, y as f32),
                radius: r as f32,
                origin: ThreatOrigin::Network(0),
            })
            .collect();
        let at = |i: usize| ((i % 4) as f64 * 1000.0, (i / 4) as f64 * 1000.0);
        for k in [0.0, 0.1, 0.5, 0.9, 1.0] {
            let mut arcs = Vec::new();
            for i in 0..16 {
                for j in 0..16 {
                    let (a, b) = (at(i), at(j));
                    let dist = (b.0 - a.0).hypot(b.1 - a.1);
                    if i == j || dist > 1500.0 {
                        continue;
                    }
                    let heading = (b.1 - a.1).atan2(b.0 - a.0) as f32;
                    let start = Pose::new(a.0 as f32, a.1 as f32, heading);
                    let goal = Pose::new(b.0 as f32, b.1 as f32, heading);
                    let path = DubinsPath::shortest(&start, &goal, 100.0).unwrap();
                    let e = dubins_exposure(&path, &threats);
                    let e_ref = segment_exposure_f64(a, b, &threats_f64);
                    assert!((e - e_ref).abs() <= 1e-3 * e_ref.max(1.0), "{e} vs {e_ref}");
                    arcs.push(GraphArc {
                        from: i,
                        to: j,
                        cost: k * dist + (1.0 - k) * e_ref,
                    });
                }
            }
            let best = bellman_ford(16, &arcs, 0);
            for (target, &b) in best.iter().enumerate().skip(1) {
                let (cost, route) = dijkstra(16, &arcs, 0, target).unwrap();
                assert!((cost - b).abs() <= 1e-9 * b, "k {k}");
                // The route is a chain from the source to the target whose arcs sum to the cost.
                assert_eq!(arcs[route[0]].from, 0);
                assert_eq!(arcs[*route.last().unwrap()].to, target);
                assert!(route.windows(2).all(|w| arcs[w[0]].to == arcs[w[1]].from));
                let sum: f64 = route.iter().map(|&i| arcs[i].cost).sum();
                assert!((sum - cost).abs() <= 1e-9 * cost);
            }
        }
        assert!(dijkstra(
            3,
            &[GraphArc {
                from: 0,
                to: 1,
                cost: 1.0
            }],
            0,
            2
        )
        .is_none());
    }

    #[test]
    fn flown_exposure_of_a_far_line_matches_its_closed_form() {
        // A line from (-L, h) to (L, h) past a site at the origin: ∫ r⁴/(x² + h²)² dx in closed
        // form, against the dense integral along the primitive.
        let (r, h, l) = (500.0f64, 800.0f64, 5000.0f64);
        let threats = [Threat {
            position: Vec2::new(0.0, 0.0),
            radius: r as f32,
            origin: ThreatOrigin::Network(0),
        }];
        let line = Primitive::Line(skyroute::Segment::new(
            Vec2::new(-l as f32, h as f32),
            Vec2::new(l as f32, h as f32),
        ));
        let f = |x: f64| x / (2.0 * h * h * (x * x + h * h)) + (x / h).atan() / (2.0 * h.powi(3));
        let exact = r.powi(4) * (f(l) - f(-l));
        let got = primitives_flown_exposure(&[line], &threats);
        assert!((got - exact).abs() < 1e-3 * exact, "{got} vs {exact}");
    }
}
