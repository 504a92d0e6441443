//! One stepping interface over two simulators of the same RTL: rust-hdl's
//! own (through [`Harness`]) and the exported Verilog compiled by Verilator
//! (through [`CompiledModel`]), chosen at run time.

use std::any::TypeId;
use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

use super::compiled::{CompiledError, CompiledModel};
use super::{Harness, HarnessError, VectorPorts};
use crate::export::{module_verilog, top_ports, Port};

/// The environment variable that picks the backend of tests and tools that
/// do not pick one themselves: `rust-hdl` or `verilator`.
pub const BACKEND_VARIABLE: &str = "MOTION_HDL_BACKEND";

/// Which simulator steps the RTL.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// rust-hdl's event-free stepping of the Rust block ([`Harness`]): no
    /// tools needed, every internal signal visible, slow on big designs.
    RustHdl,
    /// The block's Verilog compiled by Verilator ([`CompiledModel`]): more
    /// than ten times faster on the controller (`cargo bench --bench
    /// simulation_speed`); needs Verilator and g++.
    Verilator,
}

impl Backend {
    /// Both backends.
    pub const ALL: [Backend; 2] = [Backend::RustHdl, Backend::Verilator];

    /// The backend's name on the command line and in [`BACKEND_VARIABLE`].
    pub fn name(self) -> &'static str {
        match self {
            Backend::RustHdl => "rust-hdl",
            Backend::Verilator => "verilator",
        }
    }

    /// Parses a backend name.
    pub fn parse(name: &str) -> Result<Self, SimError> {
        Self::ALL
            .into_iter()
            .find(|b| b.name() == name)
            .ok_or_else(|| SimError::UnknownBackend(name.to_string()))
    }

    /// The backend named by [`BACKEND_VARIABLE`], else `default`.
    pub fn from_env_or(default: Backend) -> Result<Self, SimError> {
        match std::env::var(BACKEND_VARIABLE) {
            Ok(name) => Self::parse(&name),
            Err(_) => Ok(default),
        }
    }

    /// Whether the tools this backend needs are installed.
    pub fn available(self) -> bool {
        match self {
            Backend::RustHdl => true,
            Backend::Verilator => ["verilator", "g++"]
                .iter()
                .all(|tool| super::compiled::tool_version(tool, &["--version"]).is_ok()),
        }
    }
}

/// Why a stepper could not be made or stepped.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// The rust-hdl harness failed.
    #[error(transparent)]
    Harness(#[from] HarnessError),
    /// The compiled model failed.
    #[error(transparent)]
    Compiled(#[from] CompiledError),
    /// A backend name that is not `rust-hdl` or `verilator`.
    #[error("unknown simulation backend `{0}` (use rust-hdl or verilator)")]
    UnknownBackend(String),
    /// The backend runs whole clock cycles only.
    #[error("the {} backend cannot show the outputs before a clock edge", .0.name())]
    NoPeek(Backend),
}

/// A clocked block driven by port vectors, whichever simulator runs it.
///
/// Vectors hold one value per port, in [`VectorPorts::input_names`] and
/// [`VectorPorts::output_names`] order; a port wider than 64 bits takes
/// `ceil(width / 64)` columns, least significant word first
/// ([`VectorPorts::input_words`]).
pub trait Stepper {
    /// Applies `inputs`, runs one clock cycle and writes the outputs after
    /// its rising edge into `outputs`.
    fn step_into(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), SimError>;
    /// Clock cycles run so far.
    fn cycles(&self) -> u64;
    /// Which simulator this is.
    fn backend(&self) -> Backend;

    /// [`Stepper::step_into`], returning a new output vector.
    fn step_vector(&mut self, inputs: &[u64]) -> Result<Vec<u64>, SimError> {
        let mut outputs = vec![0; self.output_count()];
        self.step_into(inputs, &mut outputs)?;
        Ok(outputs)
    }
    /// Output ports per vector.
    fn output_count(&self) -> usize;
    /// Applies `inputs` and writes the outputs before the next clock edge
    /// (the combinational outputs of these inputs and the present state)
    /// into `outputs`, without clocking; [`Stepper::step_into`] with the
    /// same inputs then runs the clock. Only rust-hdl's harness can.
    fn peek_into(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), SimError> {
        let _ = (inputs, outputs);
        Err(SimError::NoPeek(self.backend()))
    }
}

impl<B: VectorPorts> Stepper for Harness<B> {
    fn step_into(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), SimError> {
        outputs.copy_from_slice(&self.step_vector(inputs)?);
        Ok(())
    }
    fn cycles(&self) -> u64 {
        Harness::cycles(self)
    }
    fn backend(&self) -> Backend {
        Backend::RustHdl
    }
    fn output_count(&self) -> usize {
        B::output_words().iter().sum()
    }
    fn peek_into(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), SimError> {
        outputs.copy_from_slice(&self.peek_vector(inputs)?);
        Ok(())
    }
}

/// A [`CompiledModel`] with its ports in a block's [`VectorPorts`] order.
pub struct CompiledStepper {
    model: CompiledModel,
    /// Port index in the model and vector columns, per input.
    inputs: Vec<(usize, usize)>,
    /// The same per output.
    outputs: Vec<(usize, usize)>,
}

impl CompiledStepper {
    /// The Verilog of `block`, compiled; ports ordered as `B`'s vectors.
    /// `trace` builds in VCD support.
    ///
    /// The Verilog is generated once per process for each block type and
    /// `module` name, from the first block given: a block's Verilog is
    /// fixed by its type (every block of this crate is built by `Default`
    /// from its const parameters). Generating the controller's takes about
    /// half a second, and a test may make dozens of benches of it.
    pub fn new<B: VectorPorts + 'static>(
        module: &str,
        mut block: B,
        trace: bool,
    ) -> Result<Self, SimError> {
        type Generated = Arc<(String, Vec<Port>)>;
        // One slot per block type and module, locked while its Verilog is
        // generated: a second thread asking for the same block waits for
        // it instead of generating it again, and other blocks go on.
        type Slot = Arc<Mutex<Option<Generated>>>;
        static GENERATED: OnceLock<Mutex<HashMap<(TypeId, String), Slot>>> = OnceLock::new();
        let key = (TypeId::of::<B>(), module.to_string());
        let slot = {
            let cache = GENERATED.get_or_init(Default::default);
            let mut slots = cache
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            slots.entry(key).or_default().clone()
        };
        let mut entry = slot.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let generated = match entry.as_ref() {
            Some(generated) => generated.clone(),
            None => {
                let verilog = module_verilog(module, &mut block).map_err(CompiledError::from)?;
                let generated: Generated = Arc::new((verilog, top_ports(&block)));
                *entry = Some(generated.clone());
                generated
            }
        };
        drop(entry);
        let (verilog, ports) = &*generated;
        let model = CompiledModel::from_verilog(module, verilog, "clock", ports, trace)?;
        Self::ordered::<B>(model)
    }

    /// A compiled model whose ports are `B`'s, in `B`'s vector order.
    pub fn ordered<B: VectorPorts>(model: CompiledModel) -> Result<Self, SimError> {
        let inputs = B::input_names()
            .iter()
            .zip(B::input_words())
            .map(|(n, words)| Ok((model.input_index(n)?, words)))
            .collect::<Result<Vec<_>, CompiledError>>()?;
        let outputs = B::output_names()
            .iter()
            .zip(B::output_words())
            .map(|(n, words)| Ok((model.output_index(n)?, words)))
            .collect::<Result<Vec<_>, CompiledError>>()?;
        Ok(Self {
            model,
            inputs,
            outputs,
        })
    }

    /// The model, for wide ports and the VCD.
    pub fn model(&mut self) -> &mut CompiledModel {
        &mut self.model
    }
}

impl Stepper for CompiledStepper {
    fn step_into(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), SimError> {
        let mut column = 0;
        for &(port, words) in &self.inputs {
            if words == 1 {
                self.model.set(port, inputs[column]);
            } else {
                self.model.set_words(port, &inputs[column..column + words]);
            }
            column += words;
        }
        self.model.cycle();
        let mut column = 0;
        for &(port, words) in &self.outputs {
            if words == 1 {
                outputs[column] = self.model.get(port);
            } else {
                outputs[column..column + words].copy_from_slice(self.model.get_words(port));
            }
            column += words;
        }
        Ok(())
    }
    fn cycles(&self) -> u64 {
        self.model.cycles()
    }
    fn backend(&self) -> Backend {
        Backend::Verilator
    }
    fn output_count(&self) -> usize {
        self.outputs.iter().map(|&(_, words)| words).sum()
    }
}

/// `block` on `backend`, as a [`Stepper`] in its power-up state; with
/// `vcd`, every signal is written to that file from the first clock on.
pub fn stepper<B: VectorPorts + 'static>(
    backend: Backend,
    module: &str,
    block: B,
    vcd: Option<&Path>,
) -> Result<Box<dyn Stepper>, SimError> {
    match backend {
        Backend::RustHdl => {
            let mut harness = Harness::new(module, block)?;
            if let Some(path) = vcd {
                harness.record_vcd(path)?;
            }
            Ok(Box::new(harness))
        }
        Backend::Verilator => {
            let mut compiled = CompiledStepper::new(module, block, vcd.is_some())?;
            if let Some(path) = vcd {
                compiled.model().record_vcd(path)?;
            }
            Ok(Box::new(compiled))
        }
    }
}
