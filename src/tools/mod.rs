//! The open FPGA tools, run on exported Verilog: Verilator lint, cross-simulation
//! in Icarus and Verilator against the Rust simulation, and yosys/nextpnr
//! synthesis for iCE40 HX8K. Every run works in its own temporary folder.

pub mod cosim;
pub mod lint;
pub mod report;
pub mod synth;

use std::path::PathBuf;
use std::process::Command;

/// The one line that installs every tool these checks need (Debian, as root).
pub const INSTALL_LINE: &str = "apt-get install -y yosys iverilog verilator nextpnr-ice40";

/// A tool run failed.
#[derive(Debug, thiserror::Error)]
pub enum ToolError {
    /// The program is not on PATH. Checks never pass silently without it.
    #[error("`{tool}` is not installed; install the FPGA tools with: {INSTALL_LINE}")]
    Missing {
        /// The missing program.
        tool: String,
    },
    /// The program ran and failed.
    #[error("`{command}` failed ({status}):\n{output}")]
    Failed {
        /// The command line.
        command: String,
        /// Its exit status.
        status: String,
        /// What it printed (stdout, then stderr).
        output: String,
    },
    /// A file or folder of the run could not be made or read.
    #[error("{context}: {source}")]
    Io {
        /// What was being done.
        context: String,
        /// The error.
        source: std::io::Error,
    },
    /// The tool's output did not have the expected form.
    #[error("cannot read the output of `{tool}`: {detail}")]
    Parse {
        /// The tool.
        tool: String,
        /// What was missing.
        detail: String,
    },
}

/// The repository root (where `rtl-out/` and `testbench/` are).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A new temporary work folder for one tool run.
pub(crate) fn work_dir(purpose: &str) -> Result<tempfile::TempDir, ToolError> {
    tempfile::Builder::new()
        .prefix(&format!("motion-hdl-{purpose}-"))
        .tempdir()
        .map_err(|source| ToolError::Io {
            context: format!("temporary folder for {purpose}"),
            source,
        })
}

/// Runs `command` and returns its stdout and stderr joined; fails on a
/// non-zero exit unless `allow_failure` says so.
pub(crate) fn run(command: &mut Command, allow_failure: bool) -> Result<String, ToolError> {
    let program = command.get_program().to_string_lossy().into_owned();
    let line = format!(
        "{} {}",
        program,
        command
            .get_args()
            .map(|a| a.to_string_lossy())
            .collect::<Vec<_>>()
            .join(" ")
    );
    let output = command.output().map_err(|source| {
        if source.kind() == std::io::ErrorKind::NotFound {
            ToolError::Missing {
                tool: program.clone(),
            }
        } else {
            ToolError::Io {
                context: format!("running `{line}`"),
                source,
            }
        }
    })?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    if !output.status.success() && !allow_failure {
        return Err(ToolError::Failed {
            command: line,
            status: output.status.to_string(),
            output: text,
        });
    }
    Ok(text)
}
