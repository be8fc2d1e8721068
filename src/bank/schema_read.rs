//! Reading a problem file's TOML into the schema's types without serde's derive: the parsed
//! document (toml's spanned `DeTable`) is walked by [`FromToml`], implemented once per schema
//! type by [`schema_struct!`] and by hand for the few types that take more than one form.
//!
//! Why not `#[derive(Deserialize)]`: each derived type is compiled once per toml deserializer
//! it can meet (value, table, array, spanned), ≈ 100 KB of the WebAssembly module the browser
//! page downloads; this walker is a tenth of that. The messages and positions are serde's and
//! toml's own, word for word (`missing field`, `unknown field … expected one of`, `invalid
//! type: …, expected …`), which the bank's findings and their tests rely on; a unit test
//! compares the two readers on every bank file and thousands of broken variations of them.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::ops::Range;

use serde::de::Unexpected;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// A reading error: toml's message and the byte span it points at.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadError {
    /// The message, as serde and toml word it.
    pub(crate) message: String,
    /// Where in the file, when known.
    pub(crate) span: Option<Range<usize>>,
}

impl ReadError {
    fn new(message: String, span: Range<usize>) -> ReadError {
        ReadError {
            message,
            span: Some(span),
        }
    }
}

/// Parses `text` as TOML and reads it as `T` (the whole file's table).
pub fn from_str<T: FromToml>(text: &str) -> Result<T, ReadError> {
    let root = DeTable::parse(text).map_err(|e| ReadError {
        message: e.message().to_string(),
        span: e.span(),
    })?;
    let span = root.span();
    T::read(&Spanned::new(span, DeValue::Table(root.into_inner())))
}

/// A schema type read from a TOML value.
pub trait FromToml: Sized {
    /// Reads `v`; an error points at the innermost value at fault.
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError>;

    /// The value of a field left out, when leaving it out is allowed (`Option`).
    fn missing() -> Option<Self> {
        None
    }
}

/// A TOML value as serde's visitors meet it.
enum Seen<'a, 'i> {
    Str(&'a str),
    Signed(i64),
    Unsigned(u64),
    Signed128(i128),
    Unsigned128(u128),
    Float(f64),
    Bool(bool),
    Seq(&'a [Spanned<DeValue<'i>>]),
    Map(&'a DeTable<'i>),
    /// A date-time: serde sees a one-entry map holding its text.
    Datetime(String),
}

/// What `v` is to a visitor, or toml's error for a number it cannot hold.
fn seen<'a, 'i>(v: &'a Spanned<DeValue<'i>>) -> Result<Seen<'a, 'i>, ReadError> {
    Ok(match v.get_ref() {
        DeValue::String(s) => Seen::Str(s),
        DeValue::Integer(n) => {
            let (text, radix) = (n.as_str(), n.radix());
            if let Ok(x) = i64::from_str_radix(text, radix) {
                Seen::Signed(x)
            } else if let Ok(x) = u64::from_str_radix(text, radix) {
                Seen::Unsigned(x)
            } else if let Ok(x) = i128::from_str_radix(text, radix) {
                Seen::Signed128(x)
            } else if let Ok(x) = u128::from_str_radix(text, radix) {
                Seen::Unsigned128(x)
            } else {
                return Err(ReadError::new("integer number overflowed".into(), v.span()));
            }
        }
        DeValue::Float(f) => match f.as_str().parse::<f64>() {
            Ok(x) if !x.is_infinite() || f.as_str().contains("inf") => Seen::Float(x),
            _ => {
                let message = "floating-point number overflowed".into();
                return Err(ReadError::new(message, v.span()));
            }
        },
        DeValue::Boolean(b) => Seen::Bool(*b),
        DeValue::Datetime(d) => Seen::Datetime(d.to_string()),
        DeValue::Array(a) => Seen::Seq(a),
        DeValue::Table(t) => Seen::Map(t),
    })
}

/// serde's `invalid type: {what}, expected {expected}` at `v`.
fn invalid_type(v: &Spanned<DeValue<'_>>, what: &Seen<'_, '_>, expected: &str) -> ReadError {
    let text;
    let unexpected = match what {
        Seen::Str(s) => Unexpected::Str(s),
        Seen::Signed(x) => Unexpected::Signed(*x),
        Seen::Unsigned(x) => Unexpected::Unsigned(*x),
        Seen::Signed128(x) => {
            text = format!("integer `{x}` as i128");
            Unexpected::Other(&text)
        }
        Seen::Unsigned128(x) => {
            text = format!("integer `{x}` as u128");
            Unexpected::Other(&text)
        }
        Seen::Float(x) => Unexpected::Float(*x),
        Seen::Bool(b) => Unexpected::Bool(*b),
        Seen::Seq(_) => Unexpected::Seq,
        Seen::Map(_) | Seen::Datetime(_) => Unexpected::Map,
    };
    let message = format!("invalid type: {unexpected}, expected {expected}");
    ReadError::new(message, v.span())
}

/// serde's `invalid value: {what}, expected {expected}` at `v`.
pub(crate) fn invalid_value(
    v: &Spanned<DeValue<'_>>,
    what: Unexpected,
    expected: &str,
) -> ReadError {
    ReadError::new(
        format!("invalid value: {what}, expected {expected}"),
        v.span(),
    )
}

/// The integer `v` holds when it fits an `i64` (`None` otherwise, or for another type), or
/// toml's error for a number it cannot hold.
pub(crate) fn integer(v: &Spanned<DeValue<'_>>) -> Result<Option<i64>, ReadError> {
    Ok(match seen(v)? {
        Seen::Signed(x) => Some(x),
        _ => None,
    })
}

/// The error any visitor that takes only `expected` gives `v`.
pub(crate) fn wrong_type(v: &Spanned<DeValue<'_>>, expected: &str) -> ReadError {
    match seen(v) {
        Ok(what) => invalid_type(v, &what, expected),
        Err(e) => e,
    }
}

/// A table's entries: each key with its span, and its value (borrowed from the table; owned
/// only for a date-time's one entry, so reading never clones a parsed value).
pub(crate) type Entries<'a, 'i> = Vec<(Spanned<String>, Cow<'a, Spanned<DeValue<'i>>>)>;

/// The entries of `v` as a table (a date-time is the one-entry map serde sees), or serde's
/// error for a value of another type.
pub(crate) fn entries<'a, 'i>(
    v: &'a Spanned<DeValue<'i>>,
    expected: &str,
) -> Result<Entries<'a, 'i>, ReadError> {
    match seen(v)? {
        Seen::Map(t) => Ok(t
            .iter()
            .map(|(k, x)| {
                let key = Spanned::new(k.span(), k.get_ref().to_string());
                (key, Cow::Borrowed(x))
            })
            .collect()),
        Seen::Datetime(text) => {
            let key = Spanned::new(v.span(), "$__toml_private_datetime".to_string());
            let value = DeValue::String(text.into());
            Ok(vec![(key, Cow::Owned(Spanned::new(v.span(), value)))])
        }
        what => Err(invalid_type(v, &what, expected)),
    }
}

/// serde's `unknown field` error for `key` of a struct with `fields`.
pub(crate) fn unknown_field(key: &Spanned<String>, fields: &[&str]) -> ReadError {
    let listed = |fs: &[&str]| {
        fs.iter()
            .map(|f| format!("`{f}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let expected = match fields {
        [] => "there are no fields".to_string(),
        [a] => format!("expected {}", listed(&[a])),
        [a, b] => format!("expected `{a}` or `{b}`"),
        _ => format!("expected one of {}", listed(fields)),
    };
    let message = format!("unknown field `{}`, {expected}", key.get_ref());
    ReadError::new(message, key.span())
}

/// serde's `invalid length` error of a struct read from the array `v` that ends early.
pub(crate) fn invalid_length(v: &Spanned<DeValue<'_>>, index: usize, expecting: &str) -> ReadError {
    ReadError::new(
        format!("invalid length {index}, expected {expecting}"),
        v.span(),
    )
}

/// The first number in `v` (depth first) that toml cannot hold, as the error serde meets
/// when it reads `v` whole before trying an untagged enum's forms.
pub(crate) fn numbers_fit(v: &Spanned<DeValue<'_>>) -> Result<(), ReadError> {
    match seen(v)? {
        Seen::Seq(items) => items.iter().try_for_each(numbers_fit),
        Seen::Map(t) => t.values().try_for_each(numbers_fit),
        // serde's buffer takes no 128-bit integer.
        what @ (Seen::Signed128(_) | Seen::Unsigned128(_)) => {
            Err(invalid_type(v, &what, "any value"))
        }
        _ => Ok(()),
    }
}

/// serde's `missing field` error, at the table `v` that lacks it.
pub(crate) fn missing_field(v: &Spanned<DeValue<'_>>, field: &str) -> ReadError {
    ReadError::new(format!("missing field `{field}`"), v.span())
}

/// The per-struct step of [`fields`]: reads field `i` (by position) from a value.
pub(crate) type PutField<'f> =
    dyn FnMut(usize, &Spanned<DeValue<'_>>) -> Result<(), ReadError> + 'f;

/// Hands each field of a struct read from `v` to `put`, by its position in `fields`: from a
/// table, in the file's order, with serde's `unknown field` error for a key not in `fields`;
/// from an array (serde's derive reads a struct from one too), field by field, with serde's
/// `invalid length` error where the array ends before a field without a default
/// (`defaults`). A field the table lacks is left to the caller. One compiled copy serves
/// every schema struct: only `put` is per struct.
pub(crate) fn fields(
    v: &Spanned<DeValue<'_>>,
    name: &str,
    fields: &[&str],
    defaults: &[bool],
    put: &mut PutField<'_>,
) -> Result<(), ReadError> {
    if let DeValue::Array(items) = v.get_ref() {
        for (index, default) in defaults.iter().enumerate() {
            match items.get(index) {
                Some(x) => put(index, x)?,
                None if *default => {}
                None => {
                    let n = fields.len();
                    let s = if n == 1 { "" } else { "s" };
                    let expecting = format!("struct {name} with {n} element{s}");
                    return Err(invalid_length(v, index, &expecting));
                }
            }
        }
        return Ok(());
    }
    for (key, value) in entries(v, &format!("struct {name}"))? {
        match fields.iter().position(|f| *f == key.get_ref().as_str()) {
            Some(index) => put(index, &value)?,
            None => return Err(unknown_field(&key, fields)),
        }
    }
    Ok(())
}

impl FromToml for String {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        match seen(v)? {
            Seen::Str(s) => Ok(s.to_string()),
            what => Err(invalid_type(v, &what, "a string")),
        }
    }
}

impl FromToml for bool {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        match seen(v)? {
            Seen::Bool(b) => Ok(b),
            what => Err(invalid_type(v, &what, "a boolean")),
        }
    }
}

impl FromToml for f64 {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        match seen(v)? {
            Seen::Float(x) => Ok(x),
            Seen::Signed(x) => Ok(x as f64),
            Seen::Unsigned(x) => Ok(x as f64),
            what => Err(invalid_type(v, &what, "f64")),
        }
    }
}

/// An unsigned integer type as serde reads it: from any integer in its range.
macro_rules! read_unsigned {
    ($t:ty) => {
        impl FromToml for $t {
            fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
                let name = stringify!($t);
                match seen(v)? {
                    Seen::Signed(x) => {
                        <$t>::try_from(x).map_err(|_| invalid_value(v, Unexpected::Signed(x), name))
                    }
                    Seen::Unsigned(x) => <$t>::try_from(x)
                        .map_err(|_| invalid_value(v, Unexpected::Unsigned(x), name)),
                    what => Err(invalid_type(v, &what, name)),
                }
            }
        }
    };
}
read_unsigned!(u32);
read_unsigned!(usize);

impl<T: FromToml> FromToml for Option<T> {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        T::read(v).map(Some)
    }

    fn missing() -> Option<Self> {
        Some(None)
    }
}

impl<T: FromToml> FromToml for Vec<T> {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        match seen(v)? {
            // A loop rather than `collect`: a collected `Result` costs more code per element type.
            Seen::Seq(items) => {
                let mut out = Vec::with_capacity(items.len());
                for x in items {
                    out.push(T::read(x)?);
                }
                Ok(out)
            }
            what => Err(invalid_type(v, &what, "a sequence")),
        }
    }
}

impl<T: FromToml> FromToml for BTreeMap<String, T> {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        let mut out = BTreeMap::new();
        for (k, x) in entries(v, "a map")? {
            out.insert(k.into_inner(), T::read(&x)?);
        }
        Ok(out)
    }
}

impl<T: FromToml> FromToml for Spanned<T> {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        Ok(Spanned::new(v.span(), T::read(v)?))
    }
}

/// Defines a schema struct and its reading together, from the struct written as it would be
/// for serde's derive: each field one line, `pub name: Type,`, after its doc comment and at
/// most one `#[serde(default)]` (a missing field is its type's default) or
/// `#[serde(rename = "key")]`. A field is required unless its type is an `Option` or it has
/// `#[serde(default)]`; unknown keys are errors. So adding a field is adding its line:
///
/// ```ignore
/// schema_struct! {
/// /// A part of a problem.
/// pub struct PartSpec {
///     /// What the part is about, shown with its prompt.
///     pub about: Option<String>,
///     #[serde(default)]
///     pub omit_zero_modes: bool,
/// }
/// }
/// ```
///
/// Tests also derive serde's `Deserialize` from the same lines, to compare the two readers.
macro_rules! schema_struct {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(
                $(#[doc = $doc:literal])*
                $(#[serde($($attr:tt)*)])?
                pub $field:ident : $ty:ty
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug)]
        #[cfg_attr(test, derive(serde::Deserialize))]
        #[cfg_attr(test, serde(deny_unknown_fields))]
        pub struct $name {
            $(
                $(#[doc = $doc])*
                $(#[cfg_attr(test, serde($($attr)*))])?
                pub $field: $ty,
            )*
        }

        impl $crate::bank::schema_read::FromToml for $name {
            fn read(
                v: &toml::Spanned<toml::de::DeValue<'_>>,
            ) -> Result<Self, $crate::bank::schema_read::ReadError> {
                use $crate::bank::schema_read as read;
                const FIELDS: &[&str] = &[$(schema_struct!(@key $field $($($attr)*)?)),*];
                const DEFAULTS: &[bool] = &[$(schema_struct!(@default $($($attr)*)?)),*];
                $(let mut $field: Option<$ty> = None;)*
                // Field `i` read from `x`: the one typed step, shared by both forms.
                read::fields(v, stringify!($name), FIELDS, DEFAULTS, &mut |i, x| {
                    let mut k = 0usize;
                    $(
                        if i == k {
                            $field = Some(read::FromToml::read(x)?);
                        }
                        k += 1;
                    )*
                    let _ = k;
                    Ok(())
                })?;
                Ok($name {
                    $($field: match $field {
                        Some(x) => x,
                        None => schema_struct!(
                            @missing v, $ty, schema_struct!(@key $field $($($attr)*)?) $(, $($attr)*)?
                        ),
                    },)*
                })
            }
        }
    };
    // The key a field is read from.
    (@key $field:ident rename = $key:literal) => { $key };
    (@key $field:ident $($attr:tt)*) => { stringify!($field) };
    // Whether a field the file lacks takes its type's default.
    (@default default) => { true };
    (@default $($attr:tt)*) => { false };
    // A field the table form lacks.
    (@missing $v:ident, $ty:ty, $key:expr, default) => { <$ty>::default() };
    (@missing $v:ident, $ty:ty, $key:expr $(, $($attr:tt)*)?) => {
        match <$ty as $crate::bank::schema_read::FromToml>::missing() {
            Some(x) => x,
            None => return Err($crate::bank::schema_read::missing_field($v, $key)),
        }
    };
}
pub(crate) use schema_struct;

#[cfg(test)]
#[path = "schema_read_tests.rs"]
mod tests;
