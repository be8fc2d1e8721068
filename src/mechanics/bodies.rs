//! Bodies and potentials: point masses with Cartesian positions as functions of (q, t) in 2D
//! or 3D, rigid bodies rotating about a fixed axis, free rigid bodies (see `rigid.rs`),
//! uniform gravity, springs and explicit potentials. From them follow T and V.

use super::coordinate::Coordinate;
use super::rigid::Rigid;
use crate::expr::{Id, Pool, Sym};

/// A body.
#[derive(Clone, Debug)]
pub enum Body {
    /// A point mass at `position` (2 or 3 components).
    Point { mass: Id, position: Vec<Id> },
    /// A rigid body turning about a fixed axis by `angle`, with moment of inertia `inertia`.
    Rotor { inertia: Id, angle: Id },
    /// A rigid body with a moving centre of mass and an orientation (boxed: it is large).
    Rigid(Box<Rigid>),
}

impl Body {
    /// The mass and the position gravity and springs act at: a point mass's position, a
    /// rigid body's centre of mass; none for a rotor about a fixed axis.
    pub fn mass_at(&self) -> Option<(Id, &[Id])> {
        match self {
            Body::Point { mass, position } => Some((*mass, position)),
            Body::Rigid(r) => Some((r.mass, &r.position)),
            Body::Rotor { .. } => None,
        }
    }
}

/// One end of a spring.
#[derive(Clone, Debug)]
pub enum Anchor {
    /// The position of point body number `index`.
    Body(usize),
    /// A fixed point.
    Fixed(Vec<Id>),
}

/// A potential.
#[derive(Clone, Debug)]
pub enum Potential {
    /// Uniform gravity of strength `g` pointing down along `axis` (0 = x, 1 = y, 2 = z):
    /// V = Σ m g r\[axis\] over point masses.
    Gravity { g: Id, axis: usize },
    /// A spring of stiffness `k` and natural length `natural` between two anchors.
    Spring {
        k: Id,
        natural: Id,
        a: Anchor,
        b: Anchor,
    },
    /// Any V(q, t).
    Explicit(Id),
}

/// T = Σ ½ m |ṙ|² + Σ ½ I (d angle/dt)² + Σ (½ M |v_cm|² + ½ ωᵀ I ω).
pub(crate) fn kinetic_energy(pool: &mut Pool, coordinates: &[Coordinate], bodies: &[Body]) -> Id {
    let coords: Vec<Sym> = coordinates.iter().map(|c| c.sym).collect();
    let half = pool.ratio(1, 2);
    let mut terms = Vec::new();
    for b in bodies {
        match b {
            Body::Point { mass, position } => {
                let mut v2 = Vec::new();
                for &x in position {
                    let vx = pool.dt(x, &coords);
                    v2.push(pool.powi(vx, 2));
                }
                let v2 = pool.sum(v2);
                terms.push(pool.product([half, *mass, v2]));
            }
            Body::Rotor { inertia, angle } => {
                let w = pool.dt(*angle, &coords);
                let w2 = pool.powi(w, 2);
                terms.push(pool.product([half, *inertia, w2]));
            }
            Body::Rigid(r) => terms.push(r.kinetic_energy(pool, &coords)),
        }
    }
    pool.sum(terms)
}

/// V from the potentials (gravity acts on the point masses and rigid bodies' centres of mass).
pub(crate) fn potential_energy(pool: &mut Pool, bodies: &[Body], potentials: &[Potential]) -> Id {
    let half = pool.ratio(1, 2);
    let mut terms = Vec::new();
    for p in potentials {
        match p {
            Potential::Gravity { g, axis } => {
                for b in bodies {
                    if let Some((mass, position)) = b.mass_at()
                        && let Some(&h) = position.get(*axis)
                    {
                        terms.push(pool.product([mass, *g, h]));
                    }
                }
            }
            Potential::Spring { k, natural, a, b } => {
                let pa = anchor(bodies, a);
                let pb = anchor(bodies, b);
                let mut d2 = Vec::new();
                for i in 0..pa.len().max(pb.len()) {
                    let x = pa.get(i).copied().unwrap_or_else(|| pool.zero());
                    let y = pb.get(i).copied().unwrap_or_else(|| pool.zero());
                    let d = pool.sub(x, y);
                    d2.push(pool.powi(d, 2));
                }
                let d2 = pool.sum(d2);
                let stretch2 = if pool.is_zero(*natural) {
                    d2
                } else {
                    let len = pool.sqrt(d2);
                    let s = pool.sub(len, *natural);
                    pool.powi(s, 2)
                };
                terms.push(pool.product([half, *k, stretch2]));
            }
            Potential::Explicit(v) => terms.push(*v),
        }
    }
    pool.sum(terms)
}

fn anchor(bodies: &[Body], a: &Anchor) -> Vec<Id> {
    match a {
        Anchor::Fixed(p) => p.clone(),
        Anchor::Body(i) => bodies
            .get(*i)
            .and_then(Body::mass_at)
            .map(|(_, p)| p.to_vec())
            .unwrap_or_default(),
    }
}
