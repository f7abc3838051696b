//! The Rust side of `bench/compare.sh`: what the comparison with OMPL, Walker's `dubins.c`,
//! SciPy and petgraph needs from skyroute, written against the `skyroute` crate's public API.
//!
//! * [`rng`]: a small seeded random number generator, so that every input the peers read
//!   (queries, pose pairs, sample points) is reproducible without another dependency.
//! * [`world`]: a network's obstacles, clearance, turn radius and sampled area, with skyroute's
//!   own exact predicates for points and Dubins paths, and the text form the C++ program reads.
//! * [`queries`]: start/goal pose pairs in free space, a minimum distance apart.
//! * [`dijkstra`]: single-source shortest paths over a whole network with the core's indexed
//!   heap and the network's edge accessors (the planner's own search stops at its goal and
//!   keeps its distances private).
//! * [`stats`]: medians and percentiles.
//!
//! The driver is the `peers` example (`examples/peers/`), which also holds the petgraph side
//! (a dev-dependency, so that petgraph stays out of everything but this comparison).

#![deny(missing_docs)]

pub mod dijkstra;
pub mod queries;
pub mod rng;
pub mod stats;
pub mod world;
