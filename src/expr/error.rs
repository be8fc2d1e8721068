//! Parse errors as data: a kind, a byte span and a one-line help. Rendering is elsewhere
//! (`crate::diagnostic`), so the same error prints the same way in the CLI, REPL and tests.

use std::ops::Range;

/// Longest input accepted, in bytes.
pub const MAX_INPUT_BYTES: usize = 20_000;
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
    #[error("unexpected character `{0}`")]
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
    #[error("`{name}(…)` takes the name of a coordinate")]
    DotNeedsName { name: String },
    #[error("a derivative mark applies to a name")]
    PrimeWithoutName,
    #[error("an equation is expected here")]
    EquationExpected,
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
            Self::DotNeedsName { .. } => "dot-needs-name",
            Self::PrimeWithoutName => "prime-without-name",
            Self::EquationExpected => "equation-expected",
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
            Self::DotNeedsName { name } => format!("write `{name}(theta)` for a coordinate theta"),
            Self::PrimeWithoutName => "write `theta'`, not `(…)'`".into(),
            Self::EquationExpected => "write an equation with `=`".into(),
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
