//! [`Driver::run_servo`]: the DSP's half of an analog servo axis. Once per
//! period the driver reads each analog axis's encoder, runs its position
//! loop and queues the resulting DAC code, keeping only [`SERVO_LEAD`]
//! entries ahead of the running one: the FIFO is the loop's delay, so it is
//! kept short. The step axes take their counts from the same periods.

use super::feed_hold::HoldEvent;
use super::{ControllerBus, Driver, DriverError, RunReport, StopCause};
use crate::host::servo::{FollowingError, PositionLoop};

/// Entries queued beyond the running one: the loop's delay, in periods.
pub const SERVO_LEAD: usize = 2;
/// Periods the loop may hold the end position before the stop.
pub const SETTLE_PERIODS: usize = 5000;
/// Consecutive periods within a count of the end that count as settled.
pub const SETTLED_PERIODS: usize = 50;

/// What a servo run did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ServoRunReport {
    /// Periods, positions and clocks, as [`Driver::run`] reports them (an
    /// analog axis's commanded position counts no steps: it stays 0).
    pub run: RunReport,
    /// Per analog axis: the following error over the run, counts.
    pub following: [Option<FollowingError>; 3],
    /// Per period: each analog axis's following error, counts (0 for a
    /// step axis).
    pub errors: Vec<[f64; 3]>,
    /// Periods held at the end before every analog axis settled.
    pub settle_periods: usize,
}

impl<B: ControllerBus> Driver<B> {
    /// Streams `counts` (the path's per-period counts: steps on a step
    /// axis, the encoder counts to travel on an analog axis) with the
    /// analog axes closed through `loops` (one per analog axis, run every
    /// `period_s`). After the last period the loops hold the end until
    /// every analog axis has been within a count of it for
    /// [`SETTLED_PERIODS`] periods (at most [`SETTLE_PERIODS`]); then `RUN`
    /// is written 0, which sets their outputs to 0 V. Fails like
    /// [`Driver::run`] on a stop or a fault, and with
    /// [`DriverError::Config`] when `loops` does not match the analog axes.
    pub fn run_servo(
        &mut self,
        counts: &[[i32; 3]],
        loops: &mut [Option<PositionLoop>; 3],
        period_s: f64,
        progress: impl FnMut(usize),
    ) -> Result<ServoRunReport, DriverError> {
        self.run_servo_with_holds(counts, loops, period_s, &[], progress)
    }

    /// [`Driver::run_servo`] with the feed hold requested and released at
    /// the clocks of `holds`, as [`Driver::run_with_holds`] does. The hold
    /// stretches the periods and the controller scales the analog codes by
    /// its factor (VERSION 0.6.1), so each loop still runs once a period
    /// and no period ends while the path stands. Fails with
    /// [`DriverError::Held`] when the path stands held with no release to
    /// come, and with [`DriverError::Config`] for events out of clock order.
    pub fn run_servo_with_holds(
        &mut self,
        counts: &[[i32; 3]],
        loops: &mut [Option<PositionLoop>; 3],
        period_s: f64,
        holds: &[HoldEvent],
        mut progress: impl FnMut(usize),
    ) -> Result<ServoRunReport, DriverError> {
        Self::check_hold_order(holds)?;
        if let Some(axis) = (0..3).find(|&k| loops[k].is_some() != self.config.analog[k]) {
            return Err(DriverError::Config(format!(
                "axis {axis}: a servo loop is needed for each analog axis, and for no other"
            )));
        }
        if !(period_s.is_finite() && period_s > 0.0) {
            return Err(DriverError::Config(format!("period {period_s} s")));
        }
        self.check(counts)?;
        self.ensure_runnable()?;
        // Where each axis should be after j periods, and its speed in j.
        let mut target = vec![[0i64; 3]];
        for c in counts {
            let last = target[target.len() - 1];
            target.push(std::array::from_fn(|k| last[k] + c[k] as i64));
        }
        let end = target[target.len() - 1];
        let analog: Vec<usize> = (0..3).filter(|&k| self.config.analog[k]).collect();
        let mut report = ServoRunReport {
            following: std::array::from_fn(|k| self.config.analog[k].then(FollowingError::default)),
            ..Default::default()
        };
        let faults = self.pack(
            "STATUS",
            &[("OVERFLOW", 1), ("ENCODER_ERROR", 1), ("AXIS_FAULT", 1)],
        )?;

        // Entry j, with the analog axes measured after `done` periods.
        let mut next_entry = |j: usize, done: usize, measured: [i64; 3]| -> [i32; 3] {
            let now = target[done.min(counts.len())];
            std::array::from_fn(|k| match loops[k].as_mut() {
                Some(servo) => {
                    let velocity = counts.get(j).map_or(0.0, |c| c[k] as f64 / period_s);
                    let out = servo.step(now[k] as f64, velocity, measured[k]);
                    out.code as i32
                }
                None => counts.get(j).map_or(0, |c| c[k]),
            })
        };
        let measure = |driver: &mut Self| -> Result<[i64; 3], DriverError> {
            let mut m = [0i64; 3];
            for &k in &analog {
                m[k] = driver.read("ACT_POSITION", k as u32)? as i32 as i64;
            }
            Ok(m)
        };

        let base = self.read("PERIOD_COUNT", 0)?;
        let measured = measure(self)?;
        let mut queued = 0;
        for _ in 0..=SERVO_LEAD {
            self.push_period(&next_entry(queued, 0, measured))?;
            queued += 1;
        }
        self.write("CONTROL", 0, 1)?;
        let mut popped = 0usize;
        let mut settled = 0;
        let mut next_hold = 0;
        let mut was_held = false;
        loop {
            // The next pop.
            loop {
                let until_hold = self.apply_due_holds(holds, &mut next_hold)?;
                self.bus.wait(until_hold.map_or(16, |c| c.min(16)));
                let count = self.read("PERIOD_COUNT", 0)?.wrapping_sub(base) as usize;
                if count > popped {
                    popped = count;
                    break;
                }
                let state = self.read("STATE", 0)?;
                let held = self.field("STATE", "HELD", state)? == 1;
                if held && !was_held {
                    report.run.held.push(self.bus.cycles());
                }
                was_held = held;
                if held {
                    self.fail_if_held_for_good(
                        holds,
                        next_hold,
                        queued.min(counts.len()),
                        counts.len(),
                    )?;
                }
                if self.field("STATE", "RUNNING", state)? == 0 {
                    let (cause, axis) = self.stop_cause()?;
                    let cause = if cause == StopCause::None {
                        StopCause::Stop
                    } else {
                        cause
                    };
                    return Err(self.stopped(
                        cause,
                        axis,
                        queued.min(counts.len()),
                        counts.len(),
                    )?);
                }
            }
            let status = self.read("STATUS", 0)?;
            if status & faults != 0 {
                return Err(self.fault(status)?);
            }
            // Entry popped - 1 runs: popped - 1 periods are done.
            let done = popped - 1;
            let measured = measure(self)?;
            let now = target[done.min(counts.len())];
            let mut errors = [0.0; 3];
            for &k in &analog {
                errors[k] = (now[k] - measured[k]) as f64;
                if let Some(f) = report.following[k].as_mut() {
                    f.add(errors[k]);
                }
            }
            report.errors.push(errors);
            if done >= counts.len() {
                let close = analog.iter().all(|&k| (end[k] - measured[k]).abs() <= 1);
                settled = if close { settled + 1 } else { 0 };
                report.settle_periods = done - counts.len();
                if settled >= SETTLED_PERIODS || report.settle_periods >= SETTLE_PERIODS {
                    break;
                }
            }
            self.push_period(&next_entry(queued, done, measured))?;
            queued += 1;
            progress(queued.min(counts.len()));
        }
        // RUN = 0: every analog output to 0 V; the queued entries are dropped.
        self.write("CONTROL", 0, 0)?;
        let flush = self.pack("CONTROL", &[("FLUSH", 1)])?;
        self.write("CONTROL", 0, flush)?;
        self.settle()?;
        report.run.periods = counts.len();
        for axis in 0..3u32 {
            report.run.commanded[axis as usize] = self.read("CMD_POSITION", axis)? as i32;
            report.run.actual[axis as usize] = self.read("ACT_POSITION", axis)? as i32;
        }
        report.run.cycles = self.bus.cycles();
        Ok(report)
    }
}
