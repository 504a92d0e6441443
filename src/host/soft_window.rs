//! Soft-limit windows in `simulate` (`--soft-limit AXIS=MIN:MAX`): a
//! window per axis in machine millimetres, turned into the controller's
//! `SOFT_MIN`/`SOFT_MAX` steps, and the line that reports where a tripped
//! run stood.
//!
//! The controller checks each axis against its window and stops the path
//! along itself inside it, at the feed hold's rate (the controller's "Soft
//! limits"). `simulate` programs that rate as for a feed hold without
//! `--hold-rate`: the stop from the path's peak speed within the machine's
//! limits ([`super::hold_window`]).

use super::machine::{axis_index, AXIS_LETTERS};

/// The bounds `SOFT_MIN` and `SOFT_MAX` hold: 24-bit signed steps.
const BOUND_RANGE: std::ops::RangeInclusive<i64> = -(1 << 23)..=(1 << 23) - 1;

/// One axis's window in machine millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoftWindow {
    /// The axis, 0 to 2 (x, y, z).
    pub axis: usize,
    /// The lowest position allowed, mm.
    pub min_mm: f64,
    /// The highest position allowed, mm.
    pub max_mm: f64,
}

/// Axis `axis` as the option names it (`x`).
fn option_name(axis: usize) -> char {
    AXIS_LETTERS[axis].to_ascii_lowercase()
}

impl SoftWindow {
    /// Reads `AXIS=MIN:MAX` (as `x=-10:250.5`): a known axis, two finite
    /// numbers, MIN <= MAX.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = |why: &str| format!("--soft-limit `{text}`: {why}");
        let (name, range) = text
            .split_once('=')
            .ok_or_else(|| bad("not AXIS=MIN:MAX (as x=-10:250)"))?;
        let axis = axis_index(name.trim())
            .ok_or_else(|| bad(&format!("unknown axis `{}` (x, y or z)", name.trim())))?;
        let (min, max) = range
            .split_once(':')
            .ok_or_else(|| bad("not AXIS=MIN:MAX (as x=-10:250)"))?;
        let number = |s: &str| -> Result<f64, String> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(&format!("`{}` is not a number of mm", s.trim())))
        };
        let (min_mm, max_mm) = (number(min)?, number(max)?);
        if min_mm > max_mm {
            return Err(bad(&format!(
                "the window is empty: {min_mm} mm is above {max_mm} mm"
            )));
        }
        Ok(Self {
            axis,
            min_mm,
            max_mm,
        })
    }

    /// The window as the controller's bounds in steps, for an axis of
    /// `steps_per_mm` whose step position 0 is machine step `origin`
    /// (the run's start): rounded inward to whole steps (a bound within
    /// a millionth of a step of one, as 2.01 mm x 100, is that step), so
    /// the controller allows no more than the window.
    pub fn steps(&self, steps_per_mm: f64, origin: i64) -> Result<(i32, i32), String> {
        const SLACK: f64 = 1e-6;
        let name = option_name(self.axis);
        // In f64 until the range is known: a far bound must not saturate.
        let min = (self.min_mm * steps_per_mm - SLACK).ceil() - origin as f64;
        let max = (self.max_mm * steps_per_mm + SLACK).floor() - origin as f64;
        if min > max {
            return Err(format!(
                "--soft-limit {name}: the window {}..{} mm holds no step at {steps_per_mm} steps/mm",
                self.min_mm, self.max_mm
            ));
        }
        let (low, high) = (*BOUND_RANGE.start(), *BOUND_RANGE.end());
        for bound in [min, max] {
            if !(low as f64..=high as f64).contains(&bound) {
                return Err(format!(
                    "--soft-limit {name}: a bound {bound} steps from the start does not fit SOFT_MIN/SOFT_MAX (24-bit signed, {low} to {high})"
                ));
            }
        }
        Ok((min as i32, max as i32))
    }
}

/// The windows given, one per axis at most.
pub fn by_axis(windows: &[SoftWindow]) -> Result<[Option<SoftWindow>; 3], String> {
    let mut out = [None; 3];
    for w in windows {
        if out[w.axis].replace(*w).is_some() {
            return Err(format!(
                "--soft-limit {} given twice: one window per axis",
                option_name(w.axis)
            ));
        }
    }
    Ok(out)
}

/// Where a run a soft limit stopped stood: the tripped axis, the bound it
/// headed for and how far inside it stopped (or past it: the datasheet's
/// guarantee holds only while the axis's rate does not grow), and every
/// axis's position (machine mm).
pub fn tripped_line(
    window: &SoftWindow,
    negative: bool,
    stood_mm: [f64; 3],
    periods_queued: usize,
    periods: usize,
) -> String {
    let name = AXIS_LETTERS[window.axis];
    let at = stood_mm[window.axis];
    let (side, bound, inside) = match negative {
        true => ("minimum", window.min_mm, at - window.min_mm),
        false => ("maximum", window.max_mm, window.max_mm - at),
    };
    let (distance, place) = match inside >= 0.0 {
        true => (inside, "inside"),
        false => (-inside, "PAST it"),
    };
    format!(
        "soft limit: {name} would pass its {side} {bound:.4} mm; the controlled stop held it at {at:.4} mm, {distance:.4} mm {place} (X {:.4}  Y {:.4}  Z {:.4} mm), after {periods_queued} of {periods} periods were queued; the rest of the path did not run",
        stood_mm[0], stood_mm[1], stood_mm[2]
    )
}
