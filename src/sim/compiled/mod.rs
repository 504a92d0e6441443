//! The compiled simulation backend: a Verilog module built by Verilator into
//! a shared library, loaded with `libloading` and stepped clock by clock
//! from Rust, with the same cycle as [`crate::sim::Harness`].
//!
//! One call crosses into C++ per clock: every input goes in and every output
//! comes back as 64-bit words (a port wider than 64 bits takes several, least
//! significant first). Builds are cached by a hash of the Verilog, the
//! generated glue, the tool versions and the flags (see [`cache_root`]), so
//! only the first run of a design pays for the C++ compile.

mod build;

use std::ffi::{c_void, CString};
use std::path::Path;

use rust_hdl::core::prelude::Block;

use crate::export::{module_verilog, top_ports, Port, PortDirection};

pub(crate) use build::tool_version;
#[doc(hidden)]
pub use build::Design;
pub use build::{cache_root, INSTALL_LINE};

/// Why a compiled model could not be built, loaded or used.
#[derive(Debug, thiserror::Error)]
pub enum CompiledError {
    /// Verilator or the C++ compiler is not installed.
    #[error("the compiled simulation backend needs `{tool}`, which is not installed; install Verilator 5 and a C++ compiler with: {INSTALL_LINE}")]
    Missing {
        /// The missing program.
        tool: String,
    },
    /// Verilator or g++ failed, or a file could not be written.
    #[error("building the compiled model failed: {0}")]
    Build(String),
    /// The library could not be loaded or lacks a symbol.
    #[error("loading the compiled model `{path}`: {detail}")]
    Load {
        /// The shared library.
        path: String,
        /// What went wrong.
        detail: String,
    },
    /// The design's ports are not what the caller asked for.
    #[error("compiled model of `{module}`: {detail}")]
    Ports {
        /// The module.
        module: String,
        /// What does not match.
        detail: String,
    },
    /// rust-hdl could not write the block's Verilog.
    #[error(transparent)]
    Verilog(#[from] crate::export::VerilogError),
    /// The VCD could not be opened.
    #[error("cannot open the VCD file `{0}`")]
    Trace(String),
}

/// One port's place in the word arrays passed to the library.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Slot {
    /// The port's name in the design.
    pub name: String,
    /// Width in bits.
    pub width: usize,
    /// Index of its first 64-bit word.
    pub offset: usize,
}

impl Slot {
    /// 64-bit words the port takes.
    pub fn words(&self) -> usize {
        self.width.div_ceil(64)
    }
}

type NewFn = unsafe extern "C" fn() -> *mut c_void;
type FreeFn = unsafe extern "C" fn(*mut c_void);
type CycleFn = unsafe extern "C" fn(*mut c_void, *const u64, *mut u64);
type TraceFn = unsafe extern "C" fn(*mut c_void, *const std::os::raw::c_char) -> i32;

/// A Verilated design, loaded and in its power-up state.
///
/// Not `Send`: a Verilator model may be used by one thread at a time, and
/// keeping it on the thread that made it is the simple way to ensure that.
pub struct CompiledModel {
    handle: *mut c_void,
    cycle_fn: CycleFn,
    free_fn: FreeFn,
    trace_fn: TraceFn,
    inputs: Vec<Slot>,
    outputs: Vec<Slot>,
    input_words: Vec<u64>,
    output_words: Vec<u64>,
    cycles: u64,
    module: String,
    // Declared last: dropped after the handle is freed.
    _library: libloading::Library,
}

impl CompiledModel {
    /// Builds (or takes from the cache) and loads `verilog`, whose top module
    /// is `module` with clock input `clock` and the given other ports.
    /// `trace` builds in VCD support (a slower model).
    pub fn from_verilog(
        module: &str,
        verilog: &str,
        clock: &str,
        ports: &[Port],
        trace: bool,
    ) -> Result<Self, CompiledError> {
        let inputs = slots(ports, PortDirection::Input, clock);
        let outputs = slots(ports, PortDirection::Output, clock);
        if ports.iter().any(|p| p.direction == PortDirection::InOut) {
            return Err(CompiledError::Ports {
                module: module.into(),
                detail: "inout ports are not supported".into(),
            });
        }
        let layout = build::Layout {
            module,
            clock,
            inputs: &inputs,
            outputs: &outputs,
        };
        let path = build::library(verilog, &layout, trace)?;
        Self::load(module, &path, inputs, outputs)
    }

    /// The Verilog of `block` as generated now (top module `module`).
    pub fn from_block(
        module: &str,
        block: &mut dyn Block,
        trace: bool,
    ) -> Result<Self, CompiledError> {
        let verilog = module_verilog(module, block)?;
        let ports = top_ports(block);
        Self::from_verilog(module, &verilog, "clock", &ports, trace)
    }

    fn load(
        module: &str,
        path: &Path,
        inputs: Vec<Slot>,
        outputs: Vec<Slot>,
    ) -> Result<Self, CompiledError> {
        let load_error = |detail: String| CompiledError::Load {
            path: path.display().to_string(),
            detail,
        };
        // SAFETY: the library is one this module generated and built; its
        // initializers are Verilator's and ours, and the symbols below have
        // exactly the generated signatures.
        unsafe {
            let library = libloading::Library::new(path).map_err(|e| load_error(e.to_string()))?;
            let version: libloading::Symbol<unsafe extern "C" fn() -> u32> = library
                .get(b"mh_abi_version")
                .map_err(|e| load_error(e.to_string()))?;
            if version() != build::SHIM_VERSION {
                return Err(load_error(format!(
                    "glue version {} is not {}",
                    version(),
                    build::SHIM_VERSION
                )));
            }
            let new: NewFn = *library
                .get(b"mh_new")
                .map_err(|e| load_error(e.to_string()))?;
            let cycle_fn: CycleFn = *library
                .get(b"mh_cycle")
                .map_err(|e| load_error(e.to_string()))?;
            let free_fn: FreeFn = *library
                .get(b"mh_free")
                .map_err(|e| load_error(e.to_string()))?;
            let trace_fn: TraceFn = *library
                .get(b"mh_trace")
                .map_err(|e| load_error(e.to_string()))?;
            let handle = new();
            let input_words = vec![0; inputs.iter().map(Slot::words).sum()];
            let output_words = vec![0; outputs.iter().map(Slot::words).sum()];
            Ok(Self {
                handle,
                cycle_fn,
                free_fn,
                trace_fn,
                inputs,
                outputs,
                input_words,
                output_words,
                cycles: 0,
                module: module.to_string(),
                _library: library,
            })
        }
    }

    /// The input ports (without the clock), in design order.
    pub fn inputs(&self) -> &[Slot] {
        &self.inputs
    }

    /// The output ports, in design order.
    pub fn outputs(&self) -> &[Slot] {
        &self.outputs
    }

    /// Index of the input port `name`.
    pub fn input_index(&self, name: &str) -> Result<usize, CompiledError> {
        self.inputs
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| self.no_port(name))
    }

    /// Index of the output port `name`.
    pub fn output_index(&self, name: &str) -> Result<usize, CompiledError> {
        self.outputs
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| self.no_port(name))
    }

    fn no_port(&self, name: &str) -> CompiledError {
        CompiledError::Ports {
            module: self.module.clone(),
            detail: format!("no port `{name}`"),
        }
    }

    /// Sets input `index` (up to 64 bits) for the next cycle; bits above
    /// its width are dropped.
    pub fn set(&mut self, index: usize, value: u64) {
        let slot = &self.inputs[index];
        self.input_words[slot.offset] = value;
    }

    /// Sets a wide input from its words, least significant first.
    pub fn set_words(&mut self, index: usize, words: &[u64]) {
        let slot = &self.inputs[index];
        let n = slot.words().min(words.len());
        let target = &mut self.input_words[slot.offset..slot.offset + slot.words()];
        target.fill(0);
        target[..n].copy_from_slice(&words[..n]);
    }

    /// Output `index` after the last cycle (its low 64 bits).
    pub fn get(&self, index: usize) -> u64 {
        self.output_words[self.outputs[index].offset]
    }

    /// A wide output's words, least significant first.
    pub fn get_words(&self, index: usize) -> &[u64] {
        let slot = &self.outputs[index];
        &self.output_words[slot.offset..slot.offset + slot.words()]
    }

    /// One clock cycle with the inputs set: they settle with the clock low,
    /// then the rising edge. Outputs then show the state after the edge with
    /// the inputs still applied.
    pub fn cycle(&mut self) {
        // SAFETY: the handle is live until drop, and the word arrays have
        // the lengths the generated glue reads and writes.
        unsafe {
            (self.cycle_fn)(
                self.handle,
                self.input_words.as_ptr(),
                self.output_words.as_mut_ptr(),
            )
        };
        self.cycles += 1;
    }

    /// Clock cycles run so far.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    /// Writes every signal to a VCD file from now on (Verilator's own
    /// tracer; the model must have been built with `trace`).
    pub fn record_vcd(&mut self, path: &Path) -> Result<(), CompiledError> {
        let text = path.display().to_string();
        let c_path = CString::new(text.clone()).map_err(|_| CompiledError::Trace(text.clone()))?;
        // SAFETY: live handle, NUL-terminated path.
        match unsafe { (self.trace_fn)(self.handle, c_path.as_ptr()) } {
            0 => Ok(()),
            2 => Err(CompiledError::Trace(format!(
                "{text} (the model was built without tracing)"
            ))),
            3 => Err(CompiledError::Trace(format!(
                "{text} (a VCD is already being written)"
            ))),
            _ => Err(CompiledError::Trace(text)),
        }
    }
}

/// What the plain C++ loop measured: see [`plain_loop`].
#[derive(Clone, Copy, Debug)]
pub struct PlainLoop {
    /// Cycles run.
    pub cycles: u64,
    /// Wall time of the loop alone, seconds.
    pub seconds: f64,
    /// Every output word of every cycle folded as `sum = sum * 31 + word`
    /// ([`CompiledModel::fold_outputs`] folds the same way).
    pub checksum: u64,
}

/// The reference for the backend's speed: the Verilog of `block` compiled
/// with the same flags into a plain C++ program that runs `stimulus` (one
/// input vector per cycle, in Verilog port order) from power-up `repeats`
/// times, with no Rust in the loop; one [`PlainLoop`] per run.
pub fn plain_loop(
    module: &str,
    block: &mut dyn Block,
    stimulus: &[Vec<u64>],
    repeats: usize,
) -> Result<Vec<PlainLoop>, CompiledError> {
    let verilog = module_verilog(module, block)?;
    let ports = top_ports(block);
    let inputs = slots(&ports, PortDirection::Input, "clock");
    let outputs = slots(&ports, PortDirection::Output, "clock");
    let layout = build::Layout {
        module,
        clock: "clock",
        inputs: &inputs,
        outputs: &outputs,
    };
    let failed = |e: &dyn std::fmt::Display| CompiledError::Build(format!("the plain loop: {e}"));
    let dir = tempfile::Builder::new()
        .prefix("motion-hdl-plain-loop-")
        .tempdir()
        .map_err(|e| failed(&e))?;
    let program = build::plain_loop(&verilog, &layout, dir.path())?;
    let bytes: Vec<u8> = stimulus
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let words = dir.path().join("stimulus.bin");
    std::fs::write(&words, bytes).map_err(|e| failed(&e))?;
    let output = std::process::Command::new(&program)
        .arg(&words)
        .arg(repeats.to_string())
        .output()
        .map_err(|e| failed(&e))?;
    let text = String::from_utf8_lossy(&output.stdout);
    let runs: Vec<PlainLoop> = text
        .lines()
        .filter_map(
            |line| match line.split_whitespace().collect::<Vec<_>>().as_slice() {
                [cycles, seconds, checksum] => Some(PlainLoop {
                    cycles: cycles.parse().ok()?,
                    seconds: seconds.parse().ok()?,
                    checksum: checksum.parse().ok()?,
                }),
                _ => None,
            },
        )
        .collect();
    if !output.status.success() || runs.len() != repeats {
        return Err(failed(&format!("{} {text}", output.status)));
    }
    Ok(runs)
}

impl CompiledModel {
    /// Folds every output word into `sum` as the plain loop does.
    pub fn fold_outputs(&self, sum: u64) -> u64 {
        self.output_words
            .iter()
            .fold(sum, |s, &w| s.wrapping_mul(31).wrapping_add(w))
    }
}

impl Drop for CompiledModel {
    fn drop(&mut self) {
        // SAFETY: the handle came from mh_new and is freed once; the library
        // is still loaded (dropped after this).
        unsafe { (self.free_fn)(self.handle) };
    }
}

/// The ports of one direction, other than the clock, laid out in words.
fn slots(ports: &[Port], direction: PortDirection, clock: &str) -> Vec<Slot> {
    let mut offset = 0;
    ports
        .iter()
        .filter(|p| p.direction == direction && p.name != clock)
        .map(|p| {
            let slot = Slot {
                name: p.name.clone(),
                width: p.width,
                offset,
            };
            offset += slot.words();
            slot
        })
        .collect()
}
