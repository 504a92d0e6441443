//! Formal proofs of the blocks' port contracts with yosys and `yosys-smtbmc`.
//!
//! Each property file in `formal/` is spliced into the top module of a
//! block's generated Verilog, just before its `endmodule`: the inline style
//! of ZipCPU's cores. yosys 0.23 reads no hierarchical references in
//! expressions, so this is how the invariants that induction needs can name
//! the top module's registers, while the contract properties name only the
//! ports. A submodule's register is reached through a top-module wire named
//! `\<instance>.<wire>` with the `(* hierconn *)` attribute, which `flatten`
//! connects (`formal/narrow_bus_adapter.sv`); a submodule's memory array
//! cannot be reached that way (hence `formal/command_fifo_ram.sv`). The properties are
//! immediate assertions and assumptions in the Verilog subset that
//! `read_verilog -formal` reads.
//!
//! A proof is two runs of `yosys-smtbmc` on the same SMT2 model:
//! 1. a bounded check from the power-up state (every flip-flop 0, as on an
//!    FPGA) for [`FormalSpec::bmc_depth`] clocks, with `reset` free;
//! 2. a k-induction proof (`-i`) of depth [`FormalSpec::induction_depth`].
//!
//! A failed bounded check is a real counterexample from power-up, written
//! as a VCD. A failed induction step alone (the bounded check passing)
//! means the invariants are too weak, not that the RTL is wrong; the
//! outcome says which.
//!
//! Proofs run on narrow instances built from the same Rust source as the
//! exported modules ([`formal_catalog`] says which instance each covers).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use rust_hdl::core::prelude::*;

use super::{repo_root, run, work_dir, ToolError};
use crate::export::module_verilog;

mod command_fifo;
mod external_bus_adapter;
mod freq_divider;
mod interrupt_controller;
mod motion_controller;
mod quadrature_decoder;
mod spi_bus_adapter;
mod step_output;
mod watchdog;

/// The SMT solver `yosys-smtbmc` drives (Debian's `z3` package; Debian's
/// boolector, 1.5, predates the interface `yosys-smtbmc` expects).
/// `yosys-smtbmc` itself comes with Debian's yosys. Both are in
/// [`super::INSTALL_LINE`].
pub const SOLVER: &str = "z3";

/// One proof: a block instance, its property file and the depths.
pub struct FormalSpec {
    /// The proof's name (block and instance), e.g. `freq_divider_w4`.
    pub name: &'static str,
    /// The block's folder under `src/blocks/` (its datasheet is `mod.rs`).
    pub block: &'static str,
    /// The generated top module's name (the exported module's name where
    /// the block is exported).
    pub module: &'static str,
    /// The property file under `formal/`.
    pub property_file: &'static str,
    /// The instance proved, as the README's table states it.
    pub instance: &'static str,
    /// What the property file proves, one line for the README's table.
    pub properties: &'static str,
    /// Clocks of the bounded check from power-up.
    pub bmc_depth: u32,
    /// Depth of the k-induction.
    pub induction_depth: u32,
    /// Builds the instance from the block's Rust source.
    pub build: fn() -> Box<dyn Block>,
}

/// Every proof, in the order of the README's "What is proved" table. Each
/// block's proofs are listed in its own file of this folder.
pub fn formal_catalog() -> Vec<FormalSpec> {
    [
        freq_divider::specs(),
        step_output::specs(),
        quadrature_decoder::specs(),
        command_fifo::specs(),
        interrupt_controller::specs(),
        watchdog::specs(),
        external_bus_adapter::specs(),
        motion_controller::specs(),
        spi_bus_adapter::specs(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// The proof of the catalog named `name`.
pub fn find(name: &str) -> Option<FormalSpec> {
    formal_catalog().into_iter().find(|spec| spec.name == name)
}

/// Which of the two checks failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailedCheck {
    /// The bounded check from power-up: a real counterexample.
    Bounded,
    /// The induction step: the bounded check passed, the invariants are too
    /// weak to close the proof (or the depth too small).
    Induction,
}

/// What a proof run found.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// Every check made passed (for [`Checks::Proof`], both the bounded
    /// check and the induction: the properties hold at every depth).
    Proved,
    /// An assertion fails on a trace of `steps` clocks, written to `vcd`.
    Counterexample {
        /// The check that failed.
        check: FailedCheck,
        /// The trace's length in clocks.
        steps: u32,
        /// The assertion that failed, as `yosys-smtbmc` names it (file:line).
        assertion: String,
        /// The trace (kept: the work folder is not deleted on failure).
        vcd: PathBuf,
    },
}

/// One proof's outcome and times.
#[derive(Debug, Clone)]
pub struct ProofReport {
    /// The outcome.
    pub outcome: Outcome,
    /// yosys: reading the Verilog and writing SMT2.
    pub build_time: Duration,
    /// The bounded check.
    pub bmc_time: Duration,
    /// The induction (zero when the bounded check failed).
    pub induction_time: Duration,
}

impl ProofReport {
    /// Whole wall time of the proof.
    pub fn total_time(&self) -> Duration {
        self.build_time + self.bmc_time + self.induction_time
    }
}

/// The folder of the property files.
pub fn formal_dir() -> PathBuf {
    repo_root().join("formal")
}

/// The generated Verilog of `spec`'s instance, top module `spec.module`.
pub fn instance_verilog(spec: &FormalSpec) -> Result<String, ToolError> {
    let mut block = (spec.build)();
    module_verilog(spec.module, block.as_mut()).map_err(|e| ToolError::Parse {
        tool: "rust-hdl".into(),
        detail: e.to_string(),
    })
}

/// Which checks a run makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Checks {
    /// The proof: the bounded check and the k-induction, with the
    /// property file's `INDUCTION_INVARIANTS` section defined.
    Proof,
    /// The bounded check of the contract alone, without the invariants:
    /// what a mutation must fail, so that a caught bug is caught by the
    /// contract and not only by an invariant about the RTL's registers.
    ContractBounded,
}

/// Proves `spec` on its generated Verilog.
pub fn prove(spec: &FormalSpec) -> Result<ProofReport, ToolError> {
    let verilog = instance_verilog(spec)?;
    prove_verilog(spec, &verilog, Checks::Proof)
}

/// Checks `spec`'s properties on `verilog` (the generated text, or a
/// deliberately broken copy of it: the mutation tests).
pub fn prove_verilog(
    spec: &FormalSpec,
    verilog: &str,
    checks: Checks,
) -> Result<ProofReport, ToolError> {
    let properties =
        std::fs::read_to_string(formal_dir().join(spec.property_file)).map_err(|source| {
            ToolError::Io {
                context: format!("reading formal/{}", spec.property_file),
                source,
            }
        })?;
    check_spliced(spec, verilog, &properties, checks)
}

/// Runs `checks` on `properties` spliced into the top module of `verilog`.
fn check_spliced(
    spec: &FormalSpec,
    verilog: &str,
    properties: &str,
    checks: Checks,
) -> Result<ProofReport, ToolError> {
    if spec.bmc_depth < spec.induction_depth {
        // The induction step assumes the properties for k clocks; only a
        // base case at least as deep makes that sound.
        return Err(ToolError::Parse {
            tool: "formal_catalog".into(),
            detail: format!(
                "{}: bounded depth {} is below the induction depth {}",
                spec.name, spec.bmc_depth, spec.induction_depth
            ),
        });
    }
    let dir = work_dir(&format!("formal-{}", spec.name))?;
    let io = |context: String| move |source| ToolError::Io { context, source };
    let spliced = splice(spec.module, verilog, spec.property_file)?;
    std::fs::write(dir.path().join("dut.v"), spliced).map_err(io("writing dut.v".into()))?;
    std::fs::write(dir.path().join(spec.property_file), properties)
        .map_err(io(format!("writing {}", spec.property_file)))?;

    let started = Instant::now();
    let define = match checks {
        Checks::Proof => "-DINDUCTION_INVARIANTS ",
        Checks::ContractBounded => "",
    };
    let script = format!(
        "read_verilog -formal {define}dut.v; prep -flatten -top {top}; async2sync; dffunmap; write_smt2 -wires model.smt2",
        top = spec.module
    );
    run(
        Command::new("yosys")
            .current_dir(dir.path())
            .args(["-q", "-p", &script]),
        false,
    )?;
    let build_time = started.elapsed();

    let started = Instant::now();
    let bounded = smtbmc(dir.path(), false, spec.bmc_depth)?;
    let bmc_time = started.elapsed();
    let (failure, induction_time) = match (bounded, checks) {
        (Some(failure), _) => (Some((FailedCheck::Bounded, failure)), Duration::ZERO),
        (None, Checks::ContractBounded) => (None, Duration::ZERO),
        (None, Checks::Proof) => {
            let started = Instant::now();
            let induction = smtbmc(dir.path(), true, spec.induction_depth)?;
            (
                induction.map(|failure| (FailedCheck::Induction, failure)),
                started.elapsed(),
            )
        }
    };
    let outcome = match failure {
        Some((check, (steps, assertion))) => counterexample(dir, check, steps, assertion),
        None => Outcome::Proved,
    };
    Ok(ProofReport {
        outcome,
        build_time,
        bmc_time,
        induction_time,
    })
}

fn counterexample(
    dir: tempfile::TempDir,
    check: FailedCheck,
    steps: u32,
    assertion: String,
) -> Outcome {
    let kept = dir.keep();
    Outcome::Counterexample {
        check,
        steps,
        assertion,
        vcd: kept.join("trace.vcd"),
    }
}

/// Inserts `` `include "<property file>" `` before the top module's
/// `endmodule` (the include keeps the property file's own line numbers in
/// yosys's messages).
#[doc(hidden)]
pub fn splice(top: &str, verilog: &str, property_file: &str) -> Result<String, ToolError> {
    let marker = format!("endmodule // {top}\n");
    let at = verilog.find(&marker).ok_or_else(|| ToolError::Parse {
        tool: "rust-hdl".into(),
        detail: format!("no `{}` in the generated Verilog", marker.trim_end()),
    })?;
    Ok(format!(
        "{}`ifdef FORMAL\n`include \"{property_file}\"\n`endif\n{}",
        &verilog[..at],
        &verilog[at..]
    ))
}

/// Runs one `yosys-smtbmc` check; `None` when it passed, else the failing
/// trace's length in clocks and the failed assertion.
fn smtbmc(dir: &Path, induction: bool, depth: u32) -> Result<Option<(u32, String)>, ToolError> {
    let mut command = Command::new("yosys-smtbmc");
    // `--unroll`: z3 4.8.12 (Debian 12's) stalls on the first step of any
    // model with more than a few dozen registers when the transition
    // relation stays a recursive function; unrolled, the same models
    // solve in seconds.
    command
        .current_dir(dir)
        .args(["-s", SOLVER, "--presat", "--unroll"]);
    if induction {
        command.arg("-i");
    }
    command.args([
        "-t",
        &depth.to_string(),
        "--dump-vcd",
        "trace.vcd",
        "model.smt2",
    ]);
    let output = run(&mut command, true)?;
    if output.contains("Status: PASSED") {
        return Ok(None);
    }
    if !output.contains("Status: FAILED") {
        return Err(ToolError::Parse {
            tool: "yosys-smtbmc".into(),
            detail: format!("no status line in:\n{output}"),
        });
    }
    Ok(Some(failure_of(&output, induction, depth)))
}

/// The trace length and the failed assertion from `yosys-smtbmc`'s output.
#[doc(hidden)]
pub fn failure_of(output: &str, induction: bool, depth: u32) -> (u32, String) {
    let assertion = output
        .lines()
        .find_map(|l| {
            l.split_once("Assert failed in ")
                .map(|(_, rest)| rest.trim().to_string())
        })
        .unwrap_or_else(|| "(unnamed)".into());
    // Bounded: "Checking assertions in step N.." is the last step tried,
    // and the trace runs from step 0 to it. Induction: the trace is the
    // whole window, steps 0 to the depth, failing at the last.
    let steps = if induction {
        depth + 1
    } else {
        output
            .lines()
            .rev()
            .filter_map(|l| l.split_once("Checking assertions in step "))
            .find_map(|(_, rest)| rest.trim_end_matches('.').trim().parse::<u32>().ok())
            .map_or(0, |s| s + 1)
    };
    (steps, assertion)
}

/// The header of the README's "What is proved" table.
pub const TABLE_HEADER: &str = "| block | proof | instance | what is proved | bounded depth | induction depth | time (s) |\n|---|---|---|---|---|---|---|\n";

/// A table row's fixed part: everything but the time, which is measured.
/// The README's table must contain it for every proof of the catalog.
pub fn table_row_prefix(spec: &FormalSpec) -> String {
    format!(
        "| `{}` | `{}` | {} | {} | {} | {} |",
        spec.block, spec.name, spec.instance, spec.properties, spec.bmc_depth, spec.induction_depth
    )
}

/// One row of the README's "What is proved" table, with the proof's
/// measured wall time (yosys, bounded check and induction).
pub fn table_row(spec: &FormalSpec, report: &ProofReport) -> String {
    format!(
        "{} {:.1} |",
        table_row_prefix(spec),
        report.total_time().as_secs_f64()
    )
}
