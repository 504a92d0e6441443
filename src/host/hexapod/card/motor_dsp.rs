//! A motor-control DSP of the parallel-machine card: on each release it
//! reads its period point and its joints' latched counts through its slave
//! port, runs the inverse kinematics for its two legs (position, velocity
//! and acceleration), closes a position PID per leg and writes both DAC
//! codes, which the next `period_tick` puts out.

use std::collections::VecDeque;

use crate::blocks::parallel_card::registers::{slave_map, JOINTS_PER_SLAVE};
use crate::host::servo::{DriveScale, FollowingError, PositionLoop, ServoError, ServoGains};
use crate::regmap::RegisterMap;

use super::super::{
    inverse, leg_inertia, pose_jacobian, Geometry, PeriodPoint, PlatformInertia, Pose, WORDS,
};
use super::bus::BusAgent;
use super::LEAD_PERIODS;

/// How a motor DSP sets its PID for the pose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GainSchedule {
    /// The same gains everywhere, tuned for the load at home.
    Fixed,
    /// Gains scheduled on the leg's load Λ_ii at the commanded pose
    /// ([`leg_inertia`]): with a velocity drive whose lag grows with the
    /// load (τ = τ_home·m/m_home), the proportional gain scales by
    /// m_home/m and the integral gain by its square, which keeps the
    /// loop's damping, and the acceleration feed-forward uses τ at the pose.
    Load,
}

/// What a motor DSP knows of its legs and its loop.
#[derive(Clone, Debug)]
pub struct MotorDspSettings {
    /// The mechanism.
    pub geometry: Geometry,
    /// The platform's inertia, for the schedule.
    pub inertia: PlatformInertia,
    /// Encoder counts per mm of leg.
    pub counts_per_mm: f64,
    /// Drive and DAC scale.
    pub scale: DriveScale,
    /// The velocity drive's time constant with the load at home, s.
    pub time_constant_s: f64,
    /// The gains at home.
    pub gains: ServoGains,
    /// Fixed or scheduled.
    pub schedule: GainSchedule,
    /// The period, s.
    pub period_s: f64,
}

impl Default for MotorDspSettings {
    /// The default hexapod and platform, 400 counts/mm (a 5 mm screw with a
    /// 2000-count encoder), the AD669 into the [`super::LegPlant`] default
    /// drive (2 ms at home), [`ServoGains::default`], scheduled, 1 ms.
    fn default() -> Self {
        Self {
            geometry: Geometry::default(),
            inertia: PlatformInertia::default(),
            counts_per_mm: 400.0,
            scale: DriveScale::default(),
            time_constant_s: 0.002,
            gains: ServoGains::default(),
            schedule: GainSchedule::Load,
            period_s: 0.001,
        }
    }
}

/// One release's target for a leg, in counts from home.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Target {
    counts: f64,
    /// Leg acceleration, counts/s².
    acceleration: f64,
}

/// Why a motor DSP stopped driving.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MotorDspError {
    /// The point read off the FIFO was not a point.
    #[error("slave {slave}, release {release}: {source}")]
    Command {
        /// The slave.
        slave: usize,
        /// Releases seen before it.
        release: u64,
        /// What was wrong.
        source: super::super::CommandError,
    },
    /// The point's sequence number was not the next.
    #[error("slave {slave}: point {got} where {expected} was due")]
    Sequence {
        /// The slave.
        slave: usize,
        /// Expected sequence.
        expected: u16,
        /// Read sequence.
        got: u16,
    },
}

/// One motor-control DSP driving legs `2k` and `2k + 1` through slave
/// port `k`.
pub struct MotorDsp {
    slave: usize,
    settings: MotorDspSettings,
    map: RegisterMap,
    /// Its bus to the card.
    pub bus: BusAgent,
    loops: [PositionLoop; JOINTS_PER_SLAVE],
    home: [f64; 6],
    home_load: [f64; 6],
    /// Targets of the last LEAD_PERIODS releases, oldest first: the first
    /// is this tick's.
    history: VecDeque<[Target; JOINTS_PER_SLAVE]>,
    reading: bool,
    last_ready: bool,
    releases: u64,
    /// Each leg's following error at the ticks, counts.
    pub following: [FollowingError; JOINTS_PER_SLAVE],
    /// Each leg's following error at the last tick, counts.
    pub last_error: [f64; JOINTS_PER_SLAVE],
    /// Codes clamped at the DAC's range.
    pub saturated: u64,
    /// The first bad point; the DSP then writes 0 V and stops.
    pub error: Option<MotorDspError>,
}

impl MotorDsp {
    /// The DSP of slave `slave`, its legs at home.
    pub fn new(slave: usize, settings: MotorDspSettings) -> Result<Self, ServoError> {
        let make = || PositionLoop::new(settings.gains, settings.scale, settings.period_s);
        let loops = [make()?, make()?];
        let home_pose = settings.geometry.home;
        let home = inverse(&settings.geometry, &home_pose);
        let home_load =
            leg_inertia(&settings.geometry, &home_pose, &settings.inertia).unwrap_or([1.0; 6]);
        Ok(Self {
            slave,
            map: slave_map().expect("the card's slave map is valid"),
            bus: BusAgent::default(),
            loops,
            home,
            home_load,
            history: vec![[Target::default(); JOINTS_PER_SLAVE]; LEAD_PERIODS as usize].into(),
            reading: false,
            last_ready: false,
            releases: 0,
            following: [FollowingError::default(); JOINTS_PER_SLAVE],
            last_error: [0.0; JOINTS_PER_SLAVE],
            saturated: 0,
            error: None,
            settings,
        })
    }

    fn address(&self, register: &str, index: u32) -> u64 {
        self.map
            .address_of(register, index)
            .expect("a register of the card's slave map") as u64
    }

    fn leg(&self, j: usize) -> usize {
        self.slave * JOINTS_PER_SLAVE + j
    }

    /// After each clock: this slave's `data_ready`. A rise starts the
    /// period's reads; when they are in, the loop runs and the codes are
    /// queued.
    pub fn clock(&mut self, data_ready: bool) {
        if data_ready && !self.last_ready && !self.reading && self.error.is_none() {
            let cmd = self.address("CMD", 0);
            for _ in 0..WORDS {
                self.bus.read(cmd);
            }
            for j in 0..JOINTS_PER_SLAVE as u32 {
                let count = self.address("COUNT", j);
                self.bus.read(count);
            }
            self.reading = true;
        }
        self.last_ready = data_ready;
        if self.reading && self.bus.results_ready() == WORDS + JOINTS_PER_SLAVE {
            self.reading = false;
            let words = self.bus.take_results();
            let codes = match self.period(&words) {
                Ok(codes) => codes,
                Err(e) => {
                    self.error = Some(e);
                    [0; JOINTS_PER_SLAVE]
                }
            };
            for (j, code) in codes.into_iter().enumerate() {
                let register = self.address("DAC_CODE", j as u32);
                self.bus
                    .write(register, self.settings.scale.register_value(code) as u64);
            }
            self.releases += 1;
        }
    }

    /// One period's loop on the point's words and the latched counts.
    fn period(&mut self, words: &[u64]) -> Result<[i64; JOINTS_PER_SLAVE], MotorDspError> {
        let point_words: Vec<u32> = words[..WORDS].iter().map(|&w| w as u32).collect();
        let point = PeriodPoint::decode(&point_words).map_err(|source| MotorDspError::Command {
            slave: self.slave,
            release: self.releases,
            source,
        })?;
        let expected = self.releases as u16;
        if point.sequence != expected {
            return Err(MotorDspError::Sequence {
                slave: self.slave,
                expected,
                got: point.sequence,
            });
        }
        let measured: Vec<i64> = words[WORDS..]
            .iter()
            .map(|&w| w as u32 as i32 as i64)
            .collect();
        let target = self.targets(&point);
        // The count latched at this tick is compared with the point for
        // this tick (released LEAD_PERIODS earlier); the code goes out at
        // the next tick and drives until the one after, when this point's
        // pose is due: its velocity command is the mean over that period,
        // plus the drive's lag times the acceleration.
        let now = self.history.pop_front().expect("LEAD_PERIODS targets");
        let previous = *self.history.back().unwrap_or(&now);
        self.history.push_back(target);
        let load = self.load(&point.pose);
        let mut codes = [0; JOINTS_PER_SLAVE];
        for j in 0..JOINTS_PER_SLAVE {
            let (gains, tau) = self.gains(load[j]);
            self.loops[j].set_gains(gains);
            let mean = (target[j].counts - previous[j].counts) / self.settings.period_s;
            let acceleration = 0.5 * (target[j].acceleration + previous[j].acceleration);
            let out = self.loops[j].step(now[j].counts, mean + tau * acceleration, measured[j]);
            self.following[j].add(out.following_error);
            self.last_error[j] = out.following_error;
            self.saturated += out.saturated as u64;
            codes[j] = out.code;
        }
        Ok(codes)
    }

    /// Each leg's load relative to home at `pose` (1 at home).
    fn load(&self, pose: &Pose) -> [f64; JOINTS_PER_SLAVE] {
        let s = &self.settings;
        let at = leg_inertia(&s.geometry, pose, &s.inertia);
        std::array::from_fn(|j| {
            let leg = self.leg(j);
            at.map_or(1.0, |m| m[leg] / self.home_load[leg])
        })
    }

    /// The gains and the lag assumed at a relative load.
    fn gains(&self, load: f64) -> (ServoGains, f64) {
        let s = &self.settings;
        match s.schedule {
            GainSchedule::Fixed => (s.gains, s.time_constant_s),
            GainSchedule::Load => {
                let g = s.gains;
                let r = 1.0 / load;
                (
                    ServoGains {
                        kp: g.kp * r,
                        ki: g.ki * r * r,
                        ..g
                    },
                    s.time_constant_s * load,
                )
            }
        }
    }

    /// The point's legs in counts from home, and their accelerations.
    fn targets(&self, point: &PeriodPoint) -> [Target; JOINTS_PER_SLAVE] {
        let s = &self.settings;
        let lengths = inverse(&s.geometry, &point.pose);
        let rad = |v: &[f64; 6]| -> [f64; 6] {
            std::array::from_fn(|i| if i < 3 { v[i] } else { v[i].to_radians() })
        };
        let (qd, qdd) = (rad(&point.velocity), rad(&point.acceleration));
        // Leg acceleration = J q̈ + (dJ/dt) q̇, the second term by a central
        // difference of J along q̇.
        let jacobian = pose_jacobian(&s.geometry, &point.pose);
        let h = 1e-4;
        let shifted = |sign: f64| {
            let q = point.pose.coordinates();
            let moved: [f64; 6] = std::array::from_fn(|i| q[i] + sign * h * qd[i]);
            pose_jacobian(&s.geometry, &Pose::from_coordinates(moved))
        };
        let (ahead, behind) = (shifted(1.0), shifted(-1.0));
        std::array::from_fn(|j| {
            let leg = self.leg(j);
            let dot = |row: &[f64; 6], v: &[f64; 6]| (0..6).map(|i| row[i] * v[i]).sum::<f64>();
            let jdot_qd = (dot(&ahead[leg], &qd) - dot(&behind[leg], &qd)) / (2.0 * h);
            Target {
                counts: (lengths[leg] - self.home[leg]) * s.counts_per_mm,
                acceleration: (dot(&jacobian[leg], &qdd) + jdot_qd) * s.counts_per_mm,
            }
        })
    }
}
