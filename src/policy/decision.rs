//! An instructor's decision on an answer the checker could not settle (the review queue):
//! right, wrong, or a fraction of the points.

use std::fmt;

/// What an instructor decided an answer is worth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Decision {
    /// Right: full points, status `correct`.
    Correct,
    /// Wrong: no points, status `incorrect`.
    Incorrect,
    /// A fraction of the points (strictly between 0 and 1), status `incorrect`.
    Partial(f64),
}

impl Decision {
    /// Reads a decision cell: `correct` (or `right`, `yes`, `1`), `incorrect` (or `wrong`,
    /// `no`, `0`), or a fraction of the points between 0 and 1 (`0.5`, `50%`). Case and
    /// surrounding spaces are ignored; an empty cell is `Ok(None)` (not decided yet). The error
    /// is one line saying what is accepted.
    pub fn parse(text: &str) -> Result<Option<Decision>, String> {
        let t = text.trim().to_ascii_lowercase();
        let fraction = |x: f64| {
            if !(0.0..=1.0).contains(&x) {
                return Err(format!(
                    "the decision `{}` is not between 0 and 1 (a fraction of the points)",
                    crate::expr::error::visible(text.trim())
                ));
            }
            Ok(Some(if x == 1.0 {
                Decision::Correct
            } else if x == 0.0 {
                Decision::Incorrect
            } else {
                Decision::Partial(x)
            }))
        };
        match t.as_str() {
            "" => Ok(None),
            "correct" | "right" | "yes" | "y" | "ok" => Ok(Some(Decision::Correct)),
            "incorrect" | "wrong" | "no" | "n" => Ok(Some(Decision::Incorrect)),
            _ => {
                let (number, scale) = match t.strip_suffix('%') {
                    Some(n) => (n.trim(), 100.0),
                    None => (t.as_str(), 1.0),
                };
                match number.parse::<f64>() {
                    Ok(x) if x.is_finite() => fraction(x / scale),
                    _ => Err(format!(
                        "the decision `{}` is not `correct`, `incorrect` or a fraction of the \
                         points between 0 and 1",
                        crate::expr::error::visible(text.trim())
                    )),
                }
            }
        }
    }

    /// The fraction of the points it gives.
    pub fn fraction(self) -> f64 {
        match self {
            Decision::Correct => 1.0,
            Decision::Incorrect => 0.0,
            Decision::Partial(x) => x,
        }
    }
}

/// `correct`, `incorrect` or the fraction (`0.5`): what results.csv's `override` column shows.
impl fmt::Display for Decision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Decision::Correct => f.write_str("correct"),
            Decision::Incorrect => f.write_str("incorrect"),
            Decision::Partial(x) => write!(f, "{x}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decisions_read_words_fractions_and_percentages() {
        assert_eq!(Decision::parse(" Correct "), Ok(Some(Decision::Correct)));
        assert_eq!(Decision::parse("no"), Ok(Some(Decision::Incorrect)));
        assert_eq!(Decision::parse("0.5"), Ok(Some(Decision::Partial(0.5))));
        assert_eq!(Decision::parse("25%"), Ok(Some(Decision::Partial(0.25))));
        assert_eq!(Decision::parse("1"), Ok(Some(Decision::Correct)));
        assert_eq!(Decision::parse(""), Ok(None));
        assert!(Decision::parse("1.5").is_err());
        assert!(Decision::parse("NaN").is_err());
        assert!(Decision::parse("maybe").is_err());
        assert_eq!(Decision::Partial(0.5).to_string(), "0.5");
    }
}
