//! Landmark mode, ground side (after Babel, "Flight path planning for unmanned aerial vehicles
//! with landmark-based visual navigation", 2014): the **landmark shortest-path network**.
//!
//! A vertex is an *overflight*: landmark `L` crossed with heading `α_k`, one of `directions`
//! equally spaced compass headings (0°, 30°, … 330° for the default 12), as the line element
//! "at `L` with velocity `v_nominal` along `α_k`". An edge from overflight `(A, α)` to `(B, β)` is
//! the shortest chain of quintic Hermite pieces ([`HermiteSegment`]) found in a random *basic
//! network* of line elements between the two landmarks; every piece is flyable
//! ([`HermiteSegment::check_flyable`]) and clear of every obstacle by the clearance
//! ([`HermiteSegment::conflicts_with_polygon`] / `conflicts_with_circle`, conservative). The
//! landmarks' quality rosettes `q(α, ω)` set how far the aircraft may fly after an overflight:
//! `d = d_max · q(α, ω)` in weather `ω`; they are kept per vertex so the planner can prune by
//! weather.
//!
//! # The construction, and the decisions it takes
//!
//! **Pairs.** Landmarks `A`, `B` form a pair when their distance `D` is below
//! `max(d_max_A, d_max_B)`. Each pair gets *one* basic network, which serves both `A → B` and
//! `B → A` (see *Reverse direction*).
//!
//! **Ranges.** The best-weather range of overflight `(A, α)` is `r_A(α) = d_max_A · max_ω
//! q_A(α, ω)`. A direction with `r_A(α) < D` cannot reach `B` and gets no edge to it (not even a
//! search). With [`RangeRule::PathLength`] (the default) an edge whose shortest chain is
//! **longer than** `r_A(α)` is dropped too: the navigation error grows with the distance flown,
//! so no weather can fly it (counted in [`LandmarkStats::edges_over_range`]);
//! [`RangeRule::PairDistance`] keeps it and leaves the test to the planner (every edge carries
//! its length). The range of a direction is the
//! rosette's value at that heading, linearly interpolated around the 12 given headings when
//! `directions` is not 12.
//!
//! **The ellipse.** The issue asks for line elements "inside the ellipse whose foci are the two
//! landmarks and whose major axis is that distance". With the major axis equal to the *focal*
//! distance `D` the ellipse degenerates to the segment `AB`, which leaves no room to fly around
//! an obstacle or to turn, so "that distance" is read as Babel's *travel* distance: the set of
//! points `P` with `|AP| + |PB| ≤ r` is exactly the ellipse with foci `A`, `B` and major axis
//! `r`, and it holds every path from `A` to `B` of length at most `r`. So the major axis is the
//! longest range any edge of the pair may use, `r = max(max_α r_A(α), max_β r_B(β))` (never below
//! `D`; the pair condition makes `r ≥ D` in practice). Nothing outside it could belong to an
//! edge that survives the range test, so this ellipse loses no admissible path, and it is the
//! smallest set for which that holds. The same rule gives the endpoint ellipses: the start's
//! `dist_m` for start → landmark, the landmark's range for landmark → goal.
//!
//! **Line elements.** Positions uniform in the ellipse (a uniform point of the unit disc,
//! `√u` radius, mapped affinely), speed `v_nominal`. Headings: with probability
//! `chord_heading_share` (default ½) the chord's direction `A → B` plus a normal spread of
//! [`CHORD_HEADING_SPREAD_DEG`], otherwise uniform in `[0, 2π)`. (Reversal turns an element
//! leaning `A → B` into one leaning `B → A`, so the lean serves both directions.) A position
//! within the clearance of an obstacle (or inside it) is rejected and drawn again, until
//! `line_elements_per_pair` elements are kept or `MAX_DRAW_FACTOR` times as many were drawn.
//!
//! **Guide elements** (our addition to Babel's random elements). Purely uniform headings made
//! chains that zig-zag: on `babel-II-N` the median edge was 20 % longer than the Dubins lower
//! bound of its two overflight poses (radius `v_min²/a_lat`, the tightest curvature a flyable
//! piece can have), 10 % of edges more than 2.4 times it, and 1 787 chains were found but longer
//! than their range, which left the goal unreachable from the start. A shortest flight from an
//! overflight turns hard onto the line to the other landmark; random headings almost never line
//! up with that turn. So each terminal also gets, for both turn directions, the line elements
//! of the turn-then-straight path (radius `guide_radius_factor · v_nominal²/a_lat`, 1.5 by
//! default so a quintic between them stays within `a_lat`) towards the other site: every 45° of
//! turn, at the tangent point and every half `neighbour_radius_m` along the straight (so the
//! guides of a path are always candidates of one another, however sparse the random elements
//! are in a long ellipse); a sink terminal gets those of the path flown backwards from it,
//! negated. With them (and the chord lean) the median is 6 %
//! above the bound, the 90th percentile 19 %, about 630 chains exceed their range and every
//! overflight is reachable (`prep/examples` measured this; numbers in `docs/BENCHMARKS.md`).
//! Guide elements in an obstacle's clearance are dropped; they are deterministic, so the build
//! stays reproducible.
//!
//! **Neighbour rule.** A basic network has about `N + 2·directions` nodes; trying all `≈ N²`
//! segments would cost seconds per pair. A segment `u → w` (chord `c = w − u`) is tried only
//! when
//! * both velocities point along the chord: `v_u · c > 0` and `v_w · c > 0` (a quintic Hermite
//!   segment whose start or end velocity points away from the other end must turn through more
//!   than 90° between two points; such curves are rarely flyable, and when they are, a chain
//!   through other elements does the same) — the rule is symmetric under reversal, see below;
//! * the chord is at most the basic network's neighbour radius long: `neighbour_radius_m`
//!   (default 20 turn radii `v²/a_lat`: a quintic needs a chord of a few turn radii to turn
//!   through large angles), or, where the random elements are sparser, the radius of a disc
//!   expected to hold `4·max_neighbours` of them, `√(4k·area/(π·N))` (about a quarter of them
//!   pass the velocity rule). Without it a slow aircraft with long ranges (babel-I's 45 m turn
//!   radius, 900 m, in a 13 km ellipse) kept about three candidates per element and whole
//!   basic networks fell apart; the cost stays at most `max_neighbours` segments per element;
//!   and
//! * `w` is among the `max_neighbours` (default 48) nearest such targets of `u` — or, for a
//!   landmark overflight `w` (a sink only), `u` is among the `max_neighbours` nearest such
//!   sources of `w`, so every overflight gets its own share of candidates (ties by index).
//!
//! Landmark overflights of the pair's first member are sources only, of the second sinks only;
//! the random elements are both.
//!
//! **Reverse direction.** The time reversal of a segment from `(p, v)` to `(p', v')` is the
//! segment from `(p', −v')` to `(p, −v)`: the same curve, the same length and speeds, lateral
//! accelerations of the same magnitude and longitudinal accelerations negated (so it is checked
//! with `a_long_min`, `a_long_max` swapped and negated). Hence the basic network built for
//! `A → B` also serves `B → A`: a shortest chain from `(B, β)` to `(A, α)` is the reversal of a
//! shortest chain from `(A, α + 180°)` to `(B, β + 180°)` over the reversed segments. To keep this
//! exact, the velocities of opposite directions are exact negations (for an even `directions`,
//! direction `k + n/2` is defined as `−v_k`, i.e. the local heading of compass `α_k`, plus
//! 180°; for an odd count the opposite line elements are added as extra terminals). Every
//! reversed piece is **rebuilt** with [`HermiteSegment::new`] from its reversed line elements and
//! checked on its own (flyability and clearance), so what is stored is exactly what the core
//! rebuilds from the stored line elements; only a segment whose forward version passes the
//! swapped-limit flyability test and the clearance test is tried in reverse (for symmetric
//! limits, the forward test).
//!
//! **Searches.** For each source overflight that has a reachable target, one Dijkstra on the
//! forward segments and one on the reversed segments of the basic network (a few hundred nodes),
//! to every target overflight: many-to-many by repeated one-to-many.
//!
//! **Endpoints** (Babel's Connect-Endpoints, computed for the scenario's start and goal with the
//! same machinery): the start (its pose) connects to every overflight of every landmark within
//! `dist_m`, by a basic network in the ellipse with foci start and landmark and major axis
//! `dist_m`; chains longer than `dist_m` are dropped. Every overflight `(L, α)` whose range reaches
//! the goal connects to it (the goal's heading, or each of the `directions` headings when the goal
//! has none), by a basic network in the ellipse of major axis `max_α r_L(α)`.
//!
//! **Randomness and determinism.** SplitMix64, seeded per basic network from the scenario's
//! `seed` and the network's identity (kind and landmark indices), so each basic network is the
//! same whatever order or thread builds it. Pairs run in parallel (rayon) and are collected in
//! pair order: the result is identical on any number of threads.
//!
//! **Collision check.** Each piece is tested against the obstacles whose bounding box comes
//! within the clearance (plus the chord deviation) of the piece's Bernstein bounding box, with
//! the core's conservative polyline enclosure, its chord count chosen so that the deviation bound
//! `ε` is about a tenth of the clearance (at least 1 m).

use crate::frame::LocalFrame;
use crate::local::{local, local_heading, local_obstacles, local_pose};
use crate::scenario::{Landmark, Scenario, ROSETTE_HEADINGS};
use rayon::prelude::*;
use skyroute::geometry::hermite::{FlyLimits, HermiteSegment, LineElement, MAX_PIECES};
use skyroute::geometry::predicates::{point_in_polygon, point_segment_distance, PolygonView};
use skyroute::network::write::ObstacleSpec;
use skyroute::{Pose, Vec2};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering as AtomicOrdering};
use std::time::{Duration, Instant};

/// Standard deviation of the chord-leaning headings of line elements, degrees.
pub const CHORD_HEADING_SPREAD_DEG: f64 = 25.0;

/// At most this many line elements are drawn per kept one (positions inside obstacles are drawn
/// again; an ellipse almost filled by obstacles stops here).
pub const MAX_DRAW_FACTOR: usize = 20;

/// The landmark network's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkParams {
    /// Overflight headings per landmark (`planner.directions`, default 12), equally spaced from
    /// compass 0°.
    pub directions: usize,
    /// Random line elements per basic network (`planner.line_elements_per_pair`, default 500).
    pub line_elements_per_pair: usize,
    /// Clearance from obstacles, metres (`planner.clearance_m`, default 0).
    pub clearance_m: f32,
    /// Seed (`planner.seed`, default 1).
    pub seed: u64,
    /// Longest chord tried between two line elements, metres (default 20 turn radii).
    pub neighbour_radius_m: f32,
    /// Nearest targets (and sources) tried per line element (default 48).
    pub max_neighbours: usize,
    /// Which length an edge's range limits (default [`RangeRule::PathLength`]).
    pub range_rule: RangeRule,
    /// Radius of the guide turns, in turn radii `v_nominal² / a_lat_max` (default 1.5; 0: no
    /// guide elements). See *Guide elements*.
    pub guide_radius_factor: f32,
    /// Share of the random line elements whose heading leans along the chord (default 0.5; 0:
    /// all uniform). See *Line elements*.
    pub chord_heading_share: f64,
}

/// What the best-weather range `d_max · max_ω q(α, ω)` of a source overflight limits. Either
/// way a direction whose range is shorter than the straight distance to the target gets no
/// edge there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RangeRule {
    /// Also the length of the flown chain (Babel: the navigation error grows with the distance
    /// flown since the last overflight): longer chains are dropped.
    #[default]
    PathLength,
    /// Only the straight distance between the two sites: every chain found is kept, and its
    /// `cost` lets the planner apply its own rule.
    PairDistance,
}

impl LandmarkParams {
    /// The scenario's parameters with this module's defaults for what it leaves out.
    pub fn from_scenario(s: &Scenario) -> Self {
        let p = &s.planner;
        Self {
            directions: p.directions.unwrap_or(12) as usize,
            line_elements_per_pair: p.line_elements_per_pair.unwrap_or(500) as usize,
            clearance_m: p.clearance_m.unwrap_or(0.0) as f32,
            seed: p.seed.unwrap_or(1),
            neighbour_radius_m: 20.0 * s.vehicle.turn_radius_m() as f32,
            max_neighbours: 48,
            range_rule: RangeRule::PathLength,
            guide_radius_factor: 1.5,
            chord_heading_share: 0.5,
        }
    }
}

/// Why a landmark network could not be built. Each variant names the scenario file.
#[derive(Clone, Debug, PartialEq)]
pub enum LandmarkError {
    /// The scenario lacks something landmark mode needs: (file, what).
    Missing(String, &'static str),
    /// A value is unusable: (file, field, why).
    Invalid(String, String, String),
}

impl fmt::Display for LandmarkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LandmarkError::Missing(file, what) => {
                write!(f, "{file}: {what}: required for a landmark network")
            }
            LandmarkError::Invalid(file, field, why) => write!(f, "{file}: {field}: {why}"),
        }
    }
}

impl std::error::Error for LandmarkError {}

/// A landmark's quality rosette for one weather.
#[derive(Clone, Debug, PartialEq)]
pub struct Rosette {
    /// The weather's name.
    pub weather: String,
    /// Quality in [0, 1] per overflight direction (index = direction).
    pub quality: Vec<f32>,
}

/// A landmark in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkSite {
    /// Its name.
    pub name: String,
    /// Position, metres.
    pub position: Vec2,
    /// Largest useful distance, metres.
    pub d_max_m: f32,
    /// One rosette per weather, in the scenario's weather order.
    pub rosettes: Vec<Rosette>,
}

impl LandmarkSite {
    /// The best-weather range of direction `k`: `d_max · max_ω q(k, ω)`, metres (0 for an
    /// unknown direction or no weather).
    pub fn range_m(&self, k: usize) -> f32 {
        self.rosettes
            .iter()
            .filter_map(|r| r.quality.get(k))
            .fold(0.0f32, |m, &q| m.max(q))
            * self.d_max_m
    }

    /// The largest best-weather range over all directions, metres.
    pub fn max_range_m(&self) -> f32 {
        let n = self.rosettes.first().map_or(0, |r| r.quality.len());
        (0..n).map(|k| self.range_m(k)).fold(0.0, f32::max)
    }
}

/// A start or goal in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointSite {
    /// Its name.
    pub name: String,
    /// The pose (heading 0 when the scenario gives none).
    pub pose: Pose,
    /// Local headings the endpoint may be flown with (radians): the scenario's heading, or
    /// without one, the compass headings of the overflight directions.
    pub headings: Vec<f32>,
    /// Start: the largest path length to the first landmark (`dist_m`), metres. Goal: `None`.
    pub dist_m: Option<f32>,
}

/// Everything the builder needs, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkInput {
    /// The scenario file (for messages).
    pub file: String,
    /// The local frame (`None` for inputs made by hand).
    pub frame: Option<LocalFrame>,
    /// Landmarks, in scenario order.
    pub landmarks: Vec<LandmarkSite>,
    /// Weather names, in scenario order.
    pub weather: Vec<String>,
    /// Static obstacles (no-fly polygons and threat discs).
    pub obstacles: Vec<ObstacleSpec>,
    /// The vehicle's limits.
    pub limits: FlyLimits,
    /// Nominal speed, m/s.
    pub v_nominal: f32,
    /// Per landmark, per direction `k`: the local velocity (nominal speed) of compass heading
    /// `360·k/directions` degrees, converted at the landmark by the frame (meridian
    /// convergence); for an even count, direction `k + directions/2` is exactly `−v_k`.
    pub direction_velocities: Vec<Vec<Vec2>>,
    /// The start, if any.
    pub start: Option<EndpointSite>,
    /// The goal, if any.
    pub goal: Option<EndpointSite>,
}

/// The quality of rosette `q` (given at 0°, 30°, … 330°) at compass heading `deg`, linearly
/// interpolated around the circle.
pub fn rosette_quality(q: &[f64; ROSETTE_HEADINGS], deg: f64) -> f64 {
    let step = 360.0 / ROSETTE_HEADINGS as f64;
    let x = deg.rem_euclid(360.0) / step;
    let i = (x.floor() as usize) % ROSETTE_HEADINGS;
    let f = x - x.floor();
    q[i] * (1.0 - f) + q[(i + 1) % ROSETTE_HEADINGS] * f
}

impl LandmarkInput {
    /// Converts a scenario (any mode; its landmarks, weather, obstacles, vehicle, start and goal)
    /// to the local frame.
    pub fn from_scenario(s: &Scenario, params: &LandmarkParams) -> Result<Self, LandmarkError> {
        let file = s.path.display().to_string();
        let invalid =
            |field: &str, why: String| LandmarkError::Invalid(file.clone(), field.into(), why);
        if s.landmarks.is_empty() {
            return Err(LandmarkError::Missing(file, "features: a landmark"));
        }
        if s.weather.is_empty() {
            return Err(LandmarkError::Missing(
                file,
                "weather: at least one weather",
            ));
        }
        if params.directions == 0 {
            return Err(invalid("planner.directions", "must be at least 1".into()));
        }
        if params.line_elements_per_pair == 0 {
            return Err(invalid(
                "planner.line_elements_per_pair",
                "must be at least 1".into(),
            ));
        }
        if !(params.clearance_m >= 0.0 && params.clearance_m.is_finite()) {
            return Err(invalid(
                "planner.clearance_m",
                format!(
                    "{} is not a finite non-negative distance",
                    params.clearance_m
                ),
            ));
        }
        if !(params.neighbour_radius_m > 0.0 && params.neighbour_radius_m.is_finite()) {
            return Err(invalid(
                "neighbour_radius_m",
                format!(
                    "{} is not a finite positive distance",
                    params.neighbour_radius_m
                ),
            ));
        }
        let v = &s.vehicle;
        let limits = FlyLimits {
            v_min: v.v_min_mps as f32,
            v_max: v.v_max_mps as f32,
            a_long_min: v.a_long_min_mps2 as f32,
            a_long_max: v.a_long_max_mps2 as f32,
            a_lat_max: v.a_lat_max_mps2 as f32,
        };
        if !limits.is_valid() {
            return Err(invalid(
                "vehicle",
                format!("limits are not usable: {limits:?}"),
            ));
        }
        let v_nominal = v.v_nominal_mps as f32;
        if !(v_nominal >= limits.v_min && v_nominal <= limits.v_max) {
            return Err(invalid(
                "vehicle.v_nominal_mps",
                format!("{v_nominal} is outside [v_min, v_max]"),
            ));
        }
        let frame = s.local_frame();
        let n = params.directions;
        let compass = |k: usize| 360.0 * k as f64 / n as f64;
        let mut landmarks = Vec::with_capacity(s.landmarks.len());
        let mut direction_velocities = Vec::with_capacity(s.landmarks.len());
        for l in &s.landmarks {
            landmarks.push(site(l, &s.weather, &frame, n, compass));
            direction_velocities.push(direction_velocities_at(&frame, l, n, v_nominal));
        }
        let endpoint = |e: &crate::scenario::Endpoint,
                        is_start: bool|
         -> Result<EndpointSite, LandmarkError> {
            let dist_m = if is_start {
                Some(e.dist_m.ok_or_else(|| {
                    LandmarkError::Missing(file.clone(), "start: properties.dist_m")
                })? as f32)
            } else {
                None
            };
            Ok(EndpointSite {
                name: e.name.clone(),
                pose: local_pose(&frame, e.lon, e.lat, e.heading_deg),
                headings: match e.heading_deg {
                    Some(h) => vec![local_heading(&frame, e.lon, e.lat, h)],
                    None => (0..n)
                        .map(|k| local_heading(&frame, e.lon, e.lat, compass(k)))
                        .collect(),
                },
                dist_m,
            })
        };
        let start = s.start.as_ref().map(|e| endpoint(e, true)).transpose()?;
        let goal = s.goal.as_ref().map(|e| endpoint(e, false)).transpose()?;
        Ok(Self {
            file,
            landmarks,
            weather: s.weather.clone(),
            obstacles: local_obstacles(s, &frame),
            limits,
            v_nominal,
            direction_velocities,
            start,
            goal,
            frame: Some(frame),
        })
    }
}

fn site(
    l: &Landmark,
    weather: &[String],
    frame: &LocalFrame,
    n: usize,
    compass: impl Fn(usize) -> f64,
) -> LandmarkSite {
    let rosettes = weather
        .iter()
        .map(|w| {
            let q = l
                .quality
                .iter()
                .find(|(name, _)| name == w)
                .map(|(_, q)| *q)
                .unwrap_or([0.0; ROSETTE_HEADINGS]);
            Rosette {
                weather: w.clone(),
                quality: (0..n)
                    .map(|k| rosette_quality(&q, compass(k)) as f32)
                    .collect(),
            }
        })
        .collect();
    LandmarkSite {
        name: l.name.clone(),
        position: local(frame, l.lon, l.lat),
        d_max_m: l.d_max_m as f32,
        rosettes,
    }
}

/// The local velocities of the `n` overflight directions at landmark `l`; for an even `n`,
/// direction `k + n/2` is exactly `−v_k`.
fn direction_velocities_at(frame: &LocalFrame, l: &Landmark, n: usize, v: f32) -> Vec<Vec2> {
    let mut out: Vec<Vec2> = Vec::with_capacity(n);
    for k in 0..n {
        if n.is_multiple_of(2) && k >= n / 2 {
            let o = out[k - n / 2];
            out.push(Vec2::new(-o.x, -o.y));
        } else {
            let deg = 360.0 * k as f64 / n as f64;
            let h = local_heading(frame, l.lon, l.lat, deg);
            out.push(Vec2::from_angle(h) * v);
        }
    }
    out
}

// ------------------------------------------------------------------------------------------------
// The result

/// An overflight vertex: landmark `landmark` crossed in direction `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LandmarkVertex {
    /// Index into [`LandmarkNetwork::landmarks`].
    pub landmark: u32,
    /// Direction index (`0..directions`; compass `360·direction/directions` degrees).
    pub direction: u32,
    /// The pose in the local frame (heading: the angle of `element.velocity`).
    pub pose: Pose,
    /// The line element: the landmark's position and the direction's velocity (nominal speed).
    pub element: LineElement,
}

/// A chain of quintic Hermite pieces: `elements[i] → elements[i + 1]` is piece `i`, as
/// `HermiteSegment::new(&elements[i], &elements[i + 1], v_nominal)` builds it.
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteChain {
    /// Total length, metres (the sum of the pieces' lengths).
    pub cost: f32,
    /// The line elements, first to last (one more than the pieces).
    pub elements: Vec<LineElement>,
    /// The pieces (each rebuilt from `elements` gives the same segment).
    pub pieces: Vec<HermiteSegment>,
}

/// A directed edge between overflights.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkEdge {
    /// Source vertex index.
    pub source: u32,
    /// Target vertex index.
    pub target: u32,
    /// The flight path.
    pub chain: HermiteChain,
}

/// An edge between an endpoint (start or goal) and an overflight.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointEdge {
    /// The overflight vertex (the target for the start, the source for the goal).
    pub vertex: u32,
    /// Index into [`EndpointLinks::elements`] (the endpoint's heading used).
    pub endpoint_element: u32,
    /// The flight path, from start to vertex or from vertex to goal.
    pub chain: HermiteChain,
}

/// The connections of the scenario's start or goal (Connect-Endpoints).
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointLinks {
    /// The endpoint.
    pub site: EndpointSite,
    /// Its line elements: one for a given heading; without a heading, one per direction.
    pub elements: Vec<LineElement>,
    /// The edges, ordered by landmark, then vertex, then endpoint element.
    pub edges: Vec<EndpointEdge>,
}

/// What the build did and took.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LandmarkStats {
    /// Landmark pairs closer than the larger of their `d_max`.
    pub pairs: usize,
    /// Basic networks built (pairs plus endpoint connections).
    pub basic_networks: usize,
    /// Line elements kept in all basic networks.
    pub line_elements: usize,
    /// Line elements drawn inside an obstacle's clearance and drawn again.
    pub line_elements_rejected: usize,
    /// Segments built (forward candidates of the neighbour rule).
    pub segments_tried: usize,
    /// Forward segments that passed the flyability check.
    pub segments_flyable: usize,
    /// Forward segments flyable and clear of obstacles.
    pub segments_feasible: usize,
    /// Reversed segments flyable and clear of obstacles.
    pub reverse_feasible: usize,
    /// Dijkstra searches run.
    pub searches: usize,
    /// Overflight edges.
    pub edges: usize,
    /// Source directions skipped because their range is shorter than the pair's distance.
    pub directions_out_of_range: usize,
    /// Edges dropped because their chain is longer than the source's best-weather range.
    pub edges_over_range: usize,
    /// (source, target) overflight pairs with a reachable range but no chain in the basic
    /// network.
    pub unconnected: usize,
    /// Wall time of the whole build.
    pub wall: Duration,
    /// Summed time spent building and checking segments, over all threads.
    pub segment_time: Duration,
    /// Summed time spent in the searches, over all threads.
    pub search_time: Duration,
}

/// The landmark shortest-path network.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkNetwork {
    /// The scenario file it was built from.
    pub file: String,
    /// The local frame, when built from a scenario.
    pub frame: Option<LocalFrame>,
    /// Overflight directions per landmark.
    pub directions: usize,
    /// Nominal speed, m/s (the pieces' `v_nominal`).
    pub v_nominal: f32,
    /// The limits every piece was checked against.
    pub limits: FlyLimits,
    /// The clearance every piece keeps, metres.
    pub clearance_m: f32,
    /// Weather names (the rosettes' order).
    pub weather: Vec<String>,
    /// Landmarks with `d_max` and their rosettes per weather.
    pub landmarks: Vec<LandmarkSite>,
    /// The obstacles, local frame.
    pub obstacles: Vec<ObstacleSpec>,
    /// Vertices; vertex `landmark·directions + direction`.
    pub vertices: Vec<LandmarkVertex>,
    /// Edges, ordered by (pair, direction A→B before B→A, source, target).
    pub edges: Vec<LandmarkEdge>,
    /// The start's connections.
    pub start: Option<EndpointLinks>,
    /// The goal's connections.
    pub goal: Option<EndpointLinks>,
    /// Statistics.
    pub stats: LandmarkStats,
}

impl LandmarkNetwork {
    /// Vertex index of overflight `(landmark, direction)`.
    pub fn vertex_index(&self, landmark: usize, direction: usize) -> usize {
        landmark * self.directions + direction
    }
}

// ------------------------------------------------------------------------------------------------
// Random numbers

/// SplitMix64.
#[derive(Clone, Debug)]
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller, one of the pair).
    fn normal(&mut self) -> f64 {
        let (u1, u2) = (1.0 - self.unit(), self.unit());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// The seed of basic network `(kind, a, b)`.
fn job_seed(seed: u64, kind: u64, a: u64, b: u64) -> u64 {
    let mut s = SplitMix(seed);
    let mut x = s.next_u64();
    for v in [kind, a, b] {
        x = SplitMix(x ^ v.wrapping_mul(0xD6E8_FEB8_6659_FD93)).next_u64();
    }
    x
}

// ------------------------------------------------------------------------------------------------
// Obstacles

/// Obstacles with bounding boxes.
struct Obstacles<'a> {
    items: Vec<(&'a ObstacleSpec, Vec2, Vec2)>,
}

impl<'a> Obstacles<'a> {
    fn new(obstacles: &'a [ObstacleSpec]) -> Self {
        Self {
            items: obstacles
                .iter()
                .map(|o| {
                    let (lo, hi) = o.bounding_box();
                    (o, lo, hi)
                })
                .collect(),
        }
    }

    /// Obstacles whose box comes within `margin` of `[lo, hi]`.
    fn near(&self, lo: Vec2, hi: Vec2, margin: f32) -> impl Iterator<Item = &'a ObstacleSpec> + '_ {
        self.items.iter().filter_map(move |(o, olo, ohi)| {
            let apart = lo.x - margin > ohi.x
                || hi.x + margin < olo.x
                || lo.y - margin > ohi.y
                || hi.y + margin < olo.y;
            (!apart).then_some(*o)
        })
    }

    /// Whether point `p` lies within `clearance` of an obstacle (or inside).
    fn point_blocked(&self, p: Vec2, clearance: f32) -> bool {
        self.near(p, p, clearance).any(|o| match o {
            ObstacleSpec::Polygon(points) => {
                let poly = points.as_slice();
                point_in_polygon(p, poly)
                    || (0..poly.vertex_count()).any(|i| {
                        poly.edge(i)
                            .is_none_or(|e| point_segment_distance(p, &e) <= clearance)
                    })
            }
            ObstacleSpec::Circle { centre, radius } => p.distance(*centre) <= radius + clearance,
        })
    }

    /// Whether the segment keeps `clearance` from every obstacle (conservative).
    fn segment_clear(&self, s: &HermiteSegment, clearance: f32) -> bool {
        // Chords with ε ≈ target: (Δs²/8)·A·T² ≤ target ⇒ pieces ≥ T·√(A / (8·target)).
        let target = (0.1 * clearance).max(1.0);
        let pieces = (s.t_max() * (s.acceleration_bound() / (8.0 * target)).sqrt()).ceil();
        let pieces = if pieces.is_finite() {
            (pieces as usize).clamp(1, MAX_PIECES)
        } else {
            MAX_PIECES
        };
        // Margin for the box test: clearance plus the largest chord deviation (the box already
        // holds the curve; the margin only has to cover the clearance and ε).
        let eps = {
            let ds = 1.0 / pieces as f32;
            ds * ds * 0.125 * s.acceleration_bound() * s.t_max() * s.t_max()
        };
        let (lo, hi) = s.bounding_box();
        self.near(lo, hi, clearance + eps + 1.0).all(|o| match o {
            ObstacleSpec::Polygon(points) => {
                !s.conflicts_with_polygon(points.as_slice(), clearance, pieces)
            }
            ObstacleSpec::Circle { centre, radius } => {
                !s.conflicts_with_circle(*centre, *radius, clearance, pieces)
            }
        })
    }
}

// ------------------------------------------------------------------------------------------------
// One basic network

/// The end of a basic network: a site with its terminal line elements.
struct Terminals {
    /// Terminal line elements (all at the site).
    elements: Vec<LineElement>,
}

/// A basic network to build and search.
struct Job {
    /// Source side (A): terminals are sources only.
    a: Terminals,
    /// Target side (B): terminals are sinks only.
    b: Terminals,
    /// Foci and major axis of the ellipse.
    focus_a: Vec2,
    focus_b: Vec2,
    major_axis: f32,
    seed: u64,
    /// Which A terminals to search from forward, and which (as reversed searches) backward.
    forward_sources: Vec<usize>,
    reverse_sources: Vec<usize>,
}

/// A segment of a basic network. Nodes: A terminals, then B terminals, then elements.
struct GEdge {
    to: u32,
    forward: Option<HermiteSegment>,
    reverse: Option<HermiteSegment>,
}

/// The shortest chains from one source terminal to every B terminal.
struct Paths {
    /// Per B terminal: `None` if unreachable, else the path.
    to_b: Vec<Option<Path>>,
}

/// A shortest path: its length and its steps `(node, index in the node's adjacency)`, from the
/// source terminal on.
type Path = (f32, Vec<(u32, u32)>);

#[derive(Default)]
struct JobStats {
    line_elements: usize,
    rejected: usize,
    tried: usize,
    flyable: usize,
    feasible: usize,
    reverse_feasible: usize,
    searches: usize,
    segment_time: Duration,
    search_time: Duration,
}

struct JobResult {
    nodes: Vec<LineElement>,
    adjacency: Vec<Vec<GEdge>>,
    forward: Vec<(usize, Paths)>,
    reverse: Vec<(usize, Paths)>,
    stats: JobStats,
}

struct Ctx<'a> {
    obstacles: Obstacles<'a>,
    limits: FlyLimits,
    swapped: FlyLimits,
    symmetric: bool,
    v_nominal: f32,
    /// Highest lateral acceleration, m/s² (sizes the guide turns).
    a_lat_max: f32,
    params: &'a LandmarkParams,
}

/// How guide elements are laid out.
struct Guide {
    /// Turn radius, metres.
    radius: f32,
    /// Spacing along the straight, metres (half the basic network's neighbour radius).
    spacing: f32,
}

/// Guide line elements for terminal `t`: along the two turn-then-straight paths (radius
/// `guide.radius`) from `t` towards `toward`, every 45° of turn and at the tangent point, heading
/// along the path; for a sink (`into`), along the paths from `−t`, negated, so they lead into it.
fn guide_elements(
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

fn negate(e: &LineElement) -> LineElement {
    LineElement::new(e.position, Vec2::new(-e.velocity.x, -e.velocity.y))
}

fn run_job(job: &Job, ctx: &Ctx) -> JobResult {
    let mut stats = JobStats::default();
    let t0 = Instant::now();
    // Line elements in the ellipse.
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
        // `CHORD_HEADING_SPREAD_DEG`), the rest are uniform; see *Line elements* above.
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
    let n = nodes.len();
    let is_source = |i: usize| i < na || i >= na + nb;
    let is_target = |i: usize| i >= na;

    // Candidates by the neighbour rule.
    let k = ctx.params.max_neighbours;
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

    // Segments.
    let want_reverse = !job.reverse_sources.is_empty();
    let clearance = ctx.params.clearance_m;
    let mut adjacency: Vec<Vec<GEdge>> = (0..n).map(|_| Vec::new()).collect();
    for &(i, j) in &candidates {
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

#[derive(PartialEq)]
struct HeapItem(f32, u32);

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
fn dijkstra(adj: &[Vec<GEdge>], src: usize, na: usize, nb: usize, reverse: bool) -> Paths {
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
    fn forward_chain(&self, steps: &[(u32, u32)]) -> HermiteChain {
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
    fn reverse_chain(&self, steps: &[(u32, u32)]) -> HermiteChain {
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

fn chain(elements: Vec<LineElement>, pieces: Vec<HermiteSegment>) -> HermiteChain {
    HermiteChain {
        cost: pieces.iter().map(|p| p.length()).sum(),
        elements,
        pieces,
    }
}

// ------------------------------------------------------------------------------------------------
// The build

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
    let params = LandmarkParams::from_scenario(s);
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
    let lm = &input.landmarks;
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

    // Vertices.
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

    // Jobs.
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
    let endpoint_elements = |e: &Option<EndpointSite>| -> Vec<LineElement> {
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
    };
    let start_elements = endpoint_elements(&input.start);
    if let Some(st) = &input.start {
        let dist = st.dist_m.unwrap_or(0.0);
        for (l, site) in lm.iter().enumerate() {
            if st.pose.position.distance(site.position) <= dist {
                kinds.push(JobKind::Start(l));
            }
        }
    }
    let goal_elements = endpoint_elements(&input.goal);
    if let Some(g) = &input.goal {
        for (l, site) in lm.iter().enumerate() {
            if g.pose.position.distance(site.position) <= site.max_range_m() {
                kinds.push(JobKind::Goal(l));
            }
        }
    }

    let total = kinds.len();
    let done = AtomicUsize::new(0);
    let make_job = |kind: &JobKind| -> Job {
        match *kind {
            JobKind::Pair(a, b) => {
                let d = lm[a].position.distance(lm[b].position);
                let (ta, opp_a) = landmark_terminals(input, a);
                let (tb, _) = landmark_terminals(input, b);
                // Forward: A directions whose range reaches B. Reverse: B→A edges (B β → A α)
                // come from G paths A (α+180°) → B (β+180°), needed when some B direction
                // reaches A.
                let forward_sources = (0..n).filter(|&k| lm[a].range_m(k) >= d).collect();
                let reverse_sources = if (0..n).any(|k| lm[b].range_m(k) >= d) {
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
                        elements: start_elements.clone(),
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
                        elements: goal_elements.clone(),
                    },
                    focus_a: lm[l].position,
                    focus_b: gp,
                    major_axis: lm[l].max_range_m(),
                    seed: job_seed(params.seed, 3, l as u64, 0),
                    forward_sources: (0..n).filter(|&k| lm[l].range_m(k) >= d).collect(),
                    reverse_sources: Vec::new(),
                }
            }
        }
    };
    let results: Vec<JobResult> = kinds
        .par_iter()
        .map(|kind| {
            let job = make_job(kind);
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
        stats.directions_out_of_range += match *kind {
            JobKind::Pair(a, b) => {
                let d = lm[a].position.distance(lm[b].position);
                (0..n).filter(|&k| lm[a].range_m(k) < d).count()
                    + (0..n).filter(|&k| lm[b].range_m(k) < d).count()
            }
            JobKind::Goal(l) => {
                let gp = input
                    .goal
                    .as_ref()
                    .map_or(Vec2::default(), |g| g.pose.position);
                let d = gp.distance(lm[l].position);
                (0..n).filter(|&k| lm[l].range_m(k) < d).count()
            }
            JobKind::Start(_) => 0,
        };
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
        match *kind {
            JobKind::Pair(a, b) => {
                let d = lm[a].position.distance(lm[b].position);
                // A → B.
                for (src, paths) in &r.forward {
                    let ka = *src;
                    let range = lm[a].range_m(ka);
                    for (kb, p) in paths.to_b.iter().enumerate().take(n) {
                        match p {
                            None => stats.unconnected += 1,
                            Some((_, steps)) => {
                                let c = r.forward_chain(steps);
                                if c.cost > range && params.range_rule == RangeRule::PathLength {
                                    stats.edges_over_range += 1;
                                    continue;
                                }
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
                        if range < d {
                            continue;
                        }
                        match paths.to_b.get(tb).and_then(|p| p.as_ref()) {
                            None => stats.unconnected += 1,
                            Some((_, steps)) => {
                                let c = r.reverse_chain(steps);
                                if c.cost > range && params.range_rule == RangeRule::PathLength {
                                    stats.edges_over_range += 1;
                                    continue;
                                }
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
            JobKind::Start(l) => {
                let dist = input.start.as_ref().and_then(|s| s.dist_m).unwrap_or(0.0);
                for (src, paths) in &r.forward {
                    for (k, p) in paths.to_b.iter().enumerate().take(n) {
                        match p {
                            None => stats.unconnected += 1,
                            Some((_, steps)) => {
                                let c = r.forward_chain(steps);
                                if c.cost > dist && params.range_rule == RangeRule::PathLength {
                                    stats.edges_over_range += 1;
                                    continue;
                                }
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
            JobKind::Goal(l) => {
                for (src, paths) in &r.forward {
                    let range = lm[l].range_m(*src);
                    for (g, p) in paths.to_b.iter().enumerate() {
                        match p {
                            None => stats.unconnected += 1,
                            Some((_, steps)) => {
                                let c = r.forward_chain(steps);
                                if c.cost > range && params.range_rule == RangeRule::PathLength {
                                    stats.edges_over_range += 1;
                                    continue;
                                }
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
