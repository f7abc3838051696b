//! Roadmap mode (after Niendorf, Schmitt and Adolf, "Multi-query path planning for an unmanned
//! fixed-wing aircraft", 2013): quasi-random Hammersley poses with a minimum spacing, joined to
//! their neighbours by Dubins paths that are checked exactly against every obstacle.
//!
//! Construction is parallel (rayon) and deterministic: each sample's out-edges are computed
//! independently and collected in sample order, so the same input gives the same bytes on any
//! number of threads.
//!
//! With a [`VerticalInput`] the roadmap is three-dimensional (the paper's aircraft: a Dubins
//! car in the plane plus a vertical double integrator): samples also get an altitude, an edge
//! must be a feasible climb, and an obstacle of finite height is checked only against the part
//! of an edge flown below it ([`crate::roadmap::vertical`]).

use rayon::prelude::*;
use skyroute::geometry::predicates::{
    conflicts_with_circle, conflicts_with_polygon, point_in_polygon, primitive_point_distance,
    PolygonView,
};
use skyroute::geometry::WordSet;
use skyroute::network::write::{EdgeSpec, ObstacleSpec};
use skyroute::{DubinsPath, Pose, Primitive, Vec2};

pub mod vertical;
pub use vertical::VerticalInput;

/// How edges are checked against obstacles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CollisionCheck {
    /// The core's exact predicates on every line and arc.
    Exact,
    /// The paper's discretisation: points every `arc_step_m` along each path, the chords
    /// between them tested against the obstacles.
    Discretised {
        /// Step along the path, metres.
        arc_step_m: f32,
        /// How the chords' error f = r(1 − cos(d / 2r)) enters the margin.
        sagitta: Sagitta,
    },
}

/// How the discretised check accounts for the chord error f = r(1 − cos(d / 2r)) (the sagitta
/// of a chord of length d on an arc of radius r).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sagitta {
    /// Chords tested with the clearance plus f: every accepted path keeps the whole clearance.
    Added,
    /// The paper's reading: the clearance (its 7 m tunnel) already includes f, so chords are
    /// tested with the clearance alone and an accepted path keeps at least the clearance
    /// minus f.
    InClearance,
}

/// The roadmap's parameters (the scenario's `planner` member).
#[derive(Clone, Debug, PartialEq)]
pub struct RoadmapParams {
    /// Turn radius, metres.
    pub turn_radius_m: f32,
    /// Minimum distance between samples, metres.
    pub sample_spacing_m: f32,
    /// Samples within this distance are connected, metres.
    pub neighbour_radius_m: f32,
    /// A sample with no collision-free edge in its neighbourhood tries this many nearest.
    pub k_nearest_fallback: usize,
    /// Whether CCC words are admissible.
    pub allow_ccc: bool,
    /// Clearance from obstacles, metres.
    pub clearance_m: f32,
    /// Seed of the Cranley–Patterson shift applied to the Hammersley points.
    pub seed: u64,
    /// How edges are checked.
    pub check: CollisionCheck,
}

/// The area and obstacles, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct RoadmapInput {
    /// South-west corner of the sampled area.
    pub area_min: Vec2,
    /// North-east corner of the sampled area.
    pub area_max: Vec2,
    /// Static obstacles.
    pub obstacles: Vec<ObstacleSpec>,
    /// Poses that must be vertices too (first in the vertex list, in this order).
    pub fixed_vertices: Vec<Pose>,
}

/// A built roadmap.
#[derive(Clone, Debug, PartialEq)]
pub struct Roadmap {
    /// Vertex poses.
    pub vertices: Vec<Pose>,
    /// Directed edges, grouped by source.
    pub edges: Vec<EdgeSpec>,
    /// Hammersley candidates generated.
    pub candidates: usize,
    /// Candidates dropped for lying within clearance of an obstacle.
    pub dropped_in_obstacles: usize,
    /// Candidates dropped for lying closer than the spacing to an earlier sample.
    pub dropped_by_spacing: usize,
    /// Candidate edges examined.
    pub edges_examined: usize,
    /// Vertices connected through the k-nearest fallback.
    pub fallback_vertices: usize,
    /// Three-dimensional roadmap: each vertex's altitude, metres, in vertex order; empty for a
    /// planar one.
    pub altitudes: Vec<f32>,
    /// Three-dimensional roadmap: candidate edges refused because their altitude change is not
    /// a feasible climb or descent over their path (before any collision check).
    pub edges_too_steep: usize,
    /// Three-dimensional roadmap: edges whose path meets the footprint of an obstacle of
    /// finite height (they fly over it).
    pub edges_over_low_obstacles: usize,
}

/// The radical inverse of `i` in base `b` (van der Corput).
fn radical_inverse(mut i: u64, b: u64) -> f64 {
    let (mut inv, mut f) = (0.0, 1.0 / b as f64);
    while i > 0 {
        inv += (i % b) as f64 * f;
        i /= b;
        f /= b as f64;
    }
    inv
}

/// splitmix64, for the seed's shift.
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Whether `prim` comes within `clearance` of `obstacle` (exact).
pub fn primitive_conflicts(prim: &Primitive, obstacle: &ObstacleSpec, clearance: f32) -> bool {
    match obstacle {
        ObstacleSpec::Polygon(points) => conflicts_with_polygon(prim, points.as_slice(), clearance),
        ObstacleSpec::Circle { centre, radius } => {
            conflicts_with_circle(prim, *centre, *radius, clearance)
        }
    }
}

/// Whether the point `p` lies within `clearance` of `obstacle` (inside it included).
pub(crate) fn point_conflicts(p: Vec2, obstacle: &ObstacleSpec, clearance: f32) -> bool {
    let probe = Primitive::Line(skyroute::Segment::new(p, p));
    match obstacle {
        ObstacleSpec::Polygon(points) => {
            point_in_polygon(p, points.as_slice())
                || (0..points.vertex_count()).any(|i| {
                    points.as_slice().edge(i).is_some_and(|e| {
                        skyroute::geometry::predicates::point_segment_distance(p, &e) <= clearance
                    })
                })
        }
        ObstacleSpec::Circle { centre, radius } => {
            primitive_point_distance(&probe, *centre) <= radius + clearance
        }
    }
}

/// A spatial index of the obstacles: their bounding boxes bucketed on a uniform grid, so a
/// query visits only the obstacles in the cells its (widened) box overlaps.
pub(crate) struct ObstacleIndex<'a> {
    items: Vec<(&'a ObstacleSpec, Vec2, Vec2)>,
    /// Side of a bucket, metres.
    cell: f32,
    /// Obstacle indices by bucket `(column, row)`.
    buckets: std::collections::HashMap<(i32, i32), Vec<u32>>,
    /// Obstacles whose box spans more than [`MAX_OBSTACLE_BUCKETS`] buckets: returned by every
    /// query (then tested against the query box) instead of being bucketed.
    large: Vec<u32>,
}

/// The most buckets one obstacle is entered in; a larger one goes to `ObstacleIndex::large`,
/// so that a no-fly zone or threat of hundreds of kilometres cannot fill the memory.
const MAX_OBSTACLE_BUCKETS: f32 = 65_536.0;

/// Side of an obstacle bucket, metres: a few turn radii, the size of a typical query box.
const OBSTACLE_CELL_M: f32 = 100.0;

impl<'a> ObstacleIndex<'a> {
    pub(crate) fn new(obstacles: &'a [ObstacleSpec]) -> Self {
        let items = obstacles
            .iter()
            .map(|o| {
                let (lo, hi) = o.bounding_box();
                (o, lo, hi)
            })
            .collect::<Vec<_>>();
        let cell = OBSTACLE_CELL_M;
        let mut buckets: std::collections::HashMap<(i32, i32), Vec<u32>> = Default::default();
        let mut large = Vec::new();
        for (i, (_, lo, hi)) in items.iter().enumerate() {
            let span = ((hi.x - lo.x) / cell + 2.0) * ((hi.y - lo.y) / cell + 2.0);
            // A NaN span counts as large too.
            if span.is_nan() || span > MAX_OBSTACLE_BUCKETS {
                large.push(i as u32);
                continue;
            }
            for key in cells(*lo, *hi, cell) {
                buckets.entry(key).or_default().push(i as u32);
            }
        }
        Self {
            items,
            cell,
            buckets,
            large,
        }
    }

    /// Obstacles whose box comes within `margin` of the box `[lo, hi]`, in index order.
    fn near(&self, lo: Vec2, hi: Vec2, margin: f32) -> impl Iterator<Item = &'a ObstacleSpec> + '_ {
        self.near_indexed(lo, hi, margin).map(|(_, o)| o)
    }

    /// [`Self::near`] with each obstacle's index in the list the index was built from.
    pub(crate) fn near_indexed(
        &self,
        lo: Vec2,
        hi: Vec2,
        margin: f32,
    ) -> impl Iterator<Item = (usize, &'a ObstacleSpec)> + '_ {
        let (qlo, qhi) = (
            Vec2::new(lo.x - margin, lo.y - margin),
            Vec2::new(hi.x + margin, hi.y + margin),
        );
        let span = ((qhi.x - qlo.x) / self.cell + 1.0) * ((qhi.y - qlo.y) / self.cell + 1.0);
        let mut ids: Vec<u32> = if span.is_finite() && span <= self.items.len().max(16) as f32 {
            cells(qlo, qhi, self.cell)
                .filter_map(|k| self.buckets.get(&k))
                .flatten()
                .chain(&self.large)
                .copied()
                .collect()
        } else {
            (0..self.items.len() as u32).collect() // a box larger than the index: scan all
        };
        ids.sort_unstable();
        ids.dedup();
        ids.into_iter().filter_map(move |i| {
            let (o, olo, ohi) = &self.items[i as usize];
            let apart = qlo.x > ohi.x || qhi.x < olo.x || qlo.y > ohi.y || qhi.y < olo.y;
            (!apart).then_some((i as usize, *o))
        })
    }

    /// Whether `path` keeps more than `clearance` from every obstacle (planar: every obstacle
    /// a wall of unbounded height), by `check`.
    pub(crate) fn path_is_clear(
        &self,
        path: &DubinsPath,
        clearance: f32,
        check: CollisionCheck,
    ) -> bool {
        match check {
            CollisionCheck::Exact => path.primitives().into_iter().flatten().all(|prim| {
                let (lo, hi) = prim.bounding_box();
                self.near(lo, hi, clearance)
                    .all(|o| !primitive_conflicts(&prim, o, clearance))
            }),
            CollisionCheck::Discretised {
                arc_step_m,
                sagitta,
            } => {
                // The paper's method: the path is replaced by chords between points `d` apart
                // along it. A chord deviates from an arc of radius r by at most
                // f = r(1 − cos(d/2r)) (the sagitta), so any point of the path within m of an
                // obstacle has a chord point within m + f. With the margin clearance + f the
                // check accepts a subset of the exact one; with the clearance alone (the
                // paper's reading) every accepted path keeps at least clearance − f.
                let chords = Chords::new(path, clearance, arc_step_m, sagitta);
                (0..chords.steps).all(|i| {
                    let chord = chords.chord(i);
                    let (lo, hi) = chord.bounding_box();
                    self.near(lo, hi, chords.margin)
                        .all(|o| !primitive_conflicts(&chord, o, chords.margin))
                })
            }
        }
    }
}

/// The discretised check's chords of a path: `steps` chords between points equally spaced
/// along it, at most the arc step apart, tested with `margin`.
pub(crate) struct Chords<'p> {
    path: &'p DubinsPath,
    /// Number of chords.
    pub(crate) steps: usize,
    /// The distance a chord must keep from an obstacle: the clearance, plus the sagitta
    /// f = r(1 − cos(d/2r)) with [`Sagitta::Added`].
    pub(crate) margin: f32,
}

impl<'p> Chords<'p> {
    pub(crate) fn new(
        path: &'p DubinsPath,
        clearance: f32,
        arc_step_m: f32,
        sagitta: Sagitta,
    ) -> Self {
        let r = path.radius;
        let f = r * (1.0 - (arc_step_m / (2.0 * r)).cos());
        let margin = match sagitta {
            Sagitta::Added => clearance + f,
            Sagitta::InClearance => clearance,
        };
        let steps = (path.length() / arc_step_m).ceil().max(1.0) as usize;
        Self {
            path,
            steps,
            margin,
        }
    }

    /// Arc length along the path of chord point `i` (0 ..= steps).
    pub(crate) fn at(&self, i: usize) -> f32 {
        self.path.length() * i as f32 / self.steps as f32
    }

    /// Chord `i`, from point `i` to point `i + 1`.
    pub(crate) fn chord(&self, i: usize) -> Primitive {
        let point = |i: usize| self.path.sample(self.at(i)).position;
        Primitive::Line(skyroute::Segment::new(point(i), point(i + 1)))
    }
}

/// The keys of the buckets of side `cell` that the box `[lo, hi]` overlaps.
fn cells(lo: Vec2, hi: Vec2, cell: f32) -> impl Iterator<Item = (i32, i32)> {
    let key = |v: f32| (v / cell).floor() as i32;
    let (x0, x1, y0, y1) = (key(lo.x), key(hi.x), key(lo.y), key(hi.y));
    (y0..=y1).flat_map(move |y| (x0..=x1).map(move |x| (x, y)))
}

/// About the most buckets a [`SampleGrid`] has.
const MAX_SAMPLE_BUCKETS: f32 = 1_048_576.0;

/// The most Hammersley candidates a roadmap is built from (the scenarios in `scenarios/` use
/// at most about 5 600): more is refused before anything is allocated.
pub const MAX_SAMPLE_CANDIDATES: f64 = 1_048_576.0;

/// The smallest sample spacing a roadmap is built with, metres.
pub const MIN_SAMPLE_SPACING_M: f64 = 1.0;

/// How many Hammersley candidates [`build_roadmap`] generates over the box `[lo, hi]` with
/// spacing `spacing_m`, before rounding up (NaN or infinite for a degenerate input).
pub fn candidate_count(lo: Vec2, hi: Vec2, spacing_m: f32) -> f64 {
    let (w, h) = ((hi.x - lo.x) as f64, (hi.y - lo.y) as f64);
    let spacing = spacing_m as f64;
    // Twice as many candidates as a square lattice of the spacing would hold; the spacing
    // filter then thins them to a Poisson-disc-like set.
    2.0 * w * h / (spacing * spacing)
}

/// The most neighbour pairs a roadmap may examine, as [`neighbour_pairs`] estimates them
/// (each examined pair may become an edge of about 32 bytes; the scenarios in `scenarios/`
/// estimate at most about 130 000, niendorf-urban).
pub const MAX_NEIGHBOUR_PAIRS: f64 = 33_554_432.0;

/// An estimate of the neighbour pairs [`build_roadmap`] examines: half the candidates as
/// samples, each with the samples within `radius_m` at their mean density over the box
/// `[lo, hi]` (all of them when the disc is larger than the box).
pub fn neighbour_pairs(lo: Vec2, hi: Vec2, spacing_m: f32, radius_m: f32) -> f64 {
    let samples = candidate_count(lo, hi, spacing_m) / 2.0;
    let area = (hi.x - lo.x) as f64 * (hi.y - lo.y) as f64;
    let disc = std::f64::consts::PI * radius_m as f64 * radius_m as f64;
    let share = if area > 0.0 {
        (disc / area).min(1.0)
    } else {
        1.0
    };
    samples * samples * share
}

/// Buckets of sample indices on a square grid, for neighbour queries.
struct SampleGrid {
    origin: Vec2,
    cell: f32,
    nx: usize,
    ny: usize,
    buckets: Vec<Vec<u32>>,
}

impl SampleGrid {
    fn new(points: &[Vec2], lo: Vec2, hi: Vec2, cell: f32) -> Self {
        // A cell wider than asked keeps every query a superset (radius ≤ cell) and the results
        // the same (they are filtered by distance); it bounds the buckets to about
        // MAX_SAMPLE_BUCKETS plus a row and a column.
        let cell = cell.max(((hi.x - lo.x) * (hi.y - lo.y) / MAX_SAMPLE_BUCKETS).sqrt());
        let nx = (((hi.x - lo.x) / cell).ceil() as usize).max(1);
        let ny = (((hi.y - lo.y) / cell).ceil() as usize).max(1);
        let mut g = Self {
            origin: lo,
            cell,
            nx,
            ny,
            buckets: vec![Vec::new(); nx * ny],
        };
        for (i, p) in points.iter().enumerate() {
            let c = g.cell_of(*p);
            g.buckets[c.1 * nx + c.0].push(i as u32);
        }
        g
    }

    fn cell_of(&self, p: Vec2) -> (usize, usize) {
        let x = (((p.x - self.origin.x) / self.cell).floor().max(0.0) as usize).min(self.nx - 1);
        let y = (((p.y - self.origin.y) / self.cell).floor().max(0.0) as usize).min(self.ny - 1);
        (x, y)
    }

    /// Indices of points within `radius ≤ cell` of `p` (a superset: the 3×3 block of cells).
    fn around(&self, p: Vec2) -> impl Iterator<Item = u32> + '_ {
        let (cx, cy) = self.cell_of(p);
        let xs = cx.saturating_sub(1)..=(cx + 1).min(self.nx - 1);
        let ys = cy.saturating_sub(1)..=(cy + 1).min(self.ny - 1);
        ys.flat_map(move |y| xs.clone().map(move |x| (x, y)))
            .flat_map(move |(x, y)| self.buckets[y * self.nx + x].iter().copied())
    }
}

/// Builds the planar roadmap. `progress` is called with (done, total) as sample rows finish.
pub fn build_roadmap(
    input: &RoadmapInput,
    params: &RoadmapParams,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Roadmap {
    build_roadmap_with(input, params, None, progress)
}

/// What one sample's connection counted.
#[derive(Default)]
struct Tally {
    examined: usize,
    too_steep: usize,
    over_low: usize,
}

/// The roadmap's vertices: the fixed ones, then the Hammersley candidates (4-D with the
/// altitude when `vertical` is given) that are clear of the obstacles and at least the sample
/// spacing from every vertex kept before them.
struct Samples {
    vertices: Vec<Pose>,
    /// One per vertex in a three-dimensional roadmap; empty otherwise.
    altitudes: Vec<f32>,
    positions: Vec<Vec2>,
    candidates: u64,
    dropped_in_obstacles: usize,
    dropped_by_spacing: usize,
}

/// Draws the [`Samples`] of a roadmap.
fn sample_vertices(
    input: &RoadmapInput,
    params: &RoadmapParams,
    vertical: Option<&VerticalInput>,
    obstacles: &ObstacleIndex,
) -> Samples {
    let (lo, hi) = (input.area_min, input.area_max);
    let (w, h) = ((hi.x - lo.x) as f64, (hi.y - lo.y) as f64);
    // The caller has checked it against MAX_SAMPLE_CANDIDATES (`crate::build`).
    let candidates = (candidate_count(lo, hi, params.sample_spacing_m).ceil() as u64).max(1);
    let mut state = params.seed;
    let shift = [
        splitmix(&mut state),
        splitmix(&mut state),
        splitmix(&mut state),
    ];
    // The altitude's shift is drawn after the plane's, so a planar roadmap's samples do not
    // depend on whether it is drawn.
    let altitude_shift = vertical.map(|_| splitmix(&mut state));

    let mut vertices: Vec<Pose> = input.fixed_vertices.clone();
    let mut altitudes: Vec<f32> = vertical.map_or(Vec::new(), |v| v.fixed_altitudes.clone());
    let mut positions: Vec<Vec2> = vertices.iter().map(|p| p.position).collect();
    let mut spacing_grid = SampleGrid::new(&[], lo, hi, params.sample_spacing_m);
    for (i, p) in positions.iter().enumerate() {
        let c = spacing_grid.cell_of(*p);
        spacing_grid.buckets[c.1 * spacing_grid.nx + c.0].push(i as u32);
    }
    let (mut dropped_in_obstacles, mut dropped_by_spacing) = (0, 0);
    for i in 0..candidates {
        let u = ((i as f64 / candidates as f64) + shift[0]).fract();
        let v = (radical_inverse(i, 2) + shift[1]).fract();
        let a = (radical_inverse(i, 3) + shift[2]).fract();
        let p = Vec2::new((lo.x as f64 + u * w) as f32, (lo.y as f64 + v * h) as f32);
        // The 4-D Hammersley point's fourth coordinate, the altitude: the next prime base (5)
        // with its own Cranley–Patterson shift.
        let z = vertical
            .zip(altitude_shift)
            .map(|(vin, shift_z)| vin.altitude_at((radical_inverse(i, 5) + shift_z).fract()));
        let in_obstacle = match (vertical, z) {
            (Some(vin), Some(z)) => vin.sample_conflicts(obstacles, p, z, params.clearance_m),
            _ => obstacles
                .near(p, p, params.clearance_m)
                .any(|o| point_conflicts(p, o, params.clearance_m)),
        };
        if in_obstacle {
            dropped_in_obstacles += 1;
            continue;
        }
        if spacing_grid
            .around(p)
            .any(|j| positions[j as usize].distance(p) < params.sample_spacing_m)
        {
            dropped_by_spacing += 1;
            continue;
        }
        let c = spacing_grid.cell_of(p);
        spacing_grid.buckets[c.1 * spacing_grid.nx + c.0].push(positions.len() as u32);
        positions.push(p);
        altitudes.extend(z);
        vertices.push(Pose {
            position: p,
            heading: (a * std::f64::consts::TAU - std::f64::consts::PI) as f32,
        });
    }

    Samples {
        vertices,
        altitudes,
        positions,
        candidates,
        dropped_in_obstacles,
        dropped_by_spacing,
    }
}

/// Builds the roadmap, three-dimensional when `vertical` is given (see
/// [`crate::roadmap::vertical`]; `vertical.heights` has one entry per `input.obstacles`, and
/// `vertical.fixed_altitudes` one per `input.fixed_vertices`). Without it, the planar roadmap
/// of [`build_roadmap`]. `progress` is called with (done, total) as sample rows finish.
pub fn build_roadmap_with(
    input: &RoadmapInput,
    params: &RoadmapParams,
    vertical: Option<&VerticalInput>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Roadmap {
    let obstacles = ObstacleIndex::new(&input.obstacles);
    let (lo, hi) = (input.area_min, input.area_max);
    let Samples {
        vertices,
        altitudes,
        positions,
        candidates,
        dropped_in_obstacles,
        dropped_by_spacing,
    } = sample_vertices(input, params, vertical, &obstacles);

    let words = if params.allow_ccc {
        WordSet::ALL
    } else {
        WordSet::CSC_ONLY
    };
    let grid = SampleGrid::new(&positions, lo, hi, params.neighbour_radius_m.max(1.0));
    let done = std::sync::atomic::AtomicUsize::new(0);
    let total = vertices.len();
    let connect = |s: usize,
                   targets: &mut dyn Iterator<Item = u32>,
                   tally: &mut Tally|
     -> Vec<EdgeSpec> {
        let mut out = Vec::new();
        for t in targets {
            let t = t as usize;
            if t == s {
                continue;
            }
            tally.examined += 1;
            let Some(path) =
                DubinsPath::shortest_among(&vertices[s], &vertices[t], params.turn_radius_m, words)
            else {
                continue;
            };
            let clear = match vertical {
                None => obstacles.path_is_clear(&path, params.clearance_m, params.check),
                Some(vin) => {
                    let Some(profile) = vin.profile(altitudes[s], altitudes[t], &path) else {
                        tally.too_steep += 1;
                        continue;
                    };
                    let clear = vin.path_is_clear(
                        &obstacles,
                        &path,
                        &profile,
                        params.clearance_m,
                        params.check,
                    );
                    if clear && vin.overflies(&obstacles, &path) {
                        tally.over_low += 1;
                    }
                    clear
                }
            };
            if clear {
                out.push(EdgeSpec::dubins(s as u32, t as u32, &path));
            }
        }
        out
    };
    let per_vertex: Vec<(Vec<EdgeSpec>, Tally, bool)> = (0..total)
        .into_par_iter()
        .map(|s| {
            let p = positions[s];
            let mut tally = Tally::default();
            let mut near: Vec<u32> = grid
                .around(p)
                .filter(|&t| positions[t as usize].distance(p) <= params.neighbour_radius_m)
                .collect();
            near.sort_unstable();
            let mut edges = connect(s, &mut near.into_iter(), &mut tally);
            let mut fallback = false;
            if edges.is_empty() && params.k_nearest_fallback > 0 {
                let mut order: Vec<u32> = (0..total as u32).filter(|&t| t as usize != s).collect();
                order.sort_by(|&a, &b| {
                    positions[a as usize]
                        .distance(p)
                        .total_cmp(&positions[b as usize].distance(p))
                        .then(a.cmp(&b))
                });
                order.truncate(params.k_nearest_fallback);
                edges = connect(s, &mut order.into_iter(), &mut tally);
                fallback = true;
            }
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if n.is_multiple_of(256) || n == total {
                progress(n, total);
            }
            (edges, tally, fallback)
        })
        .collect();
    let edges_examined = per_vertex.iter().map(|v| v.1.examined).sum();
    let edges_too_steep = per_vertex.iter().map(|v| v.1.too_steep).sum();
    let edges_over_low_obstacles = per_vertex.iter().map(|v| v.1.over_low).sum();
    let fallback_vertices = per_vertex.iter().filter(|v| v.2).count();
    let edges = per_vertex.into_iter().flat_map(|v| v.0).collect();
    Roadmap {
        vertices,
        edges,
        candidates: candidates as usize,
        dropped_in_obstacles,
        dropped_by_spacing,
        edges_examined,
        fallback_vertices,
        altitudes,
        edges_too_steep,
        edges_over_low_obstacles,
    }
}
