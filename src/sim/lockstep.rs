//! RTL against its plain-Rust reference model, clock by clock.
//!
//! A [`Lockstep`] holds the RTL (any [`Stepper`]: rust-hdl's [`Harness`] or
//! the compiled Verilator model) and a [`LockstepModel`]. Every clock it
//! packs the model's inputs into the block's input vector, clocks both, and
//! compares the RTL's outputs with the model's; the first disagreement is a
//! [`LockstepError::Mismatch`] naming the cycle, the inputs and both
//! outputs. [`Lockstep::run`] is the whole loop, with a stimulus closure and
//! an observer closure (for a test's coverage counters); [`Lockstep::step`]
//! is one clock, for benches that drive the pair from their own code.
//!
//! [`Harness`]: super::Harness

use std::fmt::Debug;
use std::path::Path;

use super::{stepper, Backend, SimError, Stepper, VectorPorts};

/// When in the clock the outputs are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sample {
    /// After the rising edge, the clock's inputs still applied (what
    /// [`Stepper::step_into`] returns): every registered output, and the
    /// combinational ones of the inputs just applied.
    AfterEdge,
    /// During the clock, before its edge (what [`Stepper::peek_into`]
    /// returns): for blocks with outputs that depend combinationally on
    /// the inputs, whose model gives them before the edge. Needs a backend
    /// that can settle half a cycle (rust-hdl's).
    BeforeEdge,
}

/// A cycle-exact reference model that runs beside its block's RTL.
///
/// The inputs and outputs are the model's own types; they own their port
/// vectors (`to_vector` on the inputs and `from_vector` on the outputs, in
/// the block's [`VectorPorts`] order, next to the types in the block's
/// `model.rs`). The impl only wires them up; [`crate::lockstep_model!`]
/// writes it for a model whose outputs need nothing but the vector.
pub trait LockstepModel {
    /// One clock's inputs.
    type Inputs: Debug;
    /// The outputs compared.
    type Outputs: Debug + PartialEq;
    /// When the outputs of [`LockstepModel::expected`] hold.
    const SAMPLE: Sample = Sample::AfterEdge;

    /// Writes `inputs` as the block's input vector into `vector` (which
    /// holds the last clock's vector).
    fn input_vector(inputs: &Self::Inputs, vector: &mut Vec<u64>);
    /// The outputs the RTL's output vector encodes (the model knows the
    /// shape the vector alone does not tell, such as the number of axes).
    fn read_outputs(&self, vector: &[u64]) -> Self::Outputs;
    /// Runs one clock with `inputs` and returns the outputs the RTL must
    /// show at [`LockstepModel::SAMPLE`].
    fn expected(&mut self, inputs: &Self::Inputs) -> Self::Outputs;
    /// Whether the RTL's outputs agree with the model's; equality unless a
    /// block leaves an output unspecified in some state.
    fn agrees(rtl: &Self::Outputs, model: &Self::Outputs) -> bool {
        rtl == model
    }
}

/// Implements [`LockstepModel`] for a model whose inputs have
/// `to_vector(&self) -> Vec<u64>` and whose outputs have
/// `from_vector(&[u64]) -> Self`, with `step` mapping the model and a
/// reference to the inputs to the expected outputs.
///
/// ```ignore
/// lockstep_model!(PulseCounterModel {
///     inputs: PulseCounterInputs,
///     outputs: PulseCounterOutputs,
///     step: |model, inputs| model.step(*inputs),
/// });
/// ```
#[macro_export]
macro_rules! lockstep_model {
    ($model:ty { inputs: $inputs:ty, outputs: $outputs:ty, step: |$m:ident, $i:ident| $step:expr $(,)? }) => {
        impl $crate::sim::LockstepModel for $model {
            type Inputs = $inputs;
            type Outputs = $outputs;
            fn input_vector(inputs: &$inputs, vector: &mut Vec<u64>) {
                *vector = inputs.to_vector();
            }
            fn read_outputs(&self, vector: &[u64]) -> $outputs {
                <$outputs>::from_vector(vector)
            }
            fn expected(&mut self, inputs: &$inputs) -> $outputs {
                let ($m, $i) = (self, inputs);
                $step
            }
        }
    };
}

/// Why a lockstep run stopped.
#[derive(Debug, thiserror::Error)]
pub enum LockstepError {
    /// The simulator failed.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The RTL and the model disagree.
    #[error(
        "{backend} RTL and model differ in cycle {cycle} ({sample:?})\ninputs {inputs}\nRTL    {rtl}\nmodel  {model}"
    )]
    Mismatch {
        /// The RTL's simulator.
        backend: &'static str,
        /// Clocks run before this one (0 for the first).
        cycle: u64,
        /// When the outputs were compared.
        sample: Sample,
        /// This clock's inputs (`{:?}`).
        inputs: String,
        /// The RTL's outputs (`{:?}`).
        rtl: String,
        /// The model's outputs (`{:?}`).
        model: String,
    },
}

/// A block's RTL and its model, clocked together and compared every clock.
pub struct Lockstep<M: LockstepModel> {
    rtl: Box<dyn Stepper>,
    model: M,
    cycle: u64,
    inputs: Vec<u64>,
    outputs: Vec<u64>,
    scratch: Vec<u64>,
}

impl<M: LockstepModel> Lockstep<M> {
    /// `rtl` (in its power-up state) against `model` (in the same state).
    pub fn new(rtl: Box<dyn Stepper>, model: M) -> Self {
        let outputs = vec![0; rtl.output_count()];
        Self {
            scratch: outputs.clone(),
            outputs,
            rtl,
            model,
            cycle: 0,
            inputs: Vec::new(),
        }
    }

    /// `block` on `backend` (see [`stepper`]) against `model`.
    pub fn on<B: VectorPorts + 'static>(
        backend: Backend,
        module: &str,
        block: B,
        model: M,
    ) -> Result<Self, SimError> {
        Self::recorded(backend, module, block, model, None)
    }

    /// [`Lockstep::on`], the RTL's signals written to `vcd` from the first clock.
    pub fn recorded<B: VectorPorts + 'static>(
        backend: Backend,
        module: &str,
        block: B,
        model: M,
        vcd: Option<&Path>,
    ) -> Result<Self, SimError> {
        Ok(Self::new(stepper(backend, module, block, vcd)?, model))
    }

    /// `block` in rust-hdl's [`super::Harness`] against `model`; panics if
    /// the block fails rust-hdl's checks (a test's setup).
    pub fn harness<B: VectorPorts + 'static>(module: &str, block: B, model: M) -> Self {
        Self::on(Backend::RustHdl, module, block, model).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The model, as it is after the last clock.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The model, to change what the comparison does not see.
    pub fn model_mut(&mut self) -> &mut M {
        &mut self.model
    }

    /// The RTL's simulator.
    pub fn rtl(&mut self) -> &mut dyn Stepper {
        self.rtl.as_mut()
    }

    /// Clocks compared so far.
    pub fn cycles(&self) -> u64 {
        self.cycle
    }

    /// The input vector of the last clock.
    pub fn input_vector(&self) -> &[u64] {
        &self.inputs
    }

    /// One clock: applies `inputs` to the RTL, runs the model, and returns
    /// the RTL's outputs if the two agree. Outputs are compared at the
    /// model's [`LockstepModel::SAMPLE`]: after the rising edge, or before
    /// it (and the edge then runs).
    pub fn step(&mut self, inputs: &M::Inputs) -> Result<M::Outputs, LockstepError> {
        M::input_vector(inputs, &mut self.inputs);
        match M::SAMPLE {
            Sample::AfterEdge => self.rtl.step_into(&self.inputs, &mut self.outputs)?,
            Sample::BeforeEdge => self.rtl.peek_into(&self.inputs, &mut self.outputs)?,
        }
        let rtl = self.model.read_outputs(&self.outputs);
        let model = self.model.expected(inputs);
        if !M::agrees(&rtl, &model) {
            return Err(LockstepError::Mismatch {
                backend: self.rtl.backend().name(),
                cycle: self.cycle,
                sample: M::SAMPLE,
                inputs: format!("{inputs:?}"),
                rtl: format!("{rtl:?}"),
                model: format!("{model:?}"),
            });
        }
        if M::SAMPLE == Sample::BeforeEdge {
            self.rtl.step_into(&self.inputs, &mut self.scratch)?;
        }
        self.cycle += 1;
        Ok(rtl)
    }

    /// Clocks the pair until `stimulus` returns `None`. `stimulus` gets the
    /// cycle number and the model before the clock (a closed-loop stimulus
    /// reads its outputs); `observe` gets the cycle number, the inputs and
    /// the RTL's outputs after each clock that agreed. Returns the clocks run.
    pub fn run(
        &mut self,
        mut stimulus: impl FnMut(u64, &M) -> Option<M::Inputs>,
        mut observe: impl FnMut(u64, &M::Inputs, &M::Outputs),
    ) -> Result<u64, LockstepError> {
        let start = self.cycle;
        while let Some(inputs) = stimulus(self.cycle, &self.model) {
            let outputs = self.step(&inputs)?;
            observe(self.cycle - 1, &inputs, &outputs);
        }
        Ok(self.cycle - start)
    }

    /// [`Lockstep::run`] over a list of inputs.
    pub fn run_all<'a>(
        &mut self,
        inputs: impl IntoIterator<Item = &'a M::Inputs>,
        mut observe: impl FnMut(u64, &M::Inputs, &M::Outputs),
    ) -> Result<u64, LockstepError>
    where
        M::Inputs: 'a,
    {
        let start = self.cycle;
        for i in inputs {
            let outputs = self.step(i)?;
            observe(self.cycle - 1, i, &outputs);
        }
        Ok(self.cycle - start)
    }
}
