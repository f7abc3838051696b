//! Damaging valid network images on purpose: the checksum re-fixed so that the field checks,
//! not the CRC, decide, and the rules of an offset table broken one at a time.

use skyroute::network::format::{Header, U32Record};
use skyroute::network::{image_checksum, Section};
use skyroute::{LoadError, Network};

/// Rewrites the header's CRC so that a deliberate body change reaches the field checks.
pub fn fix_crc(bytes: &mut [u8]) {
    let crc = image_checksum(bytes);
    bytes[Header::CHECKED_SIZE..Header::SIZE].copy_from_slice(&crc.to_le_bytes());
}

/// Little-endian bytes of consecutive f32 fields, as an image stores them.
pub fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Where the run `stored` starts in `bytes`; it must occur exactly once.
pub fn find_unique(bytes: &[u8], stored: &[u8]) -> usize {
    let at: Vec<usize> = bytes
        .windows(stored.len())
        .enumerate()
        .filter(|(_, w)| *w == stored)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(at.len(), 1, "the run is stored once: {at:?}");
    at[0]
}

/// `bytes` with the run `stored` (which must occur exactly once) replaced by `new` and the
/// checksum re-fixed, so that the loader's field checks decide.
pub fn replace_unique(bytes: &[u8], stored: &[u8], new: &[u8]) -> Vec<u8> {
    assert_eq!(stored.len(), new.len(), "a replacement of the same length");
    let at = find_unique(bytes, stored);
    let mut out = bytes.to_vec();
    out[at..at + new.len()].copy_from_slice(new);
    fix_crc(&mut out);
    out
}

/// Unsigned LEB128 (7 bits a byte, least significant first, the high bit set on every byte but
/// the last), written out here as the format's reference for the cell lists.
pub fn leb128(mut x: u32, out: &mut Vec<u8>) {
    while x >= 0x80 {
        out.push((x as u8 & 0x7f) | 0x80);
        x >>= 7;
    }
    out.push(x as u8);
}

fn get_u32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// One offset table of an image: where it starts, how many ranges it has (`count + 1`
/// offsets) and the total its last offset must equal.
pub struct OffsetTable {
    /// The section the loader names.
    pub section: Section,
    /// Byte offset of offset 0 in the image.
    pub at: usize,
    /// Ranges: the table holds `count + 1` offsets.
    pub count: u32,
    /// What the last offset must equal.
    pub total: u32,
}

impl OffsetTable {
    /// Offset `i` as stored in `b`.
    pub fn offset(&self, b: &[u8], i: u32) -> u32 {
        get_u32(b, self.at + i as usize * U32Record::SIZE)
    }
}

/// Breaks each rule of `table` in `good` on its own (checksum re-fixed) and asserts that the
/// loader refuses it as `BadOffsets` at the offending index: the first offset not 0, the last
/// not the total (above and below), a decrease in the middle, two neighbours swapped, a middle
/// offset above the total.
pub fn check_offset_rules_refused(good: &[u8], table: &OffsetTable) {
    let (n, total) = (table.count, table.total);
    assert_eq!(table.offset(good, 0), 0, "{:?} starts at 0", table.section);
    assert_eq!(
        table.offset(good, n),
        total,
        "{:?} ends at the total",
        table.section
    );
    assert!(total >= 2, "{:?} has entries to move", table.section);
    let refused = |changes: &[(u32, u32)], index: u32, what: &str| {
        let mut b = good.to_vec();
        for &(i, value) in changes {
            let at = table.at + i as usize * U32Record::SIZE;
            b[at..at + 4].copy_from_slice(&value.to_le_bytes());
        }
        assert_ne!(b, good, "{what}: the damage changes the image");
        fix_crc(&mut b);
        assert_eq!(
            Network::from_bytes(&b).map(|_| ()),
            Err(LoadError::BadOffsets {
                section: table.section,
                index
            }),
            "{:?}: {what}",
            table.section
        );
    };
    // The first offset not 0: the offsets before the first one above 0 raised to 1, so the
    // table still never decreases and only the first rule breaks.
    let first_used = (1..=n)
        .find(|&i| table.offset(good, i) > 0)
        .expect("an offset above 0");
    let raised: Vec<(u32, u32)> = (0..first_used).map(|i| (i, 1)).collect();
    refused(&raised, 0, "first offset 1");
    refused(
        &[(0, table.offset(good, first_used))],
        0,
        "first offset equal to the next used one",
    );
    // The last offset above the total, or below it: the offsets after the last one below the
    // total lowered to total - 1 (never decreasing, so only the last rule breaks).
    refused(&[(n, total + 1)], n, "last offset total + 1");
    refused(&[(n, u32::MAX)], n, "last offset u32::MAX");
    let last_below = (0..n)
        .rev()
        .find(|&i| table.offset(good, i) < total)
        .expect("an offset below the total");
    let lowered: Vec<(u32, u32)> = (last_below + 1..=n).map(|i| (i, total - 1)).collect();
    refused(&lowered, n, "last offset total - 1");
    // A decrease in the middle: the offset after the first one strictly between 0 and the
    // total set below it.
    let k = (1..n)
        .find(|&i| table.offset(good, i) > 0 && table.offset(good, i) < total)
        .expect("an offset strictly between 0 and the total");
    let ok = table.offset(good, k);
    refused(&[(k + 1, ok - 1)], k + 1, "offset below the one before it");
    // Two neighbours swapped where they differ: the second decreases.
    let j = (0..n)
        .find(|&i| table.offset(good, i) < table.offset(good, i + 1) && i + 1 < n)
        .expect("two different neighbours");
    let (a, b) = (table.offset(good, j), table.offset(good, j + 1));
    refused(
        &[(j, b), (j + 1, a)],
        if j == 0 { 0 } else { j + 1 },
        "neighbours swapped",
    );
    // An offset above the total in the middle (non-decreasing up to it).
    refused(&[(k, total + 1)], k, "a middle offset above the total");
}

/// `limits` with each of its three numbers in turn replaced by 0, −1, NaN and ∞: every way a
/// single bad value can make vertical limits invalid.
pub fn bad_vertical_limits(
    limits: skyroute::geometry::vertical::VerticalLimits,
) -> Vec<skyroute::geometry::vertical::VerticalLimits> {
    use skyroute::geometry::vertical::VerticalLimits;
    let mut out = Vec::new();
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        out.push(VerticalLimits {
            airspeed: bad,
            ..limits
        });
        out.push(VerticalLimits {
            climb_rate: bad,
            ..limits
        });
        out.push(VerticalLimits {
            vertical_accel: bad,
            ..limits
        });
    }
    out
}
