//! Cross-simulation: the same stimulus vectors drive the Rust simulation and
//! the exported Verilog in Icarus and in Verilator, compared cycle by cycle.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use super::{read_text, repo_root, run, work_dir, ToolError};
use crate::export::{generator, module_verilog, testbench_verilog, top_ports, Port, PortDirection};
use crate::sim::{CompiledModel, CompiledStepper, Harness, HarnessError, Stepper, VectorPorts};

/// A Verilog simulator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simulator {
    /// Icarus Verilog (`iverilog` + `vvp`) running the vector testbench.
    Icarus,
    /// Verilator (`--binary`) running the vector testbench.
    Verilator,
    /// Verilator's C++ model stepped from Rust: the compiled simulation
    /// backend ([`crate::sim::CompiledModel`]).
    Compiled,
}

impl Simulator {
    /// Every simulator.
    pub const ALL: [Simulator; 3] = [Simulator::Icarus, Simulator::Verilator, Simulator::Compiled];
    /// The simulators [`cross_simulate`] runs: Icarus on the vector
    /// testbench, and Verilator stepped from Rust. Verilator on the vector
    /// testbench would build the same Verilog into a second model (5 to
    /// 15 s of g++ per module) to compare the same vectors again; the
    /// tooling tests run the testbench in Verilator too, so the generated
    /// testbench is known to work there.
    pub const CROSS_SIMULATION: [Simulator; 2] = [Simulator::Icarus, Simulator::Compiled];

    fn arg(self) -> &'static str {
        match self {
            Simulator::Icarus => "icarus",
            Simulator::Verilator | Simulator::Compiled => "verilator",
        }
    }
}

/// The Verilog under test: RTL file, testbench file and module name.
pub struct CosimDesign {
    /// Top module name.
    pub module: String,
    /// The RTL file.
    pub rtl: PathBuf,
    /// The `<module>_tb.v` testbench.
    pub testbench: PathBuf,
    _generated_in: Option<tempfile::TempDir>,
}

impl CosimDesign {
    /// The committed export: `rtl-out/<module>.v` with `testbench/<module>_tb.v`.
    pub fn exported(module: &str) -> Self {
        let root = repo_root();
        Self {
            module: module.to_string(),
            rtl: root.join("rtl-out").join(format!("{module}.v")),
            testbench: root.join("testbench").join(format!("{module}_tb.v")),
            _generated_in: None,
        }
    }

    /// Verilog generated now from `block` (for example a narrow instance that
    /// is not exported), with its testbench, in a temporary folder.
    pub fn generated(
        module: &str,
        block: &mut dyn rust_hdl::core::prelude::Block,
    ) -> Result<Self, CosimError> {
        let dir = work_dir("generated")?;
        let verilog =
            module_verilog(module, block).map_err(|e| CosimError::Setup(e.to_string()))?;
        let testbench = testbench_verilog(module, &generator(), &top_ports(&*block));
        let rtl = dir.path().join(format!("{module}.v"));
        let tb = dir.path().join(format!("{module}_tb.v"));
        write(&rtl, &verilog)?;
        write(&tb, &testbench)?;
        Ok(Self {
            module: module.to_string(),
            rtl,
            testbench: tb,
            _generated_in: Some(dir),
        })
    }
}

/// The first difference between the Rust simulation and a Verilog simulator.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mismatch {
    /// The simulator that disagreed.
    pub simulator: Simulator,
    /// Zero-based cycle of the vector.
    pub cycle: u64,
    /// The output port.
    pub signal: String,
    /// What the Rust simulation produced (hex).
    pub expected: String,
    /// What the Verilog produced (hex).
    pub got: String,
}

/// Why a cross-simulation did not pass.
#[derive(Debug, thiserror::Error)]
pub enum CosimError {
    /// The Verilog disagrees with the Rust simulation.
    #[error("{:?} disagrees with the Rust simulation at cycle {}: signal `{}` expected {} got {}", .0.simulator, .0.cycle, .0.signal, .0.expected, .0.got)]
    Mismatch(Mismatch),
    /// The Rust simulation failed.
    #[error(transparent)]
    Harness(#[from] HarnessError),
    /// A tool failed or is missing.
    #[error(transparent)]
    Tool(#[from] ToolError),
    /// The vector ports of the Rust block do not match its Verilog ports, or
    /// the design could not be generated.
    #[error("cross-simulation setup: {0}")]
    Setup(String),
    /// The testbench ran but did not report a result.
    #[error("{simulator:?} testbench gave no verdict (expected {cycles} cycles):\n{output}")]
    NoVerdict {
        /// The simulator.
        simulator: Simulator,
        /// Cycles in the vector file.
        cycles: usize,
        /// What it printed.
        output: String,
    },
}

/// A passing cross-simulation.
#[derive(Debug, Clone)]
pub struct CosimPass {
    /// Cycles compared in the compiled Verilator model (every cycle).
    pub cycles: usize,
    /// Cycles compared in Icarus (the first ones).
    pub icarus_cycles: usize,
    /// Simulators that ran.
    pub simulators: Vec<Simulator>,
}

/// Clocks of a cross-simulation that Icarus compares: the first 10,000
/// (the compiled Verilator model compares every clock). Icarus runs the
/// exported controllers at about 220 clocks/s and the larger blocks at 3,000
/// to 10,000 (one to three quarters of each cross-simulation's time in the
/// suite), so a longer run checks Icarus on its opening stretch; the ignored
/// soaks pass [`ALL_CLOCKS`] through [`check_instance_with`].
pub const ICARUS_CLOCKS: usize = 10_000;

/// Every clock of the stimulus, in Icarus too (for [`check_instance_with`]).
pub const ALL_CLOCKS: usize = usize::MAX;

/// Runs `stimulus` (one input vector per cycle, in `B::input_names()` order) through
/// `block` in the Rust harness, then through `design` in Icarus (the vector
/// testbench, on the first `icarus_clocks` cycles) and in Verilator (the
/// compiled backend, on every cycle), and compares all outputs on every
/// cycle each runs ([`Simulator::CROSS_SIMULATION`]).
pub fn cross_simulate<B: VectorPorts>(
    design: &CosimDesign,
    block: B,
    stimulus: &[Vec<u64>],
    icarus_clocks: usize,
) -> Result<CosimPass, CosimError> {
    let ports = top_ports(&block);
    let expected = rust_outputs(&design.module, block, stimulus)?;
    let icarus = icarus_clocks.min(stimulus.len());
    compare_in_ports(
        Simulator::Icarus,
        design,
        &stimulus[..icarus],
        &expected[..icarus],
        (&B::input_words(), &B::output_words()),
    )?;
    compare_compiled::<B>(design, &ports, stimulus, &expected)?;
    Ok(CosimPass {
        cycles: stimulus.len(),
        icarus_cycles: icarus,
        simulators: Simulator::CROSS_SIMULATION.to_vec(),
    })
}

/// [`cross_simulate`] on Verilog generated now from a fresh `B::default()`
/// and named `module`: for instances that are not exported, such as narrow
/// widths. Every block's structure is fixed by its type (its const
/// parameters), so the fresh instance has the same Verilog as `block`; a
/// fresh one is used because blocks holding a RAM cannot be cloned.
pub fn cross_simulate_generated<B: VectorPorts + Default>(
    module: &str,
    block: B,
    stimulus: &[Vec<u64>],
    icarus_clocks: usize,
) -> Result<CosimPass, CosimError> {
    let mut copy = B::default();
    let design = CosimDesign::generated(module, &mut copy)?;
    cross_simulate(&design, block, stimulus, icarus_clocks)
}

/// The instance of a block a cross-simulation test checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instance<'a> {
    /// The committed export, `rtl-out/<module>.v` (the product).
    Exported(&'a str),
    /// Verilog generated now from the block's type and named so: an
    /// instance that is not exported, such as a narrow width.
    Generated(&'a str),
}

/// The cross-simulation test of one instance of `B` (built with
/// `B::default()`): `stimulus` (one input vector per clock, from the block's
/// model inputs' `to_vector`) through rust-hdl, Icarus (its first
/// [`ICARUS_CLOCKS`]) and Verilator (the compiled model, every clock), every
/// output compared on every clock. Each block's test file calls it twice,
/// for the exported instance and for a narrow one. Panics with the first
/// disagreement (a test's check).
pub fn check_instance<B: VectorPorts + Default>(
    instance: Instance,
    stimulus: impl IntoIterator<Item = Vec<u64>>,
) -> CosimPass {
    check_instance_with::<B>(instance, stimulus, ICARUS_CLOCKS)
}

/// Stack of the thread [`check_instance_with`] simulates on.
const COSIM_STACK_BYTES: usize = 256 << 20;

/// [`check_instance`] with Icarus on the first `icarus_clocks` clocks
/// ([`ALL_CLOCKS`] for every one).
pub fn check_instance_with<B: VectorPorts + Default>(
    instance: Instance,
    stimulus: impl IntoIterator<Item = Vec<u64>>,
    icarus_clocks: usize,
) -> CosimPass {
    let stimulus: Vec<Vec<u64>> = stimulus.into_iter().collect();
    // The Rust simulation of a whole controller recurses deeper than a
    // test thread's 2 MiB stack: it runs on a thread of its own.
    let result = std::thread::scope(|scope| {
        std::thread::Builder::new()
            .stack_size(COSIM_STACK_BYTES)
            .spawn_scoped(scope, || match instance {
                Instance::Exported(module) => cross_simulate(
                    &CosimDesign::exported(module),
                    B::default(),
                    &stimulus,
                    icarus_clocks,
                ),
                Instance::Generated(module) => {
                    cross_simulate_generated(module, B::default(), &stimulus, icarus_clocks)
                }
            })
            .expect("a thread for the cross-simulation")
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    });
    result.unwrap_or_else(|e| panic!("{instance:?}: {e}"))
}

/// The outputs of `block` on every cycle of `stimulus`, from the Rust harness,
/// after checking that its vector ports match its Verilog ports.
pub fn rust_outputs<B: VectorPorts>(
    module: &str,
    block: B,
    stimulus: &[Vec<u64>],
) -> Result<Vec<Vec<u64>>, CosimError> {
    check_vector_ports::<B>(&block)?;
    let mut harness = Harness::new(module, block)?;
    stimulus
        .iter()
        .map(|inputs| harness.step_vector(inputs).map_err(CosimError::from))
        .collect()
}

/// Runs `design` compiled by Verilator and stepped from Rust (the compiled
/// backend) on `stimulus`, with `B`'s vector ports (matched by name), and
/// compares its outputs with `expected` on every cycle; `ports` are the
/// design's ports (as [`top_ports`] gives them).
pub fn compare_compiled<B: VectorPorts>(
    design: &CosimDesign,
    ports: &[Port],
    stimulus: &[Vec<u64>],
    expected: &[Vec<u64>],
) -> Result<usize, CosimError> {
    let setup = |e: &dyn std::fmt::Display| CosimError::Setup(e.to_string());
    let verilog = read_text(&design.rtl)?;
    let model = CompiledModel::from_verilog(&design.module, &verilog, "clock", ports, false)
        .map_err(|e| setup(&e))?;
    let mut compiled = CompiledStepper::ordered::<B>(model).map_err(|e| setup(&e))?;
    // The port of each vector column (a wide port has several).
    let names: Vec<String> = B::output_names()
        .into_iter()
        .zip(B::output_words())
        .flat_map(|(name, words)| std::iter::repeat_n(name, words))
        .collect();
    let mut outputs = vec![0; names.len()];
    for (cycle, (inputs, want)) in stimulus.iter().zip(expected).enumerate() {
        compiled
            .step_into(inputs, &mut outputs)
            .map_err(|e| setup(&e))?;
        if let Some(index) = (0..names.len()).find(|&i| outputs[i] != want[i]) {
            return Err(CosimError::Mismatch(Mismatch {
                simulator: Simulator::Compiled,
                cycle: cycle as u64,
                signal: names[index].clone(),
                expected: format!("{:x}", want[index]),
                got: format!("{:x}", outputs[index]),
            }));
        }
    }
    Ok(stimulus.len())
}

/// Runs `design` in `simulator` on `stimulus` and compares its outputs with
/// `expected` on every cycle; returns the cycles compared. Every port takes
/// one vector column (up to 64 bits); see [`compare_in_ports`] for wider ones.
pub fn compare_in(
    simulator: Simulator,
    design: &CosimDesign,
    stimulus: &[Vec<u64>],
    expected: &[Vec<u64>],
) -> Result<usize, CosimError> {
    let inputs = vec![1; stimulus.first().map_or(0, Vec::len)];
    let outputs = vec![1; expected.first().map_or(0, Vec::len)];
    compare_in_ports(simulator, design, stimulus, expected, (&inputs, &outputs))
}

/// The hex field of a port from its vector columns (least significant first).
fn hex_field(words: &[u64]) -> String {
    let top = words.iter().rposition(|&w| w != 0).unwrap_or(0);
    let mut field = format!("{:x}", words[top]);
    for word in words[..top].iter().rev() {
        let _ = write!(field, "{word:016x}");
    }
    field
}

/// [`compare_in`] for ports of any width: `words` gives the vector columns
/// of each input and each output port ([`VectorPorts::input_words`],
/// [`VectorPorts::output_words`]); the vector file has one hex field per port.
pub fn compare_in_ports(
    simulator: Simulator,
    design: &CosimDesign,
    stimulus: &[Vec<u64>],
    expected: &[Vec<u64>],
    words: (&[usize], &[usize]),
) -> Result<usize, CosimError> {
    let mut text = String::with_capacity(stimulus.len() * 16);
    let mut fields = Vec::new();
    for (inputs, outputs) in stimulus.iter().zip(expected) {
        fields.clear();
        for (columns, widths) in [(inputs, words.0), (outputs, words.1)] {
            let mut at = 0;
            for &n in widths {
                fields.push(hex_field(&columns[at..at + n]));
                at += n;
            }
        }
        let _ = writeln!(text, "{}", fields.join(" "));
    }
    let dir = work_dir("cosim")?;
    let vectors = dir.path().join("vectors.hex");
    write(&vectors, &text)?;
    run_testbench(simulator, design, &vectors, stimulus.len(), dir.path())?;
    Ok(stimulus.len())
}

/// The vector runner: `testbench/run_vectors.sh`.
pub fn vector_runner() -> PathBuf {
    repo_root().join("testbench").join("run_vectors.sh")
}

fn run_testbench(
    simulator: Simulator,
    design: &CosimDesign,
    vectors: &Path,
    cycles: usize,
    work: &Path,
) -> Result<(), CosimError> {
    let build = work.join(simulator.arg());
    let output = run(
        Command::new("bash")
            .arg(vector_runner())
            .arg(simulator.arg())
            .arg(&design.rtl)
            .arg(&design.testbench)
            .arg(vectors)
            .arg(&build),
        true,
    )?;
    if let Some(line) = output.lines().find(|l| l.starts_with("MISMATCH")) {
        return Err(CosimError::Mismatch(parse_mismatch(simulator, line)));
    }
    let passed = format!("PASS cycles={cycles}");
    if output.lines().any(|l| l.trim() == passed) {
        Ok(())
    } else {
        Err(CosimError::NoVerdict {
            simulator,
            cycles,
            output,
        })
    }
}

fn parse_mismatch(simulator: Simulator, line: &str) -> Mismatch {
    let field = |key: &str| {
        line.split_whitespace()
            .find_map(|w| w.strip_prefix(key))
            .unwrap_or_default()
            .to_string()
    };
    Mismatch {
        simulator,
        cycle: field("cycle=").parse().unwrap_or(u64::MAX),
        signal: field("signal="),
        expected: field("expected="),
        got: field("got="),
    }
}

fn check_vector_ports<B: VectorPorts>(block: &B) -> Result<(), CosimError> {
    let ports = top_ports(block);
    let names = |dir: PortDirection| -> Vec<String> {
        ports
            .iter()
            .filter(|p| p.direction == dir && p.name != "clock")
            .map(|p| p.name.clone())
            .collect()
    };
    let words = |dir: PortDirection| -> Vec<usize> {
        ports
            .iter()
            .filter(|p| p.direction == dir && p.name != "clock")
            .map(|p| p.width.div_ceil(64).max(1))
            .collect()
    };
    let (inputs, outputs) = (names(PortDirection::Input), names(PortDirection::Output));
    if words(PortDirection::Input) != B::input_words()
        || words(PortDirection::Output) != B::output_words()
    {
        return Err(CosimError::Setup(format!(
            "vector_ports! gives input columns {:?} output columns {:?}, but the port widths need {:?} {:?}",
            B::input_words(),
            B::output_words(),
            words(PortDirection::Input),
            words(PortDirection::Output)
        )));
    }
    if inputs != B::input_names() || outputs != B::output_names() {
        return Err(CosimError::Setup(format!(
            "vector_ports! lists inputs {:?} outputs {:?}, but the block has inputs {inputs:?} outputs {outputs:?}",
            B::input_names(),
            B::output_names()
        )));
    }
    Ok(())
}

fn write(path: &Path, contents: &str) -> Result<(), ToolError> {
    std::fs::write(path, contents).map_err(|source| ToolError::Io {
        context: format!("writing {}", path.display()),
        source,
    })
}
