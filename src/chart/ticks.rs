//! An axis' range and its ticks: round numbers 1, 2 or 5 × 10ᵏ apart, about five of them,
//! the axis running from the tick at or below the data to the tick at or above it. Tick
//! values are integer multiples of the step and their texts are written from those integers,
//! so `0.30000000000000004` never appears and the text is the same on every machine.

/// An axis' extent and its ticks.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Ticks {
    /// The axis' lower end (a tick).
    pub lo: f64,
    /// The axis' upper end (a tick).
    pub hi: f64,
    /// The ticks' values, lowest first, `lo` and `hi` included.
    pub values: Vec<f64>,
    /// Each tick's text (`0.5`, `−1`, `2e−9`), with a true minus sign.
    pub texts: Vec<String>,
}

/// The ticks of an axis covering the finite values of `values` (non-finite ones are left
/// out); `-1 … 1` when there is none, and a flat set is widened around its value.
pub fn ticks(values: impl Iterator<Item = f64>) -> Ticks {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        return nice(-1.0, 1.0);
    }
    // A blown-up motion (1e308) still gets an axis whose span is a finite number.
    let (lo, hi) = (lo.clamp(-1e300, 1e300), hi.clamp(-1e300, 1e300));
    let flat = 1e-300_f64.max(1e-12 * lo.abs().max(hi.abs()));
    if hi - lo < flat {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        return nice(lo - pad, hi + pad);
    }
    nice(lo, hi)
}

/// The ticks over `[lo, hi]` (`lo < hi`, both finite): the step is the smallest of
/// 1, 2, 5 × 10ᵏ giving at most six intervals.
pub fn nice(lo: f64, hi: f64) -> Ticks {
    if !(lo < hi && (hi - lo).is_finite()) {
        return nice(-1.0, 1.0);
    }
    let raw = (hi - lo) / 6.0;
    let mut k = raw.log10().floor() as i32;
    // The mantissa of a step f × 10ᵏ, compared with a little room for log10's rounding.
    let mut pick = None;
    for _ in 0..3 {
        let mag = pow10(k);
        pick = [1_i64, 2, 5]
            .into_iter()
            .find(|&f| f as f64 * mag >= raw * (1.0 - 1e-12));
        if pick.is_some() {
            break;
        }
        k += 1;
    }
    let f = pick.unwrap_or(1);
    let step = f as f64 * pow10(k);
    // Integer multiples of the step: n·step for n from ⌊lo/step⌋ to ⌈hi/step⌉.
    // A bound a billionth of a step past a multiple (rounding) is that multiple.
    let first = (lo / step + 1e-9).floor() as i64;
    let last = (hi / step - 1e-9).ceil() as i64;
    let multiples: Vec<i64> = (first..=last.max(first + 1)).collect();
    let values: Vec<f64> = multiples.iter().map(|&n| value(n * f, k)).collect();
    let biggest = values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let scientific = k < -3 || biggest >= 1e5;
    let texts = multiples
        .iter()
        .map(|&n| text(n * f, k, scientific))
        .collect();
    Ticks {
        lo: values.first().copied().unwrap_or(lo),
        hi: values.last().copied().unwrap_or(hi),
        values,
        texts,
    }
}

/// m × 10ᵏ as the nearest float (a division for k < 0: 3/10 is 0.3, 3 × 0.1 is not).
fn value(m: i64, k: i32) -> f64 {
    if k >= 0 {
        m as f64 * 10f64.powi(k)
    } else {
        m as f64 / 10f64.powi(-k)
    }
}

/// 10ᵏ, exact for the powers a float holds exactly (10⁻ᵏ as a division, not a product of
/// inexact tenths).
fn pow10(k: i32) -> f64 {
    if k >= 0 {
        10f64.powi(k)
    } else {
        1.0 / 10f64.powi(-k)
    }
}

/// The text of m × 10ᵏ: fixed (`0.25`, `−40`) or scientific (`2.5e−9`), a true minus sign.
pub(crate) fn text(m: i64, k: i32, scientific: bool) -> String {
    if m == 0 {
        return "0".into();
    }
    let sign = if m < 0 { "−" } else { "" };
    let digits = m.unsigned_abs().to_string();
    if scientific {
        // d.ddd × 10^(k + digits − 1), trailing zeros of the mantissa dropped.
        let exp = k + digits.len() as i32 - 1;
        let rest = digits[1..].trim_end_matches('0');
        let point = if rest.is_empty() { "" } else { "." };
        let e = if exp < 0 { "e−" } else { "e" };
        return [
            sign,
            &digits[..1],
            point,
            rest,
            e,
            &exp.unsigned_abs().to_string(),
        ]
        .concat();
    }
    if k >= 0 {
        return [sign, &digits, &"0".repeat(k as usize)].concat();
    }
    let places = k.unsigned_abs() as usize;
    let padded = if digits.len() <= places {
        ["0".repeat(places + 1 - digits.len()), digits].concat()
    } else {
        digits
    };
    let (whole, frac) = padded.split_at(padded.len() - places);
    let frac = frac.trim_end_matches('0');
    if frac.is_empty() {
        [sign, whole].concat()
    } else {
        [sign, whole, ".", frac].concat()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_one_two_or_five_times_a_power_of_ten() {
        // (data lo, data hi) → (axis lo, axis hi, tick texts)
        let table: &[(f64, f64, f64, f64, &[&str])] = &[
            (0.0, 10.0, 0.0, 10.0, &["0", "2", "4", "6", "8", "10"]),
            (0.0, 2.0, 0.0, 2.0, &["0", "0.5", "1", "1.5", "2"]),
            (-1.0, 1.0, -1.0, 1.0, &["−1", "−0.5", "0", "0.5", "1"]),
            (-0.97, 0.93, -1.0, 1.0, &["−1", "−0.5", "0", "0.5", "1"]),
            (
                0.1,
                0.7,
                0.1,
                0.7,
                &["0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"],
            ),
            (-3.13, 3.13, -4.0, 4.0, &["−4", "−2", "0", "2", "4"]),
            (
                0.0,
                1000.0,
                0.0,
                1000.0,
                &["0", "200", "400", "600", "800", "1000"],
            ),
            (
                -3e-9,
                1e-9,
                -3e-9,
                1e-9,
                &["−3e−9", "−2e−9", "−1e−9", "0", "1e−9"],
            ),
            (
                0.0,
                5e5,
                0.0,
                5e5,
                &["0", "1e5", "2e5", "3e5", "4e5", "5e5"],
            ),
            (
                0.0,
                0.012,
                0.0,
                0.012,
                &["0", "0.002", "0.004", "0.006", "0.008", "0.01", "0.012"],
            ),
        ];
        for &(lo, hi, a, b, texts) in table {
            let t = nice(lo, hi);
            assert_eq!((t.lo, t.hi), (a, b), "[{lo}, {hi}]");
            assert_eq!(t.texts, texts, "[{lo}, {hi}]");
            assert_eq!(t.values.len(), texts.len());
        }
    }

    #[test]
    fn tick_values_are_exact_multiples_not_accumulated_sums() {
        // 0.1 + 0.1 + 0.1 is 0.30000000000000004; the third tick is 3/10.
        let t = nice(0.1, 0.7);
        assert_eq!(t.values[2], 0.3);
        assert_eq!(t.texts[2], "0.3");
    }

    #[test]
    fn empty_flat_and_non_finite_data_still_get_an_axis() {
        assert_eq!(
            ticks(std::iter::empty()).texts,
            ["−1", "−0.5", "0", "0.5", "1"]
        );
        assert_eq!(ticks([f64::NAN, f64::INFINITY].into_iter()).lo, -1.0);
        let flat = ticks([2.0, 2.0].into_iter());
        assert!(flat.lo < 2.0 && flat.hi > 2.0, "{flat:?}");
        let zero = ticks([0.0].into_iter());
        assert_eq!((zero.lo, zero.hi), (-1.0, 1.0));
        let t = ticks([1.0, f64::NAN, 3.0].into_iter());
        assert_eq!((t.lo, t.hi), (1.0, 3.0));
    }

    #[test]
    fn texts_of_integer_multiples() {
        let table: &[(i64, i32, bool, &str)] = &[
            (0, -3, false, "0"),
            (25, -2, false, "0.25"),
            (-4, 1, false, "−40"),
            (5, -3, false, "0.005"),
            (15, -1, false, "1.5"),
            (25, -10, true, "2.5e−9"),
            (-10, -9, true, "−1e−8"),
            (3, 5, true, "3e5"),
        ];
        for &(m, k, sci, want) in table {
            assert_eq!(text(m, k, sci), want, "{m}e{k}");
        }
    }
}
