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
    /// Where each string is in `text`: (start, end).
    spans: Vec<(u32, u32)>,
    /// Indices into `spans`, by the hash of their string.
    table: HashTable<u32>,
}

impl Interner {
    /// Room for `strings` distinct strings of `bytes` bytes in all.
    pub fn with_capacity(strings: usize, bytes: usize) -> Interner {
        Interner {
            text: String::with_capacity(bytes),
            spans: Vec::with_capacity(strings),
            table: HashTable::with_capacity(strings),
        }
    }

    /// The index of `s`, added if new.
    pub fn intern(&mut self, s: &str) -> u32 {
        let hash = FxBuildHasher.hash_one(s);
        let (text, spans) = (&self.text, &self.spans);
        let get = |i: u32| {
            let (a, b) = spans[i as usize];
            &text[a as usize..b as usize]
        };
        if let Some(&i) = self.table.find(hash, |&i| get(i) == s) {
            return i;
        }
        let i = self.spans.len() as u32;
        let start = self.text.len() as u32;
        self.text.push_str(s);
        self.spans.push((start, self.text.len() as u32));
        let (text, spans) = (&self.text, &self.spans);
        self.table.insert_unique(hash, i, |&j| {
            let (a, b) = spans[j as usize];
            FxBuildHasher.hash_one(&text[a as usize..b as usize])
        });
        i
    }

    /// The number of distinct strings.
    pub fn len(&self) -> usize {
        self.spans.len()
    }

    /// The string of index `i` (empty for an index never given).
    pub fn get(&self, i: u32) -> &str {
        self.spans
            .get(i as usize)
            .map_or("", |&(a, b)| &self.text[a as usize..b as usize])
    }
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
}
