//! The faces' progress bar: a [`Progress`] callback that draws an indicatif bar on stderr for
//! a long run — only on a terminal, never with `--json` or when stderr is piped, and only once
//! the run has lasted [`SHOW_AFTER`] (a short run never flashes one). Optionally it polls a
//! stop flag (the REPL's Ctrl-C) and then asks the run to stop.

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lagrange::progress::Progress;

/// A run is given a bar once it has lasted this long.
pub const SHOW_AFTER: Duration = Duration::from_millis(300);

/// The bar of one run; [`Bar::finish`] clears it.
pub struct Bar {
    bar: ProgressBar,
    start: Instant,
    /// Whether a bar may be drawn at all (stderr a terminal, no `--json`).
    on: bool,
    shown: bool,
    stop: Option<Arc<AtomicBool>>,
}

impl Bar {
    /// A bar with indicatif's `template` (`{bar:40} {percent}%`…), drawn only if `on` and
    /// stderr is a terminal.
    pub fn new(template: &str, on: bool) -> Bar {
        let bar = ProgressBar::hidden();
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style);
        }
        Bar {
            bar,
            start: Instant::now(),
            on: on && std::io::stderr().is_terminal(),
            shown: false,
            stop: None,
        }
    }

    /// The bar for a run over an interval of time (the library reports millionths of it).
    pub fn percent(on: bool) -> Bar {
        Bar::new("{bar:40} {percent:>3}% {elapsed} ({eta} left)", on)
    }

    /// Also asks the run to stop once `flag` is set.
    pub fn stopped_by(mut self, flag: Arc<AtomicBool>) -> Bar {
        self.stop = Some(flag);
        self
    }

    /// Clears the bar from the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.finish();
    }
}

impl Progress for Bar {
    fn report(&mut self, done: u64, total: u64) -> ControlFlow<()> {
        if self
            .stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
        {
            return ControlFlow::Break(());
        }
        if self.on && !self.shown && self.start.elapsed() >= SHOW_AFTER {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar.set_length(total);
        self.bar.set_position(done);
        ControlFlow::Continue(())
    }
}

/// One callback fed by many threads: each finished unit of work is a [`Shared::tick`], and
/// the inner callback hears the count now and then (from whichever thread gets to it). Once
/// it answers `Break`, every later tick says so.
pub struct Shared<'a> {
    inner: std::sync::Mutex<&'a mut (dyn Progress + Send)>,
    done: std::sync::atomic::AtomicU64,
    total: std::sync::atomic::AtomicU64,
    stop: AtomicBool,
}

/// Units between two reports of a [`Shared`] callback.
const SHARED_EVERY: u64 = 64;

impl<'a> Shared<'a> {
    /// The shared face of `inner`.
    pub fn new(inner: &'a mut (dyn Progress + Send)) -> Self {
        Shared {
            inner: std::sync::Mutex::new(inner),
            done: 0.into(),
            total: 0.into(),
            stop: AtomicBool::new(false),
        }
    }

    /// A new stage of `total` units, counted from 0.
    pub fn start(&self, total: u64) {
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
        self.report(0);
    }

    /// One unit done; `false` once the callback asked to stop.
    pub fn tick(&self) -> bool {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if done.is_multiple_of(SHARED_EVERY) || done == self.total.load(Ordering::Relaxed) {
            self.report(done);
        }
        !self.stopped()
    }

    /// Whether the callback asked to stop.
    pub fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    fn report(&self, done: u64) {
        if let Ok(mut p) = self.inner.try_lock()
            && p.report(done, self.total.load(Ordering::Relaxed))
                .is_break()
        {
            self.stop.store(true, Ordering::Relaxed);
        }
    }
}
