//! Times each response of the scripted tutor session (the slowest lines), for the closing note.

use std::time::Instant;

use lagrange::embedded;
use lagrange::tutor::{Progress, Session};

fn main() {
    let bank = embedded::bank();
    let mut lines = Vec::new();
    for p in &bank.problems {
        lines.push(format!(":open {}", p.id));
        for part in &p.parts {
            lines.push(
                part.wrong
                    .first()
                    .cloned()
                    .unwrap_or_else(|| "0".to_string()),
            );
            lines.push(part.reference_text(p.system.n()));
        }
        lines.push(":tutor".to_string());
        lines.push(":show".to_string());
        lines.push("0".to_string());
        lines.push(":back".to_string());
    }
    let t0 = Instant::now();
    let mut s = Session::new(bank, Progress::new());
    let open = t0.elapsed();
    let mut times: Vec<(f64, String)> = lines
        .iter()
        .map(|l| {
            let t = Instant::now();
            s.handle(l);
            (t.elapsed().as_secs_f64() * 1e3, l.clone())
        })
        .collect();
    let n = times.len();
    times.sort_by(|a, b| b.0.total_cmp(&a.0));
    println!("open {:.2} ms; {n} lines", open.as_secs_f64() * 1e3);
    for (ms, l) in times.iter().take(8) {
        println!("{ms:8.2} ms  {}", l.chars().take(70).collect::<String>());
    }
}
