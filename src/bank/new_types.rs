//! The data of a drafted problem (`problems new`): what the face asks for (the system as the
//! file format's tables), the parts as drafted, and what is left out. Every other `new_*` file
//! imports these and none of them is imported here, so the files never import each other in a
//! loop.

/// What to draft: the problem's id and title, the coordinates, and the system as the command
/// line gives it (a Lagrangian, or bodies and potentials in the problem file's fields).
#[derive(Debug, Clone, Default)]
pub struct Spec {
    pub id: String,
    /// The title; a placeholder to edit when `None`.
    pub title: Option<String>,
    pub coordinates: Vec<String>,
    pub lagrangian: Option<String>,
    /// `[[bodies]]` tables: `kind` and the fields of the file format.
    pub bodies: Vec<Table>,
    /// `[[potentials]]` tables.
    pub potentials: Vec<Table>,
    /// Dimensions given for parameters (`k` → `M T^-2`), over the guesses from their names.
    pub dimensions: Vec<(String, String)>,
}

/// One `[[bodies]]` or `[[potentials]]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub kind: String,
    pub fields: Vec<(String, Value)>,
}

/// A field's value in a body or potential table.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// One expression.
    Text(String),
    /// A list of expressions (a position, moments, Euler angles, a fixed spring end).
    List(Vec<String>),
    /// Rows of expressions (an inertia tensor).
    Rows(Vec<Vec<String>>),
    /// A body number, 1-based (a spring's end).
    Body(usize),
}

/// A parameter of the drafted file.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    pub(crate) name: String,
    pub(crate) dimension: String,
    pub(crate) range: (f64, f64),
    pub(crate) value: f64,
}

/// A drafted problem file.
#[derive(Debug, Clone)]
pub struct Drafted {
    /// The whole TOML text: it loads and verifies unedited.
    pub text: String,
    /// The ids of the parts stated, in order.
    pub stated: Vec<String>,
    /// The parts left out, each with why (also written in the file as comments).
    pub left_out: Vec<LeftOut>,
}

/// A part the draft does not state, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LeftOut {
    pub part: String,
    pub reason: String,
}

/// A part as drafted: what `new_toml` writes.
#[derive(Debug, Clone)]
pub(super) struct Candidate {
    pub(crate) id: String,
    pub(crate) kind: &'static str,
    /// Extra fields (`quantity`, `coordinate`, `up_to`, `at`, `stability`, …), in order.
    pub(crate) fields: Vec<(&'static str, Field)>,
    pub(crate) prompt: String,
    /// The reference answer: one string, or (with `many`) a list.
    pub(crate) answer: Vec<String>,
    pub(crate) many: bool,
    pub(crate) hints: Vec<String>,
}

/// A part field's value.
#[derive(Debug, Clone)]
pub(super) enum Field {
    Str(String),
    Bool(bool),
    Strs(Vec<String>),
    Map(Vec<(String, String)>),
}

/// A coordinate range widened so that the equilibria's search covers every stated point.
pub(super) type Widened = (usize, (f64, f64));

impl Candidate {
    pub(super) fn one(
        id: &str,
        kind: &'static str,
        prompt: &str,
        answer: String,
        hints: &[&str],
    ) -> Self {
        Candidate {
            id: id.to_string(),
            kind,
            fields: Vec::new(),
            prompt: prompt.to_string(),
            answer: vec![answer],
            many: false,
            hints: hints.iter().map(|h| h.to_string()).collect(),
        }
    }

    pub(super) fn with(mut self, key: &'static str, value: Field) -> Self {
        self.fields.push((key, value));
        self
    }
}
