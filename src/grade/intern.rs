//! Interned text for `lagrange grade`: each distinct string of a class file (an answer, a
//! problem or part id as typed) is stored once, in one arena, and a row holds its index. A
//! million rows of a realistic class then hold a few hundred strings, not a million, and
//! rows are compared and grouped by index.

use hashbrown::HashTable;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher as _;

/// Distinct strings, numbered in order of first appearance.
#[derive(Default)]
pub struct Interner {
    /// Every string, one after the other.
    text: String,
    /// Where each string ends in `text` (it starts where the one before ends): 4 bytes a
    /// string, not 8 (a class of all-different answers has one per row).
    ends: Vec<u32>,
    /// Indices into `ends`, by the hash of their string (empty once sealed, rebuilt if
    /// a string is added after).
    table: HashTable<u32>,
    /// Whether `table` was dropped ([`Interner::seal`]).
    sealed: bool,
}

impl Interner {
    /// Room for `strings` distinct strings of `bytes` bytes in all.
    pub fn with_capacity(strings: usize, bytes: usize) -> Interner {
        Interner {
            text: String::with_capacity(bytes),
            ends: Vec::with_capacity(strings),
            table: HashTable::with_capacity(strings),
            sealed: false,
        }
    }

    /// Room for `strings` more distinct strings of `bytes` bytes in all (reserved, not
    /// touched: the text does not grow by doubling, each step copying the last).
    pub fn reserve(&mut self, strings: usize, bytes: usize) {
        self.text.reserve(bytes);
        self.ends.reserve(strings);
        let (text, ends) = (&self.text, &self.ends);
        self.table
            .reserve(strings, |&j| FxBuildHasher.hash_one(at(text, ends, j)));
    }

    /// Drops the lookup table once every string is in (a class of all-different answers
    /// would keep one entry per answer to the end); adding a string later rebuilds it.
    pub fn seal(&mut self) {
        self.table = HashTable::new();
        self.sealed = true;
    }

    /// The hash of string `i`.
    fn hash(&self, i: u32) -> u64 {
        FxBuildHasher.hash_one(self.get(i))
    }

    /// The index of `s`, added if new.
    pub fn intern(&mut self, s: &str) -> u32 {
        if self.sealed {
            self.sealed = false;
            let mut table = HashTable::with_capacity(self.ends.len());
            for i in 0..self.ends.len() as u32 {
                table.insert_unique(self.hash(i), i, |&j| self.hash(j));
            }
            self.table = table;
        }
        let hash = FxBuildHasher.hash_one(s);
        let (text, ends) = (&self.text, &self.ends);
        if let Some(&i) = self.table.find(hash, |&i| at(text, ends, i) == s) {
            return i;
        }
        let i = self.ends.len() as u32;
        self.text.push_str(s);
        self.ends.push(self.text.len() as u32);
        let (text, ends) = (&self.text, &self.ends);
        self.table
            .insert_unique(hash, i, |&j| FxBuildHasher.hash_one(at(text, ends, j)));
        i
    }

    /// The bytes of all the strings together.
    pub fn bytes(&self) -> usize {
        self.text.len()
    }

    /// The number of distinct strings.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// The string of index `i` (empty for an index never given).
    pub fn get(&self, i: u32) -> &str {
        at(&self.text, &self.ends, i)
    }
}

/// String `i` of `text` cut at `ends` (empty for an index never given).
fn at<'t>(text: &'t str, ends: &[u32], i: u32) -> &'t str {
    let Some(&end) = ends.get(i as usize) else {
        return "";
    };
    let start = (i as usize).checked_sub(1).map_or(0, |j| ends[j]);
    &text[start as usize..end as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_strings_share_an_index_in_order_of_first_appearance() {
        let mut t = Interner::default();
        let ids: Vec<u32> = ["a", "b", "a", "", "b", "c"]
            .iter()
            .map(|s| t.intern(s))
            .collect();
        assert_eq!(ids, [0, 1, 0, 2, 1, 3]);
        assert_eq!((t.get(1), t.get(2), t.get(3), t.get(4)), ("b", "", "c", ""));
    }

    /// A sealed interner still gives every string, and adding strings after finds the old
    /// ones (the table is rebuilt).
    #[test]
    fn a_sealed_interner_reads_and_interns_as_before() {
        let mut t = Interner::default();
        t.reserve(3, 4);
        let ids: Vec<u32> = ["a", "b", "a"].iter().map(|s| t.intern(s)).collect();
        t.seal();
        assert_eq!(
            (ids, t.get(0), t.get(1), t.len()),
            (vec![0, 1, 0], "a", "b", 2)
        );
        assert_eq!((t.intern("b"), t.intern("c"), t.intern("a")), (1, 2, 0));
    }
}
