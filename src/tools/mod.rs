//! The open FPGA tools, run on exported Verilog: Verilator lint, cross-simulation
//! in Icarus and Verilator against the Rust simulation, yosys/nextpnr
//! synthesis for iCE40 HX8K, and yosys mapping on Cyclone IV E, 7-series,
//! Gowin and ECP5 (module [`families`]), with ECP5 and Gowin place and
//! route (module [`gowin`] for Gowin's). Every run works in its own
//! temporary folder.

pub mod cosim;
pub mod families;
pub mod formal;
pub mod gowin;
pub mod lint;
pub mod report;
pub mod scaling;
pub mod synth;

use std::path::PathBuf;
use std::process::Command;

/// The one line that installs every tool these checks need (Debian, as root).
pub const INSTALL_LINE: &str = "apt-get install -y yosys z3 iverilog verilator nextpnr-ice40";

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

/// The text of `path`, or an error naming it.
pub(crate) fn read_text(path: &std::path::Path) -> Result<String, ToolError> {
    std::fs::read_to_string(path).map_err(|source| ToolError::Io {
        context: format!("reading {}", path.display()),
        source,
    })
}

/// Longest any single tool run may take. nextpnr can route for ever on a
/// hopeless design; a stuck tool fails its test instead of hanging CI.
pub const TOOL_TIME_LIMIT: std::time::Duration = std::time::Duration::from_secs(300);

/// Longest one yosys mapping or ECP5 placement of a report's other families
/// may take: a whole controller's Cyclone IV E or 7-series mapping, or its
/// ECP5 placement, can pass [`TOOL_TIME_LIMIT`] on a loaded machine. Reports run outside the suite.
pub const FAMILY_MAPPING_TIME_LIMIT: std::time::Duration = std::time::Duration::from_secs(1800);

/// Runs `command` and returns its stdout and stderr joined; fails on a
/// non-zero exit unless `allow_failure` says so, and after
/// [`TOOL_TIME_LIMIT`] kills the tool and fails.
pub(crate) fn run(command: &mut Command, allow_failure: bool) -> Result<String, ToolError> {
    run_limited(command, allow_failure, TOOL_TIME_LIMIT)
}

/// [`run`] with the time limit `limit`.
pub(crate) fn run_limited(
    command: &mut Command,
    allow_failure: bool,
    limit: std::time::Duration,
) -> Result<String, ToolError> {
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
    let io_error = |context: &str, source| ToolError::Io {
        context: format!("{context} `{line}`"),
        source,
    };
    // Output goes to files, so a chatty tool can never block on a full pipe.
    let stdout = tempfile::tempfile().map_err(|e| io_error("capturing output of", e))?;
    let stderr = tempfile::tempfile().map_err(|e| io_error("capturing output of", e))?;
    // Its own process group, so that a time-out kills what a wrapper
    // script started too (run_vectors.sh's vvp outlived a killed bash and
    // kept a core busy for the rest of the suite).
    std::os::unix::process::CommandExt::process_group(&mut *command, 0);
    let mut child = command
        .stdout(
            stdout
                .try_clone()
                .map_err(|e| io_error("capturing output of", e))?,
        )
        .stderr(
            stderr
                .try_clone()
                .map_err(|e| io_error("capturing output of", e))?,
        )
        .spawn()
        .map_err(|source| {
            if source.kind() == std::io::ErrorKind::NotFound {
                ToolError::Missing {
                    tool: program.clone(),
                }
            } else {
                io_error("running", source)
            }
        })?;
    let started = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| io_error("waiting for", e))? {
            break Some(status);
        }
        if started.elapsed() > limit {
            let _ = Command::new("kill")
                .args(["-KILL", "--", &format!("-{}", child.id())])
                .status();
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let text = format!("{}{}", read_all(stdout), read_all(stderr));
    match status {
        None => Err(ToolError::Failed {
            command: line,
            status: format!("killed after {} s", limit.as_secs()),
            output: text,
        }),
        Some(status) if !status.success() && !allow_failure => Err(ToolError::Failed {
            command: line,
            status: status.to_string(),
            output: text,
        }),
        Some(_) => Ok(text),
    }
}

fn read_all(mut file: std::fs::File) -> String {
    use std::io::{Read, Seek};
    let mut bytes = Vec::new();
    let _ = file.rewind().and_then(|_| file.read_to_end(&mut bytes));
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Compiles the C `program` (which includes headers from `include_dir`)
/// with gcc as strict `standard` C (`c89`, `c99`: `-pedantic -Wall -Wextra
/// -Werror`), runs it and returns what it printed: how the tests check a
/// generated register header against its Rust map.
pub fn run_c_program(
    include_dir: &std::path::Path,
    standard: &str,
    program: &str,
) -> Result<String, ToolError> {
    let dir = work_dir("c-program")?;
    let source = dir.path().join("main.c");
    std::fs::write(&source, program).map_err(|source| ToolError::Io {
        context: "writing the C program".into(),
        source,
    })?;
    let exe = dir.path().join("program");
    run(
        Command::new("gcc")
            .arg(format!("-std={standard}"))
            .args(["-pedantic", "-Wall", "-Wextra", "-Werror", "-I"])
            .arg(include_dir)
            .arg("-o")
            .arg(&exe)
            .arg(&source),
        false,
    )?;
    let output = Command::new(&exe)
        .output()
        .map_err(|source| ToolError::Io {
            context: "running the C program".into(),
            source,
        })?;
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}
