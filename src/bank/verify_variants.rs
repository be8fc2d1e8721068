//! Verification of a problem's variants. Where a part accepts the student's numbers, a
//! declaration must not let a wrong answer pass: a varied parameter that can be 0 or ±1 (a
//! missing factor m is right for m = 1) is refused (`variant-trivial-value`), and so are two
//! varied parameters that can be equal (m₁ for m₂: `variant-equal-values`). Then every
//! variant the declarations allow — or, past [`EXHAUSTIVE`] of them, a seeded sample that
//! includes the smallest and the largest values, said so in [`coverage`] — is proved: each
//! part against the problem pinned to those numbers (`variant-fails`, naming the variant),
//! which also refuses a variant that violates an assumption or makes the system degenerate.

use super::FindingCode;
use super::finding::Finding;
use crate::mechanics::sample::seed_from;
use crate::problem::Problem;
use crate::problem::variant::{Variant, count, nth, show_number, splitmix64};

/// Up to this many variants, every one is proved; past it, a sample of this many.
pub const EXHAUSTIVE: u128 = 64;

/// The variants verification proves: all, or the first and last (every smallest value, every
/// largest) and a seeded sample between, distinct, in increasing order.
pub fn proved_variants(problem: &Problem) -> Vec<Variant> {
    let n = count(&problem.variants);
    if problem.variants.is_empty() || n == 0 {
        return Vec::new();
    }
    if n <= EXHAUSTIVE {
        return (0..n).map(|k| nth(&problem.variants, k)).collect();
    }
    let mut state = seed_from(&[&problem.id, "variants"]);
    let mut picked: Vec<u128> = vec![0, n - 1];
    let mut draws = 0;
    while (picked.len() as u128) < EXHAUSTIVE && draws < 100 * EXHAUSTIVE {
        draws += 1;
        // Two outputs make a 128-bit draw; the modulo's bias is below 2⁻⁶⁴ for any n here.
        let z = (u128::from(splitmix64(&mut state)) << 64) | u128::from(splitmix64(&mut state));
        let k = z % n;
        if !picked.contains(&k) {
            picked.push(k);
        }
    }
    picked.sort_unstable();
    picked
        .into_iter()
        .map(|k| nth(&problem.variants, k))
        .collect()
}

/// What verification proved of the variants, in words (`None` without variants).
pub fn coverage(problem: &Problem) -> Option<String> {
    if problem.variants.is_empty() {
        return None;
    }
    let n = count(&problem.variants);
    Some(if n <= EXHAUSTIVE {
        format!("answers proved for every one of the {n} variants")
    } else {
        format!(
            "answers proved for a seeded sample of {EXHAUSTIVE} of the {n} variants (the smallest and the largest values among them)"
        )
    })
}

/// The variants' findings: the refusals of declarations that let wrong answers pass, then
/// the first variant for which a part does not hold.
/// `verify_one` proves one problem as it stands (the pinned one, here).
pub(super) fn verify_variants(
    problem: &Problem,
    verify_one: fn(&Problem) -> Vec<Finding>,
) -> Vec<Finding> {
    let at = |line: usize, part: Option<&str>, code: FindingCode, message: String| Finding {
        file: problem.file.clone(),
        problem: Some(problem.id.clone()),
        part: part.map(str::to_string),
        line,
        code,
        message,
    };
    let mut out = Vec::new();
    let numbers: Vec<_> = problem.parts.iter().filter(|p| p.numbers).collect();
    if problem.variants.is_empty() {
        for p in numbers {
            out.push(at(
                p.line,
                Some(&p.id),
                FindingCode::NumbersWithoutVariants,
                "the part accepts numbers, but the problem declares no `[variants]`: a student's numbers would be compared with randomly sampled parameters; declare how the parameters vary, or remove `numbers = true`".into(),
            ));
        }
        return out;
    }
    if let Some(first) = numbers.first() {
        let why = format!("part `{}` accepts numbers", first.id);
        for v in &problem.variants {
            if let Some(x) = v.values.iter().find(|x| **x == 0.0 || x.abs() == 1.0) {
                out.push(at(
                    v.line,
                    None,
                    FindingCode::VariantTrivialValue,
                    format!(
                        "`{}` can be {}: {why}, and for that student an answer missing the factor `{}` (or with it squared) would be right; leave {} out of its values",
                        v.name,
                        show_number(*x),
                        v.name,
                        show_number(*x)
                    ),
                ));
            }
        }
        for (i, a) in problem.variants.iter().enumerate() {
            for b in &problem.variants[i + 1..] {
                if let Some(x) = a.values.iter().find(|x| b.values.contains(x)) {
                    out.push(at(
                        b.line,
                        None,
                        FindingCode::VariantEqualValues,
                        format!(
                            "`{}` and `{}` can both be {}: {why}, and for that student `{}` written for `{}` would be right; give them values that never coincide",
                            a.name,
                            b.name,
                            show_number(*x),
                            a.name,
                            b.name
                        ),
                    ));
                }
            }
        }
    }
    if !out.is_empty() {
        return out;
    }
    for variant in proved_variants(problem) {
        let mut pinned = problem.pinned(&variant);
        // Students answer a part without numbers against the problem itself: its `wrong`
        // examples are proved wrong there, not at one student's numbers.
        for p in pinned.parts.iter_mut().filter(|p| !p.numbers) {
            p.wrong.clear();
        }
        if let Some(f) = verify_one(&pinned).into_iter().next() {
            let named = variant
                .values
                .iter()
                .map(|(n, x)| {
                    let v = problem.variants.iter().find(|v| &v.name == n);
                    format!(
                        "{n} = {}",
                        v.map_or_else(|| show_number(*x), |v| v.show(*x))
                    )
                })
                .collect::<Vec<_>>()
                .join(", ");
            out.push(Finding {
                code: FindingCode::VariantFails,
                message: format!(
                    "for the variant {named}: {} [{}]; narrow the declared values so that every variant is a sound problem",
                    f.message, f.code
                ),
                ..f
            });
            break;
        }
    }
    out
}
