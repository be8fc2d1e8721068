//! What grading keeps of a checked answer: the slim verdict ([`Slim`]), its code lists stored
//! once ([`Codes`]), its words kept apart ([`Words`]) and the 128-bit grouping key of a text
//! ([`meaning`]).

use lagrange::check::{Code, Diagnosis, Status as Checked, Verdict};

/// A verdict as grading keeps it for every representative until the outputs are written:
/// the status, the score, every code (shared with the equal lists of other answers) and the
/// first diagnosis's message (results.csv, the summary, follow-through's earlier answer), by
/// its number in `Judged`'s messages. The Unicode reading is kept there too (`Judged::reading`).
/// Far smaller than a [`Verdict`]: a class of all-different answers keeps one per answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Slim {
    /// The checker's status.
    pub status: Checked,
    /// The checker's score, 0…1.
    pub score: f64,
    /// The sampling seed (kept so [`Slim::verdict`] gives back the verdict kept before).
    pub seed: u64,
    /// Every diagnosis's code, most specific first (shared with the outcomes scored from it).
    pub codes: std::sync::Arc<[Code]>,
    /// The first diagnosis's message (empty without one), as its number in the interned
    /// messages (`Judged::said`): equal messages are kept once, and none in a block of its
    /// own (a class of all-different answers has nearly a message per answer).
    pub message: u32,
}

/// What a checked answer says in words, kept apart from its [`Slim`] verdict: its Unicode
/// reading and its first diagnosis's message.
pub struct Words {
    /// How the answer was read (Unicode).
    pub reading: String,
    /// The first diagnosis's message (empty without one).
    pub message: String,
}

/// The code lists of one run's verdicts, each kept once: most wrong answers of a class get
/// one of a few (a class of all-different answers would otherwise keep a copy for each).
#[derive(Default)]
pub struct Codes(std::sync::Mutex<rustc_hash::FxHashSet<std::sync::Arc<[Code]>>>);

impl Codes {
    /// `codes`, shared with the equal list given before if there is one.
    fn share(&self, codes: Vec<Code>) -> std::sync::Arc<[Code]> {
        // A worker that panicked holding the lock left the set whole (insertions are atomic).
        let mut set = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(a) = set.get(codes.as_slice()) {
            return a.clone();
        }
        let a: std::sync::Arc<[Code]> = codes.into();
        set.insert(a.clone());
        a
    }
}

impl Slim {
    /// What grading reads of `v`, and its words (its message numbered 0).
    #[cfg(test)]
    pub fn new(v: Verdict) -> (Slim, Words) {
        Slim::shared(v, &Codes::default())
    }

    /// What grading reads of `v`, its codes shared through `codes`; and its words, to be
    /// kept apart (the message's number is set when they are: `Judged::push`).
    pub fn shared(v: Verdict, codes: &Codes) -> (Slim, Words) {
        let list = v.diagnoses.iter().map(|d| d.code).collect();
        let message = (v.diagnoses.into_iter().next()).map_or_else(String::new, |d| d.message);
        let slim = Slim {
            status: v.status,
            score: v.score,
            seed: v.seed,
            codes: codes.share(list),
            message: 0,
        };
        let words = Words {
            reading: v.reading.unicode,
            message,
        };
        (slim, words)
    }

    /// The verdict with only what grading reads (no ids, no plain reading or note, no
    /// parse error, and only the first diagnosis's message), read as `unicode` and saying
    /// `message`: what follow-through is given of an earlier answer.
    pub fn verdict(&self, unicode: &str, message: &str) -> Verdict {
        let diagnoses = (self.codes.iter().enumerate())
            .map(|(i, &code)| Diagnosis {
                code,
                message: if i == 0 {
                    message.to_string()
                } else {
                    String::new()
                },
            })
            .collect();
        Verdict::kept(
            self.status,
            self.score,
            unicode.to_string(),
            diagnoses,
            self.seed,
        )
    }

    /// The first diagnosis, as the verdict gave it (its message `message`).
    pub fn first(&self, message: &str) -> Option<Diagnosis> {
        let &code = self.codes.first()?;
        Some(Diagnosis::new(code, message.to_string()))
    }
}

/// A grouping key of 128 bits for a text (a fingerprint): SipHash-1-3 under two keys drawn
/// at random for each run, so no answer can be made to collide with another on purpose, and
/// two different texts share a key with odds of about 2⁻¹²⁸ — the summary groups by it
/// without keeping every wrong answer's fingerprint (about 100 bytes each).
pub fn meaning(text: &str) -> u128 {
    use std::hash::BuildHasher as _;
    static KEYS: std::sync::OnceLock<[std::hash::RandomState; 2]> = std::sync::OnceLock::new();
    let [a, b] =
        KEYS.get_or_init(|| [std::hash::RandomState::new(), std::hash::RandomState::new()]);
    (u128::from(a.hash_one(text)) << 64) | u128::from(b.hash_one(text))
}
