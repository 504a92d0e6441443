//! Cartesian motions for the control DSP: the pose, velocity and
//! acceleration at any time, sampled once a period into [`PeriodPoint`]s.

use std::f64::consts::TAU;

use super::super::{PeriodPoint, Pose};

/// A pose and its first two derivatives: X Y Z in mm, mm/s, mm/s²; A B C in
/// degrees, degrees/s, degrees/s² (the units of [`PeriodPoint`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionSample {
    /// Where.
    pub pose: Pose,
    /// How fast.
    pub velocity: [f64; 6],
    /// How it speeds up.
    pub acceleration: [f64; 6],
}

/// A Cartesian motion: a sample at every time from 0 to its duration; it
/// stands still at its end pose after.
pub trait CartesianMotion {
    /// Seconds from start to end.
    fn duration(&self) -> f64;
    /// The motion at `t` seconds (clamped to 0 and the duration).
    fn at(&self, t: f64) -> MotionSample;

    /// The point for period `n`: the motion at time `(n + lead)` periods of
    /// `period_s` (see [`super::LEAD_PERIODS`]).
    fn point(&self, n: u64, period_s: f64, lead: u64) -> PeriodPoint {
        let s = self.at((n + lead) as f64 * period_s);
        PeriodPoint {
            sequence: n as u16,
            pose: s.pose,
            velocity: s.velocity,
            acceleration: s.acceleration,
        }
    }
}

/// A helix about Z with the platform rolling in A and pitching in B as it
/// goes: from `start`, `turns` circles of `radius` in X Y (the first
/// centred at `start` minus `radius` in X) rising `rise` in Z, A following
/// `a_amplitude`·sin θ and B `b_amplitude`·(1 − cos θ); it ends back at
/// `start` in X Y A B, `rise` higher. The angle θ follows a quintic in time,
/// so velocity and acceleration are 0 at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Helix {
    /// The pose it starts from.
    pub start: Pose,
    /// Circle radius, mm.
    pub radius: f64,
    /// Whole turns.
    pub turns: f64,
    /// Height gained, mm.
    pub rise: f64,
    /// Roll amplitude, degrees.
    pub a_amplitude: f64,
    /// Pitch amplitude, degrees.
    pub b_amplitude: f64,
    /// Seconds.
    pub seconds: f64,
}

impl CartesianMotion for Helix {
    fn duration(&self) -> f64 {
        self.seconds
    }

    fn at(&self, t: f64) -> MotionSample {
        let u = (t / self.seconds).clamp(0.0, 1.0);
        // s = 10u³ − 15u⁴ + 6u⁵ and its derivatives in time.
        let s = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
        let ds = 30.0 * u * u * (1.0 - u) * (1.0 - u) / self.seconds;
        let dds = 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u) / (self.seconds * self.seconds);
        let k = TAU * self.turns;
        let (th, dth, ddth) = (k * s, k * ds, k * dds);
        let (sin, cos) = th.sin_cos();
        let [x0, y0, z0] = self.start.position;
        let [a0, b0, c0] = self.start.angles;
        let (r, a, b) = (self.radius, self.a_amplitude, self.b_amplitude);
        let w2 = dth * dth;
        MotionSample {
            pose: Pose {
                position: [x0 + r * (cos - 1.0), y0 + r * sin, z0 + self.rise * s],
                angles: [a0 + a * sin, b0 + b * (1.0 - cos), c0],
            },
            velocity: [
                -r * sin * dth,
                r * cos * dth,
                self.rise * ds,
                a * cos * dth,
                b * sin * dth,
                0.0,
            ],
            acceleration: [
                -r * (cos * w2 + sin * ddth),
                r * (-sin * w2 + cos * ddth),
                self.rise * dds,
                a * (-sin * w2 + cos * ddth),
                b * (cos * w2 + sin * ddth),
                0.0,
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The velocity and acceleration are the derivatives of the pose.
    #[test]
    fn the_helix_derivatives_match_finite_differences() {
        let helix = Helix {
            start: Pose {
                position: [1.0, 2.0, 508.0],
                angles: [0.5, -0.5, 1.0],
            },
            radius: 10.0,
            turns: 1.0,
            rise: 20.0,
            a_amplitude: 5.0,
            b_amplitude: 4.0,
            seconds: 2.0,
        };
        let coords = |s: &MotionSample| {
            let mut q = [0.0; 6];
            q[..3].copy_from_slice(&s.pose.position);
            q[3..].copy_from_slice(&s.pose.angles);
            q
        };
        let h = 1e-5;
        for i in 1..40 {
            let t = i as f64 * 0.05;
            let (before, now, after) = (helix.at(t - h), helix.at(t), helix.at(t + h));
            for axis in 0..6 {
                let v = (coords(&after)[axis] - coords(&before)[axis]) / (2.0 * h);
                let a = (after.velocity[axis] - before.velocity[axis]) / (2.0 * h);
                assert!(
                    (v - now.velocity[axis]).abs() < 1e-5,
                    "t {t} axis {axis}: {v}"
                );
                assert!(
                    (a - now.acceleration[axis]).abs() < 1e-4,
                    "t {t} axis {axis}: {a}"
                );
            }
        }
        let end = helix.at(2.0);
        assert!((end.pose.position[0] - 1.0).abs() < 1e-9);
        assert!((end.pose.position[2] - 528.0).abs() < 1e-9);
        assert!(end.velocity.iter().all(|v| v.abs() < 1e-9));
    }
}
