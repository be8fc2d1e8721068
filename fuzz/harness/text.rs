//! Text surgery on reference answers, for constructed answers: the two sides of an equation,
//! the top-level terms of a sum, one term scaled. Bank references are plain syntax, so a
//! depth count over parentheses is enough.

/// The two sides of `lhs = rhs` (a bare expression is `e = 0`).
pub fn split_eq(s: &str) -> (String, String) {
    match s.split_once('=') {
        Some((l, r)) => (l.trim().to_string(), r.trim().to_string()),
        None => (s.trim().to_string(), "0".to_string()),
    }
}

/// The top-level terms of a sum, each with its sign (`["a*b", "- c", "+ d"]`): a `+` or `-`
/// at depth 0 that follows an operand (not an operator, an opening parenthesis or the `e`
/// of an exponent) starts a term.
pub fn terms(s: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut depth = 0i32;
    let mut prev: Option<char> = None;
    for ch in s.chars() {
        match ch {
            '(' => depth += 1,
            ')' => depth -= 1,
            _ => {}
        }
        let binary = matches!(prev, Some(p) if !"*/^(+-=e".contains(p));
        if depth == 0 && (ch == '+' || ch == '-') && binary && !cur.trim().is_empty() {
            out.push(cur.trim().to_string());
            cur.clear();
        }
        cur.push(ch);
        if !ch.is_whitespace() {
            prev = Some(ch);
        }
    }
    if !cur.trim().is_empty() {
        out.push(cur.trim().to_string());
    }
    out
}

/// A term without its leading sign.
pub fn strip_sign(t: &str) -> String {
    t.trim_start_matches(['+', '-', ' ']).to_string()
}

/// Whether a term is the number zero.
pub fn is_zero(t: &str) -> bool {
    strip_sign(t).trim() == "0"
}

/// `s` with term `k` multiplied by `factor` (its sign kept in front).
pub fn scale(s: &str, k: usize, factor: &str) -> String {
    let mut ts = terms(s);
    if let Some(t) = ts.get_mut(k) {
        let sign = if t.starts_with('-') {
            "- "
        } else if t.starts_with('+') {
            "+ "
        } else {
            ""
        };
        *t = format!("{sign}{factor}*({})", strip_sign(t).trim());
    }
    ts.join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn terms_split_at_top_level_signs_only() {
        assert_eq!(
            terms("1/2*m*x'^2 - k*(x - 1)^2 + 1e-3*x"),
            ["1/2*m*x'^2", "- k*(x - 1)^2", "+ 1e-3*x"]
        );
        assert_eq!(terms("-m*g*l*cos(theta)"), ["-m*g*l*cos(theta)"]);
        assert_eq!(scale("a - b", 1, "2"), "a - 2*(b)");
    }
}
