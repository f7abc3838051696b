//! The loader's checks of the common header and of where the vertices lie
//! (`validate_parameters`, `validate_grid`'s reach test, `validate_edges`' cost sign): each
//! bad value is refused with the parameter it names, and each limit is tried on both sides —
//! the last value accepted and the first refused — so that a check moved by one step fails.
//! Every case edits a valid synthetic roadmap image and re-fixes its checksum, so the field
//! checks, not the CRC, decide.

use host_tests::damage::fix_crc;
use host_tests::world::world;
use skyroute::network::format::{EdgeRecord, Header, U32Record, VertexRecord};
use skyroute::network::{LoadError, Parameter};
use skyroute::Network;

/// Byte offsets of the header's fields (postcard, fixed-width little-endian).
const FLAGS: usize = 7;
const ORIGIN_LAT: usize = 8;
const ORIGIN_LON: usize = 16;
const TURN_RADIUS: usize = 24;
const CLEARANCE: usize = 28;
const GRID_ORIGIN_X: usize = 48;
const GRID_ORIGIN_Y: usize = 52;
const GRID_CELL: usize = 56;
const GRID_NX: usize = 60;
const GRID_NY: usize = 64;
const GRID_LIST_BYTES: usize = 68;

/// The valid image every case edits.
fn good() -> Vec<u8> {
    world(2, 600.0, 60.0, 40.0, 3).bytes
}

fn put(b: &mut [u8], at: usize, bytes: &[u8]) {
    b[at..at + bytes.len()].copy_from_slice(bytes);
}

/// The loader's verdict on `good` with `edit` applied and the checksum re-fixed.
fn load_edited(good: &[u8], edit: impl Fn(&mut Vec<u8>)) -> Result<(), LoadError> {
    let mut b = good.to_vec();
    edit(&mut b);
    assert_ne!(b, good, "the edit changes the image");
    fix_crc(&mut b);
    Network::from_bytes(&b).map(|_| ())
}

fn with_f32(good: &[u8], at: usize, x: f32) -> Result<(), LoadError> {
    load_edited(good, |b| put(b, at, &x.to_le_bytes()))
}

fn with_f64(good: &[u8], at: usize, x: f64) -> Result<(), LoadError> {
    load_edited(good, |b| put(b, at, &x.to_le_bytes()))
}

fn refused(parameter: Parameter) -> Result<(), LoadError> {
    Err(LoadError::InvalidParameter { parameter })
}

/// The header fields at the offsets above are the ones the loader reads.
#[test]
fn the_field_offsets_are_the_headers() {
    let good = good();
    let h = *Network::from_bytes(&good).unwrap().header();
    let f32_at = |at: usize| f32::from_le_bytes(good[at..at + 4].try_into().unwrap());
    let u32_at = |at: usize| u32::from_le_bytes(good[at..at + 4].try_into().unwrap());
    let f64_at = |at: usize| f64::from_le_bytes(good[at..at + 8].try_into().unwrap());
    assert_eq!(good[FLAGS], h.flags);
    assert_eq!(f64_at(ORIGIN_LAT), h.origin_lat_deg);
    assert_eq!(f64_at(ORIGIN_LON), h.origin_lon_deg);
    assert_eq!(f32_at(TURN_RADIUS), h.turn_radius_m);
    assert_eq!(f32_at(CLEARANCE), h.clearance_m);
    assert_eq!(f32_at(GRID_ORIGIN_X), h.grid_origin_x);
    assert_eq!(f32_at(GRID_ORIGIN_Y), h.grid_origin_y);
    assert_eq!(f32_at(GRID_CELL), h.grid_cell_m);
    assert_eq!(u32_at(GRID_NX), h.grid_nx);
    assert_eq!(u32_at(GRID_NY), h.grid_ny);
    assert_eq!(u32_at(GRID_LIST_BYTES), h.grid_list_bytes);
}

#[test]
fn the_turn_radius_must_be_finite_and_positive() {
    let good = good();
    for r in [0.0, -0.0, -40.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(
            with_f32(&good, TURN_RADIUS, r),
            refused(Parameter::TurnRadius),
            "r = {r}"
        );
    }
}

#[test]
fn the_clearance_must_be_finite_and_not_negative() {
    let good = good();
    assert_eq!(with_f32(&good, CLEARANCE, 0.0), Ok(()), "no clearance");
    for c in [-f32::MIN_POSITIVE, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(
            with_f32(&good, CLEARANCE, c),
            refused(Parameter::Clearance),
            "c = {c}"
        );
    }
}

#[test]
fn the_origin_must_be_a_latitude_and_a_longitude() {
    let good = good();
    for lat in [90.0, -90.0] {
        assert_eq!(with_f64(&good, ORIGIN_LAT, lat), Ok(()), "latitude {lat}");
    }
    for lon in [180.0, -180.0] {
        assert_eq!(with_f64(&good, ORIGIN_LON, lon), Ok(()), "longitude {lon}");
    }
    let past = |x: f64| f64::from_bits(x.to_bits() + 1); // the next value away from zero
    for lat in [past(90.0), past(-90.0), f64::NAN, f64::INFINITY] {
        assert_eq!(
            with_f64(&good, ORIGIN_LAT, lat),
            refused(Parameter::Origin),
            "latitude {lat}"
        );
    }
    for lon in [past(180.0), past(-180.0), f64::NAN, f64::NEG_INFINITY] {
        assert_eq!(
            with_f64(&good, ORIGIN_LON, lon),
            refused(Parameter::Origin),
            "longitude {lon}"
        );
    }
}

#[test]
fn the_grid_origin_and_cell_must_be_finite_and_the_cell_positive() {
    let good = good();
    for at in [GRID_ORIGIN_X, GRID_ORIGIN_Y] {
        for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            assert_eq!(
                with_f32(&good, at, x),
                refused(Parameter::GridOrigin),
                "byte {at}: {x}"
            );
        }
    }
    for cell in [0.0, -0.0, -25.0, f32::NAN, f32::INFINITY] {
        assert_eq!(
            with_f32(&good, GRID_CELL, cell),
            refused(Parameter::GridCell),
            "cell {cell}"
        );
    }
}

/// A grid of no columns or no rows. The image keeps its length: the cell-list byte count grows
/// by the cell offsets the empty grid no longer has, so only the dimension check can refuse it.
#[test]
fn a_grid_of_no_cells_is_refused_by_its_dimensions() {
    let good = good();
    let h = *Network::from_bytes(&good).unwrap().header();
    let freed = (h.grid_nx * h.grid_ny) as usize * U32Record::SIZE;
    for at in [GRID_NX, GRID_NY] {
        let result = load_edited(&good, |b| {
            put(b, at, &0u32.to_le_bytes());
            let lists = h.grid_list_bytes + freed as u32;
            put(b, GRID_LIST_BYTES, &lists.to_le_bytes());
        });
        assert_eq!(result, refused(Parameter::GridDimensions), "byte {at}");
    }
}

#[test]
fn unknown_flags_are_refused() {
    let good = good();
    for bit in [0x04u8, 0x08, 0x40, 0x80] {
        assert_eq!(
            load_edited(&good, |b| b[FLAGS] |= bit),
            refused(Parameter::Flags),
            "flag {bit:#04x}"
        );
    }
}

/// The vertices' coordinates along `axis` (0: x, 1: y), the reach the loader asks of the grid
/// beyond them (4r), and the bounds it gives: the lowest coordinate − 4r and the highest + 4r,
/// in f32 as the loader computes them.
struct AxisBounds {
    coordinates: Vec<f32>,
    reach: f32,
    low: f32,
    high: f32,
}

fn axis_bounds(net: &Network, axis: usize) -> AxisBounds {
    let h = net.header();
    let reach = 4.0 * h.turn_radius_m;
    let coordinates: Vec<f32> = (0..h.vertex_count)
        .map(|i| {
            let p = net.vertex(i).unwrap().position;
            [p.x, p.y][axis]
        })
        .collect();
    let low = coordinates
        .iter()
        .map(|&c| c - reach)
        .fold(f32::INFINITY, f32::min);
    let high = coordinates
        .iter()
        .map(|&c| c + reach)
        .fold(f32::NEG_INFINITY, f32::max);
    AxisBounds {
        coordinates,
        reach,
        low,
        high,
    }
}

/// Every Dubins path from a vertex stays within 4r of it, so the grid must cover each vertex
/// ± 4r. The grid's west and south edges are moved to the bound itself (accepted) and one f32
/// step inside it (refused, naming the first vertex the bound comes from).
#[test]
fn the_grid_must_reach_four_turn_radii_beyond_every_vertex_on_the_low_sides() {
    let good = good();
    let net = Network::from_bytes(&good).unwrap();
    for (axis, at) in [(0, GRID_ORIGIN_X), (1, GRID_ORIGIN_Y)] {
        let b = axis_bounds(&net, axis);
        let low = b.low;
        let first = b
            .coordinates
            .iter()
            .position(|&c| c - b.reach == low)
            .unwrap() as u32;
        assert_eq!(with_f32(&good, at, low), Ok(()), "byte {at} at the bound");
        assert_eq!(
            with_f32(&good, at, low.next_up()),
            Err(LoadError::GridTooSmall { vertex: first }),
            "byte {at} inside the bound"
        );
    }
}

/// The same on the east and north edges, `origin + cell · n`: the origin is searched, one f32
/// step at a time, for the last value whose far edge still lies at or beyond every vertex + 4r
/// (its far edge equal to the bound), and the next one down is refused.
#[test]
fn the_grid_must_reach_four_turn_radii_beyond_every_vertex_on_the_high_sides() {
    let good = good();
    let net = Network::from_bytes(&good).unwrap();
    let h = *net.header();
    let sides = [
        (0, GRID_ORIGIN_X, h.grid_origin_x, h.grid_nx),
        (1, GRID_ORIGIN_Y, h.grid_origin_y, h.grid_ny),
    ];
    for (axis, at, origin, n) in sides {
        let b = axis_bounds(&net, axis);
        let (low, high) = (b.low, b.high);
        let far = |o: f32| o + h.grid_cell_m * n as f32;
        assert!(
            origin <= low && far(origin) >= high,
            "the image's grid covers its vertices"
        );
        // Start from an origin whose far edge is a little beyond the bound, and step down.
        let mut o = high - h.grid_cell_m * n as f32 + 1.0;
        assert!(far(o) > high);
        while far(o.next_down()) >= high {
            o = o.next_down();
        }
        assert_eq!(far(o), high, "the far edge lands on the bound");
        assert!(o <= low, "the near edge still covers every vertex");
        let first = b
            .coordinates
            .iter()
            .position(|&c| c + b.reach > far(o.next_down()))
            .unwrap() as u32;
        assert_eq!(with_f32(&good, at, o), Ok(()), "byte {at} at the bound");
        assert_eq!(
            with_f32(&good, at, o.next_down()),
            Err(LoadError::GridTooSmall { vertex: first }),
            "byte {at} inside the bound"
        );
    }
}

/// An edge cost below zero is its own error, before the geometry it would fail.
#[test]
fn a_negative_edge_cost_is_refused_by_name() {
    let good = good();
    let h = *Network::from_bytes(&good).unwrap().header();
    let v = h.vertex_count as usize;
    let edges = Header::SIZE + v * VertexRecord::SIZE + (v + 1) * U32Record::SIZE;
    let cost_of = |e: usize| edges + e * EdgeRecord::SIZE + 3;
    for (e, cost) in [(0usize, -1.0f32), (7, -f32::MIN_POSITIVE), (11, -1e30)] {
        assert_eq!(
            load_edited(&good, |b| put(b, cost_of(e), &cost.to_le_bytes())),
            Err(LoadError::NegativeValue { edge: e as u32 }),
            "edge {e}, cost {cost}"
        );
    }
}
