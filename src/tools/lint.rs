use std::path::Path;
use std::process::Command;

use super::{repo_root, run, ToolError};

/// The Verilator waiver file: the one place where lint warnings are waived,
/// each with its reason.
pub fn waiver_file() -> std::path::PathBuf {
    repo_root().join("testbench").join("lint_waivers.vlt")
}

/// Runs `verilator --lint-only -Wall` on `rtl` with top module `top` and the
/// project's waivers. Any warning left is a failure carrying Verilator's text.
pub fn lint(rtl: &Path, top: &str) -> Result<(), ToolError> {
    let output = run(
        Command::new("verilator")
            .arg("--lint-only")
            .arg("-Wall")
            .arg(waiver_file())
            .arg(rtl)
            .arg("--top-module")
            .arg(top),
        false,
    )?;
    if output.contains("%Warning") || output.contains("%Error") {
        return Err(ToolError::Failed {
            command: format!("verilator --lint-only -Wall {}", rtl.display()),
            status: "warnings".to_string(),
            output,
        });
    }
    Ok(())
}
