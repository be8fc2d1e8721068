//! The summary's wrong-answer groups: each counted from its rows (students, attempts, rows
//! per representative and per spelling), shown as its most common reading, and only each
//! part's best few kept while the groups come in, so memory is bounded however many groups
//! a class has (a class of all-different answers has one per answer).

use std::collections::BTreeMap;

use rustc_hash::FxHashMap;

use super::super::input::Table;
use super::super::judge::{Judged, Status};
use super::{Group, PartSummary};

/// How many wrong-answer groups are listed per part.
const MAX_GROUPS: usize = 10;
/// How long a spelling may be in the summary before it is cut.
const MAX_SHOWN: usize = 80;

/// A group counted: rows, distinct students, rows per representative and per spelling (an
/// interned answer), each list sorted.
pub(super) struct Tally {
    count: usize,
    students: usize,
    by_rep: Vec<(usize, usize)>,
    by_answer: Vec<(u32, usize)>,
}

/// Runs of equal values in a sorted list, with their lengths.
fn runs<T: PartialEq + Copy>(sorted: impl IntoIterator<Item = T>) -> Vec<(T, usize)> {
    let mut out: Vec<(T, usize)> = Vec::new();
    for x in sorted {
        match out.last_mut() {
            Some((y, n)) if *y == x => *n += 1,
            _ => out.push((x, 1)),
        }
    }
    out
}

/// Counts each group from its rows' (student, representative, answer), sorted.
pub(super) fn tally(rows: &[(u32, u32, u32, u32)]) -> Tally {
    let students = runs(rows.iter().map(|r| r.1)).len();
    let mut reps: Vec<u32> = rows.iter().map(|r| r.2).collect();
    reps.sort_unstable();
    let mut answers: Vec<u32> = rows.iter().map(|r| r.3).collect();
    answers.sort_unstable();
    Tally {
        count: rows.len(),
        students,
        by_rep: runs(reps.into_iter().map(|r| r as usize)),
        by_answer: runs(answers),
    }
}

/// Groups counted and shown per batch in [`super::summarise`].
pub(super) const GROUP_BATCH: usize = 4096;

/// Each part's sorted, truncated group lists, made from the groups one at a time. Groups are
/// ordered by their counts and full text ([`Shown`]); only the listed ones are made whole
/// (codes, diagnosis, cut spellings), so a class of all-different answers keeps no more than
/// the text each is sorted by.
///
/// Per part and kind (wrong, unreadable): the best groups so far and the rows of all. Cut
/// back to the listed few whenever many have gathered, so a class of all-different answers
/// never holds every group's text at once (the order is total up to ties, which a stable
/// sort keeps in order of first appearance, as one sort of all would).
#[derive(Default)]
pub(super) struct Best {
    per_part: BTreeMap<(String, bool), (Vec<Shown>, usize)>,
}

/// The order groups are listed in: most students, then most rows, then the full text.
fn order(a: &Shown, b: &Shown) -> std::cmp::Ordering {
    b.students
        .cmp(&a.students)
        .then_with(|| b.count.cmp(&a.count))
        .then_with(|| a.full.cmp(&b.full))
}

impl Best {
    /// Adds the next group (groups come in the order of their first appearance).
    pub(super) fn push(&mut self, key: String, status: Status, g: Shown) {
        let (best, rows) = self
            .per_part
            .entry((key, status == Status::Invalid))
            .or_default();
        *rows += g.count;
        best.push(g);
        if best.len() >= 8 * MAX_GROUPS {
            best.sort_by(order);
            best.truncate(MAX_GROUPS);
        }
    }

    /// Puts each part's listed groups and the count of the others into `parts`.
    pub(super) fn finish(self, parts: &mut BTreeMap<String, PartSummary>, judged: &Judged) {
        for ((key, unreadable), (mut best, rows)) in self.per_part {
            best.sort_by(order);
            best.truncate(MAX_GROUPS);
            let other = rows - best.iter().map(|g| g.count).sum::<usize>();
            let listed: Vec<Group> = best.into_iter().map(|g| group(g, judged)).collect();
            if let Some(s) = parts.get_mut(&key) {
                if unreadable {
                    (s.unreadable, s.other_unreadable) = (listed, other);
                } else {
                    (s.wrong, s.other_wrong) = (listed, other);
                }
            }
        }
    }
}

/// Every tally shown and listed, in order (what [`super::summarise`] does a batch at a time).
#[cfg(test)]
fn add_groups(
    parts: &mut BTreeMap<String, PartSummary>,
    tallies: Vec<((String, Status), Tally)>,
    table: &Table,
    judged: &Judged,
) {
    let mut best = Best::default();
    for ((key, status), t) in tallies {
        best.push(key, status, shown(status, t, table, judged));
    }
    best.finish(parts, judged);
}

/// A group as it is sorted: its counts, its most common reading (ties: the smaller text) and
/// the representative giving it, and its spellings as typed (trimmed), most common first.
pub(super) struct Shown {
    students: usize,
    count: usize,
    status: Status,
    rep: Option<usize>,
    /// The reading and spellings uncut: ties in the order are broken by the full text,
    /// never by the cut one.
    full: (String, Vec<String>),
}

/// How a tallied group is sorted and shown.
pub(super) fn shown(status: Status, t: Tally, table: &Table, judged: &Judged) -> Shown {
    let shown_of = |rep: usize| {
        let r = &judged.reps[rep];
        match (&r.verdict, judged.reading(rep)) {
            (Ok(_), reading) if !reading.is_empty() => reading.to_string(),
            _ => table.answers.get(r.answer).trim().to_string(),
        }
    };
    let mut reps: Vec<(usize, String, usize)> =
        t.by_rep.iter().map(|&(r, n)| (n, shown_of(r), r)).collect();
    reps.sort_by(|a, b| b.0.cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
    let (answer, rep) = reps
        .into_iter()
        .next()
        .map(|(_, s, r)| (s, Some(r)))
        .unwrap_or_default();
    let mut by_text: FxHashMap<&str, usize> = FxHashMap::default();
    for &(a, n) in &t.by_answer {
        *by_text.entry(table.answers.get(a).trim()).or_insert(0) += n;
    }
    let mut texts: Vec<(&str, usize)> = by_text.into_iter().collect();
    texts.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
    Shown {
        students: t.students,
        count: t.count,
        status,
        rep,
        full: (answer, texts.iter().map(|(s, _)| s.to_string()).collect()),
    }
}

/// One listed group: shown as its most common reading, with that reading's codes and first
/// diagnosis and its two most common spellings.
fn group(g: Shown, judged: &Judged) -> Group {
    let verdict = g.rep.and_then(|r| judged.reps[r].verdict.as_ref().ok());
    Group {
        students: g.students,
        count: g.count,
        status: g.status.name().to_string(),
        answer: cut(&g.full.0),
        codes: verdict.map_or(Vec::new(), |v| {
            judged.codes(v).iter().map(|c| c.to_string()).collect()
        }),
        diagnosis: verdict.map_or(String::new(), |v| judged.said(v).to_string()),
        examples: g.full.1.iter().take(2).map(|s| cut(s)).collect(),
    }
}

/// A text cut to [`MAX_SHOWN`] characters, on one line.
fn cut(s: &str) -> String {
    let one: String = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if one.chars().count() <= MAX_SHOWN {
        return one;
    }
    let mut t: String = one.chars().take(MAX_SHOWN - 1).collect();
    t.push('…');
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::summary::empty;

    /// Many wrong-answer groups in one part, most of them tied (one student, one attempt
    /// each, as in a class of all-different answers): the groups listed and the count of the
    /// others are those one sort of every group gives, though only the best few are kept
    /// while counting.
    #[test]
    fn the_listed_groups_are_the_best_of_all_however_many() {
        let mut csv = String::from("student,problem,part,answer\n");
        let n = 500;
        for i in 0..n {
            csv.push_str(&format!("s{i},p,q,answer {:03}\n", (i * 7919) % n));
        }
        let table = super::super::super::input::parse(csv.as_bytes(), &mut Default::default());
        let table = table.map_err(|e| e.0).unwrap_or_else(|e| panic!("{e}"));
        let judged = Judged::unchecked((0..n).map(|a| a as u32));
        // Group g holds representative g; a few groups have more students and attempts.
        let tallies = |k: usize| -> Vec<((String, Status), Tally)> {
            (0..k)
                .map(|g| {
                    let extra = usize::from(g % 97 == 3) * (g % 5 + 1);
                    let tally = Tally {
                        count: 1 + extra,
                        students: 1 + extra / 2,
                        by_rep: vec![(g, 1 + extra)],
                        by_answer: vec![(g as u32, 1 + extra)],
                    };
                    (("p/q".to_string(), Status::Incorrect), tally)
                })
                .collect()
        };
        let mut parts = BTreeMap::from([("p/q".to_string(), empty(1.0))]);
        add_groups(&mut parts, tallies(n), &table, &judged);
        // The reference: every group shown, one stable sort, the first ten.
        let mut all: Vec<Shown> = (tallies(n).into_iter())
            .map(|((_, status), t)| shown(status, t, &table, &judged))
            .collect();
        all.sort_by(|a, b| {
            b.students
                .cmp(&a.students)
                .then_with(|| b.count.cmp(&a.count))
                .then_with(|| a.full.cmp(&b.full))
        });
        let want: Vec<(usize, usize, String)> = (all.iter().take(MAX_GROUPS))
            .map(|g| (g.students, g.count, g.full.0.clone()))
            .collect();
        let other: usize = all.iter().skip(MAX_GROUPS).map(|g| g.count).sum();
        let p = &parts["p/q"];
        let got: Vec<(usize, usize, String)> = (p.wrong.iter())
            .map(|g| (g.students, g.count, g.answer.clone()))
            .collect();
        assert_eq!(got, want);
        assert_eq!(p.other_wrong, other);
        assert!(want[0].0 > 1 && want[MAX_GROUPS - 1].0 == 1, "{want:?}");
    }
}
