//! Coarse interpolation by time division: the planned path is sampled every
//! interpolation period T, and each axis's step count for a period is the
//! difference of two absolute positions computed in fixed point.
//!
//! Each sample's position on its segment is the start plus
//! delta * q / 2^32, with q the travelled fraction in Q0.32 (exactly 2^32
//! at the segment's end), truncated toward minus infinity. The truncation
//! remainder of one period is therefore carried into the next (it is never
//! dropped), it stays below one step, and the last sample is the path's
//! end exactly: zero drift over any length of path.

use super::planner::PlannedSegment;

/// Q0.32 fraction scale.
const ONE: i128 = 1 << 32;

/// The per-period step counts of a planned path.
#[derive(Clone, Debug, PartialEq)]
pub struct Interpolation {
    /// Step counts, one entry per period, per axis.
    pub counts: Vec<[i32; 3]>,
    /// Path speed at the end of each period, steps per second.
    pub speeds: Vec<f64>,
    /// Absolute position at the end of each period, steps.
    pub positions: Vec<[i64; 3]>,
}

/// Position on `s` after `distance` along it, in whole steps (floor), from
/// the fraction in Q0.32.
fn position_on(s: &PlannedSegment, distance: f64) -> [i64; 3] {
    let q = if distance >= s.length {
        ONE
    } else {
        ((distance / s.length) * ONE as f64).floor().clamp(0.0, ONE as f64) as i128
    };
    let mut p = [0i64; 3];
    for k in 0..3 {
        let delta = (s.end[k] - s.start[k]) as i128;
        p[k] = s.start[k] + (delta * q).div_euclid(ONE) as i64;
    }
    p
}

/// Samples `segments` (from [`super::planner::plan`]) every `period`
/// seconds, starting at `start`.
pub fn interpolate(start: [i64; 3], segments: &[PlannedSegment], period: f64) -> Interpolation {
    let durations: Vec<f64> = segments.iter().map(|s| s.duration()).collect();
    let total: f64 = durations.iter().sum();
    let periods = (total / period).ceil().max(1.0) as usize;
    let mut out = Interpolation {
        counts: Vec::with_capacity(periods),
        speeds: Vec::with_capacity(periods),
        positions: Vec::with_capacity(periods),
    };
    let mut last = start;
    let (mut index, mut segment_start) = (0usize, 0.0f64);
    for k in 1..=periods {
        let t = k as f64 * period;
        while index < segments.len() && t >= segment_start + durations[index] {
            segment_start += durations[index];
            index += 1;
        }
        let (position, speed) = if k == periods || index == segments.len() {
            (segments.last().map_or(start, |s| s.end), 0.0)
        } else {
            let s = &segments[index];
            let (distance, speed) = s.state_at(t - segment_start);
            (position_on(s, distance), speed)
        };
        let mut count = [0i32; 3];
        for axis in 0..3 {
            count[axis] = (position[axis] - last[axis]) as i32;
        }
        out.counts.push(count);
        out.speeds.push(speed);
        out.positions.push(position);
        last = position;
    }
    out
}
