//! Laser runs: the driver streams one `LASER_FIFO` entry per period beside
//! the axes' entries on a `LASER` build (`motion_controller_dda_laser`).
//!
//! [`Driver::run_laser`] programs `LASER_PWM_PERIOD` and `LASER_CONTROL`
//! (ENABLE, DYNAMIC and the plane's axes) before the start, so that the
//! laser FIFO takes part in the run; every period then writes its axes'
//! counts and its (POWER, FEED) word, packed by field name. The run
//! streams, holds, restarts after an underrun and ends exactly as
//! [`Driver::run_with_holds`]; at its end, or when it fails, ENABLE is
//! written 0. After an abort the laser FIFO keeps the periods not taken,
//! as the axes' FIFOs do (`CONTROL.FLUSH` empties them all).
//!
//! DYNAMIC is a register, not a FIFO field: one run is all M3 or all M4,
//! and a change between them waits for the FIFOs to drain.

use super::{Driver, DriverError, HoldEvent, RunReport};
use crate::host::bus::ControllerBus;

/// One period's laser entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct LaserEntry {
    /// `LASER_FIFO.POWER`: clocks high per PWM period at the programmed
    /// feed (M4) or always (M3); 0 for a rapid.
    pub power: u16,
    /// `LASER_FIFO.FEED`: the programmed feed along the plane, 1/16 step
    /// per period (M4 only).
    pub feed: u16,
}

/// The laser's settings for one run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaserRun {
    /// `LASER_PWM_PERIOD`: clocks per PWM period.
    pub pwm_period: u16,
    /// `LASER_CONTROL.DYNAMIC`: M4 (the duty scales with the path speed
    /// over FEED); M3 (false): the duty is POWER.
    pub dynamic: bool,
    /// `LASER_CONTROL.AXIS_A` and `AXIS_B`: the plane whose vector speed
    /// scales the duty.
    pub plane: (usize, usize),
}

impl<B: ControllerBus> Driver<B> {
    /// Whether the controller has the laser unit (`CONFIG.LASER`).
    pub fn has_laser(&self) -> bool {
        self.laser_build
    }

    /// [`Driver::run_with_holds`] with the laser: `entries` holds one
    /// entry per period of `counts`. Fails with [`DriverError::Config`] on
    /// a build without the laser, a count of entries other than the
    /// periods', or a plane axis beyond the three.
    pub fn run_laser(
        &mut self,
        counts: &[[i32; 3]],
        entries: &[LaserEntry],
        laser: LaserRun,
        holds: &[HoldEvent],
        progress: impl FnMut(usize),
    ) -> Result<RunReport, DriverError> {
        if !self.laser_build {
            return Err(DriverError::Config(
                "this controller has no laser (CONFIG.LASER reads 0; motion_controller_dda_laser has one)".into(),
            ));
        }
        if entries.len() != counts.len() {
            return Err(DriverError::Config(format!(
                "{} laser entries for {} periods: one per period",
                entries.len(),
                counts.len()
            )));
        }
        let (a, b) = laser.plane;
        if a > 2 || b > 2 || a == b {
            return Err(DriverError::Config(format!(
                "the laser's plane ({a}, {b}) is not two different axes of the three"
            )));
        }
        let mut words = Vec::with_capacity(entries.len());
        for e in entries {
            words.push(self.pack(
                "LASER_FIFO",
                &[("POWER", e.power as u64), ("FEED", e.feed as u64)],
            )?);
        }
        self.write("LASER_PWM_PERIOD", 0, laser.pwm_period as u32)?;
        let control = self.pack(
            "LASER_CONTROL",
            &[
                ("ENABLE", 1),
                ("DYNAMIC", laser.dynamic as u64),
                ("AXIS_A", a as u64),
                ("AXIS_B", b as u64),
            ],
        )?;
        self.write("LASER_CONTROL", 0, control)?;
        self.laser_words = words;
        let report = self.run_with_holds(counts, holds, progress);
        self.laser_words.clear();
        self.write("LASER_CONTROL", 0, 0)?;
        report
    }

    /// Writes period `period`'s laser word, during a laser run.
    pub(super) fn push_laser(&mut self, period: usize) -> Result<(), DriverError> {
        match self.laser_words.get(period) {
            Some(&word) => self.write("LASER_FIFO", 0, word),
            None => Ok(()),
        }
    }
}
