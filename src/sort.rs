//! Stable sorting through one shared instance of the standard sort, for the WebAssembly build.
//!
//! Every `slice::sort_by` with its own element type or comparison compiles its own copy of the
//! standard library's driftsort (≈ 2–3 KB of WebAssembly each, ≈ 40 copies in the engine). The
//! page downloads the module, so on `wasm32` these helpers sort a list of indices with a
//! comparison behind `dyn` — a single compiled sort — and then move the elements into place.
//! The order is the same as the standard stable sort's (a stable order is unique), so output
//! does not depend on the target. Elsewhere they are the standard sort itself (no indirection in
//! the native hot paths).

use std::cmp::Ordering;

/// Sorts `v` stably by `cmp`, as [`slice::sort_by`] does.
pub(crate) fn sort_by<T>(v: &mut [T], cmp: impl FnMut(&T, &T) -> Ordering) {
    #[cfg(target_family = "wasm")]
    by_indices(v, cmp);
    #[cfg(not(target_family = "wasm"))]
    v.sort_by(cmp);
}

/// Sorts `v` stably by the key `f` gives each element, as [`slice::sort_by_key`] does.
pub(crate) fn sort_by_key<T, K: Ord>(v: &mut [T], mut f: impl FnMut(&T) -> K) {
    sort_by(v, |a, b| f(a).cmp(&f(b)));
}

/// Sorts `v` stably in its natural order, as [`slice::sort`] does.
pub(crate) fn sort<T: Ord>(v: &mut [T]) {
    sort_by(v, T::cmp);
}

/// Sorts `v` in its natural order where equal elements are indistinguishable (numbers,
/// handles), as [`slice::sort_unstable`] does: the result is the stable sort's.
pub(crate) fn sort_unstable<T: Ord>(v: &mut [T]) {
    #[cfg(target_family = "wasm")]
    by_indices(v, T::cmp);
    #[cfg(not(target_family = "wasm"))]
    v.sort_unstable();
}

/// The portable path: sorts the positions `0..n` by comparing the elements they name (the one
/// compiled sort), then applies that permutation to `v` in place.
#[cfg_attr(not(target_family = "wasm"), allow(dead_code))]
fn by_indices<T>(v: &mut [T], mut cmp: impl FnMut(&T, &T) -> Ordering) {
    if v.len() < 2 {
        return;
    }
    let mut order: Vec<usize> = (0..v.len()).collect();
    {
        let v: &[T] = v;
        sort_positions(&mut order, &mut |i, j| cmp(&v[i], &v[j]));
    }
    // `order[k]` is the position whose element belongs at k. Follow each cycle once, marking
    // a position done by setting `order[k] = k`.
    for start in 0..order.len() {
        let mut at = start;
        while order[at] != at {
            let from = order[at];
            order[at] = at;
            if from == start {
                break;
            }
            v.swap(at, from);
            at = from;
        }
    }
}

/// The single instance of the standard stable sort the portable path uses.
#[inline(never)]
fn sort_positions(order: &mut [usize], cmp: &mut dyn FnMut(usize, usize) -> Ordering) {
    order.sort_by(|&i, &j| cmp(i, j));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The portable path gives exactly the standard stable sort's order, equal keys included,
    /// over every permutation of a small list with repeated keys and over longer lists.
    #[test]
    fn by_indices_matches_the_standard_stable_sort() {
        let mut lists: Vec<Vec<(u8, usize)>> = Vec::new();
        let keys = [2u8, 0, 1, 2, 0, 1];
        // Every rotation and reversal of the keys, tagged by original position.
        for r in 0..keys.len() {
            let mut k = keys.to_vec();
            k.rotate_left(r);
            lists.push(k.iter().copied().zip(0..).collect());
            k.reverse();
            lists.push(k.iter().copied().zip(0..).collect());
        }
        // A longer list from a fixed linear congruential sequence.
        let mut x = 12345u64;
        let long: Vec<(u8, usize)> = (0..500)
            .map(|i| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((x >> 59) as u8, i)
            })
            .collect();
        lists.push(long);
        lists.push(vec![]);
        lists.push(vec![(1, 0)]);
        for list in lists {
            let mut want = list.clone();
            want.sort_by_key(|e| e.0);
            let mut got = list.clone();
            by_indices(&mut got, |a, b| a.0.cmp(&b.0));
            assert_eq!(got, want, "sorting {list:?}");
        }
    }

    /// A permutation made of one long cycle and fixed points is applied correctly.
    #[test]
    fn by_indices_applies_long_cycles() {
        let mut v: Vec<u32> = (0..100).rev().collect();
        by_indices(&mut v, u32::cmp);
        assert_eq!(v, (0..100).collect::<Vec<_>>());
        let mut w = vec![3, 1, 2, 0, 4];
        by_indices(&mut w, i32::cmp);
        assert_eq!(w, vec![0, 1, 2, 3, 4]);
    }
}
