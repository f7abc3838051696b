//! A small deterministic generator for the crate's own tests' sampled cases (xorshift64*):
//! the same cases on every run and machine, without a dependency.

/// xorshift64* (Vigna 2016), its state never 0.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    /// Uniform in [0, 1), 24 bits.
    pub(crate) fn unit(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in [lo, hi).
    pub(crate) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
}
