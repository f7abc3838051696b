//! Fixtures shared by the host tests (`tests/core`, `tests/modes`), the benches and nothing else:
//!
//! * [`rng`]: the one seeded random-number generator (SplitMix64) with the f64 and f32 helpers
//!   the tests use;
//! * [`damage`]: valid network images damaged on purpose (checksum re-fixed, offset-table
//!   rules broken one at a time);
//! * [`reference`]: the one independent f64 reference geometry (point–segment and
//!   point–polygon distances, even–odd containment, segment crossings, quintic Hermite
//!   evaluation) that routes and networks are checked against — written here from the
//!   textbook formulas, never calling the code under test;
//! * [`world`]: small synthetic roadmap networks built with the ground tool's real builder;
//! * [`scenarios`]: the repository's scenarios, loaded and built once per process and cached
//!   (keyed by scenario name and build options);
//! * [`tier`]: the test tiers (`SKYROUTE_TIER=fast`, the default, or `full`) and [`cases`],
//!   from which every randomized test takes its count.
//!
//! See `docs/TESTING.md`.

pub mod damage;
pub mod reference;
pub mod rng;
pub mod scenarios;
pub mod tier;
pub mod world;

pub use rng::Rng;
pub use tier::{cases, full_tier, full_tier_only, Tier};
