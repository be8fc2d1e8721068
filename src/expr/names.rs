//! Name tables shared by the lexer and the printers: Greek letters, sub- and superscript
//! digits, vulgar fractions and the normal form of a symbol name.

/// Greek letters and their spelled names. Order matters for printing: longer names first
/// where one is a suffix of another is irrelevant because names are matched whole.
pub const GREEK: &[(char, &str)] = &[
    ('α', "alpha"),
    ('β', "beta"),
    ('γ', "gamma"),
    ('δ', "delta"),
    ('ε', "epsilon"),
    ('ζ', "zeta"),
    ('η', "eta"),
    ('θ', "theta"),
    ('ι', "iota"),
    ('κ', "kappa"),
    ('λ', "lambda"),
    ('μ', "mu"),
    ('ν', "nu"),
    ('ξ', "xi"),
    ('ρ', "rho"),
    ('σ', "sigma"),
    ('τ', "tau"),
    ('υ', "upsilon"),
    ('φ', "phi"),
    ('χ', "chi"),
    ('ψ', "psi"),
    ('ω', "omega"),
    ('Γ', "Gamma"),
    ('Δ', "Delta"),
    ('Θ', "Theta"),
    ('Λ', "Lambda"),
    ('Ξ', "Xi"),
    ('Σ', "Sigma"),
    ('Φ', "Phi"),
    ('Ψ', "Psi"),
    ('Ω', "Omega"),
];

/// Alternative code points read as a Greek letter.
const GREEK_VARIANTS: &[(char, &str)] = &[
    ('ϑ', "theta"),
    ('ϕ', "phi"),
    ('ϵ', "epsilon"),
    ('ς', "sigma"),
    ('µ', "mu"),
];

/// The spelled name of a Greek letter (`θ` → `theta`); π is not here (it is a constant).
pub(crate) fn greek_name(c: char) -> Option<&'static str> {
    GREEK
        .iter()
        .chain(GREEK_VARIANTS)
        .find(|(g, _)| *g == c)
        .map(|(_, n)| *n)
}

/// The Greek letter of a spelled name (`theta` → `θ`).
pub(crate) fn greek_letter(name: &str) -> Option<char> {
    GREEK.iter().find(|(_, n)| *n == name).map(|(g, _)| *g)
}

const SUPERSCRIPT: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
const SUBSCRIPT: [char; 10] = ['₀', '₁', '₂', '₃', '₄', '₅', '₆', '₇', '₈', '₉'];

/// Precomposed Latin letters with a dot above (one derivative) or a diaeresis (two), as
/// keyboards and some fonts produce them: `ẋ` is `x` + U+0307.
const PRECOMPOSED: &[(char, char, u8)] = &[
    ('ȧ', 'a', 1),
    ('ḃ', 'b', 1),
    ('ċ', 'c', 1),
    ('ḋ', 'd', 1),
    ('ė', 'e', 1),
    ('ḟ', 'f', 1),
    ('ġ', 'g', 1),
    ('ḣ', 'h', 1),
    ('ṁ', 'm', 1),
    ('ṅ', 'n', 1),
    ('ȯ', 'o', 1),
    ('ṗ', 'p', 1),
    ('ṙ', 'r', 1),
    ('ṡ', 's', 1),
    ('ṫ', 't', 1),
    ('ẇ', 'w', 1),
    ('ẋ', 'x', 1),
    ('ẏ', 'y', 1),
    ('ż', 'z', 1),
    ('Ẋ', 'X', 1),
    ('Ẏ', 'Y', 1),
    ('Ż', 'Z', 1),
    ('ä', 'a', 2),
    ('ë', 'e', 2),
    ('ḧ', 'h', 2),
    ('ï', 'i', 2),
    ('ö', 'o', 2),
    ('ẗ', 't', 2),
    ('ü', 'u', 2),
    ('ẅ', 'w', 2),
    ('ẍ', 'x', 2),
    ('ÿ', 'y', 2),
    ('Ẍ', 'X', 2),
];

/// A precomposed dotted letter as (base letter, number of dots).
pub(crate) fn precomposed(c: char) -> Option<(char, u8)> {
    PRECOMPOSED
        .iter()
        .find(|(p, _, _)| *p == c)
        .map(|&(_, b, d)| (b, d))
}

/// The digit of a superscript character.
pub(crate) fn superscript_digit(c: char) -> Option<u32> {
    SUPERSCRIPT.iter().position(|&s| s == c).map(|d| d as u32)
}

/// The digit of a subscript character.
pub(crate) fn subscript_digit(c: char) -> Option<u32> {
    SUBSCRIPT.iter().position(|&s| s == c).map(|d| d as u32)
}

/// An integer in superscript digits (`-2` → `⁻²`).
pub fn superscript(n: i64) -> String {
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for d in n.unsigned_abs().to_string().bytes() {
        s.push(SUPERSCRIPT[(d - b'0') as usize]);
    }
    s
}

/// Digits in subscript.
pub fn subscript(digits: &str) -> String {
    digits
        .bytes()
        .map(|d| SUBSCRIPT[(d - b'0') as usize])
        .collect()
}

/// Unicode vulgar fractions and their values.
pub const FRACTIONS: &[(char, i64, i64)] = &[
    ('½', 1, 2),
    ('⅓', 1, 3),
    ('⅔', 2, 3),
    ('¼', 1, 4),
    ('¾', 3, 4),
    ('⅕', 1, 5),
    ('⅖', 2, 5),
    ('⅗', 3, 5),
    ('⅘', 4, 5),
    ('⅙', 1, 6),
    ('⅚', 5, 6),
    ('⅛', 1, 8),
    ('⅜', 3, 8),
    ('⅝', 5, 8),
    ('⅞', 7, 8),
];

/// The value of a vulgar-fraction character.
pub(crate) fn fraction_value(c: char) -> Option<(i64, i64)> {
    FRACTIONS
        .iter()
        .find(|(f, _, _)| *f == c)
        .map(|&(_, n, d)| (n, d))
}

/// The vulgar-fraction character for n/d, if there is one.
pub(crate) fn fraction_char(n: i64, d: i64) -> Option<char> {
    FRACTIONS
        .iter()
        .find(|&&(_, a, b)| a == n && b == d)
        .map(|&(f, _, _)| f)
}

/// The normal form of a symbol name: a trailing `_` before digits is dropped, so `m_1`,
/// `m1` and `m₁` are one symbol.
pub fn normalize(name: &str) -> String {
    // Repeated until nothing changes, so that normalizing is idempotent: `m_1301_1301` is
    // `m13011301` (one pass would leave `m_13011301`, which reads back as another name).
    let mut out = name.to_string();
    while let Some(i) = out.rfind('_') {
        let tail = &out[i + 1..];
        if i > 0 && !tail.is_empty() && tail.bytes().all(|b| b.is_ascii_digit()) {
            out = format!("{}{}", &out[..i], tail);
        } else {
            break;
        }
    }
    out
}

/// A plain name (`theta0`, `omega0`, `m`) as the Unicode printer writes it (`θ₀`, `ω₀`, `m`).
pub fn unicode_name(name: &str) -> String {
    let (letters, digits) = split_digits(name);
    let base = greek_letter(letters).map_or_else(|| letters.to_string(), |g| g.to_string());
    format!("{base}{}", subscript(digits))
}

/// A state's name as typed (`theta1`, `theta1'`, `x''`) in Unicode (`θ₁`, `θ̇₁`, `ẍ`): the
/// primes become dots over a one-letter name, and stay primes otherwise.
pub fn unicode_state_name(name: &str) -> String {
    let base = name.trim_end_matches('\'');
    let primes = name.len() - base.len();
    let (letters, digits) = split_digits(base);
    let letter = greek_letter(letters).map_or_else(|| letters.to_string(), |g| g.to_string());
    let dot = match primes {
        0 => Some(""),
        1 => Some("\u{0307}"),
        2 => Some("\u{0308}"),
        _ => None,
    };
    match dot {
        Some(d) if letter.chars().count() == 1 || primes == 0 => {
            format!("{letter}{d}{}", subscript(digits))
        }
        _ => format!("{letter}{}{}", subscript(digits), "'".repeat(primes)),
    }
}

/// A name as typed in a flag or an option (`θ₁`, `θ̇₁`, `ẋ`, `m_1`) in its spelled ASCII form
/// (`theta1`, `theta1'`, `x'`, `m1`): Greek letters spelled, subscript digits as digits, and
/// dots above (U+0307, U+0308, precomposed) as primes at the end. Other text is kept.
pub fn spelled(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    let mut primes = 0;
    for c in name.trim().chars() {
        match c {
            '\u{307}' => primes += 1,
            '\u{308}' => primes += 2,
            '\'' => primes += 1,
            _ => {
                if let Some(g) = greek_name(c) {
                    out.push_str(g);
                } else if let Some(d) = subscript_digit(c) {
                    out.push(char::from_digit(d, 10).unwrap_or('0'));
                } else if let Some((b, dots)) = precomposed(c) {
                    out.push(b);
                    primes += dots;
                } else {
                    out.push(c);
                }
            }
        }
    }
    let mut out = normalize(&out);
    out.extend(std::iter::repeat_n('\'', usize::from(primes)));
    out
}

/// Splits a name into its letters and its trailing digits (`theta12` → (`theta`, `12`)).
pub(crate) fn split_digits(name: &str) -> (&str, &str) {
    let k = name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    name.split_at(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_names_in_unicode() {
        // The REPL's :simulate summary printed `theta1` (issue 21).
        for (input, want) in [
            ("theta1", "θ₁"),
            ("theta1'", "θ̇₁"),
            ("x''", "x\u{308}"),
            ("phi", "φ"),
            ("x'''", "x'''"),
            ("m2", "m₂"),
            ("theta0", "θ₀"),
        ] {
            assert_eq!(unicode_state_name(input), want, "{input}");
        }
        assert_eq!(unicode_name("omega0"), "ω₀");
    }

    #[test]
    fn normal_names() {
        for (input, want) in [
            ("m_1", "m1"),
            ("m1", "m1"),
            ("q_dot", "q_dot"),
            ("_1", "_1"),
            // Regression (fuzz parse, seed 4242): one pass left `m_13011301`.
            ("m_1301_1301", "m13011301"),
            ("em_13011301", "em13011301"),
        ] {
            assert_eq!(normalize(input), want);
        }
    }

    #[test]
    fn scripts() {
        assert_eq!(superscript(-12), "⁻¹²");
        assert_eq!(subscript("20"), "₂₀");
        assert_eq!(split_digits("theta12"), ("theta", "12"));
        assert_eq!(spelled("θ₁"), "theta1");
        assert_eq!(spelled("θ̇₁"), "theta1'");
        assert_eq!(spelled(" φ' "), "phi'");
        assert_eq!(spelled("m_2"), "m2");
        assert_eq!(spelled("x"), "x");
    }
}
