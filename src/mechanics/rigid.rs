//! Rigid bodies.
//!
//! A rigid body's kinetic energy is König's split: T = ½ M |v_cm|² + ½ ωᵀ I ω, with I the
//! inertia tensor about the centre of mass in the body frame and ω the angular velocity in
//! that frame. The orientation comes from the coordinates: a planar angle (ω = θ̇ about the
//! axis normal to the plane), body-frame angular-velocity components given as expressions, or
//! z-x-z Euler angles (φ, θ, ψ), for which (Goldstein §4.9)
//!   ω₁ = φ̇ sin θ sin ψ + θ̇ cos ψ,  ω₂ = φ̇ sin θ cos ψ − θ̇ sin ψ,  ω₃ = φ̇ cos θ + ψ̇.
//!
//! Forces given as vectors at a point are in `point_force.rs`.

use crate::expr::{Func, Id, Pool, Sym};

/// The inertia about the centre of mass, in the body frame.
#[derive(Clone, Debug)]
pub enum Inertia {
    /// Principal moments: one (a planar body, about the axis normal to the plane) or three.
    Principal(Vec<Id>),
    /// A full symmetric 3×3 tensor.
    Tensor([[Id; 3]; 3]),
}

/// How the body's orientation follows from the coordinates.
#[derive(Clone, Debug)]
pub enum Orientation {
    /// A planar body turned by this angle (an expression in the coordinates).
    Planar(Id),
    /// The body-frame angular-velocity components, as expressions in q, q' and t.
    BodyRates([Id; 3]),
    /// z-x-z Euler angles (φ, θ, ψ), each an expression in the coordinates.
    Euler([Id; 3]),
}

/// A rigid body: mass, centre-of-mass position, inertia and orientation.
#[derive(Clone, Debug)]
pub struct Rigid {
    pub(crate) mass: Id,
    /// The centre of mass (2 or 3 components).
    pub(crate) position: Vec<Id>,
    pub(crate) inertia: Inertia,
    pub(crate) orientation: Orientation,
}

/// A rigid body as it is stated, in a problem file's `[[bodies]]` (`kind = "rigid"`) or in the
/// command line's `--rigid`, with its expressions already read. Both use these names
/// ([`RigidSpec::KEYS`]) and this one checker ([`RigidSpec::build`]).
#[derive(Clone, Debug, Default)]
pub struct RigidSpec {
    pub mass: Option<Id>,
    /// The centre of mass (2 or 3 components).
    pub position: Option<Vec<Id>>,
    /// One moment about the axis normal to the plane (planar).
    pub inertia: Option<Id>,
    /// Three principal moments about the centre of mass (3-D).
    pub moments: Option<Vec<Id>>,
    /// The inertia tensor about the centre of mass in the body frame, 3 rows of 3.
    pub tensor: Option<Vec<Vec<Id>>>,
    /// A planar body's angle.
    pub angle: Option<Id>,
    /// Body-frame angular-velocity components (3-D).
    pub omega_body: Option<Vec<Id>>,
    /// z-x-z Euler angles φ, θ, ψ (3-D).
    pub euler: Option<Vec<Id>>,
}

impl RigidSpec {
    /// The names of the fields, as a problem file and the command line spell them.
    pub const KEYS: [&'static str; 8] = [
        "mass",
        "position",
        "inertia",
        "moments",
        "tensor",
        "angle",
        "omega_body",
        "euler",
    ];

    /// The body, when exactly one inertia and one orientation are given and every list has
    /// its length; then [`Rigid::new`]'s checks.
    pub fn build(self, pool: &mut Pool) -> Result<Rigid, RigidError> {
        let (Some(mass), Some(position)) = (self.mass, self.position) else {
            return Err(RigidError::Missing);
        };
        let inertia = match (self.inertia, self.moments, self.tensor) {
            (Some(i), None, None) => Inertia::Principal(vec![i]),
            (None, Some(m), None) => Inertia::Principal(m),
            (None, None, Some(rows)) => {
                if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
                    return Err(RigidError::TensorShape);
                }
                let row = |r: &[Id]| [r[0], r[1], r[2]];
                Inertia::Tensor([row(&rows[0]), row(&rows[1]), row(&rows[2])])
            }
            _ => {
                return Err(RigidError::OneOf {
                    keys: "`inertia` (planar), `moments` or `tensor`",
                });
            }
        };
        let three = |key: &'static str, v: Vec<Id>| {
            let given = v.len();
            <[Id; 3]>::try_from(v).map_err(|_| RigidError::Three { key, given })
        };
        let orientation = match (self.angle, self.omega_body, self.euler) {
            (Some(a), None, None) => Orientation::Planar(a),
            (None, Some(w), None) => Orientation::BodyRates(three("omega_body", w)?),
            (None, None, Some(e)) => Orientation::Euler(three("euler", e)?),
            _ => {
                return Err(RigidError::OneOf {
                    keys: "`angle` (planar), `omega_body` or `euler`",
                });
            }
        };
        Rigid::new(pool, mass, position, inertia, orientation)
    }
}

/// What makes a rigid body or a point force ill-posed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RigidError {
    /// The mass or the centre of mass is missing.
    #[error("a rigid body needs `mass` and `position` (its centre of mass)")]
    Missing,
    /// None or several of a set of alternatives.
    #[error("a rigid body needs exactly one of {keys}")]
    OneOf { keys: &'static str },
    /// A tensor that is not 3 rows of 3.
    #[error("`tensor` is 3 rows of 3 entries")]
    TensorShape,
    /// A three-component field with another count.
    #[error("`{key}` has {given} entries (3 are needed)")]
    Three { key: &'static str, given: usize },
    /// A position or force with a component count other than 2 or 3.
    #[error("{what} has {given} components (2 or 3 are possible)")]
    Components { what: &'static str, given: usize },
    /// The force vector and its point of application differ in dimension.
    #[error("the force has {vector} components but its point has {at}")]
    ForceDimension { vector: usize, at: usize },
    /// The inertia does not fit the orientation.
    #[error("{orientation} needs {needs}, but {given} was given")]
    InertiaShape {
        orientation: &'static str,
        needs: &'static str,
        given: String,
    },
    /// A planar angle with a 3-D centre of mass (or 3-D rotation with a 2-D one).
    #[error("{orientation} with a centre of mass of {components} components")]
    PlaneMismatch {
        orientation: &'static str,
        components: usize,
    },
    /// An off-diagonal entry of the tensor differs from its mirror.
    #[error(
        "the inertia tensor is not symmetric: entry ({row}, {col}) differs from ({col}, {row})"
    )]
    Asymmetric { row: usize, col: usize },
    /// The point of application or an angle depends on velocities.
    #[error("{what} depends on the velocity {velocity}")]
    VelocityInPosition {
        what: &'static str,
        velocity: String,
    },
    /// A force with an acceleration is an inertial term.
    #[error("the force vector depends on the acceleration {acceleration}")]
    ForceWithAcceleration { acceleration: String },
}

impl RigidError {
    /// A stable kebab-case code.
    pub fn code(&self) -> &'static str {
        match self {
            RigidError::Missing | RigidError::OneOf { .. } => "bad-body",
            RigidError::TensorShape | RigidError::Three { .. } => "bad-components",
            RigidError::Components { .. } => "bad-components",
            RigidError::ForceDimension { .. } => "force-dimension",
            RigidError::InertiaShape { .. } => "inertia-shape",
            RigidError::PlaneMismatch { .. } => "plane-mismatch",
            RigidError::Asymmetric { .. } => "asymmetric-inertia",
            RigidError::VelocityInPosition { .. } => "velocity-in-position",
            RigidError::ForceWithAcceleration { .. } => "force-with-acceleration",
        }
    }

    /// What to do about it.
    pub fn help(&self) -> String {
        match self {
            RigidError::Missing => "give `mass` and `position`".into(),
            RigidError::OneOf { .. } => "give one of them, not none or two".into(),
            RigidError::TensorShape => {
                "a file gives 3 rows of 3; the command line gives 9 entries, row by row".into()
            }
            RigidError::Three { .. } => "give three components".into(),
            RigidError::Components { .. } => "give 2 (planar) or 3 components".into(),
            RigidError::ForceDimension { .. } => {
                "give the force and its point in the same dimension".into()
            }
            RigidError::InertiaShape { .. } => {
                "a planar angle takes one moment; 3-D rotation takes three moments or a 3×3 tensor"
                    .into()
            }
            RigidError::PlaneMismatch { .. } => {
                "a planar angle goes with a 2-component centre of mass; 3-D rotation with 3".into()
            }
            RigidError::Asymmetric { .. } => "write I_ij and I_ji the same".into(),
            RigidError::VelocityInPosition { .. } => {
                "positions and angles are functions of the coordinates and t only".into()
            }
            RigidError::ForceWithAcceleration { .. } => {
                "an acceleration-dependent force is an inertial term: put it in T".into()
            }
        }
    }
}

/// The first velocity or acceleration `e` depends on, named as written (`x'`).
pub(crate) fn rate_in(pool: &Pool, e: Id, min_order: u8) -> Option<String> {
    pool.variables(e)
        .into_iter()
        .find(|v| v.1 >= min_order)
        .map(|(s, o)| format!("{}{}", pool.name(s), "'".repeat(o.into())))
}

impl Rigid {
    /// A rigid body, checked: 2 or 3 components, inertia fitting the orientation, a
    /// symmetric tensor, positions and angles free of velocities.
    pub fn new(
        pool: &mut Pool,
        mass: Id,
        position: Vec<Id>,
        inertia: Inertia,
        orientation: Orientation,
    ) -> Result<Rigid, RigidError> {
        let dim = position.len();
        if !(2..=3).contains(&dim) {
            return Err(RigidError::Components {
                what: "the centre of mass",
                given: dim,
            });
        }
        let (name, planar) = match &orientation {
            Orientation::Planar(_) => ("a planar angle", true),
            Orientation::BodyRates(_) => ("body angular velocities", false),
            Orientation::Euler(_) => ("Euler angles", false),
        };
        if planar != (dim == 2) {
            return Err(RigidError::PlaneMismatch {
                orientation: name,
                components: dim,
            });
        }
        check_inertia(pool, &inertia, name, planar)?;
        for &x in &position {
            if let Some(v) = rate_in(pool, x, 1) {
                return Err(RigidError::VelocityInPosition {
                    what: "the centre of mass",
                    velocity: v,
                });
            }
        }
        let angles: &[Id] = match &orientation {
            Orientation::Planar(a) => std::slice::from_ref(a),
            Orientation::Euler(a) => a,
            Orientation::BodyRates(_) => &[],
        };
        for &a in angles {
            if let Some(v) = rate_in(pool, a, 1) {
                return Err(RigidError::VelocityInPosition {
                    what: "an angle",
                    velocity: v,
                });
            }
        }
        Ok(Rigid {
            mass,
            position,
            inertia,
            orientation,
        })
    }

    /// T = ½ M |v_cm|² + ½ ωᵀ I ω.
    pub fn kinetic_energy(&self, pool: &mut Pool, coords: &[Sym]) -> Id {
        let half = pool.ratio(1, 2);
        let mut v2 = Vec::new();
        for &x in &self.position {
            let vx = pool.dt(x, coords);
            v2.push(pool.powi(vx, 2));
        }
        let v2 = pool.sum(v2);
        let translation = pool.product([half, self.mass, v2]);
        let omega = self.angular_velocity(pool, coords);
        let rotation = match &self.inertia {
            Inertia::Principal(moments) => {
                let terms: Vec<Id> = moments
                    .iter()
                    .zip(&omega)
                    .map(|(&i, &w)| {
                        let w2 = pool.powi(w, 2);
                        pool.product([i, w2])
                    })
                    .collect();
                pool.sum(terms)
            }
            Inertia::Tensor(t) => {
                let mut terms = Vec::new();
                // zip, not indexing: a body built without `new` (a planar ω of one
                // component with a tensor) must not panic.
                for (row, &wr) in t.iter().zip(&omega) {
                    for (&i, &wc) in row.iter().zip(&omega) {
                        terms.push(pool.product([i, wr, wc]));
                    }
                }
                pool.sum(terms)
            }
        };
        let rotation = pool.product([half, rotation]);
        pool.add(translation, rotation)
    }

    /// The angular velocity in the body frame: one component for a planar body, three in 3-D.
    pub fn angular_velocity(&self, pool: &mut Pool, coords: &[Sym]) -> Vec<Id> {
        match &self.orientation {
            Orientation::Planar(a) => vec![pool.dt(*a, coords)],
            Orientation::BodyRates(w) => w.to_vec(),
            Orientation::Euler([phi, theta, psi]) => {
                let dphi = pool.dt(*phi, coords);
                let dtheta = pool.dt(*theta, coords);
                let dpsi = pool.dt(*psi, coords);
                let (s_th, c_th) = (pool.func(Func::Sin, *theta), pool.func(Func::Cos, *theta));
                let (s_ps, c_ps) = (pool.func(Func::Sin, *psi), pool.func(Func::Cos, *psi));
                let a = pool.product([dphi, s_th, s_ps]);
                let b = pool.product([dtheta, c_ps]);
                let w1 = pool.add(a, b);
                let a = pool.product([dphi, s_th, c_ps]);
                let b = pool.product([dtheta, s_ps]);
                let w2 = pool.sub(a, b);
                let a = pool.product([dphi, c_th]);
                let w3 = pool.add(a, dpsi);
                vec![w1, w2, w3]
            }
        }
    }
}

/// One moment for a planar body; three moments or a symmetric tensor in 3-D.
fn check_inertia(
    pool: &mut Pool,
    inertia: &Inertia,
    orientation: &'static str,
    planar: bool,
) -> Result<(), RigidError> {
    let shape = |needs: &'static str, given: String| RigidError::InertiaShape {
        orientation,
        needs,
        given,
    };
    match inertia {
        Inertia::Principal(m) if planar && m.len() != 1 => Err(shape(
            "one moment of inertia",
            format!("{} moments", m.len()),
        )),
        Inertia::Principal(m) if !planar && m.len() != 3 => Err(shape(
            "three principal moments or a tensor",
            format!("{} moments", m.len()),
        )),
        Inertia::Tensor(_) if planar => Err(shape("one moment of inertia", "a 3×3 tensor".into())),
        Inertia::Tensor(t) => {
            let none: Vec<Sym> = Vec::new();
            // The pairs above the diagonal, each against its mirror.
            for (r, c) in [(0, 1), (0, 2), (1, 2)] {
                let d = pool.sub(t[r][c], t[c][r]);
                let d = pool.simplify(d, &none);
                if !pool.is_zero(d) {
                    return Err(RigidError::Asymmetric {
                        row: r + 1,
                        col: c + 1,
                    });
                }
            }
            Ok(())
        }
        Inertia::Principal(_) => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::System;

    /// A system of `coords` to read expressions in, whose Lagrangian names `params` (so
    /// that they are parameters the zero test samples).
    fn sys(coords: &[&str], params: &str) -> System {
        System::from_lagrangian(params, coords).unwrap()
    }

    fn read(s: &mut System, texts: &[&str]) -> Vec<Id> {
        let ctx = s.open_context();
        texts
            .iter()
            .map(|t| s.read(t, "test", &ctx).unwrap())
            .collect()
    }

    /// `e` equals the text `want` in `s`.
    fn equals(s: &mut System, e: Id, want: &str) -> bool {
        let w = read(s, &[want])[0];
        let d = s.pool.sub(e, w);
        s.is_zero(d)
    }

    #[test]
    fn a_spherical_body_from_euler_angles_has_the_textbook_rotational_energy() {
        // I₁ = I₂ = I₃ = I: |ω|² = φ̇² + θ̇² + ψ̇² + 2 φ̇ ψ̇ cos θ (Goldstein).
        let mut s = sys(&["phi", "theta", "psi"], "m + I");
        let v = read(&mut s, &["m", "0", "0", "0", "I", "phi", "theta", "psi"]);
        let inertia = Inertia::Principal(vec![v[4]; 3]);
        let orient = Orientation::Euler([v[5], v[6], v[7]]);
        let r = Rigid::new(&mut s.pool, v[0], v[1..4].to_vec(), inertia, orient).unwrap();
        let coords = s.coordinate_syms();
        let t = r.kinetic_energy(&mut s.pool, &coords);
        let want = "1/2*I*(phi'^2 + theta'^2 + psi'^2 + 2*phi'*psi'*cos(theta))";
        assert!(equals(&mut s, t, want));
    }

    #[test]
    fn a_tensor_with_products_of_inertia_couples_the_rates() {
        // ω = (a', b', 0) with I₁₂ = I₂₁ = P: T = ½ (A a'² + 2 P a' b' + B b'²).
        let mut s = sys(&["a", "b"], "m + A + P + B + C");
        let v = read(
            &mut s,
            &["m", "0", "0", "0", "A", "P", "B", "C", "a'", "b'"],
        );
        let z = s.pool.zero();
        let t = [[v[4], v[5], z], [v[5], v[6], z], [z, z, v[7]]];
        let orient = Orientation::BodyRates([v[8], v[9], z]);
        let r = Rigid::new(
            &mut s.pool,
            v[0],
            v[1..4].to_vec(),
            Inertia::Tensor(t),
            orient,
        )
        .unwrap();
        let coords = s.coordinate_syms();
        let t = r.kinetic_energy(&mut s.pool, &coords);
        assert!(equals(&mut s, t, "1/2*(A*a'^2 + 2*P*a'*b' + B*b'^2)"));
    }

    #[test]
    fn shapes_that_do_not_fit_are_refused() {
        let mut s = sys(&["x"], "m + I");
        let v = read(&mut s, &["m", "x", "0", "0", "I", "x'"]);
        let planar = || Orientation::Planar(v[1]);
        let one = || Inertia::Principal(vec![v[4]]);
        let e = Rigid::new(&mut s.pool, v[0], vec![v[1]], one(), planar()).unwrap_err();
        assert_eq!(e.code(), "bad-components");
        let e = Rigid::new(&mut s.pool, v[0], v[1..4].to_vec(), one(), planar()).unwrap_err();
        assert_eq!(e.code(), "plane-mismatch");
        let three = Inertia::Principal(vec![v[4]; 3]);
        let e = Rigid::new(&mut s.pool, v[0], v[1..3].to_vec(), three, planar()).unwrap_err();
        assert_eq!(e.code(), "inertia-shape");
        let e = Rigid::new(&mut s.pool, v[0], vec![v[1], v[5]], one(), planar()).unwrap_err();
        assert_eq!(e.code(), "velocity-in-position");
        assert!(!e.help().is_empty());
    }
}
