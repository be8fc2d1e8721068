//! Where `lagrange grade`'s time goes, for its benchmark (`scripts/bench-grade`): with
//! `LAGRANGE_GRADE_PHASES=1` in the environment, each phase's wall time, the process's CPU
//! time (every thread, user + system) and its resident memory are printed on stderr when the
//! phase ends. A phase whose CPU time is about its wall time ran on one core: the serial part
//! that limits what a second core can give. Without the variable nothing is measured.

use std::time::Instant;

/// Times phases when asked to by the environment (the default: never).
#[derive(Default)]
pub struct Phases {
    /// When the last phase ended, and the process's CPU time (ns) then; `None`: not timing.
    last: Option<(Instant, u64)>,
}

impl Phases {
    /// Starts timing if `LAGRANGE_GRADE_PHASES` is set (to anything but `0` or nothing).
    pub fn from_env() -> Self {
        let on =
            std::env::var_os("LAGRANGE_GRADE_PHASES").is_some_and(|v| !v.is_empty() && v != "0");
        Phases {
            last: on.then(|| (Instant::now(), cpu_ns())),
        }
    }

    /// Ends the phase `name` (printing its figures) and starts the next one.
    pub fn end(&mut self, name: &str) {
        let Some((t0, c0)) = self.last else { return };
        let (t1, c1) = (Instant::now(), cpu_ns());
        let wall = (t1 - t0).as_secs_f64();
        let cpu = c1.saturating_sub(c0) as f64 / 1e9;
        let (rss, peak) = memory();
        eprintln!(
            "phase {name:<14} {:8.1} ms wall {:8.1} ms CPU  rss {rss:5} MB  peak {peak:5} MB",
            wall * 1e3,
            cpu * 1e3
        );
        // Reading /proc takes a little CPU itself: the next phase starts after it.
        self.last = Some((Instant::now(), cpu_ns()));
    }
}

impl Phases {
    /// Prints each thread's CPU time so far: with two worker threads, how evenly the work
    /// was shared (the main thread mostly waits for the workers).
    pub fn threads(&self) {
        if self.last.is_none() {
            return;
        }
        let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
            return;
        };
        let mut each: Vec<(String, u64)> = tasks
            .flatten()
            .filter_map(|t| {
                let name = std::fs::read_to_string(t.path().join("comm")).ok()?;
                let s = std::fs::read_to_string(t.path().join("schedstat")).ok()?;
                Some((
                    name.trim().to_string(),
                    s.split_whitespace().next()?.parse().ok()?,
                ))
            })
            .collect();
        each.sort();
        let shown: Vec<String> = (each.iter())
            .map(|(name, ns)| format!("{name} {:.1} ms", *ns as f64 / 1e6))
            .collect();
        eprintln!("threads: {}", shown.join(", "));
    }
}

/// The CPU time of every thread of the process, in ns (Linux: the sum of each task's
/// `schedstat`, which counts time on a CPU in ns; 0 where it cannot be read).
fn cpu_ns() -> u64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0;
    };
    tasks
        .flatten()
        .filter_map(|t| std::fs::read_to_string(t.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .sum()
}

/// The resident memory now and at its peak, in MB (0 where it cannot be read).
fn memory() -> (u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
            .map_or(0, |kb| kb / 1024)
    };
    (field("VmRSS:"), field("VmHWM:"))
}
