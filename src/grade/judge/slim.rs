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
    /// Every diagnosis's code, most specific first, as the number of the list in the run's
    /// code lists ([`Codes`]; `Judged::codes`): most wrong answers of a class get one of a
    /// few lists, and a number is a quarter of a shared list's size.
    pub codes: u32,
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
    /// Equal for answers equal at the sample points: the summary's grouping key (the
    /// checker's fingerprint, hashed: see [`meaning`]); 0: none.
    pub fingerprint: u128,
}

/// The code lists of one run's verdicts, each kept once and numbered in order of first
/// appearance: most wrong answers of a class get one of a few (a class of all-different
/// answers would otherwise keep a copy for each).
#[derive(Default)]
pub struct Codes(std::sync::Mutex<CodeLists>);

/// The lists and their numbers.
type CodeLists = (
    rustc_hash::FxHashMap<std::sync::Arc<[Code]>, u32>,
    Vec<std::sync::Arc<[Code]>>,
);

impl Codes {
    /// The number of `codes`, shared with the equal list given before if there is one, and
    /// the list.
    fn share(&self, codes: Vec<Code>) -> (u32, std::sync::Arc<[Code]>) {
        // A worker that panicked holding the lock left the lists whole (each change is one
        // insertion, made after the push it names).
        let mut lists = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((a, &n)) = lists.0.get_key_value(codes.as_slice()) {
            return (n, a.clone());
        }
        let a: std::sync::Arc<[Code]> = codes.into();
        let n = lists.1.len() as u32;
        lists.1.push(a.clone());
        lists.0.insert(a.clone(), n);
        (n, a)
    }

    /// Every list, by number.
    pub fn into_lists(self) -> Vec<std::sync::Arc<[Code]>> {
        self.0.into_inner().unwrap_or_else(|e| e.into_inner()).1
    }
}

impl Slim {
    /// What grading reads of `v`, its words (its message numbered 0) and its codes.
    #[cfg(test)]
    pub fn new(v: Verdict) -> (Slim, Words, std::sync::Arc<[Code]>) {
        Slim::shared(v, &Codes::default())
    }

    /// What grading reads of `v`, its codes shared through `codes`; its words, to be kept
    /// apart (the message's number is set when they are: `Judged::push`); and its code list.
    pub fn shared(v: Verdict, codes: &Codes) -> (Slim, Words, std::sync::Arc<[Code]>) {
        let list = v.diagnoses.iter().map(|d| d.code).collect();
        let message = (v.diagnoses.into_iter().next()).map_or_else(String::new, |d| d.message);
        let (number, list) = codes.share(list);
        let slim = Slim {
            status: v.status,
            score: v.score,
            seed: v.seed,
            codes: number,
            message: 0,
        };
        let words = Words {
            reading: v.reading.unicode,
            message,
            fingerprint: 0,
        };
        (slim, words, list)
    }

    /// The verdict with only what grading reads (no ids, no plain reading or note, no
    /// parse error, and only the first diagnosis's message), with its code list `codes`, read
    /// as `unicode` and saying `message`: what follow-through is given of an earlier answer.
    pub fn verdict(&self, codes: &[Code], unicode: &str, message: &str) -> Verdict {
        let diagnoses = (codes.iter().enumerate())
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

    /// The first diagnosis, as the verdict gave it (its code list `codes`, its message
    /// `message`).
    pub fn first(&self, codes: &[Code], message: &str) -> Option<Diagnosis> {
        let &code = codes.first()?;
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
