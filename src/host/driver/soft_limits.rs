//! The soft limits through the driver: the windows of
//! [`DriverConfig::soft_limits`](super::DriverConfig::soft_limits)
//! programmed (`SOFT_MIN`, `SOFT_MAX`, `SOFT_LIMIT.ENABLE`), the start
//! held back until the stop's reach is measured (`SOFT_LIMIT.MEASURED`),
//! and a trip turned into [`DriverError::SoftLimit`] once the path stands
//! (see the controller's "Soft limits").

use super::{ControllerBus, Driver, DriverError};

/// Clocks the driver waits for `SOFT_LIMIT.MEASURED`: the slowest rate
/// (RATE 1) is measured within 65539 clocks.
const MEASURE_CLOCKS: u64 = 70_000;

impl<B: ControllerBus> Driver<B> {
    /// Whether the configuration asks for any window.
    fn has_windows(&self) -> bool {
        self.config.soft_limits.iter().any(Option::is_some)
    }

    /// Programs the windows and their enables (nothing without windows:
    /// the build may have no soft limits).
    pub(super) fn configure_soft_limits(&mut self) -> Result<(), DriverError> {
        if !self.has_windows() {
            return Ok(());
        }
        let mut enable = 0;
        let windows = self.config.soft_limits;
        for (axis, window) in windows.iter().enumerate() {
            if let Some((min, max)) = *window {
                self.write("SOFT_MIN", axis as u32, min as u32)?;
                self.write("SOFT_MAX", axis as u32, max as u32)?;
                enable |= 1 << axis;
            }
        }
        let word = self.pack("SOFT_LIMIT", &[("ENABLE", enable)])?;
        self.write("SOFT_LIMIT", 0, word)
    }

    /// With windows, waits until the stop's reach at the present
    /// `HOLD_CONTROL.RATE` is measured: before that every moving axis
    /// is judged with the longest reach and would trip at once.
    pub(super) fn await_soft_limit_reach(&mut self) -> Result<(), DriverError> {
        if !self.has_windows() {
            return Ok(());
        }
        let start = self.bus.cycles();
        loop {
            let word = self.read("SOFT_LIMIT", 0)?;
            if self.field("SOFT_LIMIT", "MEASURED", word)? == 1 {
                return Ok(());
            }
            if self.bus.cycles() - start > MEASURE_CLOCKS {
                return Err(DriverError::Config(format!(
                    "SOFT_LIMIT.MEASURED still 0 {MEASURE_CLOCKS} clocks after the start was asked"
                )));
            }
            self.bus.wait(64);
        }
    }

    /// Whether `status` (a `STATUS` word just read) says a soft-limit
    /// verdict turned beyond.
    pub(super) fn soft_limit_tripped(&mut self, status: u32) -> Result<bool, DriverError> {
        Ok(self.has_windows() && self.field("STATUS", "SOFT_LIMIT", status)? == 1)
    }

    /// The path stands held by a soft limit: ends it where it stands
    /// ([`Driver::abandon_held_path`]: RUN 0, which clears the verdict,
    /// the periods not taken flushed, the hold released) and returns the
    /// error naming the axis.
    pub(super) fn stop_at_soft_limit(
        &mut self,
        periods_queued: usize,
        periods: usize,
    ) -> Result<DriverError, DriverError> {
        let word = self.read("SOFT_LIMIT", 0)?;
        let axis = self.field("SOFT_LIMIT", "AXIS", word)? as usize;
        let negative = self.field("SOFT_LIMIT", "NEGATIVE", word)? == 1;
        let commanded = self.abandon_held_path()?;
        Ok(DriverError::SoftLimit {
            axis,
            negative,
            commanded,
            periods_queued,
            periods,
        })
    }
}
