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
