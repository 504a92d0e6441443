//! The firmware half in Rust: programs `motion_controller` through its
//! generated register map over any [`ControllerBus`], streams per-period
//! step counts into the FIFOs from the low-water interrupt, and reports
//! underruns, faults and aborts.
//!
//! A run ends normally with the underrun of the empty FIFOs after the last
//! period. When `RUN` falls any other way (an E-stop, a limit switch, a
//! drive alarm, a home switch with `STOP_ON_HOME`, the watchdog, or `RUN`
//! written 0), the run fails with [`DriverError::Stopped`], which names the
//! cause from `STOP_CAUSE` and, for a switch or an alarm, the axis. The
//! driver sees the stop by its interrupt (`LIMIT`, `ALARM`, `ESTOP`,
//! `WATCHDOG`) or, for a cause without one, by polling `STATE` every
//! [`POLL_CLOCKS`] clocks. A run the controller would refuse (E-stop
//! active or latched, a trip held) fails at once with
//! [`DriverError::Refused`], naming what holds it.
//!
//! The feed hold ([`Driver::hold`], [`Driver::release`],
//! [`Driver::set_hold_rate`], [`Driver::hold_state`]) stops the path along
//! itself without ending the run: [`Driver::run_with_holds`] requests and
//! releases it at given clocks, and the run ends where it would without
//! them. While held no period ends, so the FIFOs are not drained and no
//! underrun comes; a run that stands held with no release to come fails
//! with [`DriverError::Held`] (a `feed_hold` input still pressed, a probe
//! trip with `PROBE_CONTROL.STOP`); [`Driver::abandon_held_path`] then
//! ends it where it stands.
//!
//! Soft limits ([`DriverConfig::soft_limits`], a build with
//! `CONFIG.SOFT_LIMITS`): the driver programs each axis's window, starts
//! a run only once `SOFT_LIMIT.MEASURED` reads 1, and a path that would
//! leave a window stops along itself inside it; the run then fails with
//! [`DriverError::SoftLimit`] naming the axis, after the driver stopped
//! the controller, flushed the periods not taken and released the hold,
//! so the next run (back into the window) starts from where it stood.

use thiserror::Error;

use super::bus::ControllerBus;
use crate::blocks::motion_controller::registers::{register_map, BuildOptions, StopCause};
use crate::regmap::{RegMapError, RegisterMap};

/// The `IRQ_ENABLE` fields the driver turns on: FIFO_LOW for refills, every
/// fault source, every abort (limit, drive alarm, E-stop) and the feed
/// hold's stop (HELD); PERIOD_DONE, HOME (any home edge), PROBE and GPIO
/// stay off.
pub const SERVICED_INTERRUPTS: &[(&str, u64)] = &[
    ("FIFO_LOW", 1),
    ("UNDERRUN", 1),
    ("OVERFLOW", 1),
    ("ENCODER_ERROR", 1),
    ("WATCHDOG", 1),
    ("AXIS_FAULT", 1),
    ("LIMIT", 1),
    ("ALARM", 1),
    ("ESTOP", 1),
    ("HELD", 1),
];

/// Clocks between two reads of `STATE` while no interrupt comes: a stop
/// without an enabled interrupt (a home stop, `RUN` written 0 elsewhere) is
/// seen within this.
pub const POLL_CLOCKS: u64 = 1024;

/// The sentence of a stop: "motion stopped: limit switch on axis 1".
fn stop_sentence(cause: &StopCause, axis: &Option<usize>) -> String {
    match axis {
        Some(axis) => format!("motion stopped: {} on axis {axis}", cause.describe()),
        None => format!("motion stopped: {}", cause.describe()),
    }
}

/// How the driver sets the controller up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriverConfig {
    /// Clocks per base tick (`TICK_DIVISOR`).
    pub tick_divisor: u32,
    /// Base ticks per interpolation period (`PERIOD_TICKS`, 1 to 65535).
    pub period_ticks: u32,
    /// Step pulse high time, clocks.
    pub step_len: u32,
    /// Minimum step low time, clocks.
    pub step_space: u32,
    /// Direction setup and hold, clocks.
    pub dir_time: u32,
    /// Per axis: the uniform pulse generator (else the DDA).
    pub uniform: [bool; 3],
    /// Per axis: an analog (DAC) axis, its FIFO entries velocity codes
    /// (needs a build with the analog outputs; see [`Driver::run_servo`]).
    pub analog: [bool; 3],
    /// Per axis: the soft-limit window (`SOFT_MIN`, `SOFT_MAX`) in steps,
    /// or none (needs a build with the soft limits, `CONFIG.SOFT_LIMITS`).
    /// A path that would leave a window stops inside it and the run
    /// fails with [`DriverError::SoftLimit`].
    pub soft_limits: [Option<(i32, i32)>; 3],
}

impl Default for DriverConfig {
    fn default() -> Self {
        Self {
            tick_divisor: 1,
            period_ticks: 200,
            step_len: 2,
            step_space: 2,
            dir_time: 2,
            uniform: [false, true, false],
            analog: [false; 3],
            soft_limits: [None; 3],
        }
    }
}

/// What a run did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunReport {
    /// Periods streamed.
    pub periods: usize,
    /// Underruns while periods were still to come (each one restarted).
    pub underruns: usize,
    /// Final commanded positions (steps emitted), per axis.
    pub commanded: [i32; 3],
    /// Final actual (encoder) positions, per axis.
    pub actual: [i32; 3],
    /// Interrupts serviced.
    pub interrupts: usize,
    /// Clocks simulated.
    pub cycles: u64,
    /// The clocks at which the driver saw `STATUS.HELD` (the feed hold
    /// brought the path to a stop), within 8 clocks of its interrupt.
    pub held: Vec<u64>,
}

/// Why a run could not be done.
#[derive(Debug, Error)]
pub enum DriverError {
    /// A setting is out of range.
    #[error("invalid configuration: {0}")]
    Config(String),
    /// A period asks more of an axis than its interpolator can emit.
    #[error("period {period}, axis {axis}: {count} steps exceed the limit of {limit} per period ({why})")]
    CountTooLarge {
        /// Period index.
        period: usize,
        /// Axis.
        axis: usize,
        /// The count.
        count: i32,
        /// The limit.
        limit: u32,
        /// Which rule.
        why: &'static str,
    },
    /// A path would take an axis's commanded position beyond the range of
    /// the controller's position counters (`CONFIG.POSITION_BITS`), where
    /// they wrap.
    #[error("period {period}, axis {axis}: the commanded position would reach {position} steps, beyond the controller's range of +-{limit} (CONFIG.POSITION_BITS = {bits})")]
    PositionOutOfRange {
        /// Period index.
        period: usize,
        /// Axis.
        axis: usize,
        /// The position the path reaches, steps.
        position: i64,
        /// The largest magnitude the counters hold, 2^(bits - 1) - 1.
        limit: i64,
        /// `CONFIG.POSITION_BITS`.
        bits: u32,
    },
    /// The controller reported a fault that loses steps.
    #[error("controller fault: STATUS {status:#x}, AXIS_STATUS {axis_status:?}")]
    Fault {
        /// STATUS when it was seen.
        status: u32,
        /// Each axis's AXIS_STATUS.
        axis_status: [u32; 3],
    },
    /// The controller is not the one this driver knows.
    #[error("unexpected controller: {0}")]
    Identity(String),
    /// The register map is inconsistent (a bug).
    #[error(transparent)]
    RegisterMap(#[from] RegMapError),
    /// The controller never came to rest.
    #[error("the axes did not come to rest after the last period")]
    Timeout,
    /// `RUN` fell before the end of the path: an abort (E-stop, limit
    /// switch, drive alarm, home stop, watchdog) or `RUN` written 0.
    #[error("{} ({detail}); commanded position {commanded:?}, {periods_queued} of {periods} periods queued", stop_sentence(.cause, .axis))]
    Stopped {
        /// `STOP_CAUSE.CAUSE`.
        cause: StopCause,
        /// `STOP_CAUSE.AXIS`, for a home, limit or drive-alarm stop.
        axis: Option<usize>,
        /// What the axis's `IO_STATUS` or `STATE` adds (which limit, what
        /// to clear before the next run).
        detail: String,
        /// Each axis's `CMD_POSITION` (the steps that left the pins).
        commanded: [i32; 3],
        /// Periods written to the FIFOs before the stop.
        periods_queued: usize,
        /// Periods of the path.
        periods: usize,
    },
    /// The controller would refuse `RUN`: why.
    #[error("RUN refused: {0}")]
    Refused(String),
    /// A geared move could not run or stopped short: why.
    #[error("spindle sync: {0}")]
    Gear(String),
    /// A soft limit stopped the path: the driver stopped the controller,
    /// flushed the periods not taken and released the hold.
    #[error("soft limit: axis {axis} would leave its window moving {}; stopped at commanded position {commanded:?}, {periods_queued} of {periods} periods queued", if *.negative { "down (SOFT_MIN)" } else { "up (SOFT_MAX)" })]
    SoftLimit {
        /// The axis (`SOFT_LIMIT.AXIS`).
        axis: usize,
        /// It moved down, toward `SOFT_MIN`.
        negative: bool,
        /// Each axis's `CMD_POSITION` where the path stood.
        commanded: [i32; 3],
        /// Periods written to the FIFOs.
        periods_queued: usize,
        /// Periods of the path.
        periods: usize,
    },
    /// The feed hold stopped the path and nothing scheduled releases it:
    /// the run cannot end.
    #[error("motion held (HOLD_CONTROL.REQUESTED{}) with no release to come; commanded position {commanded:?}, {periods_queued} of {periods} periods queued", if *.input { ", the feed_hold input active" } else { "" })]
    Held {
        /// The `feed_hold` input is what holds it.
        input: bool,
        /// Each axis's `CMD_POSITION`.
        commanded: [i32; 3],
        /// Periods written to the FIFOs.
        periods_queued: usize,
        /// Periods of the path.
        periods: usize,
    },
}

/// The driver for a 3-axis `motion_controller`.
pub struct Driver<B: ControllerBus> {
    bus: B,
    map: RegisterMap,
    config: DriverConfig,
    depth: u32,
    /// `CONFIG.POSITION_BITS`: the position counters wrap beyond it.
    position_bits: u32,
    /// `CONFIG.LASER`.
    laser_build: bool,
    /// During [`Driver::run_laser`]: each period's `LASER_FIFO` word.
    laser_words: Vec<u32>,
}

mod feed_hold;
mod gear;
mod laser;
mod probe;
mod servo_run;
mod soft_limits;
pub use feed_hold::{HoldAction, HoldEvent, HoldState};
pub use gear::{GearAction, GearReport, GearRun, GearStatus, GEAR_POLL_CLOCKS};
pub use laser::{LaserEntry, LaserRun};
pub use probe::{ProbeEdge, ProbeTrip};
pub use servo_run::{ServoRunReport, SERVO_LEAD, SETTLED_PERIODS, SETTLE_PERIODS};

impl<B: ControllerBus> Driver<B> {
    /// Checks the configuration, reads the controller's identity and build
    /// configuration, and programs it (stopped).
    pub fn new(bus: B, config: DriverConfig) -> Result<Self, DriverError> {
        if config.tick_divisor == 0 {
            return Err(DriverError::Config(
                "tick_divisor must be at least 1".into(),
            ));
        }
        if !(1..=65535).contains(&config.period_ticks) {
            return Err(DriverError::Config(format!(
                "period_ticks {} is outside 1..=65535",
                config.period_ticks
            )));
        }
        for (name, v) in [
            ("step_len", config.step_len),
            ("step_space", config.step_space),
            ("dir_time", config.dir_time),
        ] {
            if v > 65535 {
                return Err(DriverError::Config(format!(
                    "{name} {v} does not fit 16 bits"
                )));
            }
        }
        // CONFIG is at the same address in every build: read it with the
        // full build's map, then take the map of the build found.
        let map = register_map(3, 4, BuildOptions::MOTION_CONTROLLER)?;
        let mut driver = Self {
            bus,
            map,
            config,
            depth: 0,
            position_bits: 32,
            laser_build: false,
            laser_words: Vec::new(),
        };
        let id = driver.read("ID", 0)?;
        if id != crate::blocks::motion_controller::registers::ID_VALUE {
            return Err(DriverError::Identity(format!("ID reads {id:#x}")));
        }
        let build = driver.read("CONFIG", 0)?;
        let axes = driver.field("CONFIG", "AXES", build)?;
        if axes != 3 {
            return Err(DriverError::Identity(format!(
                "{axes} axes, this driver drives 3"
            )));
        }
        driver.depth = 1 << driver.field("CONFIG", "FIFO_DEPTH_LOG2", build)?;
        driver.position_bits = driver.field("CONFIG", "POSITION_BITS", build)? as u32;
        if !(2..=32).contains(&driver.position_bits) {
            return Err(DriverError::Identity(format!(
                "CONFIG.POSITION_BITS reads {}, not 2 to 32",
                driver.position_bits
            )));
        }
        let uniform = driver.field("CONFIG", "DDA_ONLY", build)? == 0;
        let analog = driver.field("CONFIG", "ANALOG", build)? == 1;
        let probe = driver.field("CONFIG", "PROBE", build)? == 1;
        let soft_limits = driver.field("CONFIG", "SOFT_LIMITS", build)? == 1;
        let spindle = driver.field("CONFIG", "SPINDLE", build)? == 1;
        let laser = driver.field("CONFIG", "LASER", build)? == 1;
        for (axis, window) in config.soft_limits.iter().enumerate() {
            match window {
                Some(_) if !soft_limits => {
                    return Err(DriverError::Config(format!(
                        "axis {axis} has a soft-limit window, and this controller has no soft limits (CONFIG.SOFT_LIMITS reads 0; motion_controller has them)"
                    )))
                }
                Some((min, max)) if min > max => {
                    return Err(DriverError::Config(format!(
                        "axis {axis}'s soft-limit window {min}..{max} is empty"
                    )))
                }
                _ => {}
            }
        }
        let options = BuildOptions {
            uniform,
            analog,
            probe,
            soft_limits,
            spindle,
            laser,
        };
        driver.map = register_map(3, driver.depth.trailing_zeros(), options)?;
        driver.laser_build = laser;
        if let Some(axis) = (0..3).find(|&k| config.analog[k] && (!analog || config.uniform[k])) {
            return Err(DriverError::Config(if analog {
                format!("axis {axis} cannot be both uniform and analog")
            } else {
                format!("axis {axis} as an analog axis needs a controller with analog outputs (motion_controller_servo); this one's CONFIG.ANALOG reads 0")
            }));
        }
        driver.configure()?;
        Ok(driver)
    }

    /// Clocks per interpolation period: `TICK_DIVISOR` x `PERIOD_TICKS`.
    pub fn period_clocks(&self) -> u64 {
        self.config.tick_divisor as u64 * self.config.period_ticks as u64
    }

    /// Clocks per base tick (`TICK_DIVISOR`).
    pub fn tick_divisor(&self) -> u32 {
        self.config.tick_divisor
    }

    /// The bus (for its statistics).
    pub fn bus(&self) -> &B {
        &self.bus
    }

    /// The bus, to drive it directly (a simulated machine input, a register
    /// the driver does not touch).
    pub fn bus_mut(&mut self) -> &mut B {
        &mut self.bus
    }

    fn address(&self, name: &str, index: u32) -> Result<u32, DriverError> {
        Ok(self.map.register(name)?.address_of(index)?)
    }

    fn write(&mut self, name: &str, index: u32, value: u32) -> Result<(), DriverError> {
        let address = self.address(name, index)?;
        self.bus.write(address, value);
        Ok(())
    }

    fn read(&mut self, name: &str, index: u32) -> Result<u32, DriverError> {
        let address = self.address(name, index)?;
        Ok(self.bus.read(address))
    }

    fn field(&self, register: &str, field: &str, word: u32) -> Result<u64, DriverError> {
        Ok(self.map.register(register)?.field(field)?.extract(word)?)
    }

    fn pack(&self, register: &str, fields: &[(&str, u64)]) -> Result<u32, DriverError> {
        Ok(self.map.register(register)?.pack(fields)?)
    }

    fn configure(&mut self) -> Result<(), DriverError> {
        let c = self.config;
        self.write("CONTROL", 0, 0)?;
        self.write("TICK_DIVISOR", 0, c.tick_divisor)?;
        self.write("PERIOD_TICKS", 0, c.period_ticks)?;
        self.write("FIFO_LOW_WATER", 0, self.depth / 2)?;
        for axis in 0..3u32 {
            let config = self.pack(
                "AXIS_CONFIG",
                &[
                    ("UNIFORM", c.uniform[axis as usize] as u64),
                    ("INTERLEAVED", 1),
                    ("ANALOG", c.analog[axis as usize] as u64),
                ],
            )?;
            self.write("AXIS_CONFIG", axis, config)?;
            self.write("STEP_LEN", axis, c.step_len)?;
            self.write("STEP_SPACE", axis, c.step_space)?;
            self.write("DIR_SETUP", axis, c.dir_time)?;
            self.write("DIR_HOLD", axis, c.dir_time)?;
            // Limits and alarms stay enabled (their reset value); the drive
            // is enabled (the controller still drops it on E-stop, watchdog
            // expiry or its alarm).
            let io = self.pack(
                "IO_CONFIG",
                &[
                    ("LIMIT_ENABLE", 1),
                    ("ALARM_ENABLE", 1),
                    ("DRIVE_ENABLE", 1),
                ],
            )?;
            self.write("IO_CONFIG", axis, io)?;
        }
        self.configure_soft_limits()?;
        let enable = self.pack("IRQ_ENABLE", SERVICED_INTERRUPTS)?;
        self.write("IRQ_ENABLE", 0, enable)?;
        let status = self.read("STATUS", 0)?;
        self.write("STATUS", 0, status)
    }

    /// The most steps an axis may take in one period: the interpolator's
    /// limit (DDA: one per tick; uniform: one per two ticks) and the output
    /// stage's (one per step_len + step_space clocks).
    pub fn limit(&self, axis: usize) -> (u32, &'static str) {
        let c = self.config;
        let interpolator = if c.uniform[axis] {
            (c.period_ticks / 2, "uniform generator: T/2")
        } else {
            (c.period_ticks, "DDA: one per tick")
        };
        let clocks = c.period_ticks as u64 * c.tick_divisor as u64;
        let per_step = (c.step_len.max(1) + c.step_space.max(1)) as u64;
        let stage = (clocks / per_step) as u32;
        if stage < interpolator.0 {
            (stage, "output stage: step_len + step_space per step")
        } else {
            interpolator
        }
    }

    /// Checks every period's counts against the interpolators' limits, and
    /// the positions they reach, from where the axes stand, against the
    /// position counters' range: the controller's counters wrap there, and
    /// the driver reads the positions only between runs.
    fn check(&mut self, counts: &[[i32; 3]]) -> Result<(), DriverError> {
        let range = (1i64 << (self.position_bits - 1)) - 1;
        let mut position = [0i64; 3];
        for (axis, p) in position.iter_mut().enumerate() {
            *p = self.read("CMD_POSITION", axis as u32)? as i32 as i64;
        }
        for (period, c) in counts.iter().enumerate() {
            // An analog axis's position is the servo loop's business.
            for axis in (0..3).filter(|&k| !self.config.analog[k]) {
                let (limit, why) = self.limit(axis);
                if c[axis].unsigned_abs() > limit {
                    return Err(DriverError::CountTooLarge {
                        period,
                        axis,
                        count: c[axis],
                        limit,
                        why,
                    });
                }
                position[axis] += c[axis] as i64;
                if position[axis].abs() > range {
                    return Err(DriverError::PositionOutOfRange {
                        period,
                        axis,
                        position: position[axis],
                        limit: range,
                        bits: self.position_bits,
                    });
                }
            }
        }
        Ok(())
    }

    fn queue(&mut self, counts: &[[i32; 3]], next: &mut usize) -> Result<(), DriverError> {
        let level = self.read("FIFO_STATUS", 0)?;
        let room = self.depth as u64 - self.field("FIFO_STATUS", "LEVEL", level)?;
        for _ in 0..room {
            let Some(c) = counts.get(*next) else { break };
            self.push_period(c)?;
            // The laser FIFO pops with the axes': its level is theirs.
            self.push_laser(*next)?;
            *next += 1;
        }
        Ok(())
    }

    /// Writes one period's entry of every axis to its FIFO.
    fn push_period(&mut self, entry: &[i32; 3]) -> Result<(), DriverError> {
        for axis in 0..3u32 {
            self.write("FIFO_WRITE", axis, entry[axis as usize] as u32)?;
        }
        Ok(())
    }

    fn fault(&mut self, status: u32) -> Result<DriverError, DriverError> {
        let mut axis_status = [0; 3];
        for (axis, s) in axis_status.iter_mut().enumerate() {
            *s = self.read("AXIS_STATUS", axis as u32)?;
        }
        Ok(DriverError::Fault {
            status,
            axis_status,
        })
    }

    /// What holds `RUN` refused now (empty: nothing). Waits first for the
    /// inputs to become ready (3 clocks after reset).
    fn refusal(&mut self) -> Result<Vec<String>, DriverError> {
        let mut state = self.read("STATE", 0)?;
        for _ in 0..16 {
            if self.field("STATE", "INPUTS_READY", state)? == 1 {
                break;
            }
            self.bus.wait(1);
            state = self.read("STATE", 0)?;
        }
        let mut reasons = Vec::new();
        if self.field("STATE", "INPUTS_READY", state)? == 0 {
            reasons.push("the switch inputs are not ready (STATE.INPUTS_READY)".to_string());
        }
        if self.field("STATE", "ESTOP_INPUT", state)? == 1 {
            reasons.push("the E-stop input is active".to_string());
        }
        if self.field("STATE", "ESTOP_LATCHED", state)? == 1 {
            reasons.push("E-stop latched (release it, then clear STATUS.ESTOP)".to_string());
        }
        if self.field("STATE", "WATCHDOG_EXPIRED", state)? == 1 {
            reasons.push("the watchdog expired (clear STATUS.WATCHDOG)".to_string());
        }
        for axis in 0..3u32 {
            reasons.extend(
                self.axis_trips(axis)?
                    .into_iter()
                    .map(|t| format!("axis {axis}: {t}")),
            );
        }
        Ok(reasons)
    }

    /// Fails with [`DriverError::Refused`], naming what holds it, when the
    /// controller would refuse `RUN` now.
    fn ensure_runnable(&mut self) -> Result<(), DriverError> {
        let reasons = self.refusal()?;
        if reasons.is_empty() {
            Ok(())
        } else {
            Err(DriverError::Refused(reasons.join("; ")))
        }
    }

    /// The trips an axis holds (each one refuses RUN), with what clears it.
    fn axis_trips(&mut self, axis: u32) -> Result<Vec<String>, DriverError> {
        let status = self.read("IO_STATUS", axis)?;
        let config = self.read("IO_CONFIG", axis)?;
        let mut trips = Vec::new();
        for (flag, what) in [
            ("LIMIT_POS_TRIPPED", "positive limit (limit_pos) tripped; clear with IO_COMMAND.CLEAR_LIMITS, then move away"),
            ("LIMIT_NEG_TRIPPED", "negative limit (limit_neg) tripped; clear with IO_COMMAND.CLEAR_LIMITS, then move away"),
            ("ALARM_TRIPPED", "drive alarm tripped; clear with IO_COMMAND.CLEAR_ALARM once the alarm is gone"),
        ] {
            if self.field("IO_STATUS", flag, status)? == 1 {
                trips.push(what.to_string());
            }
        }
        if self.field("IO_STATUS", "HOME_SEEN", status)? == 1
            && self.field("IO_CONFIG", "STOP_ON_HOME", config)? == 1
        {
            trips.push(
                "home switch seen with STOP_ON_HOME; clear with IO_COMMAND.CLEAR_HOME".to_string(),
            );
        }
        Ok(trips)
    }

    /// `STOP_CAUSE`: the cause and, for a home, limit or alarm stop, the axis.
    fn stop_cause(&mut self) -> Result<(StopCause, Option<usize>), DriverError> {
        let word = self.read("STOP_CAUSE", 0)?;
        let cause = StopCause::from_code(self.field("STOP_CAUSE", "CAUSE", word)? as u32);
        let axis = self.field("STOP_CAUSE", "AXIS", word)? as usize;
        let per_axis = matches!(
            cause,
            StopCause::Home | StopCause::Limit | StopCause::DriveAlarm
        );
        Ok((cause, per_axis.then_some(axis)))
    }

    /// The error of a run that `cause` stopped before its end.
    fn stopped(
        &mut self,
        cause: StopCause,
        axis: Option<usize>,
        periods_queued: usize,
        periods: usize,
    ) -> Result<DriverError, DriverError> {
        let mut details = Vec::new();
        if let Some(axis) = axis {
            details.extend(self.axis_trips(axis as u32)?);
            if cause == StopCause::Home {
                let cmd = self.read("HOME_CMD_POSITION", axis as u32)? as i32;
                let act = self.read("HOME_ACT_POSITION", axis as u32)? as i32;
                details.push(format!("home edge at commanded {cmd}, actual {act}"));
            }
        }
        if cause == StopCause::Estop {
            details.push(
                "every drive disabled; release the E-stop, then clear STATUS.ESTOP".to_string(),
            );
        }
        if cause == StopCause::Watchdog {
            details.push("clear STATUS.WATCHDOG".to_string());
        }
        if details.is_empty() {
            details.push(
                "the FIFOs keep the periods not taken; CONTROL.FLUSH empties them".to_string(),
            );
        }
        let commanded = self.commanded_positions()?;
        Ok(DriverError::Stopped {
            cause,
            axis,
            detail: details.join("; "),
            commanded,
            periods_queued,
            periods,
        })
    }

    /// Streams `counts` (one entry per period) and waits until every step
    /// has left and the encoders have settled. `progress` gets the number
    /// of periods queued so far. Fails with [`DriverError::Refused`] when
    /// the controller would not start, and with [`DriverError::Stopped`]
    /// when it stops before the last period (an abort), naming the cause.
    pub fn run(
        &mut self,
        counts: &[[i32; 3]],
        progress: impl FnMut(usize),
    ) -> Result<RunReport, DriverError> {
        self.run_with_holds(counts, &[], progress)
    }

    /// [`Driver::run`] with the feed hold requested and released at the
    /// clocks of `holds` (in clock order): the path slows along itself to
    /// a stop and resumes, and ends where it would without them. Fails
    /// with [`DriverError::Held`] when the path stands held and no event
    /// is left to release it. Events due after the run has ended are not
    /// made.
    pub fn run_with_holds(
        &mut self,
        counts: &[[i32; 3]],
        holds: &[HoldEvent],
        mut progress: impl FnMut(usize),
    ) -> Result<RunReport, DriverError> {
        Self::check_hold_order(holds)?;
        if let Some(axis) = (0..3).find(|&k| self.config.analog[k]) {
            return Err(DriverError::Config(format!(
                "axis {axis} is analog: its entries are codes from a servo loop (Driver::run_servo), not step counts"
            )));
        }
        self.check(counts)?;
        self.ensure_runnable()?;
        let mut report = RunReport {
            periods: counts.len(),
            ..Default::default()
        };
        let mut next = 0;
        self.queue(counts, &mut next)?;
        self.await_soft_limit_reach()?;
        self.write("CONTROL", 0, 1)?;
        let mut soft_trip = false;
        let faults = self.pack(
            "STATUS",
            &[("OVERFLOW", 1), ("ENCODER_ERROR", 1), ("AXIS_FAULT", 1)],
        )?;
        let mut quiet = 0;
        let mut next_hold = 0;
        loop {
            let until_hold = self.apply_due_holds(holds, &mut next_hold)?;
            let step = until_hold.map_or(8, |c| c.min(8));
            if self.bus.wait(step) {
                report.interrupts += 1;
            } else {
                quiet += step;
                if quiet < POLL_CLOCKS {
                    continue;
                }
            }
            quiet = 0;
            let status = self.read("STATUS", 0)?;
            if status != 0 {
                self.write("STATUS", 0, status)?;
            }
            let state = self.read("STATE", 0)?;
            let running = self.field("STATE", "RUNNING", state)? == 1;
            let mut underrun = false;
            if !running {
                match self.stop_cause()? {
                    (StopCause::Underrun, _) => underrun = true,
                    (StopCause::None, _) => {
                        // RUN never rose: refused after all.
                        let reasons = self.refusal()?;
                        return Err(DriverError::Refused(if reasons.is_empty() {
                            "CONTROL.RUN did not start".into()
                        } else {
                            reasons.join("; ")
                        }));
                    }
                    (cause, axis) => return Err(self.stopped(cause, axis, next, counts.len())?),
                }
            }
            if status & faults != 0 {
                return Err(self.fault(status)?);
            }
            if self.field("STATUS", "HELD", status)? == 1 {
                report.held.push(self.bus.cycles());
            }
            soft_trip |= self.soft_limit_tripped(status)?;
            if running && self.field("STATE", "HELD", state)? == 1 {
                if soft_trip {
                    return Err(self.stop_at_soft_limit(next, counts.len())?);
                }
                self.fail_if_held_for_good(holds, next_hold, next, counts.len())?;
            }
            self.queue(counts, &mut next)?;
            progress(next);
            if underrun {
                let level = self.read("FIFO_STATUS", 0)?;
                if self.field("FIFO_STATUS", "EMPTY", level)? == 1 {
                    break; // the end: every period has been taken
                }
                // Data came too late: restart from where it stopped, unless
                // an abort came since (then RUN would be refused).
                self.ensure_runnable()?;
                report.underruns += 1;
                self.write("CONTROL", 0, 1)?;
            }
        }
        self.settle()?;
        for axis in 0..3u32 {
            report.commanded[axis as usize] = self.read("CMD_POSITION", axis)? as i32;
            report.actual[axis as usize] = self.read("ACT_POSITION", axis)? as i32;
        }
        report.cycles = self.bus.cycles();
        Ok(report)
    }

    /// Each axis's `CMD_POSITION` now.
    fn commanded_positions(&mut self) -> Result<[i32; 3], DriverError> {
        let mut commanded = [0; 3];
        for (k, c) in commanded.iter_mut().enumerate() {
            *c = self.read("CMD_POSITION", k as u32)? as i32;
        }
        Ok(commanded)
    }

    /// Waits until no output stage is busy, then for the encoder latency.
    fn settle(&mut self) -> Result<(), DriverError> {
        for _ in 0..10_000 {
            let mut busy = false;
            for axis in 0..3u32 {
                let s = self.read("AXIS_STATUS", axis)?;
                busy |= self.field("AXIS_STATUS", "STEP_BUSY", s)? == 1
                    || self.field("AXIS_STATUS", "UNIFORM_RUNNING", s)? == 1;
            }
            if !busy {
                self.bus.wait(32);
                return Ok(());
            }
            self.bus.wait(64);
        }
        Err(DriverError::Timeout)
    }
}
