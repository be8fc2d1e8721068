//! One cancellable progress callback for the library's long calls (a long simulation, a chaos
//! run, a flip-time batch; the grade face routes its bar through the same type).
//!
//! A long call takes `&mut dyn Progress` and calls [`Progress::report`] now and then with the
//! work done so far out of a total (in the call's own units). A face draws a bar from it, and
//! stops the call by returning [`ControlFlow::Break`]: the call then returns its layer's
//! "interrupted" error ([`Interrupted`] inside it), with nothing half-built. No threads, no
//! clock, no terminal here: the callback decides what a report means.
//!
//! Not to be confused with [`crate::tutor::Progress`], the student's record.

use std::cell::RefCell;
use std::ops::ControlFlow;

/// Told how far a long call has come; may ask it to stop.
pub trait Progress {
    /// `done` units of work out of `total` are finished. `Break` stops the call, which then
    /// returns its "interrupted" error.
    fn report(&mut self, done: u64, total: u64) -> ControlFlow<()>;
}

/// Any `FnMut(done, total) -> ControlFlow<()>` is a progress callback.
impl<F: FnMut(u64, u64) -> ControlFlow<()>> Progress for F {
    fn report(&mut self, done: u64, total: u64) -> ControlFlow<()> {
        self(done, total)
    }
}

/// The callback that listens to nothing and never stops a call.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Progress for Silent {
    fn report(&mut self, _done: u64, _total: u64) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// The error a call returns when its callback asked it to stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("interrupted")]
pub struct Interrupted;

/// `report`, with `Break` as the [`Interrupted`] error (for `?` inside a long call).
pub fn tick(p: &mut dyn Progress, done: u64, total: u64) -> Result<(), Interrupted> {
    match p.report(done, total) {
        ControlFlow::Continue(()) => Ok(()),
        ControlFlow::Break(()) => Err(Interrupted),
    }
}

/// The units in which a run over an interval of time reports: millionths of the interval.
pub const PARTS: u64 = 1_000_000;

/// How far `t` is through [t0, t1], in [`PARTS`].
pub fn fraction(t: f64, t0: f64, t1: f64) -> u64 {
    let f = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
    if f.is_finite() {
        (f * PARTS as f64) as u64
    } else {
        0
    }
}

/// Stage `index` of `count` stages of one call: each stage's own (done, total) is rescaled
/// to its share of the whole, in [`PARTS`] per stage.
pub struct Stage<'a> {
    inner: &'a mut dyn Progress,
    index: u64,
    count: u64,
}

impl<'a> Stage<'a> {
    /// Stage `index` (from 0) of `count`, reporting to `inner`.
    pub fn new(inner: &'a mut dyn Progress, index: u64, count: u64) -> Self {
        Stage {
            inner,
            index,
            count: count.max(1),
        }
    }
}

impl Progress for Stage<'_> {
    fn report(&mut self, done: u64, total: u64) -> ControlFlow<()> {
        let part = if total == 0 {
            PARTS
        } else {
            ((done.min(total) as u128 * PARTS as u128) / total as u128) as u64
        };
        self.inner
            .report(self.index * PARTS + part, self.count * PARTS)
    }
}

thread_local! {
    /// The callback set by [`with_ambient`] for calls whose caller cannot pass one.
    static AMBIENT: RefCell<Option<Box<dyn Progress>>> = const { RefCell::new(None) };
}

/// Runs `f` with `p` as the callback of the long calls inside it that take none (the plain
/// entry points, such as [`crate::report::simulation()`], report to it): how a face reaches a
/// call made for it by a layer that does not pass a callback (the tutor's `:simulate`).
/// Scoped to this thread and to `f`; returns `f`'s result.
pub fn with_ambient<R>(p: Box<dyn Progress>, f: impl FnOnce() -> R) -> R {
    let before = AMBIENT.with(|a| a.borrow_mut().replace(p));
    let r = f();
    AMBIENT.with(|a| *a.borrow_mut() = before);
    r
}

/// The callback that forwards to the one [`with_ambient`] set (none: never stops).
#[derive(Clone, Copy, Debug, Default)]
pub struct Ambient;

impl Progress for Ambient {
    fn report(&mut self, done: u64, total: u64) -> ControlFlow<()> {
        AMBIENT.with(|a| match a.try_borrow_mut() {
            Ok(mut slot) => match slot.as_mut() {
                Some(p) => p.report(done, total),
                None => ControlFlow::Continue(()),
            },
            // A report from inside the callback itself: nothing to forward to.
            Err(_) => ControlFlow::Continue(()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_share_the_whole_and_ambient_is_scoped() {
        let mut seen = Vec::new();
        let mut rec = |d: u64, t: u64| {
            seen.push((d, t));
            ControlFlow::Continue(())
        };
        let mut s = Stage::new(&mut rec, 1, 2);
        let _ = s.report(1, 2);
        assert_eq!(seen, [(PARTS + PARTS / 2, 2 * PARTS)]);
        let stop = with_ambient(Box::new(|_, _| ControlFlow::Break(())), || {
            tick(&mut Ambient, 0, 1)
        });
        assert_eq!(stop, Err(Interrupted));
        assert_eq!(tick(&mut Ambient, 0, 1), Ok(()));
        assert_eq!(fraction(5.0, 0.0, 10.0), PARTS / 2);
    }
}
