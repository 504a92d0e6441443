//! The control DSP's Cartesian planner: a toolpath in X Y Z (mm) and A B C
//! (degrees), from a G-code program read with
//! [`Setup::rotary_axes`](crate::host::gcode::Setup::rotary_axes), as a
//! [`CartesianMotion`] for the card.
//!
//! ## What it plans
//! - **Exact stop.** Every move starts and ends at rest (LinuxCNC's G61),
//!   with a speed profile along it of a sine-shaped ramp up (the
//!   acceleration a half sine, from 0 to its peak and back to 0), a cruise
//!   at the move's speed and the mirror ramp down. The acceleration is
//!   continuous, so the motor DSPs' acceleration feed-forward never sees a
//!   step; a ramp to speed v at peak acceleration A takes π v / (2 A),
//!   π/2 times a trapezoid's. No blending between moves.
//! - **Shapes.** Lines, and arcs and helices (the interpreter's
//!   [`ArcGeometry`], spirals included); A, B and C move linearly with the
//!   fraction of the move. A dwell stands still for its seconds.
//! - **Speed.** A move with X Y Z travel runs at its F along X Y Z; a move
//!   of A B C alone at its F in degrees per second along the angles' change
//!   (LinuxCNC's rule); a rapid as fast as the limits allow. The speed is
//!   then lowered to every limit of [`PoseLimits`]: X Y Z speed, angular
//!   speed, on an arc the centripetal acceleration (v²/r at most half the
//!   acceleration limit), and every leg's speed to
//!   [`PoseLimits::leg_speed_share`] of the geometry's `leg_speed`,
//!   sampled at 33 points of a line and 33 per half turn of an arc.
//! - **Length.** A program of more than [`MAX_PROGRAM_SECONDS`] (a long
//!   dwell, or a feed so low a move would take that long) is refused,
//!   naming the line where it passes the limit.
//!
//! ## Checks before any motion ([`PosePlan::check`])
//! Every period's pose is checked with [`check_pose`] (workspace, stroke,
//! condition number) and every leg's speed against `leg_speed` (the full
//! limit, so the sampling above has margin); a failure is a
//! [`PlanError`] naming the program line.

use std::f64::consts::PI;

use crate::host::geometry::ArcGeometry;
use crate::host::toolpath::{moves_angles_only, Item, MoveKind, Toolpath};

use super::super::{check_pose, pose_jacobian, Geometry, Pose, PoseError};
use super::trajectory::{CartesianMotion, MotionSample};

/// The planner's limits besides the legs' (which are the geometry's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseLimits {
    /// X Y Z speed, mm/s (a rapid's).
    pub max_velocity: f64,
    /// X Y Z acceleration along the path, mm/s².
    pub max_acceleration: f64,
    /// A B C speed, degrees/s.
    pub max_angular_velocity: f64,
    /// A B C acceleration, degrees/s².
    pub max_angular_acceleration: f64,
    /// The share of the geometry's `leg_speed` the planner plans to
    /// (0 to 1); [`PosePlan::check`] holds every period to the full limit.
    pub leg_speed_share: f64,
}

impl Default for PoseLimits {
    /// 100 mm/s, 1000 mm/s², 60 degrees/s, 600 degrees/s², 90 % of the
    /// leg speed.
    fn default() -> Self {
        Self {
            max_velocity: 100.0,
            max_acceleration: 1000.0,
            max_angular_velocity: 60.0,
            max_angular_acceleration: 600.0,
            leg_speed_share: 0.9,
        }
    }
}

impl PoseLimits {
    /// Every limit above 0 and finite, the share within (0, 1].
    pub fn validate(&self) -> Result<(), PlanError> {
        let named = [
            ("max_velocity", self.max_velocity),
            ("max_acceleration", self.max_acceleration),
            ("max_angular_velocity", self.max_angular_velocity),
            ("max_angular_acceleration", self.max_angular_acceleration),
        ];
        for (name, value) in named {
            if !(value.is_finite() && value > 0.0) {
                return Err(PlanError::Limits(format!("{name} {value}: above 0")));
            }
        }
        if !(self.leg_speed_share > 0.0 && self.leg_speed_share <= 1.0) {
            return Err(PlanError::Limits(format!(
                "leg_speed_share {}: above 0 and at most 1",
                self.leg_speed_share
            )));
        }
        Ok(())
    }
}

/// A program the machine cannot run, before any motion.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// A pose of the move on this line (workspace, stroke, singularity).
    #[error("line {line}: {source}")]
    Pose {
        /// The program line.
        line: usize,
        /// Why.
        source: PoseError,
    },
    /// A leg faster than the geometry's `leg_speed` on this line.
    #[error(
        "line {line}: leg {leg} would move at {speed:.1} mm/s, above its limit of {limit} mm/s"
    )]
    LegSpeed {
        /// The program line.
        line: usize,
        /// The leg, 0 to 5.
        leg: usize,
        /// Its speed, mm/s.
        speed: f64,
        /// `leg_speed`, mm/s.
        limit: f64,
    },
    /// A move geared to the spindle (G33, G33.1, G76): the hexapod has no
    /// spindle encoder or gearbox.
    #[error("line {line}: spindle-synchronized motion (G33, G33.1, G76) needs a spindle encoder and the gearbox, which the hexapod card does not have")]
    SpindleSync {
        /// The program line.
        line: usize,
    },
    /// A program longer than [`MAX_PROGRAM_SECONDS`] (a dwell, or a feed
    /// so slow its move would take that long).
    #[error("line {line}: the program would run {seconds:.3e} s by here, more than {MAX_PROGRAM_SECONDS} s (F too low, or a long dwell?)")]
    TooLong {
        /// The program line.
        line: usize,
        /// The program's time up to the end of that line.
        seconds: f64,
    },
    /// A [`PoseLimits`] value.
    #[error("planner limits: {0}")]
    Limits(String),
}

/// The longest program planned: 10^7 periods of 1 ms (the 3-axis
/// simulation's [`MAX_PERIODS`](crate::host::simulation::MAX_PERIODS)).
pub const MAX_PROGRAM_SECONDS: f64 = 10_000.0;

/// The shape of one planned item, in pose coordinates (mm, degrees).
#[derive(Clone, Copy, Debug)]
enum Shape {
    Line {
        start: [f64; 6],
        end: [f64; 6],
    },
    Arc {
        arc: ArcGeometry,
        angles: [[f64; 3]; 2],
    },
    Rest {
        pose: [f64; 6],
    },
}

impl Shape {
    /// The pose coordinates at fraction `u` and their first two
    /// derivatives by `u`.
    fn at(&self, u: f64) -> [[f64; 6]; 3] {
        match *self {
            Shape::Line { start, end } => {
                let d: [f64; 6] = std::array::from_fn(|k| end[k] - start[k]);
                [std::array::from_fn(|k| start[k] + d[k] * u), d, [0.0; 6]]
            }
            Shape::Arc { arc, angles } => {
                let p = arc.point(u);
                let (d1, d2) = arc.derivatives(u);
                let da: [f64; 3] = std::array::from_fn(|k| angles[1][k] - angles[0][k]);
                let mut q = [[0.0; 6]; 3];
                for k in 0..3 {
                    q[0][k] = p[k];
                    q[1][k] = d1[k];
                    q[2][k] = d2[k];
                    q[0][3 + k] = angles[0][k] + da[k] * u;
                    q[1][3 + k] = da[k];
                }
                q
            }
            Shape::Rest { pose } => [pose, [0.0; 6], [0.0; 6]],
        }
    }
}

/// One item with its speed profile: `length` (mm, or degrees for the
/// angles alone) driven at up to `speed` with `acceleration`.
#[derive(Clone, Copy, Debug)]
struct Planned {
    line: usize,
    shape: Shape,
    start_time: f64,
    duration: f64,
    length: f64,
    speed: f64,
    acceleration: f64,
}

impl Planned {
    /// Distance along, its rate and its second derivative at `tau` seconds
    /// into the item.
    fn profile(&self, tau: f64) -> (f64, f64, f64) {
        let (l, v, a) = (self.length, self.speed, self.acceleration);
        if l == 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let ramp = ramp_time(v, a);
        let w = PI / ramp;
        // The ramp from rest: speed v (1 - cos wτ) / 2, acceleration
        // a sin wτ (a = v w / 2), distance v (τ - sin(wτ) / w) / 2.
        let up = |tau: f64| {
            let (sin, cos) = (w * tau).sin_cos();
            (v * (tau - sin / w) / 2.0, v * (1.0 - cos) / 2.0, a * sin)
        };
        let (tau, rest) = (tau.max(0.0), self.duration - tau);
        if rest <= 0.0 {
            (l, 0.0, 0.0)
        } else if rest < ramp {
            let (s, ds, dds) = up(rest);
            (l - s, ds, -dds)
        } else if tau < ramp {
            up(tau)
        } else {
            (v * ramp / 2.0 + v * (tau - ramp), v, 0.0)
        }
    }

    fn sample(&self, t: f64) -> MotionSample {
        let (s, ds, dds) = self.profile(t - self.start_time);
        let l = if self.length > 0.0 { self.length } else { 1.0 };
        let (u, du, ddu) = ((s / l).clamp(0.0, 1.0), ds / l, dds / l);
        let [q, d1, d2] = self.shape.at(u);
        MotionSample {
            pose: Pose::from_coordinates_degrees(q),
            velocity: std::array::from_fn(|k| d1[k] * du),
            acceleration: std::array::from_fn(|k| d2[k] * du * du + d1[k] * ddu),
        }
    }
}

/// The time of a sine ramp from rest to `speed` at peak acceleration
/// `acceleration`.
fn ramp_time(speed: f64, acceleration: f64) -> f64 {
    PI * speed / (2.0 * acceleration)
}

/// A toolpath planned into a motion of the platform.
#[derive(Clone, Debug)]
pub struct PosePlan {
    items: Vec<Planned>,
    start: Pose,
    duration: f64,
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Leg rates for pose-coordinate rates `dq` (mm/s, degrees/s) at `q`.
fn leg_rates(geometry: &Geometry, q: &[f64; 6], dq: &[f64; 6]) -> [f64; 6] {
    let j = pose_jacobian(geometry, &Pose::from_coordinates_degrees(*q));
    let rad: [f64; 6] = std::array::from_fn(|k| if k < 3 { dq[k] } else { dq[k] * PI / 180.0 });
    std::array::from_fn(|i| (0..6).map(|k| j[i][k] * rad[k]).sum())
}

impl PosePlan {
    /// Plans `toolpath` (X Y Z in mm from its start, A B C in degrees from
    /// its `start_angles`) on `geometry` within `limits`. A pose on the way
    /// that the machine cannot take is an error naming its line.
    pub fn plan(
        toolpath: &Toolpath,
        geometry: &Geometry,
        limits: &PoseLimits,
    ) -> Result<Self, PlanError> {
        limits.validate()?;
        let start = Pose {
            position: toolpath.start,
            angles: toolpath.start_angles,
        };
        let mut here = start.coordinates_degrees();
        let mut items = Vec::new();
        let mut time = 0.0;
        for item in &toolpath.items {
            let (line, shape, feed, seconds) = match item {
                Item::Dwell { seconds, line, .. } => {
                    (*line, Shape::Rest { pose: here }, None, *seconds)
                }
                Item::Synced(m) => return Err(PlanError::SpindleSync { line: m.line }),
                Item::Move(m) => {
                    let end = [m.end, m.angles].concat();
                    let end: [f64; 6] = end.try_into().expect("six coordinates");
                    let shape = match &m.kind {
                        MoveKind::Line => Shape::Line { start: here, end },
                        MoveKind::Arc(arc) => Shape::Arc {
                            arc: ArcGeometry::new(arc, [here[0], here[1], here[2]], m.end),
                            angles: [[here[3], here[4], here[5]], m.angles],
                        },
                    };
                    here = end;
                    (m.line, shape, m.feed, 0.0)
                }
            };
            let planned = Self::plan_item(line, shape, feed, seconds, time, geometry, limits)?;
            time += planned.duration;
            if time.is_nan() || time > MAX_PROGRAM_SECONDS {
                return Err(PlanError::TooLong {
                    line,
                    seconds: time,
                });
            }
            items.push(planned);
        }
        Ok(Self {
            items,
            start,
            duration: time,
        })
    }

    fn plan_item(
        line: usize,
        shape: Shape,
        feed: Option<f64>,
        seconds: f64,
        start_time: f64,
        geometry: &Geometry,
        limits: &PoseLimits,
    ) -> Result<Planned, PlanError> {
        let rest = Planned {
            line,
            shape,
            start_time,
            duration: seconds,
            length: 0.0,
            speed: 0.0,
            acceleration: 0.0,
        };
        let [_, d0, _] = shape.at(0.0);
        let (travel, turn, min_radius) = match shape {
            Shape::Rest { .. } => return Ok(rest),
            Shape::Line { start, end } => {
                let travel = if moves_angles_only(
                    [start[0], start[1], start[2]],
                    [end[0], end[1], end[2]],
                ) {
                    0.0
                } else {
                    norm(&d0[..3])
                };
                (travel, norm(&d0[3..]), f64::INFINITY)
            }
            Shape::Arc { arc, .. } => (arc.length(), norm(&d0[3..]), arc.min_radius()),
        };
        // The samples of the legs' speed: 33 a half turn of an arc.
        let samples = match shape {
            Shape::Arc { arc, .. } => 32 * (arc.sweep.abs() / PI).ceil().max(1.0) as usize,
            _ => 32,
        };
        let (length, mut speed, mut acceleration) = if travel > 0.0 {
            let mut v = limits.max_velocity.min(feed.unwrap_or(f64::INFINITY));
            let mut a = limits.max_acceleration;
            if turn > 0.0 {
                v = v.min(limits.max_angular_velocity * travel / turn);
                a = a.min(limits.max_angular_acceleration * travel / turn);
            }
            if min_radius.is_finite() {
                a = a.min(limits.max_acceleration / 2.0);
                if min_radius > 0.0 {
                    v = v.min((limits.max_acceleration / 2.0 * min_radius).sqrt());
                }
            }
            (travel, v, a)
        } else if turn > 0.0 {
            (
                turn,
                limits
                    .max_angular_velocity
                    .min(feed.unwrap_or(f64::INFINITY)),
                limits.max_angular_acceleration,
            )
        } else {
            return Ok(rest);
        };
        // The legs: the fastest leg per unit of length, over the move.
        let mut per_length: f64 = 0.0;
        // The end first: a programmed end the machine cannot take is named
        // as written, before any pose on the way to it.
        for k in std::iter::once(samples).chain(0..samples) {
            let u = k as f64 / samples as f64;
            let [q, d1, _] = shape.at(u);
            check_pose(geometry, &Pose::from_coordinates_degrees(q))
                .map_err(|source| PlanError::Pose { line, source })?;
            let rates = leg_rates(geometry, &q, &d1);
            per_length = rates
                .iter()
                .fold(per_length, |m, r| m.max(r.abs() / length));
        }
        if per_length > 0.0 {
            speed = speed.min(limits.leg_speed_share * geometry.leg_speed / per_length);
        }
        acceleration = acceleration.max(f64::MIN_POSITIVE);
        // Ramping up and down covers v times one ramp's time.
        if speed * ramp_time(speed, acceleration) > length {
            speed = (2.0 * length * acceleration / PI).sqrt();
        }
        let duration = length / speed + ramp_time(speed, acceleration);
        Ok(Planned {
            duration,
            length,
            speed,
            acceleration,
            ..rest
        })
    }

    /// The program line running at `t` seconds (the last one after the end).
    pub fn line_at(&self, t: f64) -> usize {
        self.item_at(t).map_or(0, |p| p.line)
    }

    fn item_at(&self, t: f64) -> Option<&Planned> {
        let k = self
            .items
            .partition_point(|p| p.start_time + p.duration <= t);
        self.items.get(k).or(self.items.last())
    }

    /// The pose at the end.
    pub fn end_pose(&self) -> Pose {
        self.at(self.duration).pose
    }

    /// Planned items (moves and dwells).
    pub fn items(&self) -> usize {
        self.items.len()
    }

    /// Each planned item's start time and duration (s), and the motion at
    /// its own end as the item computes it, not the next item's start.
    pub fn item_ends(&self) -> impl Iterator<Item = (f64, f64, MotionSample)> + '_ {
        self.items.iter().map(|p| {
            let end = p.start_time + p.duration;
            (p.start_time, p.duration, p.sample(end))
        })
    }

    /// Every pose at `period_s` steps from 0 to the end: one the machine
    /// cannot take, or a leg above `leg_speed`, is an error naming its line.
    pub fn check(&self, geometry: &Geometry, period_s: f64) -> Result<(), PlanError> {
        let periods = (self.duration / period_s).ceil() as u64;
        for n in 0..=periods {
            let t = n as f64 * period_s;
            let s = self.at(t);
            let line = self.line_at(t);
            check_pose(geometry, &s.pose).map_err(|source| PlanError::Pose { line, source })?;
            let q = s.pose.coordinates_degrees();
            let rates = leg_rates(geometry, &q, &s.velocity);
            if let Some((leg, speed)) = rates
                .iter()
                .map(|r| r.abs())
                .enumerate()
                .find(|(_, r)| *r > geometry.leg_speed)
            {
                return Err(PlanError::LegSpeed {
                    line,
                    leg,
                    speed,
                    limit: geometry.leg_speed,
                });
            }
        }
        Ok(())
    }
}

impl CartesianMotion for PosePlan {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn at(&self, t: f64) -> MotionSample {
        match self.item_at(t.clamp(0.0, self.duration)) {
            Some(item) => item.sample(t.clamp(0.0, self.duration)),
            None => MotionSample {
                pose: self.start,
                velocity: [0.0; 6],
                acceleration: [0.0; 6],
            },
        }
    }
}
