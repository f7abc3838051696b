//! Random numbers (SplitMix64, seeded per basic network) and the obstacle index that line
//! elements and Hermite pieces are tested against.

use skyroute::geometry::hermite::{HermiteSegment, MAX_PIECES};
use skyroute::geometry::predicates::{point_in_polygon, point_segment_distance, PolygonView};
use skyroute::network::write::ObstacleSpec;
use skyroute::Vec2;

/// SplitMix64.
#[derive(Clone, Debug)]
pub(super) struct SplitMix(pub(super) u64);

impl SplitMix {
    pub(super) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub(super) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller, one of the pair).
    pub(super) fn normal(&mut self) -> f64 {
        let (u1, u2) = (1.0 - self.unit(), self.unit());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// The seed of basic network `(kind, a, b)`.
pub(super) fn job_seed(seed: u64, kind: u64, a: u64, b: u64) -> u64 {
    let mut s = SplitMix(seed);
    let mut x = s.next_u64();
    for v in [kind, a, b] {
        x = SplitMix(x ^ v.wrapping_mul(0xD6E8_FEB8_6659_FD93)).next_u64();
    }
    x
}

/// Obstacles with bounding boxes.
pub(super) struct Obstacles<'a> {
    pub(super) items: Vec<(&'a ObstacleSpec, Vec2, Vec2)>,
}

impl<'a> Obstacles<'a> {
    pub(super) fn new(obstacles: &'a [ObstacleSpec]) -> Self {
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
    pub(super) fn near(
        &self,
        lo: Vec2,
        hi: Vec2,
        margin: f32,
    ) -> impl Iterator<Item = &'a ObstacleSpec> + '_ {
        self.items.iter().filter_map(move |(o, olo, ohi)| {
            let apart = lo.x - margin > ohi.x
                || hi.x + margin < olo.x
                || lo.y - margin > ohi.y
                || hi.y + margin < olo.y;
            (!apart).then_some(*o)
        })
    }

    /// Whether point `p` lies within `clearance` of an obstacle (or inside).
    pub(super) fn point_blocked(&self, p: Vec2, clearance: f32) -> bool {
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
    pub(super) fn segment_clear(&self, s: &HermiteSegment, clearance: f32) -> bool {
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
