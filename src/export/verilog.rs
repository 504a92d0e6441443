use regex::Regex;
use rust_hdl::core::check_error::check_all;
use rust_hdl::core::module_defines::ModuleDefines;
use rust_hdl::core::prelude::*;
use std::sync::OnceLock;

/// The block failed rust-hdl's structural checks, so no Verilog was written.
#[derive(Debug, thiserror::Error)]
#[error("module `{module}` fails rust-hdl's checks: {detail}")]
pub struct VerilogError {
    /// The module that failed.
    pub module: String,
    /// rust-hdl's description of the problem.
    pub detail: String,
}

/// Connects `block` and returns its Verilog with top module `name` and submodules named
/// `name__child__grandchild`, with no `$` in any identifier.
///
/// rust-hdl joins hierarchy levels with `$`, which is legal Verilog but
/// breaks vendor Tcl flows; a `$` that follows an identifier character is a
/// hierarchy separator, while system tasks (`$signed(`, `$display`) follow a
/// space or punctuation and are left alone.
pub fn module_verilog(name: &str, block: &mut dyn Block) -> Result<String, VerilogError> {
    block.connect_all();
    check_all(block).map_err(|e| VerilogError {
        module: name.to_string(),
        detail: format!("{e:?}"),
    })?;
    let mut defines = ModuleDefines::default();
    block.accept(name, &mut defines);
    Ok(strip_hierarchy_dollars(&defines.defines()))
}

#[doc(hidden)]
pub fn strip_hierarchy_dollars(verilog: &str) -> String {
    static SEPARATOR: OnceLock<Regex> = OnceLock::new();
    let separator = SEPARATOR.get_or_init(|| Regex::new(r"([A-Za-z0-9_])\$").expect("valid regex"));
    let renamed = separator.replace_all(verilog, "${1}__").into_owned();
    // Trailing spaces are noise in review diffs of the committed RTL.
    let mut out: String = renamed
        .lines()
        .map(str::trim_end)
        .collect::<Vec<_>>()
        .join("\n");
    out.push('\n');
    out
}
