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

    /// Uniform in [lo, hi), for any bounds: total, never a panic. Infinite bounds are
    /// taken as the largest finite values, a range whose width overflows (`[-1e308, 1e308]`)
    /// is sampled whole, and an empty or NaN range gives its one meaningful bound. Such a
    /// range is the user's statement (an answer must hold there), so it is sampled as given
    /// rather than refused or narrowed; values that overflow later are caught where they
    /// are evaluated.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let (lo, hi) = (clamp_finite(lo), clamp_finite(hi));
        if lo.is_nan() || hi.is_nan() || hi <= lo {
            // Empty, a single point, or a NaN bound: the first bound that is a number.
            return if lo.is_nan() {
                if hi.is_nan() { 0.0 } else { hi }
            } else {
                lo
            };
        }
        if (hi - lo).is_finite() {
            // The path every ordinary range takes, unchanged: seeds keep their points.
            return self.rng.random_range(lo..hi);
        }
        // The width overflows, so `rand` would refuse it; both bounds are finite and of
        // opposite signs, so the weighted mean of the bounds stays finite.
        let u: f64 = self.rng.random();
        (lo * (1.0 - u) + hi * u).clamp(lo, hi)
    }
}

/// `x` with infinities replaced by the largest finite values of the same sign (NaN stays).
fn clamp_finite(x: f64) -> f64 {
    if x.is_infinite() {
        f64::MAX.copysign(x)
    } else {
        x
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

    #[test]
    fn a_range_of_any_width_or_bound_samples_without_panicking() {
        // Issue 9, section 3: `range = [-1e308, 1e308]` panicked (`unwrap` on NonFinite).
        let mut s = Sampler::new(1);
        let mut seen_negative = false;
        let mut seen_positive = false;
        for _ in 0..200 {
            let x = s.uniform(-1e308, 1e308);
            assert!(x.is_finite() && (-1e308..=1e308).contains(&x), "{x}");
            seen_negative |= x < -1e300;
            seen_positive |= x > 1e300;
        }
        assert!(seen_negative && seen_positive, "the whole range is sampled");
        for (lo, hi) in [
            (f64::NEG_INFINITY, f64::INFINITY),
            (-f64::MAX, f64::MAX),
            (0.0, f64::INFINITY),
            (f64::NEG_INFINITY, 0.0),
        ] {
            let x = s.uniform(lo, hi);
            assert!(x.is_finite() && x >= lo && x <= hi, "[{lo}, {hi}]: {x}");
        }
        assert_eq!(s.uniform(3.0, 3.0), 3.0);
        assert_eq!(s.uniform(5.0, 1.0), 5.0);
        assert_eq!(s.uniform(f64::NAN, 2.0), 2.0);
        assert_eq!(s.uniform(2.0, f64::NAN), 2.0);
        assert_eq!(s.uniform(f64::NAN, f64::NAN), 0.0);
        assert_eq!(s.uniform(f64::INFINITY, f64::INFINITY), f64::MAX);
    }

    #[test]
    fn ordinary_ranges_draw_the_points_they_always_drew() {
        // The wide-range path must not move any ordinary draw (verdicts are seeded).
        let mut a = Sampler::new(42);
        let mut b = ChaCha8Rng::seed_from_u64(42);
        for (lo, hi) in [(0.0, 1.0), (-3.5, 3.5), (0.5, 2.0), (-1e300, 1e300)] {
            assert_eq!(a.uniform(lo, hi), b.random_range(lo..hi));
        }
    }
}
