//! The loader's obstacle checks (`validate_obstacles`): every way a static obstacle record can
//! be wrong is refused with its own `LoadError`. Each case damages the bytes of a valid
//! synthetic image (two rectangles of 4 points each, then one circle) and re-fixes its
//! checksum, so the field checks, not the CRC, decide.

use host_tests::damage::fix_crc;
use host_tests::world::world;
use skyroute::geometry::predicates::PolygonView;
use skyroute::network::format::{
    EdgeRecord, Header, ObstacleRecord, PointRecord, U32Record, VertexRecord,
};
use skyroute::network::{Obstacle, Section};
use skyroute::{LoadError, Network};

/// Field offsets inside an [`ObstacleRecord`].
const KIND: usize = 0;
const FIRST_POINT: usize = 1;
const POINT_COUNT: usize = 5;
const CIRCLE: usize = 9;
const BBOX: usize = 21;

struct Image {
    good: Vec<u8>,
    /// Byte offset of obstacle record 0.
    obstacles: usize,
    /// Byte offset of point record 0.
    points: usize,
    /// Number of polygon points.
    point_count: u32,
}

/// A valid image whose obstacles are polygon (4 points), polygon (4 points), circle.
fn image() -> Image {
    let w = world(2, 600.0, 60.0, 40.0, 3);
    let net = Network::from_bytes(&w.bytes).expect("the undamaged image loads");
    let h = *net.header();
    assert_eq!(h.obstacle_count, 3);
    assert_eq!(h.obstacle_point_count, 8);
    for (i, polygon) in [(0, true), (1, true), (2, false)] {
        let (o, _) = net.obstacle(i).unwrap();
        match o {
            Obstacle::Polygon(p) => assert!(polygon && p.vertex_count() == 4, "obstacle {i}"),
            Obstacle::Circle { .. } => assert!(!polygon, "obstacle {i}"),
        }
    }
    let (v, e) = (h.vertex_count as usize, h.edge_count as usize);
    let obstacles =
        Header::SIZE + v * VertexRecord::SIZE + (v + 1) * U32Record::SIZE + e * EdgeRecord::SIZE;
    Image {
        good: w.bytes.clone(),
        obstacles,
        points: obstacles + 3 * ObstacleRecord::SIZE,
        point_count: 8,
    }
}

impl Image {
    fn field(&self, obstacle: usize, offset: usize) -> usize {
        self.obstacles + obstacle * ObstacleRecord::SIZE + offset
    }

    /// The loader's verdict on the image with `damage` applied (checksum re-fixed).
    fn load_damaged(&self, damage: impl Fn(&mut Vec<u8>)) -> Result<(), LoadError> {
        let mut b = self.good.clone();
        damage(&mut b);
        assert_ne!(b, self.good, "the damage changes the image");
        fix_crc(&mut b);
        Network::from_bytes(&b).map(|_| ())
    }

    fn put_u32(&self, b: &mut [u8], at: usize, x: u32) {
        b[at..at + 4].copy_from_slice(&x.to_le_bytes());
    }

    fn put_f32(&self, b: &mut [u8], at: usize, x: f32) {
        b[at..at + 4].copy_from_slice(&x.to_le_bytes());
    }

    fn get_f32(&self, at: usize) -> f32 {
        f32::from_le_bytes(self.good[at..at + 4].try_into().unwrap())
    }
}

#[test]
fn undamaged_obstacles_load_and_a_rewritten_checksum_alone_changes_nothing() {
    let im = image();
    let mut b = im.good.clone();
    fix_crc(&mut b);
    assert_eq!(b, im.good);
    Network::from_bytes(&b).expect("loads");
}

#[test]
fn polygons_of_fewer_than_three_points_are_refused() {
    let im = image();
    for count in [0u32, 1, 2] {
        let e = im
            .load_damaged(|b| im.put_u32(b, im.field(0, POINT_COUNT), count))
            .unwrap_err();
        assert_eq!(e, LoadError::BadObstacle { obstacle: 0 }, "{count} points");
    }
}

#[test]
fn circles_of_radius_zero_or_less_are_refused() {
    let im = image();
    for radius in [0.0f32, -0.0, -1.0, -f32::MIN_POSITIVE] {
        let e = im
            .load_damaged(|b| im.put_f32(b, im.field(2, CIRCLE + 8), radius))
            .unwrap_err();
        assert_eq!(e, LoadError::BadObstacle { obstacle: 2 }, "radius {radius}");
    }
    // The smallest positive radius is a circle (the check is `> 0`, not `≥ 1` or similar).
    im.load_damaged(|b| im.put_f32(b, im.field(2, CIRCLE + 8), f32::MIN_POSITIVE))
        .expect("a tiny circle loads");
}

#[test]
fn unknown_obstacle_kinds_are_refused() {
    let im = image();
    for kind in [2u8, 7, 0xFF] {
        let e = im
            .load_damaged(|b| b[im.field(2, KIND)] = kind)
            .unwrap_err();
        assert_eq!(e, LoadError::BadObstacle { obstacle: 2 }, "kind {kind}");
    }
    // A circle record relabelled as a polygon owns no points: it is not back to back.
    let e = im.load_damaged(|b| b[im.field(2, KIND)] = 0).unwrap_err();
    assert_eq!(
        e,
        LoadError::BadOffsets {
            section: Section::Obstacles,
            index: 2
        }
    );
}

#[test]
fn unordered_bounding_boxes_are_refused() {
    let im = image();
    for obstacle in [0usize, 2] {
        for axis in [0usize, 1] {
            // min and max of one axis swapped.
            let lo = im.field(obstacle, BBOX + 4 * axis);
            let hi = im.field(obstacle, BBOX + 4 * (axis + 2));
            let (a, b_) = (im.get_f32(lo), im.get_f32(hi));
            assert!(a < b_);
            let e = im
                .load_damaged(|b| {
                    im.put_f32(b, lo, b_);
                    im.put_f32(b, hi, a);
                })
                .unwrap_err();
            assert_eq!(
                e,
                LoadError::BadObstacle {
                    obstacle: obstacle as u32
                },
                "obstacle {obstacle} axis {axis}"
            );
        }
    }
}

/// The planner skips an obstacle whose box a primitive's box misses, so a stored box that does
/// not enclose its polygon or disc would hide part of the obstacle: refused, on every side, by
/// as little as a float step (a zero-width box included); the box the writer computed loads.
#[test]
fn bounding_boxes_that_do_not_enclose_their_obstacle_are_refused() {
    let im = image();
    for obstacle in [0usize, 1, 2] {
        for side in 0..4usize {
            let at = im.field(obstacle, BBOX + 4 * side);
            let v = im.get_f32(at);
            // Min sides move up, max sides down: the box shrinks by one float step.
            let shrunk = if side < 2 {
                f32::from_bits(if v >= 0.0 {
                    v.to_bits() + 1
                } else {
                    v.to_bits() - 1
                })
            } else {
                f32::from_bits(if v > 0.0 {
                    v.to_bits() - 1
                } else {
                    v.to_bits() + 1
                })
            };
            let e = im.load_damaged(|b| im.put_f32(b, at, shrunk)).unwrap_err();
            assert_eq!(
                e,
                LoadError::BadObstacle {
                    obstacle: obstacle as u32
                },
                "obstacle {obstacle} side {side}"
            );
        }
    }
    // A zero-width box (min == max: ordered, but no disc fits in it).
    let lo = im.field(2, BBOX);
    let hi = im.field(2, BBOX + 8);
    let e = im
        .load_damaged(|b| im.put_f32(b, hi, im.get_f32(lo)))
        .unwrap_err();
    assert_eq!(e, LoadError::BadObstacle { obstacle: 2 });
    // Grown boxes are conservative and load.
    let at = im.field(2, BBOX + 8);
    im.load_damaged(|b| im.put_f32(b, at, im.get_f32(at) + 1.0))
        .expect("a larger box encloses the disc");
}

#[test]
fn non_finite_obstacle_values_are_refused() {
    let im = image();
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        // A polygon point, x and y.
        for (point, offset) in [(0u32, 0usize), (5, 4), (7, 0)] {
            let at = im.points + point as usize * PointRecord::SIZE + offset;
            let e = im.load_damaged(|b| im.put_f32(b, at, bad)).unwrap_err();
            assert_eq!(
                e,
                LoadError::NonFinite {
                    section: Section::ObstaclePoints,
                    index: point
                },
                "point {point} field {offset}: {bad}"
            );
        }
        // Every circle and bounding-box field, of a polygon and of the circle.
        for obstacle in [1u32, 2] {
            for k in 0..7 {
                let at = im.field(obstacle as usize, CIRCLE + 4 * k);
                let e = im.load_damaged(|b| im.put_f32(b, at, bad)).unwrap_err();
                assert_eq!(
                    e,
                    LoadError::NonFinite {
                        section: Section::Obstacles,
                        index: obstacle
                    },
                    "obstacle {obstacle} field {k}: {bad}"
                );
            }
        }
    }
}

#[test]
fn polygon_point_ranges_not_back_to_back_are_refused() {
    let im = image();
    let bad_offsets = |index| LoadError::BadOffsets {
        section: Section::Obstacles,
        index,
    };
    // Polygon 1 starts inside polygon 0's range (overlap), after it (gap), or polygon 0 does
    // not start at point 0.
    for (obstacle, first) in [(1usize, 3u32), (1, 5), (1, 0), (0, 1)] {
        let e = im
            .load_damaged(|b| im.put_u32(b, im.field(obstacle, FIRST_POINT), first))
            .unwrap_err();
        assert_eq!(
            e,
            bad_offsets(obstacle as u32),
            "obstacle {obstacle} first point {first}"
        );
    }
    // Polygon 0 one point shorter: polygon 1 no longer follows it.
    let e = im
        .load_damaged(|b| im.put_u32(b, im.field(0, POINT_COUNT), 3))
        .unwrap_err();
    assert_eq!(e, bad_offsets(1));
    // Polygon 1 one point shorter: the last point is used by no polygon.
    let e = im
        .load_damaged(|b| im.put_u32(b, im.field(1, POINT_COUNT), 3))
        .unwrap_err();
    assert_eq!(
        e,
        LoadError::BadOffsets {
            section: Section::ObstaclePoints,
            index: im.point_count - 1
        }
    );
    // Both polygons gone (relabelled circles of 1 m at their boxes' centres, so the boxes
    // enclose them): 8 points unused.
    let e = im
        .load_damaged(|b| {
            for o in [0, 1] {
                b[im.field(o, KIND)] = 1;
                let corner = |k: usize| im.get_f32(im.field(o, BBOX + 4 * k));
                im.put_f32(b, im.field(o, CIRCLE), 0.5 * (corner(0) + corner(2)));
                im.put_f32(b, im.field(o, CIRCLE + 4), 0.5 * (corner(1) + corner(3)));
                im.put_f32(b, im.field(o, CIRCLE + 8), 1.0);
            }
        })
        .unwrap_err();
    assert_eq!(
        e,
        LoadError::BadOffsets {
            section: Section::ObstaclePoints,
            index: 0
        }
    );
}

#[test]
fn polygon_point_ranges_past_the_end_are_refused() {
    let im = image();
    for (count, value) in [(5u32, 9u32), (1000, 1004), (u32::MAX, u32::MAX)] {
        let e = im
            .load_damaged(|b| im.put_u32(b, im.field(1, POINT_COUNT), count))
            .unwrap_err();
        assert_eq!(
            e,
            LoadError::IndexOutOfRange {
                section: Section::Obstacles,
                index: 1,
                value,
                limit: im.point_count
            },
            "count {count}"
        );
    }
}
