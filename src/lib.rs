//! # skyroute: the onboard core
//!
//! A flight-path planner for fixed-wing UAVs that runs on the flight computer: `#![no_std]`, no
//! allocator, no `unsafe`, fixed memory, bounded work.
//!
//! The ground tool (`prep/`) turns a mission area into a preprocessed [`network`] of flyable
//! trajectories. Onboard, [`Network::from_bytes`] validates that byte image once, where it lies
//! (a static slice in flash), and a [`Planner`] whose capacities are const generics prunes the
//! network for pop-up obstacles, connects the current pose and the goal, and runs Dijkstra (or A*)
//! within a work budget whose worst case is a documented function of the network's counts.
//!
//! ## Conventions
//! * Lengths are `f32` metres in the network's local frame: `x` east, `y` north of the frame's
//!   geographic origin (stored in the network header).
//! * Angles are `f32` radians. A **heading** is the *mathematical* direction of flight, counter-
//!   clockwise from east (`x`). Compass headings (clockwise from north) are converted at the
//!   interface with [`geometry::heading_from_compass_deg`], or from latitude/longitude with
//!   [`LocalFrame::pose`], which also corrects for the meridian convergence.
//! * A positive arc sweep turns left (counter-clockwise).
//!
//! ## Modules
//! * [`geo`]: WGS-84 longitude/latitude and compass headings to the network's local frame and
//!   back (the ground tool's transverse Mercator), for an autopilot that navigates in degrees.
//! * [`geometry`]: poses, lines, arcs, Dubins paths and the exact collision predicates.
//! * [`network`]: the network image (format version 4, `docs/FORMAT.md`), its validating loader
//!   and accessors.
//! * [`planner`]: the fixed-memory planner: pop-ups, endpoint connection, search, routes.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
// `!(a < b)` is deliberate throughout: it is true when either side is NaN, which must fail closed.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

#[cfg(feature = "std")]
extern crate std;

pub mod geo;
pub mod geometry;
pub mod network;
pub mod planner;
#[cfg(all(test, feature = "std"))]
mod test_rng;

pub use geo::{GeoError, LocalFrame};
pub use geometry::{Arc, DubinsPath, DubinsWord, Pose, Primitive, Segment, Turn, Vec2};
pub use network::{LoadError, Network};
pub use planner::{
    Goal, Phase, PlanError, Planner, PlannerConfig, Popup, PopupError, PopupSummary, Query,
    RouteSummary, Search, SmoothSummary, TurnRule, Work,
};
