//! A feed hold in `simulate` (`--hold-at`, `--resume-at`, `--hold-rate`):
//! when the driver requests and releases it, the deceleration it programs,
//! the tick that deceleration needs, and the path speed at the pins
//! through it.
//!
//! The hold's factor moves by `HOLD_CONTROL.RATE`/65536 per base tick, so
//! its slowest stop takes 65536 base ticks. The default deceleration stops
//! the path from its planned peak speed within the machine's limits: a
//! stop of T seconds, the longest of the path's peak speed over its
//! acceleration limit and each axis's peak velocity over its own.
//! On a base tick faster than 65536 / T, `simulate` raises `TICK_DIVISOR`
//! (the same period, fewer and longer ticks) so that such a stop fits,
//! choosing the divisor whose rate stops closest to T ([`hold_tick_settings`]).

use super::driver::{HoldAction, HoldEvent};
use super::MachineSettings;

/// The slowest stop, in base ticks: `HOLD_CONTROL.RATE` = 1.
pub const SLOWEST_STOP_TICKS: f64 = 65536.0;

/// A hold requested at one time and released at a later one, seconds of
/// simulated time from power-up (the clock `--trip` counts).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoldWindow {
    /// When the driver writes `HOLD_CONTROL.HOLD`.
    pub hold_at_s: f64,
    /// When it writes `HOLD_CONTROL.RELEASE`.
    pub resume_at_s: f64,
    /// `HOLD_CONTROL.RATE`, or `None` for the machine's (see the module).
    pub rate: Option<u32>,
}

/// Reads a time given to `option`: seconds (`0.35s` or `0.35`) or
/// milliseconds (`350ms`), finite and not negative.
pub fn parse_seconds(option: &str, text: &str) -> Result<f64, String> {
    let (number, scale) = if let Some(ms) = text.strip_suffix("ms") {
        (ms, 1e-3)
    } else {
        (text.strip_suffix('s').unwrap_or(text), 1.0)
    };
    number
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|t| t.is_finite() && *t >= 0.0)
        .map(|t| t * scale)
        .ok_or_else(|| {
            format!("{option} `{text}`: not a time (seconds as 0.35s or 0.35, or 350ms)")
        })
}

impl HoldWindow {
    /// Checks the window: a release after the hold, a rate of 16 bits.
    pub fn new(hold_at_s: f64, resume_at_s: f64, rate: Option<u32>) -> Result<Self, String> {
        if resume_at_s <= hold_at_s {
            return Err(format!(
                "--resume-at {resume_at_s} s is not after --hold-at {hold_at_s} s"
            ));
        }
        if let Some(rate) = rate.filter(|&r| r > 0xffff) {
            return Err(format!(
                "--hold-rate {rate} does not fit HOLD_CONTROL.RATE (0 to 65535; 0 stops at the next tick)"
            ));
        }
        Ok(Self {
            hold_at_s,
            resume_at_s,
            rate,
        })
    }

    /// `HOLD_CONTROL.RATE` on a base tick of `tick_hz`: the explicit one,
    /// or [`rate_for_stop`].
    pub fn rate(&self, stop_s: f64, tick_hz: f64) -> u32 {
        self.rate.unwrap_or_else(|| rate_for_stop(stop_s, tick_hz))
    }

    /// The driver's two events at `clock_hz`.
    pub fn events(&self, clock_hz: f64) -> [HoldEvent; 2] {
        let clock = |s: f64| (s * clock_hz).round() as u64;
        [
            HoldEvent {
                clock: clock(self.hold_at_s),
                action: HoldAction::Hold,
            },
            HoldEvent {
                clock: clock(self.resume_at_s),
                action: HoldAction::Release,
            },
        ]
    }
}

/// The smallest `TICK_DIVISOR` whose base tick lets a stop of `stop_s`
/// (see [`stop_within_limits_s`]) take at most 65536 ticks.
pub fn min_tick_divisor(stop_s: f64, clock_hz: f64) -> u64 {
    (clock_hz * stop_s / SLOWEST_STOP_TICKS).ceil().max(1.0) as u64
}

/// Clocks per base tick and base ticks per period for a hold whose stop
/// should take `stop_s`: among the tick divisors that split the period
/// into at most 65535 ticks, at least `min_period_ticks` of them (an
/// axis's steps need them), from the smallest that fits the stop in 65536
/// ticks ([`min_tick_divisor`]) to 16 times it, the one whose
/// [`rate_for_stop`] stops closest to `stop_s` (never sooner: the rate
/// is rounded down), the smaller divisor on a tie. Without one, the
/// smallest that fits the stop.
pub fn hold_tick_settings(
    period_s: f64,
    clock_hz: f64,
    stop_s: f64,
    min_period_ticks: u64,
) -> Result<(u32, u32), String> {
    let clocks = (period_s * clock_hz).round() as u64;
    let first = min_tick_divisor(stop_s, clock_hz).max(clocks.div_ceil(65_535));
    let best = (first..=first.saturating_mul(16).min(clocks))
        .filter(|d| clocks.is_multiple_of(*d) && clocks / d >= min_period_ticks.max(1))
        .map(|d| {
            let tick_hz = clock_hz / d as f64;
            (stop_time_s(rate_for_stop(stop_s, tick_hz), tick_hz), d)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    match best {
        Some((_, d)) if stop_s > 0.0 => Ok((d as u32, (clocks / d) as u32)),
        _ => super::simulation::period_settings_from(period_s, clock_hz, first),
    }
}

/// The largest `HOLD_CONTROL.RATE` whose stop from full speed on a base
/// tick of `tick_hz` takes `stop_s` or longer (0, an immediate stop, when
/// `stop_s` is 0: nothing limits the deceleration).
pub fn rate_for_stop(stop_s: f64, tick_hz: f64) -> u32 {
    if stop_s == 0.0 {
        return 0;
    }
    (SLOWEST_STOP_TICKS / (stop_s * tick_hz))
        .floor()
        .clamp(1.0, 65535.0) as u32
}

/// The shortest stop of a path from its peak speeds within the machine's
/// acceleration limits, seconds: the longest of `peak_path_speed` over
/// `path_accel` and each axis's `peak_axis_speed` over its `max_accel`
/// (a speed in the machine's units per second; an unlimited acceleration
/// adds nothing).
pub fn stop_within_limits_s(
    machine: &MachineSettings,
    peak_path_speed: f64,
    peak_axis_speed: [f64; 3],
) -> f64 {
    (0..3)
        .map(|k| peak_axis_speed[k] / machine.max_accel[k])
        .chain([peak_path_speed / machine.path_accel])
        .filter(|t| t.is_finite())
        .fold(0.0, f64::max)
}

/// The time a stop from full speed takes at `rate` on a base tick of
/// `tick_hz`, seconds: ceil(65536 / rate) ticks (one tick for rate 0).
pub fn stop_time_s(rate: u32, tick_hz: f64) -> f64 {
    let ticks = match rate {
        0 => 1.0,
        r => (SLOWEST_STOP_TICKS / r as f64).ceil(),
    };
    ticks / tick_hz
}

/// The path speed at the pins, mm/s (or steps/s with 1 step per mm), from
/// the positions sampled once per period: each value the distance over
/// the `window` periods that end with it, divided by their time.
pub fn speeds_at_the_pins(
    samples: &[[i64; 3]],
    steps_per_mm: [f64; 3],
    period_s: f64,
    window: usize,
) -> Vec<f64> {
    let window = window.max(1);
    let distance: Vec<f64> = samples
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|k| ((w[1][k] - w[0][k]) as f64 / steps_per_mm[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    (0..distance.len())
        .map(|end| {
            let start = (end + 1).saturating_sub(window);
            let span = end + 1 - start;
            distance[start..=end].iter().sum::<f64>() / (span as f64 * period_s)
        })
        .collect()
}
