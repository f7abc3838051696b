//! CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF:
//! the CRC of zlib, PNG and `crc32fast`), table-driven with a 1 KiB table built at compile time.

const TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        table[i] = c;
        i += 1;
    }
    table
};

/// The CRC-32 of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32_parts(&[bytes])
}

/// The CRC register's initial value, and the final XOR.
pub(super) const CRC32_INIT: u32 = 0xFFFF_FFFF;

/// The CRC-32 of the concatenation of `parts`, without copying them together.
pub fn crc32_parts(parts: &[&[u8]]) -> u32 {
    parts
        .iter()
        .fold(CRC32_INIT, |c, part| crc32_update(c, part))
        ^ CRC32_INIT
}

/// The CRC register `c` after `bytes` (no initial value or final XOR applied: start from
/// [`CRC32_INIT`] and XOR the result with it).
pub(super) fn crc32_update(mut c: u32, bytes: &[u8]) -> u32 {
    for &b in bytes {
        c = TABLE[((c ^ b as u32) & 0xFF) as usize] ^ (c >> 8);
    }
    c
}

#[cfg(test)]
mod tests {
    #[test]
    fn check_value() {
        // The standard check value of CRC-32/ISO-HDLC.
        assert_eq!(super::crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn parts_are_the_concatenation() {
        assert_eq!(super::crc32_parts(&[b"1234", b"", b"56789"]), 0xCBF4_3926);
    }
}
