//! The run id of `lagrange grade`: a hash of the class file, the options, the bank's parts
//! and lagrange's version, written on every row of results.csv and in summary.json so that
//! the files of one run can be told from another's.

use super::Options;

/// The class file's share of the run id ([`run_id`] goes on from it), taken while the file is
/// read: eight bytes a step ([`Fnv::add_words`]), a tenth of the time of one byte a step.
pub fn file_hash(bytes: &[u8]) -> Fnv {
    let mut h = Fnv::default();
    h.add(env!("CARGO_PKG_VERSION").as_bytes());
    h.add(&(bytes.len() as u64).to_le_bytes());
    h.add_words(bytes);
    h
}

/// The run's id: 16 hex digits of a hash of everything the outputs depend on (the class
/// file's bytes, from `h`; the options, the bank's parts, lagrange's version). Files of one
/// run carry the same id; two runs with equal ids wrote equal files, so outputs stay
/// byte-identical from run to run.
pub fn run_id(
    mut h: Fnv,
    opts: &Options,
    bank: &lagrange::bank::Bank,
    extra: &str,
    seed: u64,
) -> String {
    let settings = format!("{:?}|{}|{:?}", opts.follow_through, opts.best, opts.parts);
    h.add(settings.as_bytes());
    // The assignment's policy, seed and decisions (empty without them: ids stay as they were).
    h.add(extra.as_bytes());
    // The seed decides the students' numbers, so it is part of what the outputs depend on
    // (the default seed adds nothing: run ids from before it existed stay).
    if seed != 0 {
        h.add(format!("|seed {seed}").as_bytes());
    }
    for p in &bank.problems {
        for part in &p.parts {
            let key = format!(
                "{}/{}|{:?}|{}|{:?}|{:?}|{}|{:?}|{:?}\n",
                p.id,
                part.id,
                part.kind,
                part.points,
                part.answers,
                part.stability,
                part.tolerance,
                part.substitute,
                part.at
            );
            h.add(key.as_bytes());
        }
    }
    format!("{:016x}", h.0)
}

/// FNV-1a, 64 bits (and a word-at-a-time variant for the file): a hash that is the same on
/// every machine and Rust version.
pub struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn add(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }

    /// `bytes` eight at a time (little-endian words; the rest a byte at a time): each step
    /// xors a word in, multiplies by an odd constant whose bits are spread (FNV's prime only
    /// carries a word's low bits upward) and rotates, so that the high bits reach the low
    /// ones. Each step is one-to-one in the state, so two files differing in one word never
    /// share a hash.
    fn add_words(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            let mut word = [0; 8];
            word.copy_from_slice(w);
            self.0 = (self.0 ^ u64::from_le_bytes(word))
                .wrapping_mul(0x9e37_79b9_7f4a_7c15)
                .rotate_left(27);
        }
        self.add(words.remainder());
    }
}
