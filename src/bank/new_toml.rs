//! The text of a drafted problem file (`problems new`): the system's part — placeholders for
//! the instructor's words, coordinates, parameters, the Lagrangian or the bodies and
//! potentials — and the parts, with a comment for each part left out. Every string is written
//! as an escaped TOML basic string, so no expression or name can break the file.

use super::new_types::{Candidate, Field, LeftOut, Param, Spec, Table, Value};

/// The first lines of every drafted file.
const HEADER: &str = "\
# Drafted by `lagrange problems new`: every answer below was derived from the system and proved
# by `lagrange problems verify`. Replace each EDIT placeholder (title, source, statement, axes,
# descriptions, prompts) with your own words and review the hints; verify again after editing.
";

/// A TOML basic string: `"…"` with `\\`, `\"` and control characters escaped.
pub(super) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A key: bare when TOML allows it, quoted otherwise.
fn key(name: &str) -> String {
    let bare = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare { name.to_string() } else { quote(name) }
}

/// `["a", "b"]`.
fn list(items: &[String]) -> String {
    let quoted: Vec<String> = items.iter().map(|s| quote(s)).collect();
    format!("[{}]", quoted.join(", "))
}

/// A number as TOML writes a float (always with a point, so it reads back as a float).
fn float(x: f64) -> String {
    let s = format!("{x}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// The file up to its parts: header, placeholders, coordinates (a range where the
/// equilibria need a wider one than the default), the Lagrangian or the bodies, parameters.
pub(super) fn skeleton(spec: &Spec, params: &[Param], ranges: &[Option<(f64, f64)>]) -> String {
    let mut s = String::from(HEADER);
    s.push_str(&format!("id = {}\n", quote(&spec.id)));
    let title = spec
        .title
        .clone()
        .unwrap_or_else(|| format!("EDIT: a title for {}", spec.id));
    s.push_str(&format!("title = {}\n", quote(&title)));
    s.push_str("source = \"EDIT: where the problem comes from\"\n");
    let names: Vec<String> = params.iter().map(|p| format!("${}$", p.name)).collect();
    s.push_str(&format!(
        "statement = \"\"\"\nEDIT: describe the system for the student, naming the coordinate{} ({}){}.\n\"\"\"\n",
        if spec.coordinates.len() == 1 { "" } else { "s" },
        spec.coordinates
            .iter()
            .map(|c| format!("${c}$"))
            .collect::<Vec<_>>()
            .join(", "),
        if names.is_empty() {
            String::new()
        } else {
            format!(" and the parameters ({})", names.join(", "))
        }
    ));
    if !spec.bodies.is_empty() {
        s.push_str("axes = \"EDIT: the axes and origin the positions use, e.g. x horizontal, y up, origin at the pivot\"\n");
    }
    s.push_str("coordinates = [\n");
    for (c, range) in spec.coordinates.iter().zip(ranges) {
        let periodic = crate::mechanics::system::looks_like_angle(c);
        let mut fields = vec![format!("name = {}", quote(c))];
        if periodic {
            fields.push("periodic = true".into());
        }
        if let Some((lo, hi)) = range {
            fields.push(format!("range = [{}, {}]", float(*lo), float(*hi)));
        }
        fields.push(format!(
            "description = {}",
            quote(&format!("EDIT: what {c} measures"))
        ));
        s.push_str(&format!("  {{ {} }},\n", fields.join(", ")));
    }
    s.push_str("]\n");
    if let Some(l) = &spec.lagrangian {
        s.push_str(&format!("lagrangian = {}\n", quote(l.trim())));
    }
    s.push_str("\n[parameters]\n");
    for p in params {
        s.push_str(&format!(
            "{} = {{ dimension = {}, range = [{}, {}], value = {}, description = {} }}\n",
            key(&p.name),
            quote(&p.dimension),
            float(p.range.0),
            float(p.range.1),
            float(p.value),
            quote(&format!("EDIT: what {} is", p.name))
        ));
    }
    for (title, tables) in [("bodies", &spec.bodies), ("potentials", &spec.potentials)] {
        for t in tables {
            s.push_str(&table(title, t));
        }
    }
    s
}

/// One `[[bodies]]` or `[[potentials]]` table.
fn table(title: &str, t: &Table) -> String {
    let mut s = format!("\n[[{title}]]\nkind = {}\n", quote(&t.kind));
    for (key, v) in &t.fields {
        let value = match v {
            Value::Text(x) => quote(x),
            Value::List(items) => list(items),
            Value::Rows(rows) => {
                let rows: Vec<String> = rows.iter().map(|r| list(r)).collect();
                format!("[{}]", rows.join(", "))
            }
            Value::Body(n) => n.to_string(),
        };
        s.push_str(&format!("{key} = {value}\n"));
    }
    s
}

/// The whole file: `base` (from [`skeleton`]), the stated parts, and a comment for each part
/// left out, with its reason.
pub(super) fn compose(base: &str, parts: &[Candidate], left_out: &[LeftOut]) -> String {
    let mut s = base.to_string();
    for p in parts {
        s.push_str(&part(p));
    }
    if !left_out.is_empty() {
        s.push_str("\n# Parts not stated, and why (write them by hand if you need them):\n");
        for l in left_out {
            let reason = l.reason.replace(['\n', '\r'], " ");
            s.push_str(&format!("# - {}: {}\n", l.part, reason));
        }
    }
    s
}

/// One `[[parts]]` table.
fn part(p: &Candidate) -> String {
    let mut s = format!(
        "\n[[parts]]\nid = {}\nkind = {}\n",
        quote(&p.id),
        quote(p.kind)
    );
    for (key, f) in &p.fields {
        let value = match f {
            Field::Str(x) => quote(x),
            Field::Bool(b) => b.to_string(),
            Field::Strs(items) => list(items),
            Field::Map(pairs) => {
                let items: Vec<String> = pairs
                    .iter()
                    .map(|(k, v)| format!("{} = {}", quote(k), quote(v)))
                    .collect();
                format!("{{ {} }}", items.join(", "))
            }
        };
        s.push_str(&format!("{key} = {value}\n"));
    }
    s.push_str(&format!("prompt = {}\n", quote(&p.prompt)));
    let answer = if p.many {
        list(&p.answer)
    } else {
        quote(p.answer.first().map_or("", String::as_str))
    };
    s.push_str(&format!("answer = {answer}\n"));
    if !p.hints.is_empty() {
        s.push_str("hints = [\n");
        for h in &p.hints {
            s.push_str(&format!("  {},\n", quote(h)));
        }
        s.push_str("]\n");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_are_escaped_and_read_back_whole() {
        let nasty = "a \"quoted\" \\ back\nslash\u{1b}[31m";
        let text = format!("v = {}\n", quote(nasty));
        let t: toml::Table = toml::from_str(&text).expect("valid TOML");
        assert_eq!(t["v"].as_str(), Some(nasty));
        assert_eq!(float(2.0), "2.0");
        assert_eq!(float(9.81), "9.81");
    }
}
