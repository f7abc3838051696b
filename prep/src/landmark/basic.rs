//! One basic network: random and guide line elements in an ellipse, the candidate segments
//! of the neighbour rule, their flyable and clear Hermite pieces (forward and reversed), and
//! Dijkstra from each source terminal.

use super::network::HermiteChain;
use super::params::{LandmarkParams, CHORD_HEADING_SPREAD_DEG, MAX_DRAW_FACTOR};
use super::sampling::{Obstacles, SplitMix};
use skyroute::geometry::hermite::{FlyLimits, HermiteSegment, LineElement};
use skyroute::{Pose, Vec2};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::{Duration, Instant};

/// The end of a basic network: a site with its terminal line elements.
pub(super) struct Terminals {
    /// Terminal line elements (all at the site).
    pub(super) elements: Vec<LineElement>,
}

/// A basic network to build and search.
pub(super) struct Job {
    /// Source side (A): terminals are sources only.
    pub(super) a: Terminals,
    /// Target side (B): terminals are sinks only.
    pub(super) b: Terminals,
    /// Foci and major axis of the ellipse.
    pub(super) focus_a: Vec2,
    pub(super) focus_b: Vec2,
    pub(super) major_axis: f32,
    pub(super) seed: u64,
    /// Which A terminals to search from forward, and which (as reversed searches) backward.
    pub(super) forward_sources: Vec<usize>,
    pub(super) reverse_sources: Vec<usize>,
}

/// A segment of a basic network. Nodes: A terminals, then B terminals, then elements.
pub(super) struct GEdge {
    pub(super) to: u32,
    pub(super) forward: Option<HermiteSegment>,
    pub(super) reverse: Option<HermiteSegment>,
}

/// The shortest chains from one source terminal to every B terminal.
pub(super) struct Paths {
    /// Per B terminal: `None` if unreachable, else the path.
    pub(super) to_b: Vec<Option<Path>>,
}

/// A shortest path: its length and its steps `(node, index in the node's adjacency)`, from the
/// source terminal on.
pub(super) type Path = (f32, Vec<(u32, u32)>);

#[derive(Default)]
pub(super) struct JobStats {
    pub(super) line_elements: usize,
    pub(super) rejected: usize,
    pub(super) tried: usize,
    pub(super) flyable: usize,
    pub(super) feasible: usize,
    pub(super) reverse_feasible: usize,
    pub(super) searches: usize,
    pub(super) segment_time: Duration,
    pub(super) search_time: Duration,
}

pub(super) struct JobResult {
    pub(super) nodes: Vec<LineElement>,
    pub(super) adjacency: Vec<Vec<GEdge>>,
    pub(super) forward: Vec<(usize, Paths)>,
    pub(super) reverse: Vec<(usize, Paths)>,
    pub(super) stats: JobStats,
}

pub(super) struct Ctx<'a> {
    pub(super) obstacles: Obstacles<'a>,
    pub(super) limits: FlyLimits,
    pub(super) swapped: FlyLimits,
    pub(super) symmetric: bool,
    pub(super) v_nominal: f32,
    /// Highest lateral acceleration, m/s² (sizes the guide turns).
    pub(super) a_lat_max: f32,
    pub(super) params: &'a LandmarkParams,
}

/// How guide elements are laid out.
pub(super) struct Guide {
    /// Turn radius, metres.
    pub(super) radius: f32,
    /// Spacing along the straight, metres (half the basic network's neighbour radius).
    pub(super) spacing: f32,
}

/// Guide line elements for terminal `t`: along the two turn-then-straight paths (radius
/// `guide.radius`) from `t` towards `toward`, every 45° of turn and at the tangent point, heading
/// along the path; for a sink (`into`), along the paths from `−t`, negated, so they lead into it.
pub(super) fn guide_elements(
    t: &LineElement,
    toward: Vec2,
    guide: &Guide,
    into: bool,
    out: &mut Vec<LineElement>,
    ctx: &Ctx,
    stats: &mut JobStats,
) {
    let e = if into { negate(t) } else { *t };
    let pose = Pose {
        position: e.position,
        heading: e.velocity.angle(),
    };
    for turn in [skyroute::Turn::Left, skyroute::Turn::Right] {
        let Some(path) =
            skyroute::DubinsPath::turn_then_straight(&pose, guide.radius, toward, turn)
        else {
            continue;
        };
        let arc = path.lengths[0];
        let step = guide.radius * core::f32::consts::FRAC_PI_4;
        let mut marks: Vec<f32> = Vec::new();
        let mut s = step;
        while s < arc - 0.25 * step {
            marks.push(s);
            s += step;
        }
        marks.push(arc);
        // Along the straight, every half neighbour radius (so consecutive guides are always
        // candidates of each other), stopping half a spacing short of the other site.
        let straight = path.lengths[1];
        let spacing = guide.spacing;
        let mut s = arc + spacing;
        while spacing > 0.0 && s < arc + straight - 0.5 * spacing {
            marks.push(s);
            s += spacing;
        }
        for s in marks {
            if s <= 0.0 {
                continue;
            }
            let p = path.sample(s);
            if ctx
                .obstacles
                .point_blocked(p.position, ctx.params.clearance_m)
            {
                stats.rejected += 1;
                continue;
            }
            let v = Vec2::from_angle(p.heading) * ctx.v_nominal;
            let g = LineElement::new(p.position, v);
            out.push(if into { negate(&g) } else { g });
        }
    }
}

pub(super) fn negate(e: &LineElement) -> LineElement {
    LineElement::new(e.position, Vec2::new(-e.velocity.x, -e.velocity.y))
}

/// Builds and searches the basic network of `job`.
pub(super) fn run_job(job: &Job, ctx: &Ctx) -> JobResult {
    let mut stats = JobStats::default();
    let t0 = Instant::now();
    let (mut elements, (sa, sb)) = random_elements(job, ctx, &mut stats);
    // The neighbour radius of this basic network: the parameter, or, where the random elements
    // are sparser, the radius of a disc expected to hold 4·max_neighbours of them (about a
    // quarter pass the velocity rule), so each element keeps candidates in a long ellipse
    // (see *Neighbour rule*). Its cost stays max_neighbours segments per element.
    let density_radius = if elements.is_empty() {
        0.0
    } else {
        let area = std::f64::consts::PI * sa * sb;
        let k = ctx.params.max_neighbours as f64;
        (4.0 * k * area / (std::f64::consts::PI * elements.len() as f64)).sqrt() as f32
    };
    let radius = ctx.params.neighbour_radius_m.max(density_radius);
    if ctx.params.guide_radius_factor > 0.0 {
        let turn = ctx.params.guide_radius_factor * ctx.v_nominal * ctx.v_nominal / ctx.a_lat_max;
        let guide = Guide {
            radius: turn,
            spacing: 0.5 * radius,
        };
        for t in &job.a.elements {
            guide_elements(
                t,
                job.focus_b,
                &guide,
                false,
                &mut elements,
                ctx,
                &mut stats,
            );
        }
        for t in &job.b.elements {
            guide_elements(t, job.focus_a, &guide, true, &mut elements, ctx, &mut stats);
        }
    }
    stats.line_elements = elements.len();
    let (na, nb) = (job.a.elements.len(), job.b.elements.len());
    let mut nodes: Vec<LineElement> = Vec::with_capacity(na + nb + elements.len());
    nodes.extend_from_slice(&job.a.elements);
    nodes.extend_from_slice(&job.b.elements);
    nodes.extend_from_slice(&elements);
    let candidates = candidates(&nodes, na, nb, radius, ctx.params.max_neighbours);
    let want_reverse = !job.reverse_sources.is_empty();
    let adjacency = segments(&nodes, &candidates, want_reverse, ctx, &mut stats);
    stats.segment_time = t0.elapsed();

    // Searches.
    let t1 = Instant::now();
    let mut forward = Vec::new();
    for &src in &job.forward_sources {
        stats.searches += 1;
        forward.push((src, dijkstra(&adjacency, src, na, nb, false)));
    }
    let mut reverse = Vec::new();
    for &src in &job.reverse_sources {
        stats.searches += 1;
        reverse.push((src, dijkstra(&adjacency, src, na, nb, true)));
    }
    stats.search_time = t1.elapsed();
    JobResult {
        nodes,
        adjacency,
        forward,
        reverse,
        stats,
    }
}

/// The random line elements of `job`'s ellipse (see *Line elements*), and the ellipse's
/// semi-axes `(a, b)`, metres.
fn random_elements(job: &Job, ctx: &Ctx, stats: &mut JobStats) -> (Vec<LineElement>, (f64, f64)) {
    let mut rng = SplitMix(job.seed);
    let centre = (job.focus_a + job.focus_b) * 0.5;
    let axis = job.focus_b - job.focus_a;
    let focal = axis.norm();
    let major = job.major_axis.max(focal);
    let u = if focal > 0.0 {
        axis * (1.0 / focal)
    } else {
        Vec2::new(1.0, 0.0)
    };
    let (sa, sb) = (
        0.5 * major as f64,
        0.5 * ((major as f64).powi(2) - (focal as f64).powi(2))
            .max(0.0)
            .sqrt(),
    );
    let want = ctx.params.line_elements_per_pair;
    let mut elements = Vec::with_capacity(want);
    let mut drawn = 0usize;
    while elements.len() < want && drawn < want.saturating_mul(MAX_DRAW_FACTOR) {
        drawn += 1;
        let r = rng.unit().sqrt();
        let phi = rng.unit() * std::f64::consts::TAU;
        // Half the headings (by default) lean along the chord A → B (a normal spread of
        // `CHORD_HEADING_SPREAD_DEG`), the rest are uniform; see *Line elements* in the module documentation.
        let heading = if rng.unit() < ctx.params.chord_heading_share {
            (u.y as f64).atan2(u.x as f64) + rng.normal() * CHORD_HEADING_SPREAD_DEG.to_radians()
        } else {
            rng.unit() * std::f64::consts::TAU
        };
        let (x, y) = (sa * r * phi.cos(), sb * r * phi.sin());
        let p = Vec2::new(
            (centre.x as f64 + x * u.x as f64 - y * u.y as f64) as f32,
            (centre.y as f64 + x * u.y as f64 + y * u.x as f64) as f32,
        );
        if ctx.obstacles.point_blocked(p, ctx.params.clearance_m) {
            stats.rejected += 1;
            continue;
        }
        let v = Vec2::new(heading.cos() as f32, heading.sin() as f32) * ctx.v_nominal;
        elements.push(LineElement::new(p, v));
    }
    (elements, (sa, sb))
}

/// The segments to try, as `(from, to)` node pairs, by the neighbour rule: both velocities along
/// the chord, the chord at most `radius` long, and `to` among the `k` nearest such targets of
/// `from` (for a B terminal `to`: `from` among its `k` nearest sources). Nodes: `na` A
/// terminals, `nb` B terminals, then the line elements.
fn candidates(
    nodes: &[LineElement],
    na: usize,
    nb: usize,
    radius: f32,
    k: usize,
) -> Vec<(u32, u32)> {
    let n = nodes.len();
    let is_source = |i: usize| i < na || i >= na + nb;
    let is_target = |i: usize| i >= na;
    let admissible = |i: usize, j: usize| -> Option<f32> {
        if i == j || !is_source(i) || !is_target(j) {
            return None;
        }
        let c = nodes[j].position - nodes[i].position;
        let d = c.norm();
        (d > 0.0 && d <= radius && nodes[i].velocity.dot(c) > 0.0 && nodes[j].velocity.dot(c) > 0.0)
            .then_some(d)
    };
    let mut candidates: Vec<(u32, u32)> = Vec::new();
    let mut scratch: Vec<(f32, u32)> = Vec::new();
    for i in 0..n {
        if is_source(i) {
            scratch.clear();
            scratch.extend((0..n).filter_map(|j| admissible(i, j).map(|d| (d, j as u32))));
            scratch.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            candidates.extend(scratch.iter().take(k).map(|&(_, j)| (i as u32, j)));
        }
        let terminal = i < na + nb;
        if terminal && is_target(i) {
            scratch.clear();
            scratch.extend((0..n).filter_map(|j| admissible(j, i).map(|d| (d, j as u32))));
            scratch.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            candidates.extend(scratch.iter().take(k).map(|&(_, j)| (j, i as u32)));
        }
    }
    candidates.sort_unstable();
    candidates.dedup();
    candidates
}

/// The adjacency of the basic network: for each candidate, the forward piece if it is flyable
/// and clear, and (when `want_reverse`) the rebuilt reversed piece if it is (see *Reverse
/// direction*).
fn segments(
    nodes: &[LineElement],
    candidates: &[(u32, u32)],
    want_reverse: bool,
    ctx: &Ctx,
    stats: &mut JobStats,
) -> Vec<Vec<GEdge>> {
    let n = nodes.len();
    let clearance = ctx.params.clearance_m;
    let mut adjacency: Vec<Vec<GEdge>> = (0..n).map(|_| Vec::new()).collect();
    for &(i, j) in candidates {
        let (from, to) = (&nodes[i as usize], &nodes[j as usize]);
        stats.tried += 1;
        let Ok(s) = HermiteSegment::new(from, to, ctx.v_nominal) else {
            continue;
        };
        let fwd_ok = s.check_flyable(&ctx.limits).is_ok();
        let rev_pre = want_reverse
            && if ctx.symmetric {
                fwd_ok
            } else {
                s.check_flyable(&ctx.swapped).is_ok()
            };
        if fwd_ok {
            stats.flyable += 1;
        }
        if !fwd_ok && !rev_pre {
            continue;
        }
        if !ctx.obstacles.segment_clear(&s, clearance) {
            continue;
        }
        if fwd_ok {
            stats.feasible += 1;
        }
        let reverse = if rev_pre {
            HermiteSegment::new(&negate(to), &negate(from), ctx.v_nominal)
                .ok()
                .filter(|r| {
                    r.check_flyable(&ctx.limits).is_ok()
                        && ctx.obstacles.segment_clear(r, clearance)
                })
        } else {
            None
        };
        if reverse.is_some() {
            stats.reverse_feasible += 1;
        }
        if fwd_ok || reverse.is_some() {
            adjacency[i as usize].push(GEdge {
                to: j,
                forward: fwd_ok.then_some(s),
                reverse,
            });
        }
    }
    adjacency
}

#[derive(PartialEq)]
pub(super) struct HeapItem(f32, u32);

impl Eq for HeapItem {}

impl PartialOrd for HeapItem {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for HeapItem {
    fn cmp(&self, other: &Self) -> Ordering {
        // Min-heap on distance, ties by node index (deterministic).
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// Dijkstra over the forward (or the reversed, `reverse`) segments from node `src`.
pub(super) fn dijkstra(
    adj: &[Vec<GEdge>],
    src: usize,
    na: usize,
    nb: usize,
    reverse: bool,
) -> Paths {
    let n = adj.len();
    let mut dist = vec![f32::INFINITY; n];
    let mut pred: Vec<(u32, u32)> = vec![(u32::MAX, u32::MAX); n];
    let mut heap = BinaryHeap::new();
    dist[src] = 0.0;
    heap.push(HeapItem(0.0, src as u32));
    while let Some(HeapItem(d, u)) = heap.pop() {
        let u = u as usize;
        if d > dist[u] {
            continue;
        }
        for (ei, e) in adj[u].iter().enumerate() {
            let seg = if reverse { &e.reverse } else { &e.forward };
            let Some(s) = seg else { continue };
            let nd = d + s.length();
            let t = e.to as usize;
            if nd < dist[t] {
                dist[t] = nd;
                pred[t] = (u as u32, ei as u32);
                heap.push(HeapItem(nd, e.to));
            }
        }
    }
    let to_b = (na..na + nb)
        .map(|t| {
            if !dist[t].is_finite() {
                return None;
            }
            let mut steps = Vec::new();
            let mut v = t;
            while v != src {
                let (p, ei) = pred[v];
                steps.push((p, ei));
                v = p as usize;
            }
            steps.reverse();
            Some((dist[t], steps))
        })
        .collect();
    Paths { to_b }
}

impl JobResult {
    /// The chain of a forward path (sum of lengths recomputed in order).
    pub(super) fn forward_chain(&self, steps: &[(u32, u32)]) -> HermiteChain {
        let mut elements = Vec::with_capacity(steps.len() + 1);
        let mut pieces = Vec::with_capacity(steps.len());
        for &(u, ei) in steps {
            let e = &self.adjacency[u as usize][ei as usize];
            if elements.is_empty() {
                elements.push(self.nodes[u as usize]);
            }
            elements.push(self.nodes[e.to as usize]);
            if let Some(s) = e.forward {
                pieces.push(s);
            }
        }
        chain(elements, pieces)
    }

    /// The chain of a reversed path: the G path reversed, velocities negated, reversed pieces.
    pub(super) fn reverse_chain(&self, steps: &[(u32, u32)]) -> HermiteChain {
        let mut elements = Vec::with_capacity(steps.len() + 1);
        let mut pieces = Vec::with_capacity(steps.len());
        for &(u, ei) in steps.iter().rev() {
            let e = &self.adjacency[u as usize][ei as usize];
            if elements.is_empty() {
                elements.push(negate(&self.nodes[e.to as usize]));
            }
            elements.push(negate(&self.nodes[u as usize]));
            if let Some(s) = e.reverse {
                pieces.push(s);
            }
        }
        chain(elements, pieces)
    }
}

pub(super) fn chain(elements: Vec<LineElement>, pieces: Vec<HermiteSegment>) -> HermiteChain {
    HermiteChain {
        cost: pieces.iter().map(|p| p.length()).sum(),
        elements,
        pieces,
    }
}
