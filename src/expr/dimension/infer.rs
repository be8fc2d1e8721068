//! Inferring the dimension of an expression from its symbols' dimensions ([`Pool::dimension`]
//! and what it needs).

use super::*;

impl Pool {
    /// The dimension of `e`; `Ok(None)` when some symbol's dimension is unknown.
    pub fn dimension(&self, e: Id, dims: &Dimensions) -> Result<Option<Dimension>, DimError> {
        let mut memo = FxHashMap::default();
        self.dim_of(e, dims, &mut memo)
    }

    /// Checks that `lhs = rhs` is dimensionally consistent.
    pub fn check_equation_dimension(
        &self,
        lhs: Id,
        rhs: Id,
        dims: &Dimensions,
    ) -> Result<Option<Dimension>, DimError> {
        let a = self.dimension(lhs, dims)?;
        let b = self.dimension(rhs, dims)?;
        match (a, b) {
            (Some(x), Some(y)) if x != y && !self.is_zero(lhs) && !self.is_zero(rhs) => {
                Err(DimError::UnlikeSides {
                    lhs: self.unicode(lhs),
                    lhs_dim: x,
                    rhs: self.unicode(rhs),
                    rhs_dim: y,
                })
            }
            // `… = 0`: zero takes any dimension, so the other side decides.
            _ if self.is_zero(rhs) => Ok(a),
            _ if self.is_zero(lhs) => Ok(b),
            _ => Ok(a.and(b)),
        }
    }

    fn dim_of(
        &self,
        e: Id,
        dims: &Dimensions,
        memo: &mut Memo,
    ) -> Result<Option<Dimension>, DimError> {
        if let Some(d) = memo.get(&e) {
            return Ok(*d);
        }
        let d = match self.node(e) {
            Node::Num(_) | Node::Pi => Some(Dimension::NONE),
            Node::Var(s, o) => dims
                .get(self.name(*s))
                .map(|d| d / Dimension::new(0, 0, i32::from(*o))),
            Node::Mul(ch) => {
                let mut acc = Some(Dimension::NONE);
                for &c in ch.iter() {
                    let dc = self.dim_of(c, dims, memo)?;
                    acc = acc.zip(dc).map(|(a, b)| a * b);
                }
                acc
            }
            Node::Add(ch) => self.dim_of_sum(ch, dims, memo)?,
            Node::Pow(b, x) => self.dim_of_power(*b, *x, dims, memo)?,
            Node::Func(f, a) => self.dim_of_func(*f, *a, dims, memo)?,
        };
        memo.insert(e, d);
        Ok(d)
    }

    /// Every term of a sum must have one dimension; the error lists one term per dimension,
    /// in display order.
    fn dim_of_sum(
        &self,
        ch: &[Id],
        dims: &Dimensions,
        memo: &mut Memo,
    ) -> Result<Option<Dimension>, DimError> {
        let mut seen: Vec<(String, Dimension)> = Vec::new();
        let mut unknown = false;
        let mut terms = ch.to_vec();
        self.display_sort_terms(&mut terms);
        for &c in &terms {
            match self.dim_of(c, dims, memo)? {
                Some(d) => {
                    if !seen.iter().any(|(_, x)| *x == d) {
                        seen.push((self.unicode(c), d));
                    }
                }
                None => unknown = true,
            }
        }
        if seen.len() > 1 {
            return Err(DimError::UnlikeTerms { terms: seen });
        }
        Ok(if unknown {
            None
        } else {
            seen.first().map(|x| x.1)
        })
    }

    /// `b ^ x`: x dimensionless, and a number unless b is dimensionless.
    fn dim_of_power(
        &self,
        b: Id,
        x: Id,
        dims: &Dimensions,
        memo: &mut Memo,
    ) -> Result<Option<Dimension>, DimError> {
        let db = self.dim_of(b, dims, memo)?;
        let dx = self.dim_of(x, dims, memo)?;
        if let Some(dx) = dx
            && !dx.is_none()
        {
            return Err(DimError::DimensionfulExponent {
                exponent: self.unicode(x),
                dim: dx,
            });
        }
        Ok(match (db, self.as_num(x)) {
            (Some(d), _) if d.is_none() => Some(d),
            (Some(d), Some(v)) => {
                let r = v
                    .numer()
                    .to_i32()
                    .zip(v.denom().to_i32())
                    .map(|(n, k)| Rational32::new(n, k));
                r.map(|r| d.pow(r))
            }
            // `r^n` with n a constant: the dimension is L^n, which no fixed exponent states
            // and no check can refute: undecided.
            (Some(_), None)
                if self
                    .variables(x)
                    .iter()
                    .all(|&(s, o)| o == 0 && !dims.varies(self.name(s))) =>
            {
                None
            }
            (Some(d), None) => {
                return Err(DimError::SymbolicExponent {
                    base: self.unicode(b),
                    dim: d,
                    exponent: self.unicode(x),
                });
            }
            (None, _) => None,
        })
    }

    /// `f(a)`: a dimensionless argument for every function but `abs`.
    fn dim_of_func(
        &self,
        f: Func,
        a: Id,
        dims: &Dimensions,
        memo: &mut Memo,
    ) -> Result<Option<Dimension>, DimError> {
        let da = self.dim_of(a, dims, memo)?;
        if !f.needs_dimensionless() {
            debug_assert_eq!(f, Func::Abs);
            return Ok(da);
        }
        if let Some(d) = da
            && !d.is_none()
        {
            return Err(DimError::DimensionfulArgument {
                func: f.name(),
                arg: self.unicode(a),
                dim: d,
            });
        }
        Ok(Some(Dimension::NONE))
    }
}

/// Dimensions already found, by node.
type Memo = FxHashMap<Id, Option<Dimension>>;
