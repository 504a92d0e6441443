//! The board examples' generated files. A board in `boards/<board>/` has a
//! hand-written top (PLL, reset, pins) around a controller configuration
//! that is not one of the exported modules: six axes on the Colorlight
//! 5A-75E, four on the Tang Nano 20K. `motion-hdl export` writes that
//! controller's Verilog, with the same datasheet header as an exported
//! module, and its register map (C header and Markdown) into the board's
//! folder, so that a clone builds the board with no Rust toolchain.
//!
//! These configurations are not in [`super::catalog`]: a six-axis
//! controller does not fit the iCE40 HX8K every exported module is placed
//! on. They are generated from the same parameterized block as the
//! exported `motion_controller`, which the suite cross-simulates; the
//! board build (`boards/<board>/build.sh`) synthesizes and places them.

use super::catalog::ModuleSpec;
use crate::blocks::motion_controller::{
    self,
    registers::{register_map, BuildOptions},
    MotionController4, MotionController6,
};
use crate::regmap::{RegMapError, RegisterMap};

/// One board example.
pub struct BoardSpec {
    /// Its folder under `boards/`, and its name in FuseSoC and the README.
    pub dir: &'static str,
    /// The top module of its hand-written `<dir>/<top>.v`.
    pub top: &'static str,
    /// The controller configuration its top instantiates, rendered into
    /// `<dir>/<controller.name>.v` like an exported module.
    pub controller: ModuleSpec,
    /// Axes of the controller (its register map's K).
    pub axes: usize,
    /// The controller's build options (its register map's options).
    pub options: BuildOptions,
}

impl BoardSpec {
    /// The controller's register map, for `<dir>/<controller>_regs.h/.md`.
    pub fn register_map(&self) -> Result<RegisterMap, RegMapError> {
        register_map(self.axes, 4, self.options)
    }
}

/// The controller's catalog parameters at `K` axes, as the exported
/// `motion_controller` lists them.
macro_rules! controller_parameters {
    ($axes:literal) => {
        &[
            ("K", $axes, "axes"),
            ("N", "4", "FIFO depth 2^N = 16 periods per axis"),
            ("T", "16", "step timing register width"),
            (
                "P",
                "8",
                "each output stage's pending-step count width: +127 / -128 steps",
            ),
        ]
    };
}

/// Every board example with a generated controller, in a fixed order.
pub fn boards() -> Vec<BoardSpec> {
    vec![
        BoardSpec {
            dir: "colorlight-5a-75e",
            top: "colorlight_5a_75e_motion",
            controller: ModuleSpec {
                name: "motion_controller_k6",
                block: "motion_controller",
                summary: motion_controller::SUMMARY,
                parameters: controller_parameters!("6"),
                port_docs: motion_controller::PORT_DOCS,
                fmax_target_mhz: 50.0,
                lut4_budget: None,
                logic_cell_budget: None,
                build: || Box::new(MotionController6::default()),
            },
            axes: 6,
            options: BuildOptions::MOTION_CONTROLLER,
        },
        BoardSpec {
            dir: "tang-nano-20k",
            top: "tang_nano_20k_motion",
            controller: ModuleSpec {
                name: "motion_controller_k4",
                block: "motion_controller",
                summary: motion_controller::SUMMARY,
                parameters: controller_parameters!("4"),
                port_docs: motion_controller::PORT_DOCS,
                fmax_target_mhz: 50.0,
                lut4_budget: None,
                logic_cell_budget: None,
                build: || Box::new(MotionController4::default()),
            },
            axes: 4,
            options: BuildOptions::MOTION_CONTROLLER,
        },
    ]
}
