//! The three-dimensional roadmap (Niendorf et al.): the aircraft is a Dubins car in the plane
//! plus a vertical double integrator (climb rate `v_c`, vertical acceleration `a_z`) at a
//! constant horizontal airspeed, samples are `(x, y, z, heading)`, and obstacles have heights.
//!
//! An edge between samples at altitudes `z_a` and `z_b` exists when
//! - its altitude change is a rest-to-rest move within the limits over its horizontal length
//!   (`VerticalProfile::new(z_a, z_b, L)` is `Some`), and
//! - for every obstacle of footprint F and height h, the part of its Dubins path P flown below
//!   h + c (`pieces_within(P, span_below(h + c))`, c the clearance) keeps more than c from F,
//!   by the planar exact predicates. An obstacle of unbounded height is checked against the
//!   whole path, as in a planar roadmap.
//!
//! The edge's cost stays its horizontal length (its time at the constant airspeed). The
//! profile climbs as early and descends as late as it can ([`VerticalProfile`]), so the part
//! below a ceiling is one interval at an end of the edge.

use super::{point_conflicts, primitive_conflicts, Chords, CollisionCheck, ObstacleIndex, Roadmap};
use crate::frame::LocalFrame;
use crate::scenario::Scenario;
use skyroute::geometry::vertical::{pieces_within, VerticalLimits, VerticalProfile};
use skyroute::{DubinsPath, Vec2};

/// What makes a roadmap three-dimensional.
#[derive(Clone, Debug, PartialEq)]
pub struct VerticalInput {
    /// The aircraft's airspeed, climb rate and vertical acceleration.
    pub limits: VerticalLimits,
    /// Lowest sample altitude, metres.
    pub altitude_min_m: f32,
    /// Highest sample altitude, metres (≥ `altitude_min_m`).
    pub altitude_max_m: f32,
    /// Height of each obstacle of the roadmap's input, metres, in its order; `f32::INFINITY`
    /// (or a missing entry): unbounded, no altitude clears it.
    pub heights: Vec<f32>,
    /// Altitude of each of the input's fixed vertices, metres, in their order.
    pub fixed_altitudes: Vec<f32>,
}

/// `x` as the nearest f32 not below it, so that a height rounded to f32 never lowers the
/// building.
fn f32_at_least(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x {
        f.next_up()
    } else {
        f
    }
}

/// The scenario's three-dimensional roadmap input in `frame` (airspeed: the nominal speed);
/// `None` for a planar scenario. The heights follow [`crate::local::local_obstacles`]: each
/// piece of a no-fly zone has the zone's height, a threat disc is unbounded.
pub fn vertical_input(s: &Scenario, frame: &LocalFrame) -> Option<VerticalInput> {
    let v = s.vertical()?;
    let heights = crate::local::local_obstacle_heights(s, frame)
        .into_iter()
        .map(|h| h.map_or(f32::INFINITY, f32_at_least))
        .collect();
    Some(VerticalInput {
        limits: VerticalLimits {
            airspeed: s.vehicle.v_nominal_mps as f32,
            climb_rate: v.climb_rate_mps as f32,
            vertical_accel: v.vertical_accel_mps2 as f32,
        },
        altitude_min_m: v.altitude_min_m as f32,
        altitude_max_m: v.altitude_max_m as f32,
        heights,
        fixed_altitudes: Vec::new(),
    })
}

impl VerticalInput {
    /// The altitude at the fraction `w` ∈ [0, 1) of the band, kept within it after rounding.
    pub(crate) fn altitude_at(&self, w: f64) -> f32 {
        let (lo, hi) = (self.altitude_min_m, self.altitude_max_m);
        ((lo as f64 + w * (hi as f64 - lo as f64)) as f32).clamp(lo, hi)
    }

    /// Obstacle `i`'s height (unbounded when not given).
    fn height(&self, i: usize) -> f32 {
        self.heights.get(i).copied().unwrap_or(f32::INFINITY)
    }

    /// Whether a sample at `p`, altitude `z`, lies within `clearance` of an obstacle: within
    /// it horizontally and not above its height plus the clearance.
    pub(crate) fn sample_conflicts(
        &self,
        obstacles: &ObstacleIndex,
        p: Vec2,
        z: f32,
        clearance: f32,
    ) -> bool {
        obstacles.near_indexed(p, p, clearance).any(|(i, o)| {
            // NaN-safe: a NaN altitude or ceiling is not above, so the sample is dropped.
            let above = z > self.height(i) + clearance;
            !above && point_conflicts(p, o, clearance)
        })
    }

    /// The altitude profile of an edge along `path` from `from` to `to`; `None` when the climb
    /// is not feasible over the path's length.
    pub(crate) fn profile(&self, from: f32, to: f32, path: &DubinsPath) -> Option<VerticalProfile> {
        VerticalProfile::new(from, to, path.length(), &self.limits)
    }

    /// Whether `path`, flown with `profile`, keeps `clearance` from every obstacle in 3-D (the
    /// rule in the module's doc). The discretised check tests the chords of the planar check
    /// (the same points along the path) and tests a chord against an obstacle of finite height
    /// when the stretch of path it replaces meets the span flown below the obstacle's height
    /// plus the clearance: every point of the path flown below it lies on such a stretch, so
    /// the planar check's sagitta argument carries over.
    pub(crate) fn path_is_clear(
        &self,
        obstacles: &ObstacleIndex,
        path: &DubinsPath,
        profile: &VerticalProfile,
        clearance: f32,
        check: CollisionCheck,
    ) -> bool {
        match check {
            CollisionCheck::Exact => {
                path.primitives().iter().enumerate().all(|(k, prim)| {
                    let Some(prim) = prim else {
                        return true;
                    };
                    let (lo, hi) = prim.bounding_box();
                    obstacles.near_indexed(lo, hi, clearance).all(|(i, o)| {
                        let h = self.height(i);
                        if !h.is_finite() {
                            return !primitive_conflicts(prim, o, clearance);
                        }
                        let Some((first, last)) = profile.span_below(h + clearance) else {
                            return true; // the whole edge is above it
                        };
                        // Piece k of the path cut to the span: the part of this primitive
                        // flown below the ceiling.
                        pieces_within(path, first, last)[k]
                            .is_none_or(|piece| !primitive_conflicts(&piece, o, clearance))
                    })
                })
            }
            CollisionCheck::Discretised {
                arc_step_m,
                sagitta,
            } => {
                let chords = Chords::new(path, clearance, arc_step_m, sagitta);
                (0..chords.steps).all(|j| {
                    let chord = chords.chord(j);
                    let (a, b) = (chords.at(j), chords.at(j + 1));
                    let (lo, hi) = chord.bounding_box();
                    obstacles.near_indexed(lo, hi, chords.margin).all(|(i, o)| {
                        let h = self.height(i);
                        let below = !h.is_finite()
                            || profile
                                .span_below(h + clearance)
                                .is_some_and(|(first, last)| first <= b && a <= last);
                        !below || !primitive_conflicts(&chord, o, chords.margin)
                    })
                })
            }
        }
    }

    /// Whether `path` meets the footprint of an obstacle of finite height (it flies over it).
    pub(crate) fn overflies(&self, obstacles: &ObstacleIndex, path: &DubinsPath) -> bool {
        path.primitives().into_iter().flatten().any(|prim| {
            let (lo, hi) = prim.bounding_box();
            obstacles
                .near_indexed(lo, hi, 0.0)
                .any(|(i, o)| self.height(i).is_finite() && primitive_conflicts(&prim, o, 0.0))
        })
    }
}

/// A line for `skyroute build` about a three-dimensional roadmap: its vertices' altitude range,
/// the candidate edges refused as too steep and the edges over a building of finite height;
/// `None` for a planar roadmap.
pub fn summary(r: &Roadmap) -> Option<String> {
    let lo = r.altitudes.iter().copied().reduce(f32::min)?;
    let hi = r.altitudes.iter().copied().reduce(f32::max)?;
    Some(format!(
        "three-dimensional: vertex altitudes {lo:.1}–{hi:.1} m; {} candidate edges too steep to \
         climb; {} edges fly over a building of finite height",
        r.edges_too_steep, r.edges_over_low_obstacles
    ))
}

#[cfg(test)]
mod tests {
    use super::super::{ObstacleIndex, Sagitta};
    use super::*;
    use skyroute::network::write::ObstacleSpec;
    use skyroute::Pose;

    const CLEARANCE: f32 = 7.0;

    /// A 20 m square building over `x ∈ [x0, x0 + 20]`, `y ∈ [-10, 10]`.
    fn square(x0: f32) -> ObstacleSpec {
        ObstacleSpec::Polygon(vec![
            Vec2::new(x0, -10.0),
            Vec2::new(x0 + 20.0, -10.0),
            Vec2::new(x0 + 20.0, 10.0),
            Vec2::new(x0, 10.0),
        ])
    }

    fn input(heights: Vec<f32>) -> VerticalInput {
        VerticalInput {
            limits: VerticalLimits::niendorf(25.0),
            altitude_min_m: 40.0,
            altitude_max_m: 120.0,
            heights,
            fixed_altitudes: Vec::new(),
        }
    }

    /// The straight 400 m path along the x axis.
    fn straight() -> DubinsPath {
        let pose = |x: f32| Pose {
            position: Vec2::new(x, 0.0),
            heading: 0.0,
        };
        DubinsPath::shortest(&pose(0.0), &pose(400.0), 64.0).unwrap()
    }

    /// Whether the straight path from `from` to `to` metres of altitude is clear of a building
    /// at `x0` of height `h`, by both checks (which must agree here).
    fn clear(from: f32, to: f32, x0: f32, h: f32) -> bool {
        let obstacles = [square(x0)];
        let index = ObstacleIndex::new(&obstacles);
        let v = input(vec![h]);
        let path = straight();
        let profile = v.profile(from, to, &path).expect("feasible");
        let exact = v.path_is_clear(&index, &path, &profile, CLEARANCE, CollisionCheck::Exact);
        let chords = CollisionCheck::Discretised {
            arc_step_m: 40.0,
            sagitta: Sagitta::Added,
        };
        let discretised = v.path_is_clear(&index, &path, &profile, CLEARANCE, chords);
        assert_eq!(
            exact, discretised,
            "{from} -> {to}, building at {x0}, {h} m"
        );
        exact
    }

    #[test]
    fn a_level_edge_clears_only_a_building_below_it_by_the_clearance() {
        assert!(clear(60.0, 60.0, 200.0, 30.0));
        assert!(clear(60.0, 60.0, 200.0, 52.9));
        assert!(!clear(60.0, 60.0, 200.0, 53.1)); // 53.1 + 7 > 60
        assert!(!clear(60.0, 60.0, 200.0, f32::INFINITY));
    }

    #[test]
    fn a_climb_is_low_at_its_start_and_a_descent_at_its_end() {
        // 40 → 100 m: v_c / v = 0.4 m per metre after an easing of 12.5 m, so the aircraft
        // is at 42.7 m 13 m in and at 100 m from 162.5 m on.
        assert!(!clear(40.0, 100.0, 20.0, 50.0));
        assert!(clear(40.0, 100.0, 300.0, 50.0));
        assert!(clear(100.0, 40.0, 20.0, 50.0));
        assert!(!clear(100.0, 40.0, 360.0, 50.0));
        // Too steep over 400 m: 0.4 (400 − 12.5) = 155 m at most.
        assert!(input(vec![]).profile(40.0, 200.0, &straight()).is_none());
        assert!(input(vec![]).profile(40.0, 190.0, &straight()).is_some());
    }

    #[test]
    fn with_unbounded_heights_the_check_is_the_planar_one() {
        let obstacles = [square(100.0), square(250.0)];
        let index = ObstacleIndex::new(&obstacles);
        let v = input(vec![f32::INFINITY; 2]);
        for y in [-40.0, -20.0, -17.5, -16.0, 16.0, 20.0] {
            let pose = |x: f32| Pose {
                position: Vec2::new(x, y),
                heading: 0.3,
            };
            let path = DubinsPath::shortest(&pose(0.0), &pose(400.0), 64.0).unwrap();
            let profile = v.profile(80.0, 80.0, &path).unwrap();
            let planar = index.path_is_clear(&path, CLEARANCE, CollisionCheck::Exact);
            let three_d =
                v.path_is_clear(&index, &path, &profile, CLEARANCE, CollisionCheck::Exact);
            assert_eq!(planar, three_d, "y {y}");
        }
    }

    #[test]
    fn a_sample_above_a_low_building_is_kept() {
        let obstacles = [square(0.0)];
        let index = ObstacleIndex::new(&obstacles);
        let v = input(vec![30.0]);
        let p = Vec2::new(10.0, 0.0);
        assert!(!v.sample_conflicts(&index, p, 37.5, CLEARANCE));
        assert!(v.sample_conflicts(&index, p, 37.0, CLEARANCE));
        assert!(input(vec![f32::INFINITY]).sample_conflicts(&index, p, 1e4, CLEARANCE));
        assert!(v.overflies(&index, &straight()));
        assert!(!input(vec![f32::INFINITY]).overflies(&index, &straight()));
    }

    #[test]
    fn heights_round_up_to_f32() {
        for h in [25.3, 0.1, 1e-40, 3.4e38, 123_456.789] {
            assert!(f32_at_least(h) as f64 >= h, "{h}");
        }
        assert_eq!(f32_at_least(1e300), f32::INFINITY);
        assert_eq!(f32_at_least(25.5), 25.5);
    }
}
