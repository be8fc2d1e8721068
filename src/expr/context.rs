//! The reading context: which names are coordinates, which are parameters, and whether an
//! unknown name is an error (a problem's answer) or a new parameter (a Lagrangian typed at
//! the command line).

use super::names;
use super::node::Func;

/// Function names accepted by the parser, including those rewritten on reading.
pub const FUNCTION_NAMES: &[&str] = &[
    "sin", "cos", "tan", "sec", "csc", "cot", "asin", "acos", "atan", "sinh", "cosh", "tanh",
    "exp", "log", "ln", "sqrt", "abs", "dot", "ddot", "arcsin", "arccos", "arctan",
];

/// A function as written (before `sec` → 1/cos and friends).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Call {
    F(Func),
    Sec,
    Csc,
    Cot,
    Sqrt,
}

/// The call named `name`, if it is one (`dot` and `ddot` are handled by the parser).
pub(crate) fn call_named(name: &str) -> Option<Call> {
    Some(match name {
        "sec" => Call::Sec,
        "csc" => Call::Csc,
        "cot" => Call::Cot,
        "sqrt" => Call::Sqrt,
        "ln" => Call::F(Func::Log),
        "arcsin" => Call::F(Func::Asin),
        "arccos" => Call::F(Func::Acos),
        "arctan" => Call::F(Func::Atan),
        _ => Call::F(*Func::ALL.iter().find(|f| f.name() == name)?),
    })
}

/// How a name was resolved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Resolved {
    /// A coordinate (declared, or implied by a derivative mark in an open context) and the
    /// derivative order.
    Coordinate(String, u8),
    /// A parameter (a constant).
    Parameter(String),
    /// The time `t`.
    Time,
    /// π.
    Pi,
}

/// Declared names. Names are stored normalized (`m_1` → `m1`).
#[derive(Clone, Debug, Default)]
pub struct Context {
    coordinates: Vec<String>,
    parameters: Vec<String>,
    open: bool,
    /// The longest input read in this context, in bytes (`None`: the default limit, sized
    /// for answers; a system's own text may be larger).
    max_input: Option<usize>,
    /// Named quantities a problem defines (`theta0` = `acos(g/(R*omega^2))`), normalized
    /// name and text in the parameters: a definition's name reads as its value.
    definitions: Vec<(String, String)>,
}

impl Context {
    /// A closed context: only declared names may appear.
    pub fn new() -> Self {
        Context::default()
    }

    /// An open context: any unknown name is a parameter.
    pub fn open() -> Self {
        Context {
            open: true,
            ..Context::default()
        }
    }

    /// Declares coordinates.
    pub fn with_coordinates<S: AsRef<str>>(mut self, names: impl IntoIterator<Item = S>) -> Self {
        for n in names {
            let n = names::normalize(n.as_ref());
            if !self.coordinates.contains(&n) {
                self.coordinates.push(n);
            }
        }
        self
    }

    /// Declares parameters.
    pub fn with_parameters<S: AsRef<str>>(mut self, names: impl IntoIterator<Item = S>) -> Self {
        for n in names {
            let n = names::normalize(n.as_ref());
            if !self.parameters.contains(&n) {
                self.parameters.push(n);
            }
        }
        self
    }

    /// Declares named quantities: each name reads as its text's value (the text is read in
    /// this context without the definitions, so one definition never refers to another).
    pub fn with_definitions<S: AsRef<str>, T: AsRef<str>>(
        mut self,
        definitions: impl IntoIterator<Item = (S, T)>,
    ) -> Self {
        for (n, text) in definitions {
            let n = names::normalize(n.as_ref());
            if !self.definitions.iter().any(|(d, _)| *d == n) {
                self.definitions.push((n, text.as_ref().to_string()));
            }
        }
        self
    }

    /// The text a defined name stands for (`None` when `raw` names no definition).
    pub(crate) fn definition(&self, raw: &str) -> Option<&str> {
        let name = names::normalize(raw);
        self.definitions
            .iter()
            .find(|(d, _)| *d == name)
            .map(|(_, t)| t.as_str())
    }

    /// This context without its definitions: where a definition's own text is read.
    pub(crate) fn without_definitions(&self) -> Context {
        Context {
            definitions: Vec::new(),
            ..self.clone()
        }
    }

    /// The defined names, normalized, in order.
    pub fn defined_names(&self) -> impl Iterator<Item = &str> {
        self.definitions.iter().map(|(n, _)| n.as_str())
    }

    /// Raises (or lowers) the input limit: a system's Lagrangian may be far larger than an
    /// answer (a bicycle's T is 24 kB).
    pub fn with_max_input(mut self, bytes: usize) -> Self {
        self.max_input = Some(bytes);
        self
    }

    /// The longest input read in this context, in bytes.
    pub fn max_input(&self) -> usize {
        self.max_input.unwrap_or(super::error::MAX_INPUT_BYTES)
    }

    /// Whether unknown names become parameters.
    pub(crate) fn is_open(&self) -> bool {
        self.open
    }

    /// Declared coordinates, in order.
    pub fn coordinates(&self) -> &[String] {
        &self.coordinates
    }

    /// Declared parameters, in order.
    pub fn parameters(&self) -> &[String] {
        &self.parameters
    }

    /// Whether `name` is a declared coordinate.
    pub fn is_coordinate(&self, name: &str) -> bool {
        self.coordinates.iter().any(|c| c == name)
    }

    /// Whether `name` is a declared parameter.
    pub(crate) fn is_parameter(&self, name: &str) -> bool {
        self.parameters.iter().any(|c| c == name)
    }

    /// Whether `name` (as typed) is a declared coordinate or parameter: such a name keeps
    /// its meaning even where it could start a notation (`d` in `d/dt`, `sqrt2`).
    pub(crate) fn is_declared(&self, raw: &str) -> bool {
        let name = names::normalize(raw);
        self.is_coordinate(&name) || self.is_parameter(&name)
    }

    /// Resolves a plain name (no derivative marks). `None` means unknown.
    pub(crate) fn resolve(&self, raw: &str) -> Option<Resolved> {
        let name = names::normalize(raw);
        if name == "pi" {
            return Some(Resolved::Pi);
        }
        if name == "t" && !self.is_parameter("t") && !self.is_coordinate("t") {
            return Some(Resolved::Time);
        }
        if self.is_coordinate(&name) {
            return Some(Resolved::Coordinate(name, 0));
        }
        if self.is_parameter(&name) {
            return Some(Resolved::Parameter(name));
        }
        for (suffix, order) in [("_ddot", 2), ("ddot", 2), ("_dot", 1), ("dot", 1)] {
            if let Some(base) = raw.strip_suffix(suffix) {
                let base = names::normalize(base);
                if self.is_coordinate(&base) {
                    return Some(Resolved::Coordinate(base, order));
                }
            }
        }
        if self.open {
            return Some(Resolved::Parameter(name));
        }
        None
    }

    /// The known name closest to `name`, if close enough to be a likely typo.
    pub(crate) fn suggest(&self, name: &str) -> Option<String> {
        // `T` is the kinetic energy, not a typo for `g`: its help says so instead.
        if super::error::quantity_name(name).is_some() {
            return None;
        }
        let mut candidates: Vec<String> = Vec::new();
        for c in &self.coordinates {
            candidates.push(c.clone());
            candidates.push(format!("{c}dot"));
            candidates.push(format!("{c}ddot"));
        }
        candidates.extend(self.parameters.iter().cloned());
        candidates.push("pi".into());
        closest(name, candidates.iter().map(String::as_str))
    }

    /// The function name closest to `name`.
    pub(crate) fn suggest_function(name: &str) -> Option<String> {
        closest(name, FUNCTION_NAMES.iter().copied())
    }

    /// `mgl` → `m*g*l` when the name is a run of declared names.
    pub fn split(&self, name: &str) -> Option<String> {
        let known: Vec<&str> = self
            .coordinates
            .iter()
            .chain(&self.parameters)
            .map(String::as_str)
            .collect();
        let parts = split_into(name, &known, 0)?;
        (parts.len() > 1).then(|| parts.join("*"))
    }
}

fn split_into<'a>(s: &str, known: &[&'a str], depth: usize) -> Option<Vec<&'a str>> {
    if s.is_empty() {
        return Some(Vec::new());
    }
    if depth > 16 {
        return None;
    }
    let mut best: Option<Vec<&'a str>> = None;
    for k in known {
        if let Some(rest) = s.strip_prefix(k)
            && let Some(mut tail) = split_into(rest, known, depth + 1)
        {
            tail.insert(0, k);
            if best.as_ref().is_none_or(|b| tail.len() < b.len()) {
                best = Some(tail);
            }
        }
    }
    best
}

/// The closest candidate by edit distance (with transpositions); ties go to the first.
fn closest<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<String> {
    let limit = if name.chars().count() <= 3 { 1 } else { 2 };
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c == name {
            continue;
        }
        // A difference of case only (`M` for `m`) is the likeliest slip of all.
        if c.eq_ignore_ascii_case(name) {
            return Some(c.to_string());
        }
        let d = strsim::damerau_levenshtein(name, c);
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolution() {
        let ctx = Context::new()
            .with_coordinates(["theta", "x_1"])
            .with_parameters(["m", "g"]);
        let cases = [
            ("theta", Some(Resolved::Coordinate("theta".into(), 0))),
            ("thetadot", Some(Resolved::Coordinate("theta".into(), 1))),
            ("theta_dot", Some(Resolved::Coordinate("theta".into(), 1))),
            ("thetaddot", Some(Resolved::Coordinate("theta".into(), 2))),
            ("theta_ddot", Some(Resolved::Coordinate("theta".into(), 2))),
            ("x1", Some(Resolved::Coordinate("x1".into(), 0))),
            ("x_1dot", Some(Resolved::Coordinate("x1".into(), 1))),
            ("m", Some(Resolved::Parameter("m".into()))),
            ("t", Some(Resolved::Time)),
            ("pi", Some(Resolved::Pi)),
            ("mdot", None),
            ("k", None),
        ];
        for (name, want) in cases {
            assert_eq!(ctx.resolve(name), want, "{name}");
        }
        let open = Context::open().with_coordinates(["q"]);
        assert_eq!(open.resolve("k"), Some(Resolved::Parameter("k".into())));
        assert_eq!(
            open.resolve("qdot"),
            Some(Resolved::Coordinate("q".into(), 1))
        );
    }

    #[test]
    fn suggestions() {
        let ctx = Context::new()
            .with_coordinates(["theta"])
            .with_parameters(["m", "g", "l"]);
        assert_eq!(ctx.suggest("thta").as_deref(), Some("theta"));
        assert_eq!(ctx.suggest("tehta").as_deref(), Some("theta"));
        assert_eq!(ctx.suggest("zzzzz"), None);
        assert_eq!(ctx.split("mgl").as_deref(), Some("m*g*l"));
        assert_eq!(ctx.split("mx"), None);
        assert_eq!(Context::suggest_function("sinn").as_deref(), Some("sin"));
    }
}
