//! Geared moves: the driver arms the electronic gearbox of a `SPINDLE`
//! build for one axis and watches it to the end of the move.
//!
//! The gearbox runs beside the period FIFO and independent of `RUN`; the
//! driver runs a geared move between two streamed runs, with the FIFOs
//! empty. It programs `GEAR_NUMERATOR`, `GEAR_DENOMINATOR`, `GEAR_RAMP`
//! and `GEAR_LENGTH`, arms with the directions and the axis in
//! `GEAR_CONTROL`, then polls `GEAR_STATUS` every [`GEAR_POLL_CLOCKS`]
//! clocks until the run is idle again. A run that ends short of its
//! length (an abort halts it, an overrun, an encoder error), an arm the
//! controller refuses and an index that never comes are errors naming
//! the cause.

use super::{Driver, DriverError};
use crate::host::bus::ControllerBus;

/// Clocks between two reads of `GEAR_STATUS` while a geared move runs.
pub const GEAR_POLL_CLOCKS: u64 = 32;

/// One geared move as the gearbox takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GearRun {
    /// The geared axis.
    pub axis: usize,
    /// Steps per count: `numerator` / `denominator`, at most 1.
    pub numerator: u32,
    /// See `numerator`.
    pub denominator: u32,
    /// Largest rate change per count, in 1 / `denominator` step per count.
    pub ramp: u32,
    /// Steps to move (not 0): the run stops there exactly.
    pub length: u32,
    /// The spindle's forward counts down (M4).
    pub spindle_reverse: bool,
    /// A forward count steps the axis down.
    pub axis_reverse: bool,
}

/// `GEAR_STATUS` decoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct GearStatus {
    /// 0 idle, 1 armed, 2 ramp-in, 3 track, 4 stopping.
    pub phase: u64,
    /// Tracking with the lag caught up.
    pub locked: bool,
    /// The last run reached its length.
    pub done: bool,
    /// An arm was refused.
    pub invalid: bool,
    /// A count came while one waited: the gearbox halted.
    pub overrun: bool,
    /// The spindle encoder saw an illegal transition.
    pub encoder_error: bool,
}

/// What the caller asks after each poll.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GearAction {
    /// Keep watching.
    Continue,
    /// Write `GEAR_CONTROL.STOP`: ramp out and stop where the ramp ends.
    Stop,
    /// Write `GEAR_CONTROL.HALT`: stop at once (where the axis stands:
    /// a rigid tap's turn at the top).
    Halt,
}

/// What a geared move did, in the clocks of the bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct GearReport {
    /// The clock of the arm.
    pub armed_at: u64,
    /// The first poll that saw the gearbox engaged.
    pub engaged_at: u64,
    /// The first poll that saw it locked (`None`: it never locked).
    pub locked_at: Option<u64>,
    /// The first poll that saw it ramping out (`None`: it reached its
    /// length from the lock without a ramp-out seen).
    pub stopping_at: Option<u64>,
    /// The poll that saw it idle again.
    pub ended_at: u64,
    /// `GEAR_POSITION` at the end: net steps of the run.
    pub position: i32,
    /// It reached its length (`GEAR_STATUS.DONE`).
    pub done: bool,
}

impl<B: ControllerBus> Driver<B> {
    /// `GEAR_STATUS` now.
    pub fn gear_status(&mut self) -> Result<GearStatus, DriverError> {
        let word = self.read("GEAR_STATUS", 0)?;
        let flag = |d: &Self, name: &str| d.field("GEAR_STATUS", name, word).map(|v| v == 1);
        Ok(GearStatus {
            phase: self.field("GEAR_STATUS", "PHASE", word)?,
            locked: flag(self, "LOCKED")?,
            done: flag(self, "DONE")?,
            invalid: flag(self, "INVALID")?,
            overrun: flag(self, "OVERRUN")?,
            encoder_error: flag(self, "ENCODER_ERROR")?,
        })
    }

    /// `SPINDLE_SPEED`: counts in the last speed window, signed.
    pub fn spindle_speed(&mut self) -> Result<i32, DriverError> {
        Ok(self.read("SPINDLE_SPEED", 0)? as i32)
    }

    /// The speed window, clocks (`2^SPINDLE_CONFIG.SPEED_WINDOW`).
    pub fn speed_window_clocks(&mut self) -> Result<u64, DriverError> {
        let config = self.read("SPINDLE_CONFIG", 0)?;
        Ok(1 << self.field("SPINDLE_CONFIG", "SPEED_WINDOW", config)?)
    }

    /// Runs `run` to its end: arms, waits for the index (at most
    /// `index_timeout` clocks), then polls until the gearbox is idle.
    /// `watch` sees the bus, each poll's status and `GEAR_POSITION`, and
    /// may ask for a stop or a halt; the run then ends where that leaves
    /// it, without an error.
    pub fn gear_run(
        &mut self,
        run: &GearRun,
        index_timeout: u64,
        mut watch: impl FnMut(&mut B, GearStatus, i32) -> GearAction,
    ) -> Result<GearReport, DriverError> {
        if self.map.register("GEAR_CONTROL").is_err() {
            return Err(DriverError::Gear(
                "this controller has no gearbox (CONFIG.SPINDLE reads 0; motion_controller_dda_spindle has one)".into(),
            ));
        }
        if run.length == 0 {
            return Err(DriverError::Gear("a geared move of 0 steps".into()));
        }
        let status = self.gear_status()?;
        if status.phase != 0 {
            return Err(DriverError::Gear(format!(
                "the gearbox is not idle (GEAR_STATUS.PHASE reads {})",
                status.phase
            )));
        }
        self.write("GEAR_NUMERATOR", 0, run.numerator)?;
        self.write("GEAR_DENOMINATOR", 0, run.denominator)?;
        self.write("GEAR_RAMP", 0, run.ramp)?;
        self.write("GEAR_LENGTH", 0, run.length)?;
        let arm = self.pack(
            "GEAR_CONTROL",
            &[
                ("ARM", 1),
                ("CLEAR_ENCODER_ERROR", 1),
                ("SPINDLE_REVERSE", run.spindle_reverse as u64),
                ("AXIS_REVERSE", run.axis_reverse as u64),
                ("AXIS", run.axis as u64),
            ],
        )?;
        self.write("GEAR_CONTROL", 0, arm)?;
        let mut report = GearReport {
            armed_at: self.bus.cycles(),
            ..GearReport::default()
        };
        let mut stop_written = false;
        let mut engaged = false;
        loop {
            self.bus.wait(GEAR_POLL_CLOCKS);
            let status = self.gear_status()?;
            let now = self.bus.cycles();
            if status.invalid {
                return Err(DriverError::Gear(format!(
                    "the controller refused the ratio {}/{} with ramp {} (GEAR_STATUS.INVALID)",
                    run.numerator, run.denominator, run.ramp
                )));
            }
            match status.phase {
                1 if now - report.armed_at > index_timeout => {
                    self.halt_gear()?;
                    return Err(DriverError::Gear(format!(
                        "no spindle index within {index_timeout} clocks of the arm: is the spindle turning, its encoder wired?"
                    )));
                }
                2..=4 if !engaged => {
                    engaged = true;
                    report.engaged_at = now;
                }
                _ => {}
            }
            if status.locked && report.locked_at.is_none() {
                report.locked_at = Some(now);
            }
            if status.phase == 4 && report.stopping_at.is_none() {
                report.stopping_at = Some(now);
            }
            if status.phase == 0 {
                report.ended_at = now;
                report.done = status.done;
                report.position = self.read("GEAR_POSITION", 0)? as i32;
                if status.overrun {
                    return Err(DriverError::Gear(format!(
                        "the spindle counted faster than the gearbox takes counts (GEAR_STATUS.OVERRUN): halted after {} steps",
                        report.position
                    )));
                }
                if status.encoder_error {
                    return Err(DriverError::Gear(format!(
                        "the spindle encoder saw an illegal transition (GEAR_STATUS.ENCODER_ERROR) after {} steps",
                        report.position
                    )));
                }
                if !status.done && !stop_written {
                    // An abort halts the gearbox: what holds the
                    // controller names it.
                    let reasons = self.refusal()?;
                    let why = match reasons.is_empty() {
                        true => "halted (GEAR_CONTROL.HALT)".to_string(),
                        false => reasons.join("; "),
                    };
                    return Err(DriverError::Gear(format!(
                        "the gearbox stopped after {} of {} steps: {why}",
                        report.position, run.length
                    )));
                }
                return Ok(report);
            }
            if stop_written {
                continue;
            }
            let position = self.gear_position()?;
            match watch(&mut self.bus, status, position) {
                GearAction::Continue => {}
                GearAction::Stop => {
                    let stop = self.pack("GEAR_CONTROL", &[("STOP", 1)])?;
                    self.write("GEAR_CONTROL", 0, stop)?;
                    stop_written = true;
                }
                GearAction::Halt => {
                    self.halt_gear()?;
                    stop_written = true;
                }
            }
        }
    }

    /// `GEAR_CONTROL.HALT`: the gearbox stops at once.
    pub fn halt_gear(&mut self) -> Result<(), DriverError> {
        let halt = self.pack("GEAR_CONTROL", &[("HALT", 1)])?;
        self.write("GEAR_CONTROL", 0, halt)
    }

    /// Sets the spindle's speed window to 2^`log2` clocks
    /// (`SPINDLE_CONFIG.SPEED_WINDOW`; the encoder's other options stay
    /// at reset).
    pub fn set_speed_window(&mut self, log2: u32) -> Result<(), DriverError> {
        let config = self.pack("SPINDLE_CONFIG", &[("SPEED_WINDOW", log2 as u64)])?;
        self.write("SPINDLE_CONFIG", 0, config)
    }

    /// Each axis's `CMD_POSITION` and `ACT_POSITION` now.
    pub fn positions(&mut self) -> Result<([i32; 3], [i32; 3]), DriverError> {
        let commanded = self.commanded_positions()?;
        let mut actual = [0; 3];
        for (k, a) in actual.iter_mut().enumerate() {
            *a = self.read("ACT_POSITION", k as u32)? as i32;
        }
        Ok((commanded, actual))
    }

    /// `GEAR_POSITION` now: the last run's net steps.
    pub fn gear_position(&mut self) -> Result<i32, DriverError> {
        Ok(self.read("GEAR_POSITION", 0)? as i32)
    }
}
