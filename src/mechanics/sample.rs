//! Seeded, portable sampling: the same seed gives the same points on every machine
//! (ChaCha8), and seeds come from names through FNV-1a, never from the clock.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A 64-bit seed from strings (e.g. a problem id and a part id).
pub(crate) fn seed_from(parts: &[&str]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for p in parts {
        for b in p.bytes().chain(std::iter::once(0xff)) {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// A seeded source of uniform samples.
pub struct Sampler {
    rng: ChaCha8Rng,
}

impl Sampler {
    /// A sampler with a fixed seed.
    pub fn new(seed: u64) -> Self {
        Sampler {
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    /// Uniform in [lo, hi).
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        if hi > lo {
            self.rng.random_range(lo..hi)
        } else {
            lo
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_are_stable() {
        // FNV-1a is fixed: these values must never change, or verdicts would.
        assert_eq!(seed_from(&[]), 0xcbf2_9ce4_8422_2325);
        assert_ne!(seed_from(&["a", "b"]), seed_from(&["ab"]));
        let mut a = Sampler::new(7);
        let mut b = Sampler::new(7);
        for _ in 0..5 {
            assert_eq!(a.uniform(0.0, 1.0), b.uniform(0.0, 1.0));
        }
    }
}
