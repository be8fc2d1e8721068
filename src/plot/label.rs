//! A coordinate's name as it is read: `theta1` → θ₁, `theta1'` → θ̇₁, `x''` → ẍ.

/// Greek letters by their spelled names.
const GREEK: &[(&str, char)] = &[
    ("alpha", 'α'),
    ("beta", 'β'),
    ("gamma", 'γ'),
    ("delta", 'δ'),
    ("epsilon", 'ε'),
    ("zeta", 'ζ'),
    ("eta", 'η'),
    ("theta", 'θ'),
    ("iota", 'ι'),
    ("kappa", 'κ'),
    ("lambda", 'λ'),
    ("mu", 'μ'),
    ("nu", 'ν'),
    ("xi", 'ξ'),
    ("omicron", 'ο'),
    ("pi", 'π'),
    ("rho", 'ρ'),
    ("sigma", 'σ'),
    ("tau", 'τ'),
    ("upsilon", 'υ'),
    ("phi", 'φ'),
    ("chi", 'χ'),
    ("psi", 'ψ'),
    ("omega", 'ω'),
];

/// `theta1'` → θ̇₁: a Greek name as its letter, one dot per prime over the letter (combining
/// U+0307, U+0308 for two), trailing digits (after an optional `_`) as subscripts.
pub fn unicode(name: &str) -> String {
    let primes = name.len() - name.trim_end_matches('\'').len();
    let bare = name.trim_end_matches('\'');
    let digits_at = bare.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    let (base, digits) = bare.split_at(digits_at);
    let base = base.strip_suffix('_').unwrap_or(base);
    let mut out = match GREEK.iter().find(|(n, _)| *n == base) {
        Some((_, c)) => c.to_string(),
        None => base.to_string(),
    };
    match primes {
        0 => {}
        1 => out.push('\u{307}'),
        2 => out.push('\u{308}'),
        k => out.push_str(&"'".repeat(k)),
    }
    out.extend(
        digits
            .chars()
            .map(|d| char::from_u32(0x2080 + d.to_digit(10).unwrap_or(0)).unwrap_or(d)),
    );
    out
}

#[cfg(test)]
mod tests {
    use super::unicode;

    #[test]
    fn names() {
        assert_eq!(unicode("theta1"), "θ₁");
        assert_eq!(unicode("theta1'"), "θ\u{307}₁");
        assert_eq!(unicode("x''"), "x\u{308}");
        assert_eq!(unicode("phi_2"), "φ₂");
        assert_eq!(unicode("r"), "r");
    }
}
