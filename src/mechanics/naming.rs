//! Which names can be coordinates: not time, π or a function, one name, and each listed once.
//! A leaf of the mechanics layer, so that systems and errors can both use it.

use crate::expr::error::visible;
use crate::expr::{Context, Pool, read_expr};

/// Why a name cannot be a coordinate: it reads as something else, or is listed twice.
/// `System::from_lagrangian` and `System::from_energies` check the names they are given
/// with [`check_coordinate_names`], so that `t`, `sin` or a repeated `x` get their own message
/// rather than a degenerate mass matrix.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NameError {
    /// `t` is time.
    #[error("`t` is time, not a coordinate")]
    Time,
    /// `pi` is π.
    #[error("`{0}` is the constant π, not a coordinate")]
    Pi(String),
    /// A function's name.
    #[error("`{0}` is a function, not a coordinate")]
    Function(String),
    /// Not one name (`2x`, `x'`, `a+b`, empty).
    #[error("`{0}` is not a name")]
    NotAName(String),
    /// The same coordinate twice.
    #[error("coordinate `{0}` is listed twice")]
    Repeated(String),
}

impl NameError {
    /// A stable code.
    pub fn code(&self) -> &'static str {
        match self {
            NameError::Repeated(_) => "repeated-coordinate",
            NameError::NotAName(_) => "not-a-name",
            _ => "reserved-name",
        }
    }

    /// What the name is, for a message about a parameter as well as a coordinate.
    pub fn reason(&self) -> String {
        match self {
            NameError::Time => "`t` is time".into(),
            NameError::Pi(n) => format!("`{n}` is the constant π"),
            NameError::Function(n) => format!("`{n}` is a function"),
            NameError::NotAName(n) => format!("`{n}` is not a name"),
            NameError::Repeated(n) => format!("`{n}` is listed twice"),
        }
    }

    /// One line on how to fix it.
    pub fn help(&self) -> String {
        match self {
            NameError::Repeated(_) => "list each coordinate once".into(),
            NameError::NotAName(_) => "a coordinate is a name such as x, theta or theta1".into(),
            _ => "choose another name for the coordinate, e.g. x, theta or q1".into(),
        }
    }
}

/// Checks that `name` can be a coordinate (or a parameter): not time, π or a function, and
/// one name.
pub fn check_coordinate_name(name: &str) -> Result<(), NameError> {
    let n = crate::expr::names::normalize(name.trim());
    if n == "t" {
        return Err(NameError::Time);
    }
    if n == "pi" || n == "π" {
        return Err(NameError::Pi(n));
    }
    if crate::expr::context::FUNCTION_NAMES.contains(&n.as_str()) {
        return Err(NameError::Function(n));
    }
    // It must read back as itself: one name, not a number, a sum or a derivative.
    let mut pool = Pool::new();
    let ctx = Context::new().with_coordinates([n.as_str()]);
    match read_expr(&n, &ctx, &mut pool).map(|e| pool.node(e).clone()) {
        Ok(crate::expr::Node::Var(s, 0)) if pool.name(s) == n => Ok(()),
        _ => Err(NameError::NotAName(visible(name))),
    }
}

/// Checks every name of a coordinate list, and that none is listed twice.
pub fn check_coordinate_names(names: &[&str]) -> Result<(), NameError> {
    let mut seen: Vec<String> = Vec::new();
    for name in names {
        check_coordinate_name(name)?;
        let n = crate::expr::names::normalize(name.trim());
        if seen.contains(&n) {
            return Err(NameError::Repeated(n));
        }
        seen.push(n);
    }
    Ok(())
}
