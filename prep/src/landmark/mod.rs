//! Landmark mode, ground side (after Babel, "Flight path planning for unmanned aerial vehicles
//! with landmark-based visual navigation", 2014): the **landmark shortest-path network**.
//!
//! A vertex is an *overflight*: landmark `L` crossed with heading `α_k`, one of `directions`
//! equally spaced compass headings (0°, 30°, … 330° for the default 12), as the line element
//! "at `L` with velocity `v_nominal` along `α_k`". An edge from overflight `(A, α)` to `(B, β)` is
//! the shortest chain of quintic Hermite pieces ([`HermiteSegment`](skyroute::geometry::hermite::HermiteSegment)) found in a random *basic
//! network* of line elements between the two landmarks; every piece is flyable
//! ([`HermiteSegment::check_flyable`](skyroute::geometry::hermite::HermiteSegment::check_flyable)) and clear of every obstacle by the clearance
//! ([`HermiteSegment::conflicts_with_polygon`](skyroute::geometry::hermite::HermiteSegment::conflicts_with_polygon) / `conflicts_with_circle`, conservative). The
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
//! its length), and [`RangeRule::Onboard`] (Babel's reading, `build --landmark-ranges onboard`)
//! also searches the directions whose straight leg is out of range, storing every chain for
//! the onboard pruning. The range of a direction is the
//! rosette's value at that heading, linearly interpolated around the 12 given headings when
//! `directions` is not 12.
//!
//! **The ellipse.** Babel's method asks for line elements "inside the ellipse whose foci are the two
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
//! reversed piece is **rebuilt** with [`HermiteSegment::new`](skyroute::geometry::hermite::HermiteSegment::new) from its reversed line elements and
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

mod basic;
mod build;
mod input;
mod network;
mod params;
mod sampling;

pub use build::{build_from_input, build_landmark_network, build_landmark_network_with};
pub use input::{rosette_quality, EndpointSite, LandmarkInput, LandmarkSite, Rosette};
pub use network::{
    EndpointEdge, EndpointLinks, HermiteChain, LandmarkEdge, LandmarkNetwork, LandmarkStats,
    LandmarkVertex,
};
pub use params::{
    LandmarkError, LandmarkParams, RangeRule, CHORD_HEADING_SPREAD_DEG, MAX_DRAW_FACTOR,
};
