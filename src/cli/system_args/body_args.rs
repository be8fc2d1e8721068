//! Bodies and point forces on the command line: `--point "mass=m; position=x, y"`,
//! `--rigid "mass=M; position=…; inertia=I; angle=theta"` (or `moments=…`/`tensor=…` with
//! `omega_body=…`/`euler=…`), `--gravity "g"` or `"g, z"`, `--spring "k=k; from=1; to=0, 0"`, and
//! `--force-at "x, y: Fx, Fy"`.
//! The text is split here; the physics is the library's (`mechanics::rigid`).

use lagrange::expr::Id;
use lagrange::mechanics::bodies::{Anchor, Body, Potential};
use lagrange::mechanics::{MechError, RigidSpec, System};

use super::CliError;

/// Splits at top-level occurrences of `sep` (not inside parentheses or brackets), trimmed.
pub(crate) fn split_top(text: &str, sep: char) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            c if c == sep && depth == 0 => {
                parts.push(text[start..i].trim());
                start = i + c.len_utf8();
            }
            _ => {}
        }
    }
    parts.push(text[start..].trim());
    parts
}

/// `key=value; key=value` as pairs, each key once and known to `flag`.
fn fields<'a>(
    flag: &str,
    text: &'a str,
    known: &[&str],
) -> Result<Vec<(&'a str, &'a str)>, CliError> {
    let mut out: Vec<(&str, &str)> = Vec::new();
    for item in split_top(text, ';').into_iter().filter(|s| !s.is_empty()) {
        let Some((k, v)) = item.split_once('=') else {
            return Err(CliError::Usage(format!(
                "{flag}: `{item}` is not key=value (keys: {}; fields are separated by `;`)",
                known.join(", ")
            )));
        };
        let k = k.trim();
        // The names before the command line took the problem file's.
        if let Some((_, now)) = [("at", "position"), ("omega", "omega_body")]
            .iter()
            .find(|(old, now)| *old == k && known.contains(now))
        {
            return Err(CliError::Usage(format!(
                "{flag}: `{k}=` is now `{now}=`, the name a problem file uses"
            )));
        }
        if !known.contains(&k) {
            return Err(CliError::Usage(format!(
                "{flag}: unknown key `{k}` (keys: {})",
                known.join(", ")
            )));
        }
        if out.iter().any(|(o, _)| *o == k) {
            return Err(CliError::Usage(format!("{flag}: `{k}` given twice")));
        }
        out.push((k, v.trim()));
    }
    Ok(out)
}

/// Reads a comma-separated list of expressions into the system's pool.
fn list(sys: &mut System, text: &str, what: &str) -> Result<Vec<Id>, CliError> {
    let ctx = sys.open_context();
    split_top(text, ',')
        .into_iter()
        .map(|t| sys.read(t, what, &ctx).map_err(CliError::from))
        .collect()
}

fn one(sys: &mut System, text: &str, what: &str) -> Result<Id, CliError> {
    let ctx = sys.open_context();
    Ok(sys.read(text, what, &ctx)?)
}

/// The body flags, read into `base`'s pool (a system of the coordinates only).
pub(super) struct BodyFlags<'a> {
    pub points: &'a [String],
    pub rigids: &'a [String],
    pub gravity: Option<&'a str>,
    pub springs: &'a [String],
    pub potential: Option<&'a str>,
}

impl BodyFlags<'_> {
    /// Whether any body is given (the system is then built from bodies).
    pub fn any(&self) -> bool {
        !self.points.is_empty() || !self.rigids.is_empty()
    }

    /// The system from the bodies and potentials, over `base`'s coordinates.
    pub fn build(&self, mut base: System) -> Result<System, CliError> {
        let mut bodies = Vec::new();
        for p in self.points {
            let f = fields("--point", p, &["mass", "position"])?;
            let get = |k: &str| f.iter().find(|(o, _)| *o == k).map(|(_, v)| *v);
            let (Some(m), Some(at)) = (get("mass"), get("position")) else {
                return Err(CliError::usage(
                    "--point needs mass=… and position=…, separated by `;`, as in --point \"mass=m; position=l*sin(theta), -l*cos(theta)\"",
                ));
            };
            let mass = one(&mut base, m, "--point mass")?;
            let position = list(&mut base, at, "--point position")?;
            if !(2..=3).contains(&position.len()) {
                return Err(CliError::usage("--point position=… has 2 or 3 components"));
            }
            bodies.push(Body::Point { mass, position });
        }
        for r in self.rigids {
            bodies.push(rigid(&mut base, r)?);
        }
        let mut potentials = Vec::new();
        if let Some(g) = self.gravity {
            let parts = split_top(g, ',');
            let axis = match parts.get(1).copied().unwrap_or("y") {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                other => {
                    return Err(CliError::Usage(format!(
                        "--gravity: axis `{other}` (use x, y or z)"
                    )));
                }
            };
            let g = one(&mut base, parts[0], "--gravity")?;
            potentials.push(Potential::Gravity { g, axis });
        }
        for s in self.springs {
            potentials.push(spring(&mut base, s, bodies.len())?);
        }
        if let Some(v) = self.potential {
            potentials.push(Potential::Explicit(one(&mut base, v, "--potential")?));
        }
        Ok(System::from_bodies(
            base.pool,
            base.coordinates,
            &bodies,
            &potentials,
        ))
    }
}

/// `--rigid "mass=M; position=x, y; inertia=I; angle=theta"` (or 3-D: `moments=I1, I2, I3` or
/// `tensor=` nine entries row by row, with `omega_body=w1, w2, w3` or `euler=phi, theta, psi`):
/// the problem file's names, read into the library's [`RigidSpec`] and checked there.
fn rigid(sys: &mut System, text: &str) -> Result<Body, CliError> {
    let f = fields("--rigid", text, &RigidSpec::KEYS)?;
    let get = |k: &str| f.iter().find(|(o, _)| *o == k).map(|(_, v)| *v);
    let one = |sys: &mut System, k: &str| {
        get(k)
            .map(|v| one(sys, v, &format!("--rigid {k}")))
            .transpose()
    };
    let mass = one(sys, "mass")?;
    let inertia = one(sys, "inertia")?;
    let angle = one(sys, "angle")?;
    let all = |sys: &mut System, k: &str| {
        get(k)
            .map(|v| list(sys, v, &format!("--rigid {k}")))
            .transpose()
    };
    let spec = RigidSpec {
        mass,
        position: all(sys, "position")?,
        inertia,
        moments: all(sys, "moments")?,
        // Nine entries on one line, row by row; any other count is the checker's error.
        tensor: all(sys, "tensor")?.map(|v| v.chunks(3).map(<[Id]>::to_vec).collect()),
        angle,
        omega_body: all(sys, "omega_body")?,
        euler: all(sys, "euler")?,
    };
    let r = spec.build(&mut sys.pool).map_err(MechError::from)?;
    Ok(Body::Rigid(Box::new(r)))
}

/// `--spring "k=k; from=1; to=0, 0; natural=l0"`: ends are body numbers (1-based, in the
/// order --point then --rigid) or fixed points.
fn spring(sys: &mut System, text: &str, n_bodies: usize) -> Result<Potential, CliError> {
    let f = fields("--spring", text, &["k", "from", "to", "natural"])?;
    let get = |k: &str| f.iter().find(|(o, _)| *o == k).map(|(_, v)| *v);
    let (Some(from), Some(to)) = (get("from"), get("to")) else {
        return Err(CliError::usage("--spring needs from=… and to=…"));
    };
    let k = one(sys, get("k").unwrap_or("k"), "--spring k")?;
    let natural = one(sys, get("natural").unwrap_or("0"), "--spring natural")?;
    let mut end = |text: &str| -> Result<Anchor, CliError> {
        match text.parse::<usize>() {
            Ok(i) if (1..=n_bodies).contains(&i) => Ok(Anchor::Body(i - 1)),
            Ok(i) => Err(CliError::Usage(format!(
                "--spring: {i} is not a body number (1 to {n_bodies})"
            ))),
            Err(_) => Ok(Anchor::Fixed(list(sys, text, "--spring end")?)),
        }
    };
    let a = end(from)?;
    let b = end(to)?;
    Ok(Potential::Spring { k, natural, a, b })
}

/// `--force-at "x, y: Fx, Fy"`: a force vector at a point, added to the generalized forces.
pub(super) fn force_at(sys: &mut System, text: &str) -> Result<(), CliError> {
    let Some((at, vector)) = text.split_once(':') else {
        return Err(CliError::usage(
            "--force-at is \"point: vector\", e.g. \"l*sin(theta), -l*cos(theta): F, 0\"",
        ));
    };
    let at = split_top(at, ',');
    let vector = split_top(vector, ',');
    Ok(sys.add_point_force(&at, &vector)?)
}
