//! SI units for the axes of a simulation's pictures, from the dimensions a bank problem
//! declares: "rad" for an angle, "m" for a length, "rad s⁻¹" for its rate, "J" for energy.
//! A system typed on the command line has no declared dimensions, so it gets no units at all —
//! not even "s" on the time axis, so that a picture never mixes known and guessed units.

use num_traits::{ToPrimitive, Zero};

use crate::expr::Dimension;
use crate::problem::Problem;

/// The units of the quantities a simulation draws (each `None` when not known).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct AxisUnits {
    /// Of t.
    pub time: Option<String>,
    /// Of each coordinate, in order.
    pub coordinates: Vec<Option<String>>,
    /// Of each coordinate's rate.
    pub velocities: Vec<Option<String>>,
    /// Of the energy function h.
    pub energy: Option<String>,
}

impl AxisUnits {
    /// The units of `problem`'s time, coordinates, rates and h from its declared dimensions;
    /// h is an energy only when every parameter's dimension is declared (L's dimension is then
    /// checked by the bank), else it has no unit.
    pub fn of(problem: &Problem) -> AxisUnits {
        let time = Dimension::new(0, 0, 1);
        let mut coordinates = Vec::new();
        let mut velocities = Vec::new();
        for c in &problem.system.coordinates {
            let d = problem.dims.get(&c.name);
            coordinates.push(d.and_then(|d| unit(d, c.periodic)));
            velocities.push(d.and_then(|d| unit(d / time, c.periodic)));
        }
        let every_parameter = problem
            .system
            .parameters
            .iter()
            .all(|p| problem.dims.get(&p.name).is_some());
        let energy = problem
            .system
            .pool
            .dimension(problem.system.lagrangian, &problem.dims)
            .ok()
            .flatten()
            .filter(|_| every_parameter)
            .and_then(|d| unit(d, false));
        AxisUnits {
            time: unit(time, false),
            coordinates,
            velocities,
            energy,
        }
    }
}

/// The SI unit of a dimension: `J` for energy, else kg, m, s and C with Unicode exponents;
/// "rad" heads a dimensionless angle's unit; `None` for a dimensionless quantity that is not
/// an angle, or an exponent that is not an integer.
pub fn unit(d: Dimension, angle: bool) -> Option<String> {
    if d == Dimension::energy() {
        return Some("J".into());
    }
    let mut parts: Vec<String> = Vec::new();
    if angle {
        parts.push("rad".into());
    }
    for (symbol, e) in [("kg", d.m), ("m", d.l), ("s", d.t), ("C", d.q)] {
        if e.is_zero() {
            continue;
        }
        if !e.is_integer() {
            return None;
        }
        let e = e.to_integer().to_i64()?;
        parts.push(if e == 1 {
            symbol.to_string()
        } else {
            format!("{symbol}{}", superscript(e))
        });
    }
    (!parts.is_empty()).then(|| parts.join(" "))
}

/// An integer in superscript digits, `⁻¹`.
fn superscript(e: i64) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if e < 0 {
        s.push('⁻');
    }
    for c in e.unsigned_abs().to_string().chars() {
        s.push(c.to_digit(10).map_or(c, |d| DIGITS[d as usize]));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_of_common_dimensions() {
        assert_eq!(unit(Dimension::NONE, true).as_deref(), Some("rad"));
        assert_eq!(
            unit(Dimension::new(0, 0, -1), true).as_deref(),
            Some("rad s⁻¹")
        );
        assert_eq!(unit(Dimension::new(0, 1, 0), false).as_deref(), Some("m"));
        assert_eq!(
            unit(Dimension::new(0, 1, -1), false).as_deref(),
            Some("m s⁻¹")
        );
        assert_eq!(unit(Dimension::new(1, 2, -2), false).as_deref(), Some("J"));
        assert_eq!(unit(Dimension::NONE, false), None);
    }

    #[test]
    fn the_bank_pendulum_has_si_units() {
        let p = crate::bank::embedded::problem("simple-pendulum").unwrap();
        let u = AxisUnits::of(&p);
        assert_eq!(u.time.as_deref(), Some("s"));
        assert_eq!(u.coordinates, vec![Some("rad".to_string())]);
        assert_eq!(u.velocities, vec![Some("rad s⁻¹".to_string())]);
        assert_eq!(u.energy.as_deref(), Some("J"));
        let p = crate::bank::embedded::problem("spring-incline").unwrap();
        let u = AxisUnits::of(&p);
        assert_eq!(u.coordinates, vec![Some("m".to_string())]);
        assert_eq!(u.velocities, vec![Some("m s⁻¹".to_string())]);
    }
}
