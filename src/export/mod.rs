//! Verilog export: the catalog of shipped modules, and the files
//! `motion-hdl export` writes into `rtl-out/` (RTL and its index),
//! `testbench/` (one vector testbench per module) and `boards/` (each
//! board example's controller configuration).

pub mod boards;
pub mod catalog;
pub mod datasheet;
pub mod fusesoc;
mod header;
mod index;
mod ports;
mod testbench;
mod verilog;

use std::path::{Path, PathBuf};

pub use catalog::{catalog, ModuleSpec};
pub use header::{generator, PortDocError};
pub use ports::{top_ports, Port, PortDirection};
pub use testbench::testbench_verilog;
#[doc(hidden)]
pub use verilog::strip_hierarchy_dollars;
pub use verilog::{module_verilog, VerilogError};

/// Why an export could not be produced or written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// rust-hdl rejected a block.
    #[error(transparent)]
    Verilog(#[from] VerilogError),
    /// The catalog's port documentation disagrees with the RTL.
    #[error(transparent)]
    PortDoc(#[from] PortDocError),
    /// A datasheet's port table disagrees with the RTL.
    #[error(transparent)]
    Datasheet(#[from] datasheet::DatasheetError),
    /// A register map does not validate.
    #[error(transparent)]
    RegisterMap(#[from] crate::regmap::RegMapError),
    /// A file could not be written.
    #[error("cannot write `{path}`: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

/// One exported module, rendered.
pub struct RenderedModule {
    /// Its catalog entry.
    pub spec: ModuleSpec,
    /// Its top-level ports.
    pub ports: Vec<Port>,
    /// `<name>.v`: header and Verilog.
    pub verilog: String,
    /// `<name>_tb.v`: the vector testbench.
    pub testbench: String,
}

/// Renders one catalog entry.
pub fn render_module(spec: ModuleSpec) -> Result<RenderedModule, ExportError> {
    let mut block = (spec.build)();
    let ports = top_ports(block.as_ref());
    let rows = header::port_rows(&spec, &ports)?;
    let header = header::verilog_header(&spec, &rows);
    // `default_nettype none makes a mistyped net an error in the user's
    // project; it is restored at the end so that other files are unaffected.
    let verilog = format!(
        "{header}\n`default_nettype none\n{}\n`default_nettype wire\n",
        module_verilog(spec.name, block.as_mut())?.trim()
    );
    let testbench = testbench_verilog(spec.name, &generator(), &ports);
    Ok(RenderedModule {
        spec,
        ports,
        verilog,
        testbench,
    })
}

/// Which output folder a generated file belongs in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputDir {
    /// `rtl-out/` (or `--out`).
    Rtl,
    /// `testbench/` (or `--testbench-out`).
    Testbench,
    /// `src/blocks/` (or `--datasheet-out`): each block's port table,
    /// `<block>/ports.md`, included in its rustdoc.
    Datasheets,
    /// `boards/` (or `--boards-out`): each board example's controller
    /// configuration and its register map, `<board>/<controller>.v`.
    Boards,
}

/// Where `write_export` puts each kind of generated file.
pub struct ExportDirs<'a> {
    /// `rtl-out/`.
    pub rtl: &'a Path,
    /// `testbench/`.
    pub testbench: &'a Path,
    /// `src/blocks/`.
    pub datasheets: &'a Path,
    /// `boards/`.
    pub boards: &'a Path,
}

impl ExportDirs<'_> {
    /// The folder of `dir`.
    pub fn of(&self, dir: OutputDir) -> &Path {
        match dir {
            OutputDir::Rtl => self.rtl,
            OutputDir::Testbench => self.testbench,
            OutputDir::Datasheets => self.datasheets,
            OutputDir::Boards => self.boards,
        }
    }
}

/// One file of the export, with its contents.
pub struct GeneratedFile {
    /// The folder it goes in.
    pub dir: OutputDir,
    /// File name within that folder.
    pub file_name: String,
    /// Exact contents (deterministic: the same source gives the same bytes).
    pub contents: String,
}

/// Every file the export writes, in a fixed order.
pub fn generated_files() -> Result<Vec<GeneratedFile>, ExportError> {
    let modules = catalog()
        .into_iter()
        .map(render_module)
        .collect::<Result<Vec<_>, _>>()?;
    let mut files = Vec::new();
    for module in &modules {
        files.push(GeneratedFile {
            dir: OutputDir::Rtl,
            file_name: format!("{}.v", module.spec.name),
            contents: module.verilog.clone(),
        });
        files.push(GeneratedFile {
            dir: OutputDir::Testbench,
            file_name: format!("{}_tb.v", module.spec.name),
            contents: module.testbench.clone(),
        });
        files.push(GeneratedFile {
            dir: OutputDir::Rtl,
            file_name: format!("{}.core", module.spec.name),
            contents: fusesoc::module_core(&module.spec),
        });
        files.push(GeneratedFile {
            dir: OutputDir::Testbench,
            file_name: format!("{}_tb.core", module.spec.name),
            contents: fusesoc::testbench_core(module.spec.name),
        });
    }
    files.push(GeneratedFile {
        dir: OutputDir::Testbench,
        file_name: "lint_waivers.core".to_string(),
        contents: fusesoc::lint_waivers_core(),
    });
    use crate::blocks::{dac_interface, motion_controller, parallel_card, sync_fifo_bridge};
    // The register maps of the exported configurations (see the catalog).
    let maps = [
        (
            "dac_interface_regs",
            dac_interface::registers::register_map(3, 16)?,
        ),
        (
            "motion_controller_regs",
            motion_controller::registers::register_map(
                3,
                4,
                motion_controller::registers::BuildOptions::MOTION_CONTROLLER,
            )?,
        ),
        (
            "motion_controller_dda_regs",
            motion_controller::registers::register_map(
                3,
                4,
                motion_controller::registers::BuildOptions::MOTION_CONTROLLER_DDA,
            )?,
        ),
        (
            "motion_controller_dda_spindle_regs",
            motion_controller::registers::register_map(
                3,
                4,
                motion_controller::registers::BuildOptions::MOTION_CONTROLLER_DDA_SPINDLE,
            )?,
        ),
        (
            "motion_controller_dda_laser_regs",
            motion_controller::registers::register_map(
                3,
                4,
                motion_controller::registers::BuildOptions::MOTION_CONTROLLER_DDA_LASER,
            )?,
        ),
        (
            "motion_controller_servo_regs",
            motion_controller::registers::register_map(
                3,
                4,
                motion_controller::registers::BuildOptions::MOTION_CONTROLLER_SERVO,
            )?,
        ),
        (
            "sync_fifo_bridge_master_regs",
            sync_fifo_bridge::registers::master_map(
                sync_fifo_bridge::EXPORTED_SLAVES,
                sync_fifo_bridge::EXPORTED_FIFO_LOG2 as u32,
            )?,
        ),
        (
            "sync_fifo_bridge_slave_regs",
            sync_fifo_bridge::registers::slave_map(sync_fifo_bridge::EXPORTED_FIFO_LOG2 as u32)?,
        ),
        (
            "parallel_card_master_regs",
            parallel_card::registers::master_map()?,
        ),
        (
            "parallel_card_slave_regs",
            parallel_card::registers::slave_map()?,
        ),
    ];
    for (name, map) in &maps {
        files.push(GeneratedFile {
            dir: OutputDir::Rtl,
            file_name: format!("{name}.h"),
            contents: crate::regmap::c_header(map, &header::generator()),
        });
        files.push(GeneratedFile {
            dir: OutputDir::Rtl,
            file_name: format!("{name}.md"),
            contents: crate::regmap::markdown(map, &header::generator()),
        });
    }
    for board in boards::boards() {
        let map = board.register_map()?;
        let controller = render_module(board.controller)?;
        let name = controller.spec.name;
        files.push(GeneratedFile {
            dir: OutputDir::Boards,
            file_name: format!("{}/{name}.v", board.dir),
            contents: controller.verilog,
        });
        for (extension, contents) in [
            ("h", crate::regmap::c_header(&map, &header::generator())),
            ("md", crate::regmap::markdown(&map, &header::generator())),
        ] {
            files.push(GeneratedFile {
                dir: OutputDir::Boards,
                file_name: format!("{}/{name}_regs.{extension}", board.dir),
                contents,
            });
        }
    }
    files.push(GeneratedFile {
        dir: OutputDir::Rtl,
        file_name: "README.md".to_string(),
        contents: index::rtl_index(&modules),
    });
    for spec in datasheet::datasheets() {
        files.push(GeneratedFile {
            dir: OutputDir::Datasheets,
            file_name: format!("{}/ports.md", spec.block),
            contents: datasheet::port_table(&spec)?,
        });
    }
    Ok(files)
}

/// Writes the export into `dirs` and returns the paths written.
pub fn write_export(dirs: &ExportDirs) -> Result<Vec<PathBuf>, ExportError> {
    let mut written = Vec::new();
    for file in generated_files()? {
        let path = dirs.of(file.dir).join(&file.file_name);
        let parent = path.parent().unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(|source| ExportError::Io {
            path: parent.display().to_string(),
            source,
        })?;
        std::fs::write(&path, &file.contents).map_err(|source| ExportError::Io {
            path: path.display().to_string(),
            source,
        })?;
        written.push(path);
    }
    Ok(written)
}
