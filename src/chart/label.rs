//! A coordinate's name as it is read: `theta1` → θ₁, `theta1'` → θ̇₁, `x''` → ẍ; an axis
//! label with its unit, "θ₁ / rad". One rule for every face's pictures (the CLI's files, the
//! page's charts, the terminal chart).

use crate::expr::{Context, Node, Pool, Style, read_expr};

/// `theta1'` → θ̇₁: the name read and printed in Unicode by the library (Greek letters,
/// `m_1` and `m1` alike as m₁, one dot per prime); the name itself if it cannot be read.
pub fn unicode(name: &str) -> String {
    let bare = name.trim_end_matches('\'');
    let order = u8::try_from(name.len() - bare.len()).unwrap_or(u8::MAX);
    let mut pool = Pool::new();
    let coordinate = Context::new().with_coordinates([bare]);
    match read_expr(bare, &coordinate, &mut pool) {
        Ok(id) => match pool.node(id) {
            Node::Var(sym, 0) => pool.var_name(*sym, order, Style::Unicode),
            _ => name.to_string(),
        },
        Err(_) => name.to_string(),
    }
}

/// An axis label, "θ₁ / rad" with a unit, "θ₁" without (the quantity divided by its unit).
pub fn axis(quantity: &str, unit: Option<&str>) -> String {
    match unit {
        Some(u) => [quantity, " / ", u].concat(),
        None => quantity.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::{axis, unicode};

    #[test]
    fn axes_carry_units_when_known() {
        assert_eq!(axis("θ₁", Some("rad")), "θ₁ / rad");
        assert_eq!(axis("t", None), "t");
    }

    #[test]
    fn names() {
        assert_eq!(unicode("theta1"), "θ₁");
        assert_eq!(unicode("theta1'"), "θ\u{307}₁");
        assert_eq!(unicode("x''"), "x\u{308}");
        assert_eq!(unicode("phi_2"), "φ₂");
        assert_eq!(unicode("r"), "r");
        // Not a name the reader takes: shown as typed.
        assert_eq!(unicode("2x'"), "2x'");
    }
}
