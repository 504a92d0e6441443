//! Reference model of [`super::DdaInterpolator`], cycle-exact. It is built
//! from the models of the blocks the RTL is built from (the sequential
//! divider and the DDA integrator), wired the same way.

use crate::blocks::dda_integrator::model::{DdaIntegratorInputs, DdaIntegratorModel};
use crate::blocks::sequential_divider::model::{SequentialDividerInputs, SequentialDividerModel};

/// Inputs of one clock cycle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct InterpolatorInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Time base.
    pub tick: bool,
    /// Queue the next period.
    pub load: bool,
    /// P of the next period (1 to 2^24 - 1; other values are refused).
    pub next_period: u32,
    /// Per axis: signed Q16.16 steps of the next period.
    pub next_delta: Vec<i32>,
    /// Clears the sticky flags.
    pub clear_status: bool,
}

impl InterpolatorInputs {
    /// The RTL's input vector, in its port order (one `next_delta` column
    /// per axis).
    pub fn to_vector(&self) -> Vec<u64> {
        let mut v = vec![
            self.reset as u64,
            self.tick as u64,
            self.load as u64,
            self.next_period as u64,
        ];
        v.extend(self.next_delta.iter().map(|&d| d as u32 as u64));
        v.push(self.clear_status as u64);
        v
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct InterpolatorOutputs {
    /// Per axis: step pulse.
    pub step: Vec<bool>,
    /// Per axis: direction (true = positive).
    pub dir: Vec<bool>,
    /// Strobe after each period's last tick.
    pub period_done: bool,
    /// The next-period slot is free.
    pub ready: bool,
    /// A period is in progress.
    pub running: bool,
    /// Sticky underrun.
    pub underrun: bool,
    /// Sticky overrange.
    pub overrange: bool,
    /// Sticky load error.
    pub load_error: bool,
}

impl InterpolatorOutputs {
    /// Reads the RTL's output vector, in its port order: a `step` and a
    /// `dir` column per axis, then six flags.
    pub fn from_vector(v: &[u64]) -> Self {
        let k = (v.len() - 6) / 2;
        Self {
            step: v[..k].iter().map(|&x| x != 0).collect(),
            dir: v[k..2 * k].iter().map(|&x| x != 0).collect(),
            period_done: v[2 * k] != 0,
            ready: v[2 * k + 1] != 0,
            running: v[2 * k + 2] != 0,
            underrun: v[2 * k + 3] != 0,
            overrange: v[2 * k + 4] != 0,
            load_error: v[2 * k + 5] != 0,
        }
    }
}

/// A command for one period of one axis: d = q * P + r, 0 <= r < P.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct AxisCommand {
    q: i64,
    r: u64,
}

#[derive(Clone, Debug)]
struct AxisModel {
    staged_delta: i32,
    pending: AxisCommand,
    active: AxisCommand,
    q_stage: [i64; 2],
    tick_stage: [bool; 3],
    /// The last position update, fraction + q (+1): in [-2^16, 2^17).
    fraction: i64,
    step: bool,
    dir: bool,
    dda: DdaIntegratorModel,
}

impl AxisModel {
    fn new() -> Self {
        Self {
            staged_delta: 0,
            pending: AxisCommand::default(),
            active: AxisCommand::default(),
            q_stage: [0; 2],
            tick_stage: [false; 3],
            fraction: 0,
            step: false,
            dir: false,
            dda: DdaIntegratorModel::new(super::PERIOD_BITS as u32),
        }
    }

    fn magnitude(&self) -> u64 {
        self.staged_delta.unsigned_abs() as u64
    }

    /// The pending command for the staged delta from |d| = q'P + r';
    /// returns whether it was clamped to one step per tick.
    fn command_from(
        &self,
        quotient: u64,
        remainder: u64,
        period: u64,
        clamped: bool,
    ) -> AxisCommand {
        let one_step = 1u64 << 16;
        let negative = self.staged_delta < 0;
        if clamped {
            AxisCommand {
                q: if negative {
                    -(one_step as i64)
                } else {
                    one_step as i64
                },
                r: 0,
            }
        } else if !negative {
            AxisCommand {
                q: quotient as i64,
                r: remainder,
            }
        } else if remainder == 0 {
            AxisCommand {
                q: -(quotient as i64),
                r: 0,
            }
        } else {
            AxisCommand {
                q: -(quotient as i64) - 1,
                r: period - remainder,
            }
        }
    }

    /// One edge of the tick pipeline: the DDA, then the position fraction.
    fn clock_ticks(&mut self, tick: bool, active_period: u64) {
        let extra = self.dda.outputs().pulse;
        self.step = false;
        if self.tick_stage[2] && self.fraction >= 1 << 16 {
            self.step = true;
            self.dir = true;
        } else if self.tick_stage[2] && self.fraction < 0 {
            self.step = true;
            self.dir = false;
        }
        if self.tick_stage[1] {
            self.fraction = self.fraction.rem_euclid(1 << 16) + self.q_stage[1] + extra as i64;
        }
        self.dda.step(DdaIntegratorInputs {
            reset: false,
            tick,
            integrand: self.active.r,
            modulus: active_period,
            clear_overrange: false,
        });
        self.tick_stage = [tick, self.tick_stage[0], self.tick_stage[1]];
        self.q_stage = [self.active.q, self.q_stage[0]];
    }
}

/// Plain-Rust, cycle-exact model of a K-axis interpolator.
#[derive(Clone, Debug)]
pub struct InterpolatorModel {
    axes: Vec<AxisModel>,
    divider: SequentialDividerModel,
    staged_period: u64,
    pending_period: u64,
    active_period: u64,
    ticks_done: u64,
    running: bool,
    pending_valid: bool,
    computing: bool,
    division_issued: bool,
    axis_index: usize,
    period_done: bool,
    underrun: bool,
    overrange: bool,
    load_error: bool,
    /// The divider's result, one clock after its `done`, with the clamp test.
    result: Option<(u64, u64, bool)>,
}

impl InterpolatorModel {
    /// A `k`-axis interpolator in its power-up state.
    pub fn new(k: usize) -> Self {
        Self {
            axes: (0..k).map(|_| AxisModel::new()).collect(),
            divider: SequentialDividerModel::new(32, super::PERIOD_BITS as u32),
            staged_period: 0,
            pending_period: 0,
            active_period: 0,
            ticks_done: 0,
            running: false,
            pending_valid: false,
            computing: false,
            division_issued: false,
            axis_index: 0,
            period_done: false,
            underrun: false,
            overrange: false,
            load_error: false,
            result: None,
        }
    }

    /// The outputs after the last edge.
    pub fn outputs(&self) -> InterpolatorOutputs {
        InterpolatorOutputs {
            step: self.axes.iter().map(|a| a.step).collect(),
            dir: self.axes.iter().map(|a| a.dir).collect(),
            period_done: self.period_done,
            ready: !self.computing && !self.pending_valid,
            running: self.running,
            underrun: self.underrun,
            overrange: self.overrange,
            load_error: self.load_error,
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, inputs: &InterpolatorInputs) -> InterpolatorOutputs {
        if inputs.reset {
            *self = Self::new(self.axes.len());
            // The divider and the DDAs are reset with the block.
            return self.outputs();
        }
        let slot_free = !self.computing && !self.pending_valid;
        let used_tick = inputs.tick && self.running;
        let last_tick = used_tick && self.ticks_done + 1 == self.active_period;
        let commit = self.pending_valid && (last_tick || !self.running);
        let next_period = inputs.next_period;
        let accept =
            inputs.load && slot_free && next_period != 0 && next_period >> super::PERIOD_BITS == 0;
        let divider_out = self.divider.outputs();
        let start = self.computing && !self.division_issued;

        // Axes: tick pipelines (with the active command of this cycle), then
        // result writes, staging and commits.
        for axis in &mut self.axes {
            axis.clock_ticks(used_tick, self.active_period);
        }
        // `active` takes the pending command as it was before this edge.
        for (axis, delta) in self.axes.iter_mut().zip(&inputs.next_delta) {
            if commit {
                axis.active = axis.pending;
            }
            if accept {
                axis.staged_delta = *delta;
            }
        }
        let result = self.result.take();
        if let Some((quotient, remainder, clamped)) = result {
            let index = self.axis_index;
            self.axes[index].pending =
                self.axes[index].command_from(quotient, remainder, self.staged_period, clamped);
            self.overrange |= clamped;
        }
        if divider_out.done {
            let one_step = 1u64 << 16;
            let (q, r) = (divider_out.quotient, divider_out.remainder);
            self.result = Some((q, r, q > one_step || (q == one_step && r != 0)));
        }
        let dividend = self.axes[self.axis_index.min(self.axes.len() - 1)].magnitude();
        self.divider.step(SequentialDividerInputs {
            reset: false,
            start,
            dividend,
            divisor: self.staged_period,
        });

        // Sequencer and period timing, in the RTL's statement order.
        self.period_done = last_tick;
        if used_tick {
            self.ticks_done += 1;
        }
        if last_tick {
            self.ticks_done = 0;
            self.running = false;
            if !self.pending_valid {
                self.underrun = true;
            }
        }
        if commit {
            self.active_period = self.pending_period;
            self.ticks_done = 0;
            self.running = true;
            self.pending_valid = false;
        }
        if inputs.load && !accept {
            self.load_error = true;
        }
        if accept {
            self.staged_period = next_period as u64;
            self.computing = true;
            self.division_issued = false;
            self.axis_index = 0;
        }
        if start {
            self.division_issued = true;
        }
        if result.is_some() {
            self.division_issued = false;
            self.axis_index += 1;
            if self.axis_index == self.axes.len() {
                self.computing = false;
                self.pending_valid = true;
                self.pending_period = self.staged_period;
            }
        }
        if inputs.clear_status {
            self.underrun = false;
            self.overrange = false;
            self.load_error = false;
        }
        self.outputs()
    }
}

crate::lockstep_model!(InterpolatorModel {
    inputs: InterpolatorInputs,
    outputs: InterpolatorOutputs,
    step: |model, inputs| model.step(inputs),
});
