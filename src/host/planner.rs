//! Velocity planning with look-ahead: a trapezoidal speed profile per
//! segment, junction speeds limited by acceleration and contour error.
//!
//! * Corner speed (the junction-deviation rule): a corner between unit
//!   directions u1 and u2 is passed at most at
//!   v = sqrt(a * e * s / (1 - s)), s = sin(theta / 2), theta the angle
//!   between -u1 and u2 (180 degrees for a straight continuation, 0 for a
//!   reversal): the speed at which a circular arc of deviation e from the
//!   corner is driven at acceleration a. A reversal gives 0, a straight
//!   continuation only the feed limit.
//! * Look-ahead: a backward pass caps each entry speed so that the segment
//!   can still decelerate to its exit speed (v0^2 <= v1^2 + 2aL), a forward
//!   pass caps each exit speed by what the segment can reach
//!   (v1^2 <= v0^2 + 2aL). So no segment is entered faster than it can be
//!   left, and the path starts and ends at rest.
//! * Each segment then accelerates to min(feed, the triangle peak
//!   sqrt((2aL + v0^2 + v1^2) / 2)), cruises, and decelerates.
//!
//! Lengths are Euclidean in steps; speeds in steps per second.

use super::path::Path;

/// One segment with its speed profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlannedSegment {
    /// Start position, steps.
    pub start: [i64; 3],
    /// End position, steps.
    pub end: [i64; 3],
    /// Length, steps.
    pub length: f64,
    /// Entry speed.
    pub v_entry: f64,
    /// Cruise (peak) speed.
    pub v_cruise: f64,
    /// Exit speed.
    pub v_exit: f64,
    /// Acceleration used.
    pub accel: f64,
}

impl PlannedSegment {
    fn accel_distance(&self) -> f64 {
        (self.v_cruise.powi(2) - self.v_entry.powi(2)).max(0.0) / (2.0 * self.accel)
    }

    fn decel_distance(&self) -> f64 {
        (self.v_cruise.powi(2) - self.v_exit.powi(2)).max(0.0) / (2.0 * self.accel)
    }

    fn cruise_distance(&self) -> f64 {
        (self.length - self.accel_distance() - self.decel_distance()).max(0.0)
    }

    fn phase_times(&self) -> (f64, f64, f64) {
        let ta = (self.v_cruise - self.v_entry).max(0.0) / self.accel;
        let td = (self.v_cruise - self.v_exit).max(0.0) / self.accel;
        let tc = if self.v_cruise > 0.0 {
            self.cruise_distance() / self.v_cruise
        } else {
            0.0
        };
        (ta, tc, td)
    }

    /// Time to drive the segment, seconds.
    pub fn duration(&self) -> f64 {
        let (ta, tc, td) = self.phase_times();
        ta + tc + td
    }

    /// (distance along the segment, speed) at time `t` after its start,
    /// clamped to the segment.
    pub fn state_at(&self, t: f64) -> (f64, f64) {
        let (ta, tc, td) = self.phase_times();
        let a = self.accel;
        let t = t.clamp(0.0, ta + tc + td);
        if t <= ta {
            (self.v_entry * t + 0.5 * a * t * t, self.v_entry + a * t)
        } else if t <= ta + tc {
            (self.accel_distance() + self.v_cruise * (t - ta), self.v_cruise)
        } else {
            let u = t - ta - tc;
            let d = self.accel_distance() + self.cruise_distance() + self.v_cruise * u - 0.5 * a * u * u;
            (d.min(self.length), (self.v_cruise - a * u).max(self.v_exit))
        }
    }
}

fn direction(from: [i64; 3], to: [i64; 3]) -> ([f64; 3], f64) {
    let d: Vec<f64> = (0..3).map(|k| (to[k] - from[k]) as f64).collect();
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    ([d[0] / length, d[1] / length, d[2] / length], length)
}

/// The corner speed limit between two directions (see the module docs).
pub fn junction_speed(u1: [f64; 3], u2: [f64; 3], accel: f64, contour_error: f64, feed: f64) -> f64 {
    let cos_theta = -(u1[0] * u2[0] + u1[1] * u2[1] + u1[2] * u2[2]);
    let sin_half = (0.5 * (1.0 - cos_theta)).max(0.0).sqrt();
    if sin_half >= 1.0 - 1e-12 {
        return feed;
    }
    (accel * contour_error * sin_half / (1.0 - sin_half)).sqrt().min(feed)
}

/// Plans `path`: zero-length moves are dropped; the path starts and ends
/// at rest.
pub fn plan(path: &Path) -> Vec<PlannedSegment> {
    let mut segments: Vec<PlannedSegment> = Vec::new();
    let mut directions: Vec<[f64; 3]> = Vec::new();
    let mut at = path.start;
    for s in &path.segments {
        if s.end == at {
            continue;
        }
        let (u, length) = direction(at, s.end);
        segments.push(PlannedSegment {
            start: at,
            end: s.end,
            length,
            v_entry: 0.0,
            v_cruise: 0.0,
            v_exit: 0.0,
            accel: path.accel,
        });
        directions.push(u);
        at = s.end;
    }
    let n = segments.len();
    // Junction limits: v[i] is the speed between segment i-1 and i.
    let mut v = vec![0.0; n + 1];
    for i in 1..n {
        v[i] = junction_speed(directions[i - 1], directions[i], path.accel, path.contour_error, path.feed);
    }
    let reach = |v0: f64, length: f64| (v0 * v0 + 2.0 * path.accel * length).sqrt();
    for i in (0..n).rev() {
        v[i] = v[i].min(reach(v[i + 1], segments[i].length));
    }
    for i in 0..n {
        v[i + 1] = v[i + 1].min(reach(v[i], segments[i].length));
    }
    for (i, s) in segments.iter_mut().enumerate() {
        s.v_entry = v[i];
        s.v_exit = v[i + 1];
        let peak = ((2.0 * path.accel * s.length + v[i] * v[i] + v[i + 1] * v[i + 1]) / 2.0).sqrt();
        s.v_cruise = path.feed.min(peak).max(v[i]).max(v[i + 1]);
    }
    segments
}
