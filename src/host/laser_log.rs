//! What a laser run records at the pins, and the energy per millimetre
//! made from it.
//!
//! **The record** ([`LaserLog`]): the clocks `laser_pwm` was high so far,
//! sampled at every step that leaves the pins. A
//! burn's energy is the laser's full-power time: high clocks over the
//! clock rate.
//!
//! **Energy per mm** ([`burn_energy`]). A burn is a stretch of the path
//! at one programmed power, feed and mode: a run of periods. Every period
//! ends at a step index (the steps of the periods before it, counted over
//! all axes in the order they leave: a period's counts leave the pins
//! within it) and moves the planned path a known length, the exact path
//! its steps approximate. Periods within [`TRIM_MM`] of either end of the
//! burn are left out (the engine's lag, a period shared with the
//! neighbour move), and the rest are grouped into windows of at least
//! [`WINDOW_MM`]; a window's energy per mm is the laser's high time
//! between its first and last periods' step indices over its length. A
//! burn shorter than the trims and a window has no windows.
//!
//! The length is the plan's, not the pins' staircase: the staircase's
//! summed steps are the Manhattan length (41 % long on a diagonal), and
//! chords across it cut the corners short (a chord across a star's tip
//! reads a third of the path it spans).
//!
//! The programmed energy per mm is S / `laser_s_max` over the feed: what
//! M4 aims at everywhere, and M3 only at the programmed speed.

/// Path left out at each end of a burn, mm (the 0.1 mm).
pub const TRIM_MM: f64 = 0.1;

/// Shortest window of path the energy is measured over, mm.
pub const WINDOW_MM: f64 = 0.5;

/// The laser pin's high time at one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StepSample {
    /// Steps left the pins so far, over all axes (this one included).
    pub steps: u64,
    /// Clocks `laser_pwm` was high so far.
    pub high: u64,
}

/// The record of a laser run, kept by the bus.
#[derive(Clone, Debug)]
pub struct LaserLog {
    /// Clocks `laser_pwm` was high so far.
    pub high: u64,
    /// Steps left the pins so far.
    pub steps: u64,
    /// One sample per step.
    pub samples: Vec<StepSample>,
}

impl Default for LaserLog {
    fn default() -> Self {
        Self::new()
    }
}

impl LaserLog {
    /// An empty record: its first sample, 0 steps.
    pub fn new() -> Self {
        Self {
            high: 0,
            steps: 0,
            samples: vec![StepSample { steps: 0, high: 0 }],
        }
    }

    /// After a clock: the pin and the steps that left in it.
    pub fn clock(&mut self, laser: bool, new_steps: u64) {
        self.high += laser as u64;
        if new_steps > 0 {
            self.steps += new_steps;
            self.samples.push(StepSample {
                steps: self.steps,
                high: self.high,
            });
        }
    }
}

/// Below this many steps a period at the feed, the gateware's speed of
/// whole steps per period reads high on a diagonal: a period's counts
/// (1, 0) and (0, 1) make two steps of speed where the path went 1.41.
/// `simulate` says so for such a burn; a longer `period_us` gives more
/// steps a period.
pub const FEW_STEPS_PER_PERIOD: f64 = 2.5;

/// One window's figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyWindow {
    /// Its middle, mm along the burn from the burn's start.
    pub at_mm: f64,
    /// Full-power seconds per mm.
    pub energy: f64,
}

/// One burn's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct BurnEnergy {
    /// The program line of its first move.
    pub line: usize,
    /// M4 (dynamic) or M3.
    pub dynamic: bool,
    /// Programmed: power fraction over the feed, full-power s/mm.
    pub programmed: f64,
    /// The burn's planned length, mm.
    pub length_mm: f64,
    /// The programmed feed in steps a period along the laser's plane,
    /// averaged over the burn's length (see [`FEW_STEPS_PER_PERIOD`]).
    pub feed_steps: f64,
    /// The windows, in order along the burn.
    pub windows: Vec<EnergyWindow>,
}

impl BurnEnergy {
    /// Lowest and highest window, full-power s/mm; `None` without windows.
    pub fn range(&self) -> Option<(f64, f64)> {
        let first = self.windows.first()?.energy;
        Some(self.windows.iter().fold((first, first), |(lo, hi), w| {
            (lo.min(w.energy), hi.max(w.energy))
        }))
    }

    /// The largest deviation of a window from the programmed value, as a
    /// fraction of it.
    pub fn worst_deviation(&self) -> Option<f64> {
        let (lo, hi) = self.range()?;
        Some(((hi - self.programmed).abs()).max((self.programmed - lo).abs()) / self.programmed)
    }
}

/// The high clocks up to the last of the first `steps` steps (0 before
/// any).
fn high_at(log: &LaserLog, steps: u64) -> u64 {
    let k = log.samples.partition_point(|s| s.steps <= steps);
    k.checked_sub(1).map_or(0, |k| log.samples[k].high)
}

/// The windows of a burn (see the [module documentation](self)):
/// `periods` holds each of its periods' step index at the period's end
/// and the planned path's length in it, mm; `first` is the step index at
/// the burn's start.
pub fn burn_energy(
    log: &LaserLog,
    first: u64,
    periods: &[(u64, f64)],
    clock_hz: f64,
) -> Vec<EnergyWindow> {
    let total: f64 = periods.iter().map(|p| p.1).sum();
    let mut windows = Vec::new();
    let (mut along, mut length) = (0.0, 0.0);
    let mut opened = first;
    for &(steps, mm) in periods {
        let (begin, end) = (along, along + mm);
        along = end;
        if begin < TRIM_MM || end > total - TRIM_MM {
            opened = steps;
            continue;
        }
        length += mm;
        if length >= WINDOW_MM {
            let high = high_at(log, steps) - high_at(log, opened);
            windows.push(EnergyWindow {
                at_mm: end - length / 2.0,
                energy: high as f64 / clock_hz / length,
            });
            length = 0.0;
            opened = steps;
        }
    }
    windows
}
