//! Product structure: when the forces of some coordinates depend on those coordinates only
//! (six uncoupled pendula; a cart whose x enters no force), the equations at rest decouple
//! into blocks, each searched on its own, and the equilibria are every combination of the
//! blocks' roots (3⁶ = 729 for the pendula, where one search over six dimensions finds a
//! fraction). What the search covered is reported with it ([`Coverage`]).

use super::Statics;
use super::newton::{
    Block, NEWTON_WANDER, NewtonScale, force_scale, newton, normalize_root, same_point,
    snap_to_zero, start_points,
};
use crate::mechanics::error::MechError;
use crate::mechanics::system::System;

/// At most this many equilibria are formed from the blocks' roots (a product grows fast;
/// past this the list is refused rather than cut short).
pub(super) const MAX_PRODUCT: usize = 4096;

/// What the search covered: how sure a list of equilibria is.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coverage {
    /// The blocks of coordinates (indices) whose equations at rest decouple, each searched
    /// on its own; one block holding every coordinate when nothing decouples.
    pub(crate) blocks: Vec<Vec<usize>>,
    /// Newton starts in each block (a grid plus seeded random points over its ranges).
    pub(crate) starts: Vec<usize>,
}

impl System {
    /// The blocks of coordinates whose forces at rest depend only on each other: the
    /// connected components of "Gᵢ depends on qⱼ" (∂Gᵢ/∂qⱼ not identically zero).
    pub(super) fn decoupled_blocks(&self, statics: &Statics) -> Vec<Vec<usize>> {
        let n = self.n();
        let mut link = vec![vec![false; n]; n];
        for (k, &entry) in statics.jacobian.iter().enumerate() {
            let (i, j) = (k / n, k % n);
            if i != j && !self.is_zero(entry) {
                link[i][j] = true;
                link[j][i] = true;
            }
        }
        let mut block_of = vec![usize::MAX; n];
        let mut blocks: Vec<Vec<usize>> = Vec::new();
        for start in 0..n {
            if block_of[start] != usize::MAX {
                continue;
            }
            let id = blocks.len();
            let mut members = vec![start];
            block_of[start] = id;
            let mut k = 0;
            while k < members.len() {
                let i = members[k];
                for (j, &linked) in link[i].iter().enumerate() {
                    if linked && block_of[j] == usize::MAX {
                        block_of[j] = id;
                        members.push(j);
                    }
                }
                k += 1;
            }
            crate::sort::sort_unstable(&mut members);
            blocks.push(members);
        }
        blocks
    }
}

/// The search's ranges and yardsticks, shared by every block.
pub(super) struct Search<'a> {
    pub(super) statics: &'a Statics,
    pub(super) ranges: &'a [(f64, f64)],
    pub(super) periodic: &'a [bool],
    pub(super) widths: &'a [f64],
}

impl Search<'_> {
    /// The roots of one block (full points, the other coordinates at `rest`), the number
    /// of starts, and the block's force scale.
    pub(super) fn block_roots(
        &self,
        active: &[usize],
        rest: &[f64],
    ) -> (Vec<Vec<f64>>, usize, f64) {
        let sub: Vec<(f64, f64)> = active.iter().map(|&i| self.ranges[i]).collect();
        let starts: Vec<Vec<f64>> = start_points(&sub)
            .into_iter()
            .map(|s| {
                let mut q = rest.to_vec();
                for (k, &i) in active.iter().enumerate() {
                    q[i] = s[k];
                }
                q
            })
            .collect();
        let b = Block {
            statics: self.statics,
            active,
        };
        let scale = NewtonScale {
            force: force_scale(b, &starts),
            limit: NEWTON_WANDER * self.widths.iter().fold(1.0f64, |a, &w| a.max(w.min(1e300))),
        };
        if scale.force == 0.0 {
            // No force in this block anywhere: its coordinates are free (a cyclic x), and
            // one representative stands for the continuum.
            return (vec![rest.to_vec()], starts.len(), 0.0);
        }
        let mut scratch = self.statics.program.scratch();
        let mut found: Vec<Vec<f64>> = Vec::new();
        for q0 in &starts {
            let Some(q) = newton(b, q0.clone(), scale, &mut scratch) else {
                continue;
            };
            let Some(q) = normalize_root(q, self.ranges, self.periodic) else {
                continue;
            };
            let q = snap_to_zero(b, q, self.widths, &mut scratch);
            if !found
                .iter()
                .any(|p| same_point(p, &q, self.periodic, self.widths))
            {
                found.push(q);
            }
        }
        (found, starts.len(), scale.force)
    }
}

/// Every combination of the blocks' roots as a full point (`rest` for coordinates no
/// block sets); [`MechError::TooManyEquilibria`] past [`MAX_PRODUCT`].
pub(super) fn product(
    blocks: &[Vec<usize>],
    roots: &[Vec<Vec<f64>>],
    rest: &[f64],
) -> Result<Vec<Vec<f64>>, MechError> {
    let count = roots
        .iter()
        .try_fold(1usize, |a, r| a.checked_mul(r.len()))
        .unwrap_or(usize::MAX);
    if count > MAX_PRODUCT {
        return Err(MechError::TooManyEquilibria {
            count: count.to_string(),
            max: MAX_PRODUCT,
        });
    }
    let mut out = vec![rest.to_vec()];
    for (block, rs) in blocks.iter().zip(roots) {
        let mut next = Vec::with_capacity(out.len() * rs.len());
        for p in &out {
            for r in rs {
                let mut q = p.clone();
                for &i in block {
                    q[i] = r[i];
                }
                next.push(q);
            }
        }
        out = next;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_product_combines_every_root_of_every_block() {
        let blocks = vec![vec![0], vec![1]];
        let roots = vec![
            vec![vec![-1.0, 9.0], vec![1.0, 9.0]],
            vec![vec![9.0, 0.0], vec![9.0, 2.0], vec![9.0, 3.0]],
        ];
        let all = product(&blocks, &roots, &[0.0, 0.0]).unwrap();
        assert_eq!(all.len(), 6);
        assert!(all.contains(&vec![1.0, 3.0]));
    }
}
