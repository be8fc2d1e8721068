//! The codes of problem-file findings: one enum, each variant with the stable kebab-case name
//! that output, JSON and the documentation use (as the checker's [`crate::check::Code`] is).

use std::fmt;

/// Declares [`FindingCode`]: each variant with its doc and its stable name, in one table, so
/// that a name cannot be forgotten in `as_str` or [`FindingCode::ALL`].
macro_rules! finding_codes {
    ($($(#[doc = $doc:literal])+ $variant:ident => $name:literal,)*) => {
        /// What is wrong with a problem file, as a stable code. Displayed as its kebab-case
        /// name (`wrong-eom`), the string the output and the documentation use.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        #[non_exhaustive]
        pub enum FindingCode {
            $($(#[doc = $doc])+ $variant,)*
            /// An error of the engine met while building or verifying the file keeps the
            /// engine's own code (`acceleration-in-lagrangian`, `bad-at`, …).
            Engine(&'static str),
        }

        impl FindingCode {
            /// Every code of the format's own (not [`FindingCode::Engine`]), in declaration
            /// order.
            pub const ALL: &'static [FindingCode] = &[$(FindingCode::$variant,)*];

            /// The stable kebab-case name, e.g. `wrong-eom`.
            pub const fn as_str(self) -> &'static str {
                match self {
                    $(FindingCode::$variant => $name,)*
                    FindingCode::Engine(code) => code,
                }
            }
        }
    };
}

finding_codes! {
    // Reading the file.
    /// The file cannot be read (missing, no permission, an I/O error).
    UnreadableFile => "unreadable-file",
    /// The path is a folder, a device or a link loop, not a regular file.
    NotAFile => "not-a-file",
    /// The file is not UTF-8 text.
    NotUtf8 => "not-utf8",
    /// The file or one of its values is larger than the format allows.
    TooLarge => "too-large",
    /// The TOML nests deeper than the format allows.
    TooDeep => "too-deep",
    /// The file is not valid TOML.
    TomlSyntax => "toml-syntax",
    /// A key the format does not know (a typo, or a key of another table).
    UnknownKey => "unknown-key",
    /// A key the format requires is missing.
    MissingKey => "missing-key",
    /// A value has the wrong TOML type (a number for a string…).
    WrongType => "wrong-type",
    /// Two files of one bank define the same problem id.
    DuplicateId => "duplicate-id",
    // Building the problem.
    /// A problem or part id that is empty or not of letters, digits, `-` and `_`.
    BadId => "bad-id",
    /// The problem gives neither a Lagrangian nor bodies.
    NoSystem => "no-system",
    /// The problem declares no coordinate.
    NoCoordinates => "no-coordinates",
    /// Two coordinates share a name.
    DuplicateCoordinate => "duplicate-coordinate",
    /// A parameter or coordinate uses a name the language reserves.
    ReservedName => "reserved-name",
    /// A symbol that is neither a coordinate nor a declared parameter.
    UndeclaredSymbol => "undeclared-symbol",
    /// A parameter range that is empty, reversed or not finite.
    BadRange => "bad-range",
    /// A declared dimension that cannot be read.
    BadDimension => "bad-dimension",
    /// An assumption (`assume`) that cannot be read.
    BadAssumption => "bad-assumption",
    /// A constraint that cannot be read.
    BadConstraint => "bad-constraint",
    /// A generalized or point force that cannot be read.
    BadForce => "bad-force",
    /// A definition (a named quantity) that cannot be read.
    BadDefinition => "bad-definition",
    /// A coordinate domain that cannot be read or is empty.
    BadDomain => "bad-domain",
    /// A body (a point mass or a rigid body) that cannot be read.
    BadBody => "bad-body",
    /// A potential that cannot be read.
    BadPotential => "bad-potential",
    /// A `[simulation]` table that cannot be used.
    BadSimulation => "bad-simulation",
    /// An expression or name of the file (a force, a potential, a listed coordinate) that
    /// cannot be read.
    Unreadable => "unreadable",
    // Building a part.
    /// Two parts share an id.
    DuplicatePart => "duplicate-part",
    /// A part kind the format does not know.
    BadKind => "bad-kind",
    /// A quantity the format does not know, or one that does not fit the part's kind.
    BadQuantity => "bad-quantity",
    /// A coordinate a part names that the system does not have.
    BadCoordinate => "bad-coordinate",
    /// A constraint multiplier a part names that the system does not have.
    BadMultiplier => "bad-multiplier",
    /// A tolerance that is not a small positive number.
    BadTolerance => "bad-tolerance",
    /// A points value that is not a positive number.
    BadPoints => "bad-points",
    /// An `accept` value the format does not know, or one the part's kind cannot take.
    BadAccept => "bad-accept",
    /// An `up_to` value the format does not know.
    BadUpTo => "bad-up-to",
    /// A stability that is not `stable`, `unstable` or `marginal`.
    BadStability => "bad-stability",
    /// `require_stability` on a part that has no stability to ask for.
    BadRequireStability => "bad-require-stability",
    /// A part gives no answer.
    NoAnswer => "no-answer",
    /// `about` on a part with nothing to expand, or naming what is not a coordinate.
    BadAbout => "bad-about",
    /// `omit_zero_modes` or `growth` on a part that is not `frequencies`, or both together.
    BadFrequencyOption => "bad-frequency-option",
    /// A numeric part's `values` (or its answers' units) that cannot be used: no tolerance, a
    /// parameter without a number, a unit of the wrong dimension.
    BadValues => "bad-values",
    // Verifying the answers.
    /// The part's values cannot be sampled in the parameter ranges (undefined everywhere…).
    Sampling => "sampling",
    /// A part the engine derives nothing to compare with: it would pass unchecked.
    Unprovable => "unprovable",
    /// The part cannot be prepared for checking (its system's dynamics cannot be set up).
    Unusable => "unusable",
    /// An answer has the wrong dimension or adds unlike terms.
    Dimension => "dimension",
    /// The reference answer is not what the Lagrangian gives.
    WrongAnswer => "wrong-answer",
    /// A reference equation of motion that does not follow from the Lagrangian.
    WrongEom => "wrong-eom",
    /// A reference condition (a steady motion, a relation) that does not hold.
    WrongCondition => "wrong-condition",
    /// The bodies and the given Lagrangian describe different motions.
    LagrangianMismatch => "lagrangian-mismatch",
    /// The checker refuses the part's own reference answer.
    ReferenceRejected => "reference-rejected",
    /// A listed wrong answer that the checker accepts.
    WrongAccepted => "wrong-accepted",
    /// A listed wrong answer that cannot be read.
    UnreadableWrong => "unreadable-wrong",
    /// A stability stated where the part does not require it.
    StabilityNotRequired => "stability-not-required",
    /// An equilibrium of the system the part does not list.
    MissingEquilibrium => "missing-equilibrium",
    /// A listed point that is not an equilibrium.
    SpuriousEquilibrium => "spurious-equilibrium",
    /// The same equilibrium listed twice.
    DuplicateEquilibrium => "duplicate-equilibrium",
    /// A listed equilibrium that is not isolated (a line or surface of equilibria).
    NotIsolated => "not-isolated",
    /// A listed stability that is not the equilibrium's.
    WrongStability => "wrong-stability",
    /// A frequency asked at a point that is not an equilibrium.
    NotAnEquilibrium => "not-an-equilibrium",
    /// A reference frequency that is not the system's.
    WrongFrequency => "wrong-frequency",
    /// A conserved momentum asked of a coordinate that is not cyclic.
    NotCyclic => "not-cyclic",
    /// A cyclic coordinate whose momentum the part does not list.
    MissingCyclic => "missing-cyclic",
    /// A part asks for T or V of a problem that gives no bodies (or T and V) to check against.
    NoTruth => "no-truth",
    /// A steady-motion part whose `at` does not give every coordinate but the moving one.
    BadSteady => "bad-steady",
    /// A stated steady motion that is not one.
    NotSteady => "not-steady",
    // Per-student variants.
    /// A `[variants]` declaration that cannot be read (no values, a bad range or step…).
    BadVariant => "bad-variant",
    /// A part accepts numbers but no parameter varies (every student has one answer).
    NumbersWithoutVariants => "numbers-without-variants",
    /// A varied parameter can be 0 or ±1, so a missing factor would pass with numbers.
    VariantTrivialValue => "variant-trivial-value",
    /// Two varied parameters can be equal, so one could stand for the other with numbers.
    VariantEqualValues => "variant-equal-values",
    /// A part does not hold for some student's numbers.
    VariantFails => "variant-fails",
}

impl fmt::Display for FindingCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Serialised as its stable name (`"wrong-eom"`), as the checker's codes are.
impl serde::Serialize for FindingCode {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

/// A code compares equal to its stable name, so that a test or a tool can ask for `"wrong-eom"`.
impl PartialEq<&str> for FindingCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_distinct_kebab_case() {
        let mut seen = std::collections::BTreeSet::new();
        for code in FindingCode::ALL {
            let name = code.as_str();
            assert!(seen.insert(name), "{name} twice");
            assert!(
                name.split('-').all(|w| !w.is_empty()
                    && w.bytes()
                        .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit())),
                "{name}"
            );
        }
        assert_eq!(FindingCode::WrongEom.to_string(), "wrong-eom");
        assert_eq!(FindingCode::Engine("bad-at").to_string(), "bad-at");
        // In JSON (the browser page's findings) as the same name.
        assert_eq!(
            serde_json::to_string(&FindingCode::DuplicateId).ok(),
            Some("\"duplicate-id\"".to_string())
        );
    }
}
