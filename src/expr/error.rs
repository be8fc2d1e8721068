//! Parse errors as data: a kind, a byte span and a one-line help. Rendering is elsewhere
//! (`crate::diagnostic`), so the same error prints the same way in the CLI, REPL and tests.

use std::ops::Range;

/// Longest input accepted, in bytes.
pub const MAX_INPUT_BYTES: usize = 20_000;
/// The longest text a system is built from (a Lagrangian, T, V, a force, a constraint):
/// larger than an answer, still bounded.
pub const MAX_SYSTEM_INPUT_BYTES: usize = 1_000_000;
/// Highest order of a time derivative a student may write (primes, `dot(q')`, combining dots):
/// far above any equation of motion, low enough that every order the tool derives from it
/// still fits its counters. A higher order is a positioned error, never read as a lower one.
pub const MAX_DERIVATIVE_ORDER: usize = 20;
/// Deepest nesting accepted (parentheses, unary signs, exponents, function calls).
pub const MAX_DEPTH: usize = 100;

/// What went wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseErrorKind {
    #[error("the input is empty")]
    Empty,
    #[error("the input is {len} bytes long; at most {max} are read")]
    TooLong { len: usize, max: usize },
    #[error("the expression is nested more than {max} levels deep")]
    TooDeep { max: usize },
    #[error("unexpected {}", describe_char(*.0))]
    UnexpectedChar(char),
    #[error("this `(` is never closed")]
    UnclosedParen,
    #[error("this `)` has no matching `(`")]
    UnmatchedParen,
    #[error("expected a value {context}")]
    MissingOperand { context: String },
    #[error("two numbers side by side")]
    MissingOperator,
    #[error("unknown function `{name}`")]
    UnknownFunction {
        name: String,
        suggestion: Option<String>,
    },
    #[error("`{name}` is a function but has no argument")]
    FunctionWithoutArgs { name: String },
    #[error("unknown name `{name}`")]
    UnknownName {
        name: String,
        suggestion: Option<String>,
        split: Option<String>,
    },
    #[error("`{name}` is not a coordinate, so it has no time derivative")]
    NotACoordinate { name: String },
    #[error("an equation (`=`) is not expected here")]
    EquationNotAllowed,
    #[error("a list is not expected here")]
    ListNotAllowed,
    #[error("an equation has only one `=`")]
    ChainedEquals,
    #[error("this number cannot be read")]
    BadNumber,
    /// A decimal exponent beyond the limit (`1e301`): refused rather than rounded to ∞ or 0.
    #[error(
        "this number's exponent is beyond ±{max}: lagrange reads numbers from 1e-{max} to 1e{max}"
    )]
    ExponentTooLarge { max: i64 },
    /// A literal with too many digits.
    #[error("this number has more than {max} digits")]
    TooManyDigits { max: usize },
    #[error("`{name}(…)` takes the name of a coordinate")]
    DotNeedsName { name: String },
    #[error("a derivative mark applies to a name")]
    PrimeWithoutName,
    /// `q` followed by more derivative marks than [`MAX_DERIVATIVE_ORDER`].
    #[error("a derivative of order {order} is beyond the highest order lagrange reads ({max})")]
    OrderTooHigh { order: u32, max: usize },
    #[error("an equation is expected here")]
    EquationExpected,
    /// `sin θ²`, `sin θ/2`, `sin ωt`: a bare argument with two common readings.
    #[error("this can be read as `{one}` or as `{other}`")]
    AmbiguousArgument { one: String, other: String },
    /// `sin⁻¹`, `sin^-1`: arcsin to some, 1/sin to others.
    #[error("`{name}` with a negative power can mean the inverse function or one over `{name}`")]
    InversePower { name: String },
    /// An item with several `±` whose pairing is unclear (a `∓` among them) or with too many
    /// to expand.
    #[error("{reason}")]
    SignChoices { reason: String },
    /// A tuple point `(a, b)` with the wrong number of values.
    #[error("a point needs {want} values, one per coordinate ({names})")]
    PointSize { want: usize, names: String },
}

impl ParseErrorKind {
    /// A stable code, for JSON output and tests.
    pub fn code(&self) -> &'static str {
        match self {
            Self::Empty => "empty",
            Self::TooLong { .. } => "too-long",
            Self::TooDeep { .. } => "too-deep",
            Self::UnexpectedChar(_) => "unexpected-character",
            Self::UnclosedParen => "unclosed-paren",
            Self::UnmatchedParen => "unmatched-paren",
            Self::MissingOperand { .. } => "missing-operand",
            Self::MissingOperator => "missing-operator",
            Self::UnknownFunction { .. } => "unknown-function",
            Self::FunctionWithoutArgs { .. } => "function-without-argument",
            Self::UnknownName { .. } => "unknown-symbol",
            Self::NotACoordinate { .. } => "not-a-coordinate",
            Self::EquationNotAllowed => "equation-not-allowed",
            Self::ListNotAllowed => "list-not-allowed",
            Self::ChainedEquals => "chained-equals",
            Self::BadNumber => "bad-number",
            Self::ExponentTooLarge { .. } => "number-too-large",
            Self::TooManyDigits { .. } => "too-many-digits",
            Self::DotNeedsName { .. } => "dot-needs-name",
            Self::PrimeWithoutName => "prime-without-name",
            Self::OrderTooHigh { .. } => "order-too-high",
            Self::EquationExpected => "equation-expected",
            Self::AmbiguousArgument { .. } => "ambiguous",
            Self::InversePower { .. } => "ambiguous",
            Self::PointSize { .. } => "point-size",
            Self::SignChoices { .. } => "ambiguous-signs",
        }
    }

    /// One line telling the student how to fix it.
    pub fn help(&self) -> String {
        match self {
            Self::Empty => "type an expression, e.g. `m*g*l*cos(theta)`".into(),
            Self::TooLong { .. } => "shorten the input".into(),
            Self::TooDeep { .. } => "remove some parentheses or split the expression".into(),
            Self::UnexpectedChar(c) => match c {
                '{' | '}' => "use round parentheses `( )` for grouping".into(),
                '\\' => "type plain syntax, not LaTeX: `sin(theta)`, `theta''`".into(),
                '!' => "factorials are not part of the language".into(),
                '∂' => "a partial derivative of L cannot be checked (there is no L here to refer to): work it out and write the result".into(),
                '±' => "`±` gives two values: it is read only in a list (`±sqrt(g/l)`); otherwise write one sign".into(),
                c if c.is_control() || invisible_name(*c).is_some() => {
                    "delete it (retype the answer if you cannot see it)".into()
                }
                _ => "use numbers, names, + - * / ^, parentheses and functions".into(),
            },
            Self::UnclosedParen => "add a `)` to close it".into(),
            Self::UnmatchedParen => "remove it, or add a `(` before it".into(),
            Self::MissingOperand { context }
                if context.contains("`,`") || context.contains("`;`") =>
            {
                "each item of a list needs a value: remove the extra separator".into()
            }
            Self::MissingOperand { .. } => "an operator needs a value on each side".into(),
            Self::MissingOperator => "put `*` between the numbers, or remove the space".into(),
            Self::UnknownFunction { name, suggestion } => match suggestion {
                Some(s) => format!("did you mean `{s}`?"),
                None => format!(
                    "the functions are sin cos tan sec csc cot asin acos atan sinh cosh tanh exp log ln sqrt abs; to multiply, write `{name}*(…)`"
                ),
            },
            Self::FunctionWithoutArgs { name } => format!("write `{name}(x)`"),
            Self::UnknownName { name, .. } if word_hint(name).is_some() => {
                word_hint(name).unwrap_or_default().into()
            }
            Self::UnknownName { name, .. } if quantity_name(name).is_some() => format!(
                "`{name}` ({}) is not a symbol here: write it out in the coordinates and parameters",
                quantity_name(name).unwrap_or_default()
            ),
            Self::UnknownName {
                suggestion, split, ..
            } => match (suggestion, split) {
                (_, Some(p)) => format!("did you mean `{p}`? put spaces or `*` between names"),
                (Some(s), None) => format!("did you mean `{s}`?"),
                (None, None) => "use only the problem's coordinates and parameters".into(),
            },
            Self::NotACoordinate { .. } => {
                "only coordinates change with time; parameters are constants".into()
            }
            Self::EquationNotAllowed => "give an expression without `=`".into(),
            Self::ListNotAllowed => "give a single answer, without `,` or `;`".into(),
            Self::ChainedEquals => "write one equation per item, separated by `;`".into(),
            Self::BadNumber => "write numbers like `2`, `0.5` or `1e-3`".into(),
            Self::ExponentTooLarge { max } => {
                format!(
                    "rescale the quantity (change units) so that it lies between 1e-{max} and 1e{max}"
                )
            }
            Self::TooManyDigits { .. } => {
                "round it, or write it with an exponent, e.g. `1.5e3`".into()
            }
            Self::DotNeedsName { name } => format!("write `{name}(theta)` for a coordinate theta"),
            Self::PrimeWithoutName => "write `theta'`, not `(…)'`".into(),
            Self::OrderTooHigh { max, .. } => {
                format!("write at most {max} derivative marks on a name")
            }
            Self::EquationExpected => "write an equation with `=`".into(),
            Self::AmbiguousArgument { .. } => {
                "add parentheses to say which: a function's argument without `(` is only the number and name right after it".into()
            }
            Self::PointSize { names, .. } => format!("write each point as ({names})"),
            Self::SignChoices { .. } => {
                "write each value as its own item, separated by commas".into()
            }
            Self::InversePower { name } => {
                format!("write `a{name}(x)` for the inverse, or `1/{name}(x)`")
            }
        }
    }

    /// The short label placed under the span.
    pub(crate) fn label(&self) -> String {
        match self {
            Self::UnclosedParen => "opened here".into(),
            Self::UnknownName { .. } | Self::UnknownFunction { .. } => "not known here".into(),
            Self::MissingOperand { .. } => "a value is missing here".into(),
            Self::TooLong { .. } => "reading stops here".into(),
            _ => "here".into(),
        }
    }
}

/// The help for an ordinary word a student writes in an answer: a unit (`rad/s`), a
/// conjunction between items (`θ = 0 and θ = π`), a statement that something is constant
/// (`p = const`). Each says what kind of answer is read instead.
fn word_hint(name: &str) -> Option<&'static str> {
    Some(match name {
        "rad" | "rads" | "radian" | "radians" | "Hz" | "rpm" | "sec" | "deg" | "degrees" => {
            "no units needed: write the value alone, e.g. `sqrt(g/l)`"
        }
        "and" | "or" => "separate the items with commas: `theta = 0, theta = pi`",
        "const" | "constant" | "conserved" | "C" => {
            "write the quantity itself as an expression (what stays constant), not the word that it is constant"
        }
        "d" | "dt" => {
            "write time derivatives with primes: `theta'` for dθ/dt, `theta''` for d²θ/dt²"
        }
        _ => return None,
    })
}

/// What `T`, `V`, `U` and `L` stand for when a student uses them undeclared (`L = T − V`).
pub(crate) fn quantity_name(name: &str) -> Option<&'static str> {
    Some(match name {
        "T" => "the kinetic energy",
        "V" | "U" => "the potential energy",
        "L" => "the Lagrangian",
        _ => return None,
    })
}

/// An error in reading an input, with its position.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{kind} (at byte {})", span.start)]
pub struct ParseError {
    pub kind: ParseErrorKind,
    pub span: Range<usize>,
}

impl ParseError {
    /// An error of `kind` at `span`.
    pub fn new(kind: ParseErrorKind, span: Range<usize>) -> Self {
        ParseError { kind, span }
    }

    /// The one-line help.
    pub fn help(&self) -> String {
        self.kind.help()
    }
}

/// Invisible characters (zero-width, bidirectional controls and the like) and their names:
/// shown by name, never as themselves, since they cannot be seen and some reorder the text
/// around them on a terminal.
const INVISIBLE: &[(char, &str)] = &[
    ('\u{00AD}', "soft hyphen"),
    ('\u{034F}', "combining grapheme joiner"),
    ('\u{061C}', "Arabic letter mark"),
    ('\u{180E}', "Mongolian vowel separator"),
    ('\u{200B}', "zero-width space"),
    ('\u{200C}', "zero-width non-joiner"),
    ('\u{200D}', "zero-width joiner"),
    ('\u{200E}', "left-to-right mark"),
    ('\u{200F}', "right-to-left mark"),
    ('\u{2028}', "line separator"),
    ('\u{2029}', "paragraph separator"),
    ('\u{202A}', "left-to-right embedding"),
    ('\u{202B}', "right-to-left embedding"),
    ('\u{202C}', "pop directional formatting"),
    ('\u{202D}', "left-to-right override"),
    ('\u{202E}', "right-to-left override"),
    ('\u{2060}', "word joiner"),
    ('\u{2061}', "function application"),
    ('\u{2062}', "invisible times"),
    ('\u{2063}', "invisible separator"),
    ('\u{2064}', "invisible plus"),
    ('\u{2066}', "left-to-right isolate"),
    ('\u{2067}', "right-to-left isolate"),
    ('\u{2068}', "first strong isolate"),
    ('\u{2069}', "pop directional isolate"),
    ('\u{FEFF}', "zero-width no-break space"),
];

/// The name of an invisible character (`U+200B zero-width space`), or `None` for a character
/// that shows as itself. Variation selectors, tags and interlinear annotation marks, which
/// are invisible too, get a generic name.
pub fn invisible_name(c: char) -> Option<String> {
    let name = INVISIBLE
        .iter()
        .find(|(x, _)| *x == c)
        .map(|(_, n)| *n)
        .or(match c {
            '\u{FE00}'..='\u{FE0F}' | '\u{E0100}'..='\u{E01EF}' => Some("variation selector"),
            '\u{E0000}'..='\u{E007F}' => Some("tag character"),
            '\u{FFF9}'..='\u{FFFB}' => Some("interlinear annotation mark"),
            _ => None,
        })?;
    Some(format!("U+{:04X} {name}", c as u32))
}

/// A character for a message: `` `$` ``, a control character escaped (`` `\u{1b}` ``, so a
/// terminal never obeys it), an invisible one by name.
pub fn describe_char(c: char) -> String {
    if let Some(name) = invisible_name(c) {
        format!("invisible character {name}")
    } else if c.is_control() {
        format!("control character `{}`", c.escape_unicode())
    } else {
        format!("character `{c}`")
    }
}

/// User text made safe to echo on one line: control characters (newlines included) escaped
/// as `\u{1b}`, invisible characters named as `⟨U+200B zero-width space⟩`. Text without
/// either is returned unchanged.
pub fn visible(text: &str) -> String {
    show(text, false)
}

/// [`visible`], keeping line breaks: for whole messages, which may span lines.
pub fn visible_lines(text: &str) -> String {
    show(text, true)
}

fn show(text: &str, keep_newlines: bool) -> String {
    if !text.chars().any(needs_showing) {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        push_shown(&mut out, c, keep_newlines);
    }
    out
}

/// Whether `c` is shown other than as itself.
pub(crate) fn needs_showing(c: char) -> bool {
    c.is_control() || invisible_name(c).is_some()
}

/// Appends `c` as [`visible`] shows it.
pub(crate) fn push_shown(out: &mut String, c: char, keep_newlines: bool) {
    if keep_newlines && c == '\n' {
        out.push(c);
    } else if let Some(name) = invisible_name(c) {
        out.push_str(&format!("⟨{name}⟩"));
    } else if c.is_control() {
        out.extend(c.escape_unicode());
    } else {
        out.push(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_and_invisible_ones_named() {
        assert_eq!(visible("theta\u{1b}]0;x\u{7}"), "theta\\u{1b}]0;x\\u{7}");
        assert_eq!(visible("a\nb"), "a\\u{a}b");
        assert_eq!(visible_lines("a\nb\u{1b}"), "a\nb\\u{1b}");
        assert_eq!(visible("x\u{200b}"), "x⟨U+200B zero-width space⟩");
        assert_eq!(visible("θ̇ · ½"), "θ̇ · ½");
        assert_eq!(
            describe_char('\u{202e}'),
            "invisible character U+202E right-to-left override"
        );
        assert_eq!(describe_char('\u{1b}'), "control character `\\u{1b}`");
        assert_eq!(describe_char('$'), "character `$`");
        assert_eq!(invisible_name('a'), None);
    }
}
