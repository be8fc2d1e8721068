//! What grading keeps of a checked answer: the slim verdict ([`Slim`]), its messages and code
//! lists stored once ([`Messages`]) and the 128-bit grouping key of a text ([`meaning`]).

use lagrange::check::{Code, Diagnosis, Status as Checked, Verdict};

/// A verdict as grading keeps it for every representative until the outputs are written:
/// the status, the score, every code and the first diagnosis's message (results.csv, the
/// summary, follow-through's earlier answer), both shared with the equal ones of other
/// answers. The Unicode reading is kept apart, in one string for all
/// (`Judged::reading`). Far smaller than a [`Verdict`]: a class of all-different answers
/// keeps one per answer.
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
    /// The first diagnosis's message (empty without one), shared by the representatives
    /// given the same ([`Messages`]).
    pub message: std::sync::Arc<str>,
}

/// The messages and code lists of one run's verdicts, each kept once: most wrong answers of
/// a class get one of a few (a class of all-different answers would otherwise keep a copy
/// for each answer).
#[derive(Default)]
pub struct Messages(std::sync::Mutex<Shared>);

/// The messages and code lists given so far.
#[derive(Default)]
pub struct Shared {
    messages: rustc_hash::FxHashSet<std::sync::Arc<str>>,
    codes: rustc_hash::FxHashSet<std::sync::Arc<[Code]>>,
}

impl Messages {
    /// `m` and `codes`, each shared with the equal one given before if there is one.
    fn share(&self, m: String, codes: Vec<Code>) -> (std::sync::Arc<str>, std::sync::Arc<[Code]>) {
        // A worker that panicked holding the lock left the sets whole (insertions are atomic).
        let mut shared = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let m = match shared.messages.get(m.as_str()) {
            Some(a) => a.clone(),
            None => {
                let a: std::sync::Arc<str> = m.into();
                shared.messages.insert(a.clone());
                a
            }
        };
        let codes = match shared.codes.get(codes.as_slice()) {
            Some(a) => a.clone(),
            None => {
                let a: std::sync::Arc<[Code]> = codes.into();
                shared.codes.insert(a.clone());
                a
            }
        };
        (m, codes)
    }
}

impl Slim {
    /// What grading reads of `v`, and its Unicode reading.
    #[cfg(test)]
    pub fn new(v: Verdict) -> (Slim, String) {
        Slim::shared(v, &Messages::default())
    }

    /// What grading reads of `v`, its message and codes shared through `messages`; and its
    /// Unicode reading.
    pub fn shared(v: Verdict, messages: &Messages) -> (Slim, String) {
        let codes = v.diagnoses.iter().map(|d| d.code).collect();
        let first = (v.diagnoses.into_iter().next()).map_or_else(String::new, |d| d.message);
        let (message, codes) = messages.share(first, codes);
        let slim = Slim {
            status: v.status,
            score: v.score,
            seed: v.seed,
            codes,
            message,
        };
        (slim, v.reading.unicode)
    }

    /// The verdict with only what grading reads (no ids, no plain reading or note, no
    /// parse error, and only the first diagnosis's message), read as `unicode`: what
    /// follow-through is given of an earlier answer.
    pub fn verdict(&self, unicode: &str) -> Verdict {
        let diagnoses = (self.codes.iter().enumerate())
            .map(|(i, &code)| Diagnosis {
                code,
                message: if i == 0 {
                    self.message.to_string()
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

    /// The first diagnosis, as the verdict gave it.
    pub fn first(&self) -> Option<Diagnosis> {
        let &code = self.codes.first()?;
        Some(Diagnosis::new(code, self.message.to_string()))
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
