//! The build: the basic networks of all pairs and endpoints, run in parallel, assembled into
//! the landmark network.

use super::basic::{run_job, Ctx, Job, JobResult, JobStats, Terminals};
use super::input::{EndpointSite, LandmarkInput};
use super::network::{
    EndpointEdge, EndpointLinks, HermiteChain, LandmarkEdge, LandmarkNetwork, LandmarkStats,
    LandmarkVertex,
};
use super::params::{LandmarkError, LandmarkParams, RangeRule};
use super::sampling::{job_seed, Obstacles};
use crate::scenario::Scenario;
use rayon::prelude::*;
use skyroute::geometry::hermite::{FlyLimits, LineElement};
use skyroute::{Pose, Vec2};
use std::sync::atomic::{AtomicUsize, Ordering as AtomicOrdering};
use std::time::Instant;

/// A basic network's role.
enum JobKind {
    /// Landmarks `a < b`.
    Pair(usize, usize),
    /// Start to landmark.
    Start(usize),
    /// Landmark to goal.
    Goal(usize),
}

/// Terminals of landmark `l`: its direction line elements, plus the exact opposites when the
/// direction count is odd. Returns (terminals, index of direction k's opposite).
fn landmark_terminals(input: &LandmarkInput, l: usize) -> (Vec<LineElement>, Vec<usize>) {
    let vel = &input.direction_velocities[l];
    let pos = input.landmarks[l].position;
    let n = vel.len();
    let mut elements: Vec<LineElement> = vel.iter().map(|&v| LineElement::new(pos, v)).collect();
    let opposite = if n.is_multiple_of(2) {
        (0..n).map(|k| (k + n / 2) % n).collect()
    } else {
        elements.extend(
            vel.iter()
                .map(|&v| LineElement::new(pos, Vec2::new(-v.x, -v.y))),
        );
        (0..n).map(|k| n + k).collect()
    };
    (elements, opposite)
}

/// Builds the landmark network of a scenario with its own parameters.
pub fn build_landmark_network(
    s: &Scenario,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<LandmarkNetwork, LandmarkError> {
    build_landmark_network_with(s, RangeRule::default(), progress)
}

/// [`build_landmark_network`] with the range rule given (`skyroute build --landmark-ranges`).
pub fn build_landmark_network_with(
    s: &Scenario,
    range_rule: RangeRule,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<LandmarkNetwork, LandmarkError> {
    let params = LandmarkParams {
        range_rule,
        ..LandmarkParams::from_scenario(s)
    };
    let input = LandmarkInput::from_scenario(s, &params)?;
    Ok(build_from_input(&input, &params, progress))
}

/// Builds the landmark network from a prepared input. `progress` is called with (done, total)
/// basic networks as they finish (from worker threads).
pub fn build_from_input(
    input: &LandmarkInput,
    params: &LandmarkParams,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> LandmarkNetwork {
    let wall = Instant::now();
    let n = params.directions;
    let swapped = FlyLimits {
        a_long_min: -input.limits.a_long_max,
        a_long_max: -input.limits.a_long_min,
        ..input.limits
    };
    let ctx = Ctx {
        obstacles: Obstacles::new(&input.obstacles),
        limits: input.limits,
        swapped,
        symmetric: swapped == input.limits,
        v_nominal: input.v_nominal,
        a_lat_max: input.limits.a_lat_max,
        params,
    };
    let vertices = overflight_vertices(input, n);
    let (kinds, pairs) = job_kinds(input);
    let start_elements = endpoint_elements(input, &input.start);
    let goal_elements = endpoint_elements(input, &input.goal);

    let total = kinds.len();
    let done = AtomicUsize::new(0);
    let results: Vec<JobResult> = kinds
        .par_iter()
        .map(|kind| {
            let job = make_job(input, params, kind, &start_elements, &goal_elements);
            let r = if job.forward_sources.is_empty() && job.reverse_sources.is_empty() {
                JobResult {
                    nodes: Vec::new(),
                    adjacency: Vec::new(),
                    forward: Vec::new(),
                    reverse: Vec::new(),
                    stats: JobStats::default(),
                }
            } else {
                run_job(&job, &ctx)
            };
            let k = done.fetch_add(1, AtomicOrdering::Relaxed) + 1;
            progress(k, total);
            r
        })
        .collect();

    // Assembly, in job order.
    let mut stats = LandmarkStats {
        pairs,
        ..LandmarkStats::default()
    };
    let mut edges = Vec::new();
    let mut start_edges = Vec::new();
    let mut goal_edges = Vec::new();
    for (kind, r) in kinds.iter().zip(&results) {
        stats.directions_out_of_range += directions_out_of_range(input, params, kind);
        add_job_stats(&mut stats, r);
        match *kind {
            JobKind::Pair(a, b) => pair_edges(input, params, (a, b), r, &mut stats, &mut edges),
            JobKind::Start(l) => start_links(input, params, l, r, &mut stats, &mut start_edges),
            JobKind::Goal(l) => goal_links(input, params, l, r, &mut stats, &mut goal_edges),
        }
    }
    stats.edges = edges.len();
    stats.wall = wall.elapsed();
    LandmarkNetwork {
        file: input.file.clone(),
        frame: input.frame,
        directions: n,
        v_nominal: input.v_nominal,
        limits: input.limits,
        clearance_m: params.clearance_m,
        weather: input.weather.clone(),
        landmarks: input.landmarks.clone(),
        obstacles: input.obstacles.clone(),
        vertices,
        edges,
        start: input.start.clone().map(|site| EndpointLinks {
            site,
            elements: start_elements,
            edges: start_edges,
        }),
        goal: input.goal.clone().map(|site| EndpointLinks {
            site,
            elements: goal_elements,
            edges: goal_edges,
        }),
        stats,
    }
}

/// The overflight vertices: `n` per landmark, in landmark order.
fn overflight_vertices(input: &LandmarkInput, n: usize) -> Vec<LandmarkVertex> {
    let lm = &input.landmarks;
    let mut vertices = Vec::with_capacity(lm.len() * n);
    for (l, site) in lm.iter().enumerate() {
        for k in 0..n {
            let v = input
                .direction_velocities
                .get(l)
                .and_then(|d| d.get(k))
                .copied()
                .unwrap_or_default();
            vertices.push(LandmarkVertex {
                landmark: l as u32,
                direction: k as u32,
                pose: Pose {
                    position: site.position,
                    heading: v.angle(),
                },
                element: LineElement::new(site.position, v),
            });
        }
    }
    vertices
}

/// The basic networks to build, in order: every pair of landmarks closer than the larger of
/// their `d_max`, then start → every landmark within the start's `dist_m`, then every landmark
/// whose largest range reaches the goal → goal. Also returns the number of pairs.
fn job_kinds(input: &LandmarkInput) -> (Vec<JobKind>, usize) {
    let lm = &input.landmarks;
    let mut kinds = Vec::new();
    for a in 0..lm.len() {
        for b in a + 1..lm.len() {
            let d = lm[a].position.distance(lm[b].position);
            if d < lm[a].d_max_m.max(lm[b].d_max_m) {
                kinds.push(JobKind::Pair(a, b));
            }
        }
    }
    let pairs = kinds.len();
    if let Some(st) = &input.start {
        let dist = st.dist_m.unwrap_or(0.0);
        for (l, site) in lm.iter().enumerate() {
            if st.pose.position.distance(site.position) <= dist {
                kinds.push(JobKind::Start(l));
            }
        }
    }
    if let Some(g) = &input.goal {
        for (l, site) in lm.iter().enumerate() {
            if g.pose.position.distance(site.position) <= site.max_range_m() {
                kinds.push(JobKind::Goal(l));
            }
        }
    }
    (kinds, pairs)
}

/// The line elements of an endpoint: one per heading it may be flown with, at nominal speed.
fn endpoint_elements(input: &LandmarkInput, e: &Option<EndpointSite>) -> Vec<LineElement> {
    e.iter()
        .flat_map(|e| {
            e.headings.iter().map(|&h| {
                LineElement::from_pose(
                    &Pose {
                        position: e.pose.position,
                        heading: h,
                    },
                    input.v_nominal,
                )
            })
        })
        .collect()
}

/// The basic network of `kind`: its terminals, ellipse, seed and the sources to search from.
fn make_job(
    input: &LandmarkInput,
    params: &LandmarkParams,
    kind: &JobKind,
    start_elements: &[LineElement],
    goal_elements: &[LineElement],
) -> Job {
    let n = params.directions;
    let lm = &input.landmarks;
    match *kind {
        JobKind::Pair(a, b) => {
            let d = lm[a].position.distance(lm[b].position);
            let (ta, opp_a) = landmark_terminals(input, a);
            let (tb, _) = landmark_terminals(input, b);
            // Forward: A directions whose range reaches B. Reverse: B→A edges (B β → A α)
            // come from G paths A (α+180°) → B (β+180°), needed when some B direction
            // reaches A.
            let rule = params.range_rule;
            let forward_sources = (0..n)
                .filter(|&k| rule.searches(lm[a].range_m(k), d))
                .collect();
            let reverse_sources = if (0..n).any(|k| rule.searches(lm[b].range_m(k), d)) {
                (0..n).map(|k| opp_a[k]).collect()
            } else {
                Vec::new()
            };
            Job {
                a: Terminals { elements: ta },
                b: Terminals { elements: tb },
                focus_a: lm[a].position,
                focus_b: lm[b].position,
                major_axis: lm[a].max_range_m().max(lm[b].max_range_m()),
                seed: job_seed(params.seed, 1, a as u64, b as u64),
                forward_sources,
                reverse_sources,
            }
        }
        JobKind::Start(l) => {
            let st = input.start.as_ref();
            let (tl, _) = landmark_terminals(input, l);
            Job {
                a: Terminals {
                    elements: start_elements.to_vec(),
                },
                b: Terminals { elements: tl },
                focus_a: st.map_or(Vec2::default(), |s| s.pose.position),
                focus_b: lm[l].position,
                major_axis: st.and_then(|s| s.dist_m).unwrap_or(0.0),
                seed: job_seed(params.seed, 2, l as u64, 0),
                forward_sources: (0..start_elements.len()).collect(),
                reverse_sources: Vec::new(),
            }
        }
        JobKind::Goal(l) => {
            let g = input.goal.as_ref();
            let gp = g.map_or(Vec2::default(), |g| g.pose.position);
            let d = gp.distance(lm[l].position);
            let (tl, _) = landmark_terminals(input, l);
            Job {
                a: Terminals { elements: tl },
                b: Terminals {
                    elements: goal_elements.to_vec(),
                },
                focus_a: lm[l].position,
                focus_b: gp,
                major_axis: lm[l].max_range_m(),
                seed: job_seed(params.seed, 3, l as u64, 0),
                forward_sources: (0..n)
                    .filter(|&k| params.range_rule.searches(lm[l].range_m(k), d))
                    .collect(),
                reverse_sources: Vec::new(),
            }
        }
    }
}

/// How many source directions of `kind` the range rule left unsearched (their range is shorter
/// than the straight distance to the other site; none under [`RangeRule::Onboard`]).
fn directions_out_of_range(
    input: &LandmarkInput,
    params: &LandmarkParams,
    kind: &JobKind,
) -> usize {
    let n = params.directions;
    let lm = &input.landmarks;
    let skipped = |l: usize, d: f32| {
        (0..n)
            .filter(|&k| !params.range_rule.searches(lm[l].range_m(k), d))
            .count()
    };
    match *kind {
        JobKind::Pair(a, b) => {
            let d = lm[a].position.distance(lm[b].position);
            skipped(a, d) + skipped(b, d)
        }
        JobKind::Goal(l) => {
            let gp = input
                .goal
                .as_ref()
                .map_or(Vec2::default(), |g| g.pose.position);
            skipped(l, gp.distance(lm[l].position))
        }
        JobKind::Start(_) => 0,
    }
}

/// Adds a basic network's counts and times to the network's statistics.
fn add_job_stats(stats: &mut LandmarkStats, r: &JobResult) {
    if !r.nodes.is_empty() {
        stats.basic_networks += 1;
    }
    let js = &r.stats;
    stats.line_elements += js.line_elements;
    stats.line_elements_rejected += js.rejected;
    stats.segments_tried += js.tried;
    stats.segments_flyable += js.flyable;
    stats.segments_feasible += js.feasible;
    stats.reverse_feasible += js.reverse_feasible;
    stats.searches += js.searches;
    stats.segment_time += js.segment_time;
    stats.search_time += js.search_time;
}

/// The chain of a found path, or `None` (counted as over range) when the range rule drops it
/// for being longer than `range`.
fn within_range(
    c: HermiteChain,
    range: f32,
    params: &LandmarkParams,
    stats: &mut LandmarkStats,
) -> Option<HermiteChain> {
    if c.cost > range && params.range_rule == RangeRule::PathLength {
        stats.edges_over_range += 1;
        return None;
    }
    Some(c)
}

/// The edges of pair `(a, b)`: A → B from the forward searches, then B → A from the reversed
/// ones (sorted by source and target).
fn pair_edges(
    input: &LandmarkInput,
    params: &LandmarkParams,
    (a, b): (usize, usize),
    r: &JobResult,
    stats: &mut LandmarkStats,
    edges: &mut Vec<LandmarkEdge>,
) {
    let n = params.directions;
    let lm = &input.landmarks;
    let d = lm[a].position.distance(lm[b].position);
    // A → B.
    for (src, paths) in &r.forward {
        let ka = *src;
        let range = lm[a].range_m(ka);
        for (kb, p) in paths.to_b.iter().enumerate().take(n) {
            match p {
                None => stats.unconnected += 1,
                Some((_, steps)) => {
                    let Some(c) = within_range(r.forward_chain(steps), range, params, stats) else {
                        continue;
                    };
                    edges.push(LandmarkEdge {
                        source: (a * n + ka) as u32,
                        target: (b * n + kb) as u32,
                        chain: c,
                    });
                }
            }
        }
    }
    // B → A: from the G search from A's terminal opposite to direction α, the path
    // to B's terminal opposite to β, reversed, is the edge (B, β) → (A, α).
    let (_, opp_a) = landmark_terminals(input, a);
    let (_, opp_b) = landmark_terminals(input, b);
    let mut rev_edges = Vec::new();
    for (src, paths) in &r.reverse {
        let Some(ka) = opp_a.iter().position(|&t| t == *src) else {
            continue;
        };
        for (kb, &tb) in opp_b.iter().enumerate() {
            let range = lm[b].range_m(kb);
            if !params.range_rule.searches(range, d) {
                continue;
            }
            match paths.to_b.get(tb).and_then(|p| p.as_ref()) {
                None => stats.unconnected += 1,
                Some((_, steps)) => {
                    let Some(c) = within_range(r.reverse_chain(steps), range, params, stats) else {
                        continue;
                    };
                    rev_edges.push(LandmarkEdge {
                        source: (b * n + kb) as u32,
                        target: (a * n + ka) as u32,
                        chain: c,
                    });
                }
            }
        }
    }
    rev_edges.sort_by_key(|e| (e.source, e.target));
    edges.extend(rev_edges);
}

/// The start's edges to the overflights of landmark `l`, each within the start's `dist_m`.
fn start_links(
    input: &LandmarkInput,
    params: &LandmarkParams,
    l: usize,
    r: &JobResult,
    stats: &mut LandmarkStats,
    start_edges: &mut Vec<EndpointEdge>,
) {
    let n = params.directions;
    let dist = input.start.as_ref().and_then(|s| s.dist_m).unwrap_or(0.0);
    for (src, paths) in &r.forward {
        for (k, p) in paths.to_b.iter().enumerate().take(n) {
            match p {
                None => stats.unconnected += 1,
                Some((_, steps)) => {
                    let Some(c) = within_range(r.forward_chain(steps), dist, params, stats) else {
                        continue;
                    };
                    start_edges.push(EndpointEdge {
                        vertex: (l * n + k) as u32,
                        endpoint_element: *src as u32,
                        chain: c,
                    });
                }
            }
        }
    }
}

/// The edges from the overflights of landmark `l` to the goal, each within its overflight's
/// range.
fn goal_links(
    input: &LandmarkInput,
    params: &LandmarkParams,
    l: usize,
    r: &JobResult,
    stats: &mut LandmarkStats,
    goal_edges: &mut Vec<EndpointEdge>,
) {
    let n = params.directions;
    for (src, paths) in &r.forward {
        let range = input.landmarks[l].range_m(*src);
        for (g, p) in paths.to_b.iter().enumerate() {
            match p {
                None => stats.unconnected += 1,
                Some((_, steps)) => {
                    let Some(c) = within_range(r.forward_chain(steps), range, params, stats) else {
                        continue;
                    };
                    goal_edges.push(EndpointEdge {
                        vertex: (l * n + src) as u32,
                        endpoint_element: g as u32,
                        chain: c,
                    });
                }
            }
        }
    }
}
