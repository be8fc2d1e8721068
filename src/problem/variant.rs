//! Per-student variants: how a problem's parameters vary (a set of values, or a range on a
//! grid of a step or of significant digits, with a unit for display) and which numbers one
//! student gets — a pure function of the course seed, the problem id and the student's
//! normalised key, through a hash written out here so that it is the same on every machine
//! and every release (never `std`'s `DefaultHasher`, whose output may change).
//!
//! A student's answer to a part that accepts numbers is judged against the problem with the
//! varied parameters pinned to the student's values ([`Problem::pinned`]): `m*g*l` and
//! `1.5*9.81*1.2` then mean the same number.

use crate::expr::Dimensions;

use super::Problem;

/// The most values one parameter may take (a larger grid is refused when the file loads).
pub const MAX_VALUES: usize = 10_000;

/// How one parameter varies, as declared under `[variants.NAME]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Varied {
    /// The parameter's name (normalised, as in the system).
    pub(crate) name: String,
    /// The values it may take, in increasing order (or as listed).
    pub(crate) values: Vec<f64>,
    /// The unit shown after the number (`kg`, `m/s^2`); empty for none.
    pub(crate) unit: String,
    /// Line of the declaration in its file.
    pub(crate) line: usize,
}

impl Varied {
    /// `value` with its unit, as a sheet shows it (`1.5 kg`).
    pub fn show(&self, value: f64) -> String {
        if self.unit.is_empty() {
            show_number(value)
        } else {
            format!("{} {}", show_number(value), self.unit)
        }
    }
}

/// The shortest decimal that reads back as `v` (`1.2`, not `1.2000000000000002`: the grids
/// build their values from decimal text, so they are exactly the decimals declared).
pub fn show_number(v: f64) -> String {
    format!("{v}")
}

/// The values of a grid over `[lo, hi]` with spacing `step`: `lo`, `lo + step`, … up to `hi`
/// (within a millionth of a step), each made from its decimal text so that `0.1 + 0.2` is
/// `0.3`. `None` when the step is not a positive decimal of at most 9 places or the grid has
/// more than [`MAX_VALUES`] values.
pub fn step_grid(lo: f64, hi: f64, step: f64) -> Option<Vec<f64>> {
    if !(step > 0.0 && lo.is_finite() && hi.is_finite() && lo <= hi) {
        return None;
    }
    let places = [lo, step].iter().map(|&x| decimals(x)).max()??;
    let scale = 10f64.powi(places as i32);
    let (l, s, h) = (
        (lo * scale).round(),
        (step * scale).round(),
        (hi * scale + step * scale * 1e-6).floor(),
    );
    if s < 1.0 || !((h - l) / s).is_finite() || (h - l) / s >= MAX_VALUES as f64 {
        return None;
    }
    let n = ((h - l) / s).floor() as i64;
    (0..=n)
        .map(|k| decimal(l as i64 + k * s as i64, places))
        .collect()
}

/// Every number with `digits` significant digits in `[lo, hi]` (`lo > 0`): 2 digits over
/// [10, 50] are 10, 11, …, 50. `None` when there are more than [`MAX_VALUES`] or the range
/// is not positive.
pub fn digits_grid(lo: f64, hi: f64, digits: u32) -> Option<Vec<f64>> {
    if !(lo > 0.0 && hi >= lo && hi.is_finite() && (1..=9).contains(&digits)) {
        return None;
    }
    let mut out = Vec::new();
    let first = lo.log10().floor() as i32 - 1;
    let last = hi.log10().floor() as i32 + 1;
    for e in first..=last {
        let low = 10i64.pow(digits - 1);
        for m in low..low * 10 {
            // m × 10^(e − digits + 1), from its decimal text.
            let v: f64 = format!("{m}e{}", e - digits as i32 + 1).parse().ok()?;
            if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) && !out.contains(&v) {
                out.push(v);
                if out.len() > MAX_VALUES {
                    return None;
                }
            }
        }
    }
    crate::sort::sort_by(&mut out, f64::total_cmp);
    Some(out)
}

/// The fewest decimal places (at most 9) that write `x` exactly enough to read back.
fn decimals(x: f64) -> Option<u32> {
    (0..=9).find(|&d| {
        let scaled = x * 10f64.powi(d as i32);
        (scaled - scaled.round()).abs() <= 1e-9 * scaled.abs().max(1.0)
    })
}

/// `n / 10^places`, read from its decimal text (exactly the nearest double).
fn decimal(n: i64, places: u32) -> Option<f64> {
    format!("{n}e-{places}").parse().ok()
}

/// A student's key as the variant sees it: trimmed and lower-cased, so `Ada@Uni.example ` and
/// `ada@uni.example` get one variant (the grader merges such keys too).
pub fn normalise_key(key: &str) -> String {
    key.trim().to_lowercase()
}

/// FNV-1a, 64 bits: offset basis 0xcbf29ce484222325, prime 0x100000001b3, over `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// One step of SplitMix64 (Steele, Lea and Flood 2014): advances `state` by the golden-ratio
/// increment and returns the mixed value.
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A uniform index below `n` from a 64-bit `z` (the high word of z × n: no modulo bias worth
/// the name for n ≤ [`MAX_VALUES`]).
fn index_below(z: u64, n: usize) -> usize {
    ((u128::from(z) * n as u128) >> 64) as usize
}

/// The values one student gets: one per declared parameter, in declaration order.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// (parameter name, value), in the order of the problem's declarations.
    pub values: Vec<(String, f64)>,
}

impl Variant {
    /// The value of parameter `name`, if it varies.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }

    /// A short stable text of the numbers (`g=9.81 l=1.2 m=1.5`), for grouping and records.
    pub fn key(&self) -> String {
        self.values
            .iter()
            .map(|(n, v)| format!("{n}={}", show_number(*v)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// The variant of the student `key` for `problem` under the course `seed`:
///
/// 1. the state starts as `seed` XOR FNV-1a-64 of the problem id, a 0xff byte and the
///    normalised key's UTF-8 bytes ([`normalise_key`]);
/// 2. each declared parameter, in the order of their names, takes one SplitMix64 output `z` from the
///    state and the value at index ⌊z·n / 2⁶⁴⌋ of its n values.
///
/// `None` when the problem declares no variants.
pub fn pick(problem: &Problem, seed: u64, key: &str) -> Option<Variant> {
    pick_normalised(problem, seed, &normalise_key(key))
}

/// The variant a learner practising on their own gets from their `seed` (the empty key):
/// [`pick`] with `""`, without the Unicode case tables a key needs (the browser's module
/// is smaller without them).
pub fn pick_own(problem: &Problem, seed: u64) -> Option<Variant> {
    pick_normalised(problem, seed, "")
}

/// [`pick`] for a key already normalised.
fn pick_normalised(problem: &Problem, seed: u64, key: &str) -> Option<Variant> {
    if problem.variants.is_empty() {
        return None;
    }
    let mut bytes = problem.id.as_bytes().to_vec();
    bytes.push(0xff);
    bytes.extend_from_slice(key.as_bytes());
    let mut state = seed ^ fnv1a64(&bytes);
    Some(Variant {
        values: problem
            .variants
            .iter()
            .map(|v| {
                let z = splitmix64(&mut state);
                (v.name.clone(), v.values[index_below(z, v.values.len())])
            })
            .collect(),
    })
}

/// How many variants the declarations allow (saturating).
pub fn count(varied: &[Varied]) -> u128 {
    varied
        .iter()
        .fold(1u128, |n, v| n.saturating_mul(v.values.len() as u128))
}

/// The variant number `k` (0 ≤ k < [`count`]) in mixed radix, the first declaration varying
/// slowest.
pub fn nth(varied: &[Varied], mut k: u128) -> Variant {
    let mut values = vec![(String::new(), 0.0); varied.len()];
    for (i, v) in varied.iter().enumerate().rev() {
        let n = v.values.len() as u128;
        values[i] = (v.name.clone(), v.values[(k % n) as usize]);
        k /= n;
    }
    Variant { values }
}

/// `{{name}}` in `text` replaced by the varied parameter's value and unit in `variant`, or by
/// the name alone without one (the sheet for no particular student). Other text is kept.
pub fn fill(text: &str, varied: &[Varied], variant: Option<&Variant>) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find("{{") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let Some(j) = after.find("}}") else {
            out.push_str(&rest[i..]);
            return out;
        };
        let name = crate::expr::names::normalize(after[..j].trim());
        match varied.iter().find(|v| v.name == name) {
            Some(v) => match variant.and_then(|x| x.get(&name)) {
                Some(value) => out.push_str(&v.show(value)),
                None => out.push_str(&name),
            },
            None => out.push_str(&rest[i..i + 2 + j + 2]),
        }
        rest = &after[j + 2..];
    }
    out.push_str(rest);
    out
}

/// The names `{{…}}` mentions in `text`, as written (for the loader's check that each is a
/// varied parameter).
pub fn placeholders(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("{{") {
        let after = &rest[i + 2..];
        let Some(j) = after.find("}}") else { break };
        out.push(after[..j].trim().to_string());
        rest = &after[j + 2..];
    }
    out
}

impl Problem {
    /// This problem for one student: each varied parameter pinned to the student's value (its
    /// sampling range a single point, which the sampler keeps, wide points included), and no
    /// dimensions known — a number carries no unit, so `1.5*9.81*1.2` is as good an energy as
    /// `m*g*l`. Parts that accept numbers are judged against it; other parts against the
    /// problem itself.
    pub fn pinned(&self, variant: &Variant) -> Problem {
        let mut p = self.clone();
        for q in &mut p.system.parameters {
            if let Some(v) = variant.get(&q.name) {
                q.range = (v, v);
            }
        }
        p.dims = Dimensions::new();
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hashes_are_the_published_ones() {
        // FNV-1a's test vectors and SplitMix64's first output from 0: fixed forever.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        let mut s = 0;
        assert_eq!(splitmix64(&mut s), 0xe220_a839_7b1d_cdaf);
    }

    #[test]
    fn grids_are_exact_decimals() {
        assert_eq!(
            step_grid(0.5, 1.0, 0.1).unwrap(),
            vec![0.5, 0.6, 0.7, 0.8, 0.9, 1.0]
        );
        assert_eq!(
            step_grid(1.0, 2.0, 0.25).unwrap(),
            vec![1.0, 1.25, 1.5, 1.75, 2.0]
        );
        assert_eq!(step_grid(0.55, 0.75, 0.1).unwrap(), vec![0.55, 0.65, 0.75]);
        assert!(step_grid(0.0, 1e9, 1e-3).is_none());
        let d = digits_grid(9.0, 12.0, 2).unwrap();
        assert_eq!(
            d,
            vec![
                9.0, 9.1, 9.2, 9.3, 9.4, 9.5, 9.6, 9.7, 9.8, 9.9, 10.0, 11.0, 12.0
            ]
        );
        assert!(digits_grid(0.0, 1.0, 2).is_none());
    }

    #[test]
    fn placeholders_fill_with_value_and_unit() {
        let varied = vec![Varied {
            name: "m".into(),
            values: vec![1.5],
            unit: "kg".into(),
            line: 1,
        }];
        let v = Variant {
            values: vec![("m".into(), 1.5)],
        };
        assert_eq!(
            fill("mass {{m}}, {{x}}", &varied, Some(&v)),
            "mass 1.5 kg, {{x}}"
        );
        assert_eq!(fill("mass {{ m }}", &varied, None), "mass m");
        assert_eq!(fill("open {{m", &varied, None), "open {{m");
        assert_eq!(placeholders("a {{m}} b {{ l }}"), vec!["m", "l"]);
    }
}
