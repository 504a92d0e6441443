//! Coarse interpolation by time division: the planned path is sampled every
//! interpolation period T, and each axis's step count for a period is the
//! difference of two absolute positions in steps.
//!
//! * On a line, a sample's position is the start plus delta * q / 2^32,
//!   with q the travelled fraction in Q0.32 (exactly 2^32 at the line's
//!   end), truncated toward minus infinity.
//! * On an arc, a sample's position is the arc's point at the travelled
//!   fraction of its angle, in machine units, rounded to the nearest step;
//!   the arc's end is its end point rounded the same way.
//!
//! Counts are differences of absolute positions, so the truncation or
//! rounding of one period is carried into the next (it is never dropped),
//! it stays within one step, and the last sample is the path's end
//! exactly: zero drift over any length of path. A dwell's periods are
//! zero counts.

use super::planner::{to_steps, PlannedSegment, Shape};

/// Q0.32 fraction scale.
const ONE: i128 = 1 << 32;

/// The per-period step counts of a planned path.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Interpolation {
    /// Step counts, one entry per period, per axis.
    pub counts: Vec<[i32; 3]>,
    /// Path speed at the end of each period, machine units per second.
    pub speeds: Vec<f64>,
    /// Absolute position at the end of each period, steps.
    pub positions: Vec<[i64; 3]>,
    /// The exact (unquantized) position at the end of each period, machine
    /// units: what the steps approximate.
    pub points: Vec<[f64; 3]>,
    /// Index of the move each period ends on.
    pub moves: Vec<usize>,
}

/// Position on `s` after `distance` along it, in whole steps.
fn position_on(s: &PlannedSegment, distance: f64) -> [i64; 3] {
    if distance >= s.length {
        return s.end;
    }
    match s.shape {
        Shape::Arc(_) => to_steps(s.point_at(distance), s.steps_per_unit),
        Shape::Line { .. } | Shape::Dwell { .. } => {
            let q = ((distance / s.length) * ONE as f64)
                .floor()
                .clamp(0.0, ONE as f64) as i128;
            std::array::from_fn(|k| {
                let delta = (s.end[k] - s.start[k]) as i128;
                s.start[k] + (delta * q).div_euclid(ONE) as i64
            })
        }
    }
}

/// Samples `segments` (from [`super::planner::plan_toolpath`]) every
/// `period` seconds, starting at `start` (steps).
pub fn interpolate(start: [i64; 3], segments: &[PlannedSegment], period: f64) -> Interpolation {
    let durations: Vec<f64> = segments.iter().map(|s| s.duration()).collect();
    let total: f64 = durations.iter().sum();
    let periods = (total / period).ceil().max(1.0) as usize;
    let mut out = Interpolation {
        counts: Vec::with_capacity(periods),
        speeds: Vec::with_capacity(periods),
        positions: Vec::with_capacity(periods),
        points: Vec::with_capacity(periods),
        moves: Vec::with_capacity(periods),
    };
    let mut last = start;
    let (mut index, mut segment_start) = (0usize, 0.0f64);
    for k in 1..=periods {
        let t = k as f64 * period;
        while index < segments.len() && t >= segment_start + durations[index] {
            segment_start += durations[index];
            index += 1;
        }
        let (position, point, speed, on) = if k == periods || index == segments.len() {
            match segments.last() {
                Some(s) => (s.end, s.point_at(s.length), 0.0, segments.len() - 1),
                None => (start, [0.0; 3], 0.0, 0),
            }
        } else {
            let s = &segments[index];
            let (distance, speed) = s.state_at(t - segment_start);
            (position_on(s, distance), s.point_at(distance), speed, index)
        };
        out.counts.push(std::array::from_fn(|axis| {
            (position[axis] - last[axis]) as i32
        }));
        out.speeds.push(speed);
        out.positions.push(position);
        out.points.push(point);
        out.moves.push(on);
        last = position;
    }
    out
}
