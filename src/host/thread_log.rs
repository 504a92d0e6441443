//! What a threading run records at the pins, and the figures made from it:
//! each spindle count with the geared axis's position once that count's
//! step has had time to leave, and each index edge.
//!
//! **Lead error.** At every spindle count c of a pass, while the gearbox
//! is locked, the error is e(c) = p(c) - (s + dir x k x (c - c0)) steps:
//! p(c) the axis's position at the pins [`SAMPLE_DELAY`] clocks after the
//! count's edge (the gearbox's count-to-step latency and two clocks), s the
//! pass's start (its programmed start in steps, unrounded), k the pitch in
//! steps per count and c0 the count of the index that engaged the pass.
//! The thread's ideal is a helix of exact pitch in one phase for all its
//! passes, so the lead error is half the spread of e over every pass:
//! (max e - min e) / 2. A pass's phase is the mean of its e; the pass
//! phase spread is the largest minus the smallest.

use crate::blocks::motion_controller::latency;

/// Clocks from a spindle count's edge to the sample of the axis's
/// position: the gearbox's count-to-step latency, and two clocks for the
/// pins to reach the plant and the step's edge to reach the position.
pub const SAMPLE_DELAY: u64 = latency::SPINDLE_COUNT_TO_STEP + 2;

/// A spindle count and the geared axis's position after it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CountSample {
    /// The clock of the count's edge.
    pub clock: u64,
    /// The spindle encoder's count (from power-up).
    pub count: i64,
    /// The axis's net steps at the pins, [`SAMPLE_DELAY`] clocks later.
    pub position: i64,
}

/// The record of one geared move, kept by the bus while it runs.
#[derive(Clone, Debug, Default)]
pub struct GearLog {
    /// The geared axis.
    pub axis: usize,
    /// Counts waiting for their sample: (due clock, edge clock, count).
    pending: std::collections::VecDeque<(u64, u64, i64)>,
    last_count: Option<i64>,
    last_index: bool,
    /// Every count, with its position.
    pub samples: Vec<CountSample>,
    /// Every rising edge of the index pin: (clock, count).
    pub indexes: Vec<(u64, i64)>,
}

impl GearLog {
    /// An empty record for `axis`.
    pub fn new(axis: usize) -> Self {
        Self {
            axis,
            ..Self::default()
        }
    }

    /// After clock `clock`: the spindle's count and index pin, and the
    /// geared axis's position at the pins.
    pub fn clock(&mut self, clock: u64, count: i64, index: bool, position: i64) {
        while let Some(&(due, edge, c)) = self.pending.front() {
            if due > clock {
                break;
            }
            self.samples.push(CountSample {
                clock: edge,
                count: c,
                position,
            });
            self.pending.pop_front();
        }
        if self.last_count.is_some_and(|last| last != count) {
            self.pending.push_back((clock + SAMPLE_DELAY, clock, count));
        }
        if index && !self.last_index {
            self.indexes.push((clock, count));
        }
        self.last_count = Some(count);
        self.last_index = index;
    }

    /// The count of the last index edge at or before `clock`.
    pub fn index_before(&self, clock: u64) -> Option<i64> {
        self.indexes
            .iter()
            .rev()
            .find(|(c, _)| *c <= clock)
            .map(|(_, count)| *count)
    }
}

/// One pass's errors against its ideal, steps.
#[derive(Clone, Debug, PartialEq)]
pub struct PassErrors {
    /// e(c) at every count of the locked part.
    pub errors: Vec<f64>,
}

impl PassErrors {
    /// The errors of the samples between clocks `from` and `to` (the
    /// locked part), against a pass starting at `start` steps, moving
    /// `dir` (+1 or -1) `steps_per_count` steps per count from the count
    /// `engaged_at`.
    pub fn measure(
        samples: &[CountSample],
        (from, to): (u64, u64),
        start: f64,
        dir: f64,
        steps_per_count: f64,
        engaged_at: i64,
    ) -> Self {
        let errors = samples
            .iter()
            .filter(|s| s.clock >= from && s.clock <= to)
            .map(|s| {
                let ideal = start + dir * steps_per_count * (s.count - engaged_at) as f64;
                s.position as f64 - ideal
            })
            .collect();
        Self { errors }
    }

    /// The mean error: the pass's phase.
    pub fn phase(&self) -> Option<f64> {
        (!self.errors.is_empty())
            .then(|| self.errors.iter().sum::<f64>() / self.errors.len() as f64)
    }
}

/// A thread's figures over its passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreadFigures {
    /// (max e - min e) / 2 over every locked count of every pass, steps.
    pub lead_error: f64,
    /// Largest minus smallest pass phase, steps.
    pub phase_spread: f64,
    /// Counts measured.
    pub counts: usize,
    /// Passes measured.
    pub passes: usize,
}

impl ThreadFigures {
    /// The figures of `passes`; `None` when no pass has a locked count.
    pub fn of(passes: &[PassErrors]) -> Option<Self> {
        let all = passes.iter().flat_map(|p| p.errors.iter().copied());
        let (low, high) = all.fold((f64::MAX, f64::MIN), |(l, h), e| (l.min(e), h.max(e)));
        let phases: Vec<f64> = passes.iter().filter_map(PassErrors::phase).collect();
        if phases.is_empty() {
            return None;
        }
        let spread = phases.iter().fold(f64::MIN, |m, &p| m.max(p))
            - phases.iter().fold(f64::MAX, |m, &p| m.min(p));
        Some(Self {
            lead_error: (high - low) / 2.0,
            phase_spread: spread,
            counts: passes.iter().map(|p| p.errors.len()).sum(),
            passes: phases.len(),
        })
    }
}
