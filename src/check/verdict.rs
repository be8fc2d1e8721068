//! The verdict on an answer: data only (rendering is the faces' business).

use serde::Serialize;

/// Correct, incorrect, or unreadable / not of the part's kind (never a wrong attempt).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Correct,
    Incorrect,
    Invalid,
}

impl Status {
    /// "correct", "incorrect" or "invalid".
    pub fn name(self) -> &'static str {
        match self {
            Status::Correct => "correct",
            Status::Incorrect => "incorrect",
            Status::Invalid => "invalid",
        }
    }
}

/// How the input was read.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ReadAs {
    pub plain: String,
    pub unicode: String,
    /// Anything the reader assumed, e.g. "read as … = 0".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// A diagnosis code. Declaration order is report order: most specific first, so `Ord` ranks.
/// Serialised (and displayed) in kebab-case, the strings the documentation and JSON use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Code {
    /// The answer names a symbol the problem does not declare.
    UnknownSymbol,
    /// The answer uses a parameter this part substitutes away.
    SubstitutedSymbol,
    /// The answer (or the reference) cannot be read.
    Syntax,
    /// The answer is not of the part's kind (an equation for an expression, a list…).
    WrongKind,
    /// The answer (or an item) has the wrong dimension or adds unlike terms.
    Dimension,
    /// The answer is undefined where the right one is defined.
    Undefined,
    /// Wrong, but exactly what follows from the student's own earlier wrong answer (their L →
    /// the equation of motion of that L…): the real mistake is in the earlier part.
    FollowsFromEarlier,
    /// T + V written where L = T − V (or h) is asked.
    TPlusV,
    /// The Lagrangian given where T, V, h or a momentum is asked.
    GaveLagrangian,
    /// ω² given for ω (or the square of an ω²).
    OmegaSquared,
    /// ω given for ω² (or √ω for ω).
    OmegaRoot,
    /// An equation multiplied by a factor that vanishes somewhere (the energy law θ'·(EOM) = 0,
    /// θ·(EOM) = 0): it no longer determines the accelerations there.
    VanishingFactor,
    /// The linearized (small-angle) equation given for the full one.
    SmallAngle,
    /// Two symbols exchanged.
    SwappedSymbols,
    /// A sign flipped, in one term or overall.
    SignError,
    /// Off by a constant factor, in one term or overall.
    ConstantFactor,
    /// Right at rest: a velocity-dependent term is wrong.
    VelocityTerm,
    /// Agrees only to a few digits: a decimal where an exact constant belongs.
    RoundedConstant,
    /// Not as many equations as asked for.
    EquationCount,
    /// Equations that hold but do not determine the accelerations.
    DependentEquations,
    /// One equation of a system does not hold for the true motion.
    WrongEquation,
    /// A list answer lacks items.
    MissingItem,
    /// A list answer has an item too many.
    ExtraItem,
    /// A list item matches no reference item.
    WrongItem,
    /// Correct up to an allowed additive constant.
    UpToConstant,
    /// A Lagrangian giving the same equations of motion.
    EquivalentLagrangian,
    /// Wrong, with no more specific diagnosis.
    NotEqual,
}

impl Code {
    /// Every code, most specific first.
    pub const ALL: [Code; 27] = [
        Code::UnknownSymbol,
        Code::SubstitutedSymbol,
        Code::Syntax,
        Code::WrongKind,
        Code::Dimension,
        Code::Undefined,
        Code::FollowsFromEarlier,
        Code::TPlusV,
        Code::GaveLagrangian,
        Code::OmegaSquared,
        Code::OmegaRoot,
        Code::VanishingFactor,
        Code::SmallAngle,
        Code::SwappedSymbols,
        Code::SignError,
        Code::ConstantFactor,
        Code::VelocityTerm,
        Code::RoundedConstant,
        Code::EquationCount,
        Code::DependentEquations,
        Code::WrongEquation,
        Code::MissingItem,
        Code::ExtraItem,
        Code::WrongItem,
        Code::UpToConstant,
        Code::EquivalentLagrangian,
        Code::NotEqual,
    ];

    /// The stable kebab-case name, e.g. `sign-error`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Code::UnknownSymbol => "unknown-symbol",
            Code::SubstitutedSymbol => "substituted-symbol",
            Code::Syntax => "syntax",
            Code::WrongKind => "wrong-kind",
            Code::Dimension => "dimension",
            Code::Undefined => "undefined",
            Code::FollowsFromEarlier => "follows-from-earlier",
            Code::TPlusV => "t-plus-v",
            Code::GaveLagrangian => "gave-lagrangian",
            Code::OmegaSquared => "omega-squared",
            Code::OmegaRoot => "omega-root",
            Code::VanishingFactor => "vanishing-factor",
            Code::SmallAngle => "small-angle",
            Code::SwappedSymbols => "swapped-symbols",
            Code::SignError => "sign-error",
            Code::ConstantFactor => "constant-factor",
            Code::VelocityTerm => "velocity-term",
            Code::RoundedConstant => "rounded-constant",
            Code::EquationCount => "equation-count",
            Code::DependentEquations => "dependent-equations",
            Code::WrongEquation => "wrong-equation",
            Code::MissingItem => "missing-item",
            Code::ExtraItem => "extra-item",
            Code::WrongItem => "wrong-item",
            Code::UpToConstant => "up-to-constant",
            Code::EquivalentLagrangian => "equivalent-lagrangian",
            Code::NotEqual => "not-equal",
        }
    }
}

impl std::fmt::Display for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One reason, with a stable code.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnosis {
    pub code: Code,
    pub message: String,
}

impl Diagnosis {
    /// A diagnosis.
    pub fn new(code: Code, message: impl Into<String>) -> Self {
        Diagnosis {
            code,
            message: message.into(),
        }
    }
}

impl From<&Diagnosis> for crate::diagnostic::Diagnostic {
    fn from(d: &Diagnosis) -> Self {
        crate::diagnostic::Diagnostic::new(d.code.as_str(), d.message.clone(), "")
    }
}

/// The verdict on one answer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    pub problem: String,
    pub part: String,
    pub status: Status,
    /// 0…1; partial credit for lists and systems.
    pub score: f64,
    pub reading: ReadAs,
    pub diagnoses: Vec<Diagnosis>,
    /// The sampling seed (from the problem and part ids).
    pub seed: u64,
    /// The reader's error, for rendering with a caret (not serialized).
    #[serde(skip)]
    pub parse_error: Option<crate::expr::ParseError>,
}

impl Verdict {
    /// Orders the diagnoses most specific first and removes repeats.
    pub fn sort(&mut self) {
        self.diagnoses.sort_by_key(|d| d.code);
        self.diagnoses.dedup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_serialise_as_their_names_in_report_order() {
        // The codes as documented (README, JSON consumers), most specific first.
        const DOCUMENTED: [&str; 27] = [
            "unknown-symbol",
            "substituted-symbol",
            "syntax",
            "wrong-kind",
            "dimension",
            "undefined",
            "follows-from-earlier",
            "t-plus-v",
            "gave-lagrangian",
            "omega-squared",
            "omega-root",
            "vanishing-factor",
            "small-angle",
            "swapped-symbols",
            "sign-error",
            "constant-factor",
            "velocity-term",
            "rounded-constant",
            "equation-count",
            "dependent-equations",
            "wrong-equation",
            "missing-item",
            "extra-item",
            "wrong-item",
            "up-to-constant",
            "equivalent-lagrangian",
            "not-equal",
        ];
        assert_eq!(Code::ALL.len(), DOCUMENTED.len());
        for (i, c) in Code::ALL.iter().enumerate() {
            assert_eq!(
                serde_json::to_string(c).ok(),
                Some(format!("\"{}\"", c.as_str()))
            );
            assert_eq!(c.to_string(), DOCUMENTED[i]);
            if i > 0 {
                assert!(Code::ALL[i - 1] < *c);
            }
        }
    }
}
