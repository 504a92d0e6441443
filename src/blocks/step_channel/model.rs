//! Reference model of [`super::StepChannel`]: the two blocks' models wired
//! as the RTL wires them.

use crate::blocks::dda_integrator::model::{DdaIntegratorInputs, DdaIntegratorModel};
use crate::blocks::step_output::model::{StepOutputInputs, StepOutputModel};

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepChannelInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// DDA accumulate enable.
    pub tick: bool,
    /// J.
    pub integrand: u64,
    /// M; 0 means 2^W.
    pub modulus: u64,
    /// Direction of this tick's step: true = forward.
    pub dir: bool,
    /// Clears `overrange`.
    pub clear_overrange: bool,
    /// 0 step/dir, 1 up/down, 2 quadrature, 3 reserved.
    pub mode: u8,
    /// Pulse high time.
    pub step_len: u64,
    /// Minimum low time.
    pub step_space: u64,
    /// Direction setup time.
    pub dir_setup: u64,
    /// Direction hold time.
    pub dir_hold: u64,
}

impl StepChannelInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.tick as u64,
            self.integrand,
            self.modulus,
            self.dir as u64,
            self.clear_overrange as u64,
            self.mode as u64,
            self.step_len,
            self.step_space,
            self.dir_setup,
            self.dir_hold,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepChannelOutputs {
    /// Step / up / A.
    pub out_a: bool,
    /// Dir / down / B.
    pub out_b: bool,
    /// Sticky overrun.
    pub overrun: bool,
    /// Sticky overrange.
    pub overrange: bool,
    /// Mode 3 selected.
    pub mode_invalid: bool,
    /// Steps pending or a pulse in progress.
    pub busy: bool,
}

impl StepChannelOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            out_a: v[0] != 0,
            out_b: v[1] != 0,
            overrun: v[2] != 0,
            overrange: v[3] != 0,
            mode_invalid: v[4] != 0,
            busy: v[5] != 0,
        }
    }
}

/// Cycle-exact model of a step channel with a `dda_bits` DDA and
/// `timer_bits` timers.
#[derive(Clone, Debug)]
pub struct StepChannelModel {
    dda: DdaIntegratorModel,
    output: StepOutputModel,
    /// `dir` delayed by the DDA latency, oldest last.
    dir_delay: [bool; super::DDA_LATENCY],
}

impl StepChannelModel {
    /// A channel in its power-up state.
    pub fn new(dda_bits: u32, timer_bits: u32) -> Self {
        Self {
            dda: DdaIntegratorModel::new(dda_bits),
            output: StepOutputModel::new(timer_bits, 16),
            dir_delay: [false; super::DDA_LATENCY],
        }
    }

    /// Steps requested by the DDA but not yet emitted (signed).
    pub fn pending(&self) -> i64 {
        self.output.pending()
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: StepChannelInputs) -> StepChannelOutputs {
        // The output stage samples the DDA's registered pulse and the
        // delayed direction as they were before this edge.
        let request = self.dda.outputs().pulse;
        let request_dir = self.dir_delay[super::DDA_LATENCY - 1];
        let dda = self.dda.step(DdaIntegratorInputs {
            reset: i.reset,
            tick: i.tick,
            integrand: i.integrand,
            modulus: i.modulus,
            clear_overrange: i.clear_overrange,
        });
        let out = self.output.step(StepOutputInputs {
            reset: i.reset,
            step: request,
            dir: request_dir,
            mode: i.mode,
            step_len: i.step_len,
            step_space: i.step_space,
            dir_setup: i.dir_setup,
            dir_hold: i.dir_hold,
            clear_overrun: false,
            flush: false,
        });
        self.dir_delay.rotate_right(1);
        self.dir_delay[0] = i.dir && !i.reset;
        if i.reset {
            self.dir_delay = [false; super::DDA_LATENCY];
        }
        StepChannelOutputs {
            out_a: out.out_a,
            out_b: out.out_b,
            overrun: out.overrun,
            overrange: dda.overrange,
            mode_invalid: out.mode_invalid,
            busy: out.busy,
        }
    }
}

crate::lockstep_model!(StepChannelModel {
    inputs: StepChannelInputs,
    outputs: StepChannelOutputs,
    step: |model, inputs| model.step(*inputs),
});
