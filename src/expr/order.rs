//! A total, deterministic structural order on expressions.
//!
//! Ids are canonical within one pool but their numeric order depends on construction order;
//! this order depends only on structure and symbol names, so choices made with it (which of
//! `sin(a − b)` and `−sin(b − a)` is canonical, how a sum is printed) are stable.

use std::cmp::Ordering;

use super::node::{Id, Node};
use super::pool::Pool;

fn rank(node: &Node) -> u8 {
    match node {
        Node::Num(_) => 0,
        Node::Pi => 1,
        Node::Var(..) => 2,
        Node::Pow(..) => 3,
        Node::Mul(_) => 4,
        Node::Add(_) => 5,
        Node::Func(..) => 6,
    }
}

/// Compares names so that `theta2 < theta10` (digit runs compare by value); ties between
/// different spellings of one number (`l02`, `l2`) fall back to byte order, so the order is total.
pub(crate) fn natural_cmp(a: &str, b: &str) -> Ordering {
    natural_only(a, b).then_with(|| a.cmp(b))
}

fn natural_only(a: &str, b: &str) -> Ordering {
    let (mut x, mut y) = (a.as_bytes(), b.as_bytes());
    loop {
        match (x.first(), y.first()) {
            (None, None) => return Ordering::Equal,
            (None, Some(_)) => return Ordering::Less,
            (Some(_), None) => return Ordering::Greater,
            (Some(p), Some(q)) if p.is_ascii_digit() && q.is_ascii_digit() => {
                let dx = x.iter().take_while(|c| c.is_ascii_digit()).count();
                let dy = y.iter().take_while(|c| c.is_ascii_digit()).count();
                let (nx, ny) = (trim_zeros(&x[..dx]), trim_zeros(&y[..dy]));
                let o = nx.len().cmp(&ny.len()).then_with(|| nx.cmp(ny));
                if o != Ordering::Equal {
                    return o;
                }
                x = &x[dx..];
                y = &y[dy..];
            }
            (Some(p), Some(q)) => {
                if p != q {
                    return p.cmp(q);
                }
                x = &x[1..];
                y = &y[1..];
            }
        }
    }
}

fn trim_zeros(d: &[u8]) -> &[u8] {
    let k = d.iter().take_while(|&&c| c == b'0').count();
    &d[k.min(d.len().saturating_sub(1))..]
}

/// The structural order: by kind, then by contents (symbols by name).
pub(crate) fn cmp(pool: &Pool, a: Id, b: Id) -> Ordering {
    if a == b {
        return Ordering::Equal;
    }
    let (na, nb) = (pool.node(a), pool.node(b));
    let r = rank(na).cmp(&rank(nb));
    if r != Ordering::Equal {
        return r;
    }
    match (na, nb) {
        (Node::Num(x), Node::Num(y)) => x.cmp(y),
        (Node::Var(s, o), Node::Var(t, p)) => {
            natural_cmp(pool.name(*s), pool.name(*t)).then_with(|| o.cmp(p))
        }
        (Node::Add(x), Node::Add(y)) | (Node::Mul(x), Node::Mul(y)) => cmp_lists(pool, x, y),
        (Node::Pow(b1, e1), Node::Pow(b2, e2)) => {
            cmp(pool, *b1, *b2).then_with(|| cmp(pool, *e1, *e2))
        }
        (Node::Func(f, x), Node::Func(g, y)) => f.cmp(g).then_with(|| cmp(pool, *x, *y)),
        _ => Ordering::Equal,
    }
}

fn cmp_lists(pool: &Pool, x: &[Id], y: &[Id]) -> Ordering {
    let mut xs = x.to_vec();
    let mut ys = y.to_vec();
    crate::sort::sort_by(&mut xs, |&p, &q| cmp(pool, p, q));
    crate::sort::sort_by(&mut ys, |&p, &q| cmp(pool, p, q));
    for (p, q) in xs.iter().zip(&ys) {
        let o = cmp(pool, *p, *q);
        if o != Ordering::Equal {
            return o;
        }
    }
    xs.len().cmp(&ys.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn natural_order_of_names() {
        let cases = [
            ("theta2", "theta10", Ordering::Less),
            ("a", "b", Ordering::Less),
            ("x1", "x1", Ordering::Equal),
            ("m", "m1", Ordering::Less),
            ("l02", "l2", Ordering::Less),
        ];
        for (a, b, want) in cases {
            assert_eq!(natural_cmp(a, b), want, "{a} vs {b}");
        }
    }
}
