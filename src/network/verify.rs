//! Re-checking a loaded image in flight: a byte of the network corrupted in flash after
//! `Network::from_bytes` accepted it (a radiation upset, a failing cell) is found by recomputing
//! the image's CRC-32 against the one the header held at load. [`ImageVerifier`] does that a
//! slice at a time, so a flight loop can spread the O(bytes) work over its cycles.

use super::crc::{crc32_update, CRC32_INIT};
use super::format::Header;
use super::{LoadError, Network};

/// Progress of an on-demand checksum pass over an image: where it is and the CRC so far. A pass
/// covers what the header's `image_crc` covers (the header's first [`Header::CHECKED_SIZE`]
/// bytes, then the body), in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ImageVerifier {
    /// Checked bytes so far, counted over the covered bytes only.
    done: usize,
    /// The CRC register after them.
    crc: u32,
}

/// What a [`ImageVerifier::step`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum VerifyStep {
    /// More bytes remain: call `step` again.
    InProgress {
        /// Bytes checked so far.
        done: usize,
        /// Bytes a whole pass checks.
        total: usize,
    },
    /// The pass ended and the image has the checksum it was loaded with. The next `step`
    /// starts a new pass.
    Intact,
    /// The pass ended and the image's bytes no longer have that checksum
    /// ([`LoadError::ChecksumMismatch`]: `stored` the header's at load, `computed` now). The next
    /// `step` starts a new pass.
    Corrupted(LoadError),
}

impl Default for ImageVerifier {
    fn default() -> Self {
        Self::new()
    }
}

impl ImageVerifier {
    /// A verifier at the start of a pass.
    pub const fn new() -> Self {
        ImageVerifier {
            done: 0,
            crc: CRC32_INIT,
        }
    }

    /// Checks up to `max_bytes` more bytes of `image` against `expected` (the CRC the image was
    /// accepted with). Work: at most `max_bytes` table steps (at least one byte is checked when
    /// any remain). An image shorter than its header is `Corrupted` at once.
    pub fn step(&mut self, image: &[u8], expected: u32, max_bytes: usize) -> VerifyStep {
        let body = image.get(Header::SIZE..).unwrap_or(&[]);
        let total = Header::CHECKED_SIZE + body.len();
        let mut budget = max_bytes.max(1);
        while budget > 0 && self.done < total {
            // The covered bytes are the header's checked part, then the body.
            let (part, from) = if self.done < Header::CHECKED_SIZE {
                (image.get(..Header::CHECKED_SIZE).unwrap_or(&[]), self.done)
            } else {
                (body, self.done - Header::CHECKED_SIZE)
            };
            let Some(rest) = part.get(from..) else {
                break;
            };
            if rest.is_empty() {
                break; // a header shorter than its checked part
            }
            let take = rest.len().min(budget);
            self.crc = crc32_update(self.crc, rest.get(..take).unwrap_or(&[]));
            self.done += take;
            budget -= take;
        }
        if self.done < total && image.len() >= Header::SIZE {
            return VerifyStep::InProgress {
                done: self.done,
                total,
            };
        }
        let computed = self.crc ^ CRC32_INIT;
        *self = Self::new();
        if computed == expected && image.len() >= Header::SIZE {
            VerifyStep::Intact
        } else {
            VerifyStep::Corrupted(LoadError::ChecksumMismatch {
                stored: expected,
                computed,
            })
        }
    }
}

impl Network<'_> {
    /// Recomputes the whole image's checksum and compares it with the one it was loaded with.
    /// Work: O(bytes), the CRC of the image ([`Network::verify_step`] spreads it).
    pub fn verify(&self) -> Result<(), LoadError> {
        let mut v = ImageVerifier::new();
        match v.step(self.image(), self.header.image_crc, usize::MAX) {
            VerifyStep::Corrupted(e) => Err(e),
            VerifyStep::Intact | VerifyStep::InProgress { .. } => Ok(()),
        }
    }

    /// Checks up to `max_bytes` more bytes of the image in the pass `verifier` holds
    /// ([`ImageVerifier::step`] against the checksum the image was loaded with).
    pub fn verify_step(&self, verifier: &mut ImageVerifier, max_bytes: usize) -> VerifyStep {
        verifier.step(self.image(), self.header.image_crc, max_bytes)
    }

    /// The image the network was loaded from (empty for [`Network::empty`]).
    pub fn image(&self) -> &[u8] {
        self.bytes.unwrap_or(&[])
    }
}
