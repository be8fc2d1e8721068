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
#[non_exhaustive]
pub enum Code {
    /// The answer names a symbol the problem does not declare.
    UnknownSymbol,
    /// The answer uses a parameter this part substitutes away.
    SubstitutedSymbol,
    /// The answer (or the reference) cannot be read.
    Syntax,
    /// The answer is not of the part's kind (an equation for an expression, a list…).
    WrongKind,
    /// Numbers where the part asks for an expression in the problem's symbols (the part does
    /// not accept numbers): not judged as a value.
    NumbersForSymbols,
    /// A named answer (`T = …`) names another quantity than the part asks for.
    WrongName,
    /// The answer (or an item) has the wrong dimension or adds unlike terms.
    Dimension,
    /// The answer is undefined where the right one is defined.
    Undefined,
    /// Wrong, but exactly what follows from the student's own earlier wrong answer (their L →
    /// the equation of motion of that L…): the real mistake is in the earlier part.
    FollowsFromEarlier,
    /// Right in another common convention (angle from the horizontal, y pointing down) than the
    /// one the problem states.
    Convention,
    /// A height or an extension measured wrongly in the potential (heights multiplied instead of
    /// added; gravity on a mass it does not act on).
    PeGeometry,
    /// A product- or chain-rule term lost in d/dt ∂L/∂q̇.
    DerivativeRule,
    /// A conserved momentum put into L before differentiating.
    PrematureSubstitution,
    /// The energy function taken as T + V where they differ (a moving frame or constraint), or a
    /// wrong claim that T + V is conserved.
    HVsE,
    /// T + V written where L = T − V (or h) is asked.
    TPlusV,
    /// The Lagrangian given where T, V, h or a momentum is asked.
    GaveLagrangian,
    /// ω² = V''/m where the inertia is m·l² (or I): the wrong inertia in a frequency.
    EffectiveMass,
    /// ω² given for ω (or the square of an ω²).
    OmegaSquared,
    /// ω given for ω² (or √ω for ω).
    OmegaRoot,
    /// f = ω/2π given for the angular frequency ω.
    OrdinaryFrequency,
    /// A period 2π/ω given for a frequency.
    Period,
    /// An equation multiplied by a factor that vanishes somewhere (the energy law θ'·(EOM) = 0,
    /// θ·(EOM) = 0): it no longer determines the accelerations there.
    VanishingFactor,
    /// The linearized (small-angle) equation given for the full one.
    SmallAngle,
    /// Linearised about another point than the one asked for.
    ExpansionPoint,
    /// Right, but not expanded where a linearized part asks for the Taylor polynomial (the
    /// full V, sin θ kept in a linearized equation).
    NotExpanded,
    /// Expanded to another order than asked (the second-order term dropped, or θ⁴ kept).
    ExpansionOrder,
    /// Two symbols exchanged.
    SwappedSymbols,
    /// A sign flipped, in one term or overall.
    SignError,
    /// Off by a constant factor, in one term or overall.
    ConstantFactor,
    /// A wrong factor inside one term (sin for cos, l for l², θ₁ + θ₂ for θ₁ − θ₂).
    WrongFactor,
    /// A term of the right answer is missing.
    MissingTerm,
    /// A term the right answer does not have.
    ExtraTerm,
    /// Right at rest: a velocity-dependent term is wrong.
    VelocityTerm,
    /// Right in a limit (a parameter set to zero): the mistake is in a term with that parameter.
    RightInLimit,
    /// Agrees only to a few digits: a decimal where an exact constant belongs.
    RoundedConstant,
    /// Equilibria missing because a factor (sin θ) was divided out.
    LostRoot,
    /// An equilibrium's stability stated wrongly.
    WrongStability,
    /// An equilibrium's stability not stated where the part asks for it.
    MissingStability,
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
    /// A Lagrangian that differs from T − V by a total time derivative dF(q, t)/dt (another
    /// gauge), accepted; and a momentum or h that follows from such an accepted L.
    TotalDerivative,
    /// A Lagrangian giving the same equations of motion at another scale, on a part that
    /// accepts any L with the right motion (`accept = "same-motion"`).
    EquivalentLagrangian,
    /// Wrong, with no more specific diagnosis.
    NotEqual,
}

impl Code {
    /// Every code, most specific first.
    pub const ALL: [Code; 48] = [
        Code::UnknownSymbol,
        Code::SubstitutedSymbol,
        Code::Syntax,
        Code::WrongKind,
        Code::NumbersForSymbols,
        Code::WrongName,
        Code::Dimension,
        Code::Undefined,
        Code::FollowsFromEarlier,
        Code::Convention,
        Code::PeGeometry,
        Code::DerivativeRule,
        Code::PrematureSubstitution,
        Code::HVsE,
        Code::TPlusV,
        Code::GaveLagrangian,
        Code::EffectiveMass,
        Code::OmegaSquared,
        Code::OmegaRoot,
        Code::OrdinaryFrequency,
        Code::Period,
        Code::VanishingFactor,
        Code::SmallAngle,
        Code::ExpansionPoint,
        Code::NotExpanded,
        Code::ExpansionOrder,
        Code::SwappedSymbols,
        Code::SignError,
        Code::ConstantFactor,
        Code::WrongFactor,
        Code::MissingTerm,
        Code::ExtraTerm,
        Code::VelocityTerm,
        Code::RightInLimit,
        Code::RoundedConstant,
        Code::LostRoot,
        Code::WrongStability,
        Code::MissingStability,
        Code::EquationCount,
        Code::DependentEquations,
        Code::WrongEquation,
        Code::MissingItem,
        Code::ExtraItem,
        Code::WrongItem,
        Code::UpToConstant,
        Code::TotalDerivative,
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
            Code::NumbersForSymbols => "numbers-for-symbols",
            Code::WrongName => "wrong-name",
            Code::Dimension => "dimension",
            Code::Undefined => "undefined",
            Code::FollowsFromEarlier => "follows-from-earlier",
            Code::Convention => "convention",
            Code::PeGeometry => "pe-geometry",
            Code::DerivativeRule => "derivative-rule",
            Code::PrematureSubstitution => "premature-substitution",
            Code::HVsE => "h-vs-e",
            Code::TPlusV => "t-plus-v",
            Code::GaveLagrangian => "gave-lagrangian",
            Code::EffectiveMass => "effective-mass",
            Code::OmegaSquared => "omega-squared",
            Code::OmegaRoot => "omega-root",
            Code::OrdinaryFrequency => "ordinary-frequency",
            Code::Period => "period",
            Code::VanishingFactor => "vanishing-factor",
            Code::SmallAngle => "small-angle",
            Code::ExpansionPoint => "expansion-point",
            Code::NotExpanded => "not-expanded",
            Code::ExpansionOrder => "expansion-order",
            Code::SwappedSymbols => "swapped-symbols",
            Code::SignError => "sign-error",
            Code::ConstantFactor => "constant-factor",
            Code::WrongFactor => "wrong-factor",
            Code::MissingTerm => "missing-term",
            Code::ExtraTerm => "extra-term",
            Code::VelocityTerm => "velocity-term",
            Code::RightInLimit => "right-in-limit",
            Code::RoundedConstant => "rounded-constant",
            Code::LostRoot => "lost-root",
            Code::WrongStability => "wrong-stability",
            Code::MissingStability => "missing-stability",
            Code::EquationCount => "equation-count",
            Code::DependentEquations => "dependent-equations",
            Code::WrongEquation => "wrong-equation",
            Code::MissingItem => "missing-item",
            Code::ExtraItem => "extra-item",
            Code::WrongItem => "wrong-item",
            Code::UpToConstant => "up-to-constant",
            Code::TotalDerivative => "total-derivative",
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
#[non_exhaustive]
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
    /// A verdict with no problem or part ids, no plain reading, note or parse error: what a
    /// face that keeps many verdicts (grading a class) keeps of one, given back whole to the
    /// library (follow-through reads an earlier answer through it).
    pub fn kept(
        status: Status,
        score: f64,
        unicode: String,
        diagnoses: Vec<Diagnosis>,
        seed: u64,
    ) -> Verdict {
        Verdict {
            problem: String::new(),
            part: String::new(),
            status,
            score,
            reading: ReadAs {
                plain: String::new(),
                unicode,
                note: None,
            },
            diagnoses,
            seed,
            parse_error: None,
        }
    }

    /// Orders the diagnoses most specific first and removes repeats.
    pub fn sort(&mut self) {
        crate::sort::sort_by_key(&mut self.diagnoses, |d| d.code);
        self.diagnoses.dedup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_serialise_as_their_names_in_report_order() {
        // The codes as documented (docs/checking.md, JSON consumers), most specific first.
        const DOCUMENTED: [&str; 48] = [
            "unknown-symbol",
            "substituted-symbol",
            "syntax",
            "wrong-kind",
            "numbers-for-symbols",
            "wrong-name",
            "dimension",
            "undefined",
            "follows-from-earlier",
            "convention",
            "pe-geometry",
            "derivative-rule",
            "premature-substitution",
            "h-vs-e",
            "t-plus-v",
            "gave-lagrangian",
            "effective-mass",
            "omega-squared",
            "omega-root",
            "ordinary-frequency",
            "period",
            "vanishing-factor",
            "small-angle",
            "expansion-point",
            "not-expanded",
            "expansion-order",
            "swapped-symbols",
            "sign-error",
            "constant-factor",
            "wrong-factor",
            "missing-term",
            "extra-term",
            "velocity-term",
            "right-in-limit",
            "rounded-constant",
            "lost-root",
            "wrong-stability",
            "missing-stability",
            "equation-count",
            "dependent-equations",
            "wrong-equation",
            "missing-item",
            "extra-item",
            "wrong-item",
            "up-to-constant",
            "total-derivative",
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
