//! A class file's header: the columns `grade` needs (long format `student,problem,part,answer`,
//! or wide format with one `PROBLEM/PART` column per part) found by name, whatever their order
//! and case.

/// The columns the header must have, for the error message.
pub(super) const EXPECTED: &str = "expected the columns `student,problem,part,answer` (long format) or \
                        `student` plus one `PROBLEM/PART` column per part (wide format)";

/// Where each needed column is in a header.
pub(super) enum Layout {
    Long {
        student: usize,
        problem: usize,
        part: usize,
        answer: usize,
    },
    /// The student column and each part column with its problem and part ids.
    Wide {
        student: usize,
        parts: Vec<(usize, String, String)>,
    },
}

/// A header cell as compared: trimmed, lower-case, without a byte-order mark.
pub(super) fn header_name(field: &[u8]) -> String {
    let text = String::from_utf8_lossy(field);
    text.trim_start_matches('\u{feff}').trim().to_lowercase()
}

/// The layout a header describes, or the error naming the expected columns.
pub(super) fn layout(names: &[String]) -> Result<Layout, String> {
    let find = |n: &str| names.iter().position(|h| h == n);
    let found = || {
        // Control characters shown escaped, and a binary file's "header" cut short.
        let shown: String = lagrange::expr::error::visible(&names.join(","))
            .chars()
            .take(200)
            .collect();
        format!("found `{shown}`")
    };
    let Some(student) = find("student") else {
        return Err(format!("bad header: {EXPECTED}; {}", found()));
    };
    if let (Some(problem), Some(part), Some(answer)) =
        (find("problem"), find("part"), find("answer"))
    {
        return Ok(Layout::Long {
            student,
            problem,
            part,
            answer,
        });
    }
    let parts: Vec<(usize, String, String)> = names
        .iter()
        .enumerate()
        .filter_map(|(i, n)| {
            let (problem, part) = n.split_once('/')?;
            let (problem, part) = (problem.trim(), part.trim());
            (!problem.is_empty() && !part.is_empty())
                .then(|| (i, problem.to_string(), part.to_string()))
        })
        .collect();
    if parts.is_empty() {
        return Err(format!("bad header: {EXPECTED}; {}", found()));
    }
    Ok(Layout::Wide { student, parts })
}
