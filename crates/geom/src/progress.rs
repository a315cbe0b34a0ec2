//! How far a long computation got, for a caller that shows it (a progress bar), without the
//! stages knowing who watches: a stage takes a `&dyn Fn(u64, u64)` and reports through a
//! [`Meter`].
//!
//! What is decided:
//! * The bar has a fixed length, [`TOTAL`] thousandths of the whole computation: the stages'
//!   phases count different things (points inserted, passes, tets of a list), so each phase
//!   gets a share of the bar ([`Span`]) and reports the fraction of its own work it has done.
//!   Shares come from measured times or from estimates the stage makes as it learns more; they
//!   only decide how evenly the bar moves, never what is computed.
//! * `done` never decreases, `total` never changes, and the last report of a computation that
//!   succeeds is `done == total` ([`Meter::finish`]).
//! * Reports are throttled: one when `done` advanced by [`STEP`] since the last, so at most
//!   `TOTAL / STEP + 2` per computation, whatever calls `Span::reach` makes. A `reach` that
//!   reports nothing costs a few floating-point operations, cheap enough per inserted point.
//! * Progress is read-only: nothing a stage computes may depend on it, so a mesh is the same
//!   bit for bit with or without a watcher.

use std::cell::Cell;

/// The length of every meter's bar.
pub const TOTAL: u64 = 1000;
/// Reports are at least this many thousandths apart (the last one excepted).
pub const STEP: u64 = 5;

/// The progress of one computation, reported to `report(done, TOTAL)`.
pub struct Meter<'a> {
    report: &'a dyn Fn(u64, u64),
    /// The last `done` reported.
    last: Cell<u64>,
}

impl<'a> Meter<'a> {
    /// A meter that reports `0` of [`TOTAL`] at once.
    pub fn new(report: &'a dyn Fn(u64, u64)) -> Meter<'a> {
        report(0, TOTAL);
        Meter {
            report,
            last: Cell::new(0),
        }
    }

    /// The whole bar.
    pub fn whole(&self) -> Span<'_> {
        Span {
            meter: Some(self),
            lo: 0.0,
            hi: 1.0,
        }
    }

    /// The bar from where it stands to its end: what is left when the plan changes (a method
    /// that gave way to another).
    pub fn rest(&self) -> Span<'_> {
        Span {
            meter: Some(self),
            lo: self.last.get() as f64 / TOTAL as f64,
            hi: 1.0,
        }
    }

    /// Reports `done == total`, unless it was reported already.
    pub fn finish(&self) {
        if self.last.get() < TOTAL {
            self.last.set(TOTAL);
            (self.report)(TOTAL, TOTAL);
        }
    }

    /// The bar reached `x` (a fraction of it).
    fn reach(&self, x: f64) {
        let done = ((x * TOTAL as f64) as u64).min(TOTAL);
        let last = self.last.get();
        if done >= last + STEP || (done == TOTAL && last < TOTAL) {
            self.last.set(done);
            (self.report)(done, TOTAL);
        }
    }
}

/// A share of a meter's bar, from `lo` to `hi` (fractions of it), that one phase fills; or
/// nothing ([`Span::none`]) for work nobody watches.
#[derive(Clone, Copy)]
pub struct Span<'m> {
    meter: Option<&'m Meter<'m>>,
    lo: f64,
    hi: f64,
}

impl<'m> Span<'m> {
    /// A span that reports nothing.
    pub fn none() -> Span<'static> {
        Span {
            meter: None,
            lo: 0.0,
            hi: 1.0,
        }
    }

    /// The part of this span from fraction `from` to `to` of it.
    pub fn part(self, from: f64, to: f64) -> Span<'m> {
        let w = self.hi - self.lo;
        Span {
            meter: self.meter,
            lo: self.lo + w * from.clamp(0.0, 1.0),
            hi: self.lo + w * to.clamp(from.clamp(0.0, 1.0), 1.0),
        }
    }

    /// This span cut into consecutive parts in proportion to `weights` (equal parts when they
    /// are all zero).
    pub fn split<const N: usize>(self, weights: [f64; N]) -> [Span<'m>; N] {
        let weights = weights.map(|w| if w.is_finite() && w > 0.0 { w } else { 0.0 });
        let sum: f64 = weights.iter().sum();
        let mut at = 0.0;
        std::array::from_fn(|k| {
            let share = if sum > 0.0 {
                weights[k] / sum
            } else {
                1.0 / N as f64
            };
            let part = self.part(at, at + share);
            at += share;
            part
        })
    }

    /// This phase has done fraction `f` of its work (clamped to `[0, 1]`; a lower fraction than
    /// one reported before reports nothing).
    #[inline]
    pub fn reach(self, f: f64) {
        if let Some(m) = self.meter {
            m.reach(self.lo + (self.hi - self.lo) * f.clamp(0.0, 1.0));
        }
    }

    /// This phase has done `k` of its `n` steps.
    #[inline]
    pub fn step(self, k: usize, n: usize) {
        if n > 0 {
            self.reach(k as f64 / n as f64);
        }
    }

    /// This phase is over.
    pub fn done(self) {
        self.reach(1.0);
    }
}

/// Whether item `k` is in a sample of about one in `every` items, for estimates that feed only
/// a progress bar: picked by a multiplicative hash, not a stride, so that a pattern in the items'
/// order (the fans an insertion creates, each a few slots long) does not bias the sample.
#[inline]
pub fn sampled(k: usize, every: usize) -> bool {
    every <= 1
        || ((k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 32).is_multiple_of(every as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    #[test]
    fn reports_are_monotone_throttled_and_end_at_the_total() {
        let seen = RefCell::new(Vec::new());
        let report = |d: u64, t: u64| seen.borrow_mut().push((d, t));
        let meter = Meter::new(&report);
        let [a, b, c] = meter.whole().split([1.0, 2.0, 1.0]);
        for k in 0..=10_000 {
            a.step(k, 10_000);
        }
        b.reach(0.5);
        b.reach(0.25); // backwards: nothing
        c.part(0.5, 1.0).reach(0.5);
        meter.finish();
        meter.finish();
        let seen = seen.into_inner();
        assert!(seen.iter().all(|&(_, t)| t == TOTAL));
        assert!(seen.windows(2).all(|w| w[0].0 < w[1].0), "{seen:?}");
        assert_eq!(seen.first(), Some(&(0, TOTAL)));
        assert_eq!(seen.last(), Some(&(TOTAL, TOTAL)));
        // a: 250 thousandths in steps of 5; b at its half (500); c at 3/4 of its part (937).
        assert_eq!(seen.len(), 1 + 50 + 1 + 1 + 1, "{seen:?}");
        assert!(seen.contains(&(500, TOTAL)) && seen.contains(&(937, TOTAL)));
    }

    #[test]
    fn a_sample_takes_about_one_in_every() {
        for every in [1, 3, 4, 17] {
            let n = (0..100_000).filter(|&k| sampled(k, every)).count();
            let want = 100_000 / every;
            assert!(n.abs_diff(want) * 50 < want, "{every}: {n}");
            // Not a stride: consecutive runs of `every` items are not each sampled once.
            if every > 1 {
                assert!((0..every * 20).step_by(every).any(|k| !sampled(k, every)));
            }
        }
    }

    #[test]
    fn a_span_of_nothing_and_the_rest_of_a_bar() {
        Span::none().reach(0.5);
        let n = Cell::new(0);
        let report = |_: u64, _: u64| n.set(n.get() + 1);
        let meter = Meter::new(&report);
        meter.whole().reach(0.6);
        let rest = meter.rest();
        rest.reach(0.5);
        assert_eq!(meter.last.get(), 800);
        assert_eq!(n.get(), 3);
    }
}
