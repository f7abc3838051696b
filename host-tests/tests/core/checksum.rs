//! The core's CRC-32 against `crc32fast`, an independent implementation of the same CRC
//! (IEEE 802.3, reflected, as zlib and PNG use). The network writer and loader share the core's
//! function, so a wrong table would round-trip unnoticed; only a second implementation sees it.

use host_tests::Rng;
use skyroute::network::format::Header;
use skyroute::network::{crc32, crc32_parts, image_checksum};

fn reference(bytes: &[u8]) -> u32 {
    let mut h = crc32fast::Hasher::new();
    h.update(bytes);
    h.finalize()
}

#[test]
fn crc32_matches_crc32fast_on_the_check_string_and_random_bytes() {
    // The catalogue's check value of CRC-32/ISO-HDLC.
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    assert_eq!(crc32(&[]), reference(&[]));
    let mut rng = Rng(0x5eed_c3c3);
    for len in (0..300).chain([1023, 4096, 65_537]) {
        let bytes: Vec<u8> = (0..len).map(|_| rng.below(256) as u8).collect();
        assert_eq!(crc32(&bytes), reference(&bytes), "{len} random bytes");
        // Every byte value through every table entry.
        let all: Vec<u8> = (0..=255u8)
            .cycle()
            .skip(len % 256)
            .take(len + 256)
            .collect();
        assert_eq!(crc32(&all), reference(&all), "byte ramp from {}", len % 256);
        let cut = rng.below(len as u64 + 1) as usize;
        let (a, b) = bytes.split_at(cut);
        assert_eq!(
            crc32_parts(&[a, &[], b]),
            reference(&bytes),
            "{len} bytes cut at {cut}"
        );
    }
}

#[test]
fn an_image_checksum_is_the_crc_of_the_header_without_its_crc_then_the_body() {
    let mut rng = Rng(0xc0ff_ee00);
    for len in [
        0,
        10,
        Header::CHECKED_SIZE,
        Header::SIZE,
        Header::SIZE + 1,
        5000,
    ] {
        let image: Vec<u8> = (0..len).map(|_| rng.below(256) as u8).collect();
        let mut checked = image[..len.min(Header::CHECKED_SIZE)].to_vec();
        checked.extend_from_slice(image.get(Header::SIZE..).unwrap_or(&[]));
        assert_eq!(image_checksum(&image), reference(&checked), "{len} bytes");
    }
}
