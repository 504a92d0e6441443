//! # motion-hdl
//!
//! The FPGA half of a CPU/DSP + FPGA CNC motion controller, as synchronous
//! hardware blocks written in rust-hdl, each with a reference model, and
//! exported to Verilog (`motion-hdl export`, into `rtl-out/`).
//!
//! * [`blocks`]: the hardware blocks and their models.
//! * [`sim`]: the fast stepping harness every test uses.
//! * [`export`]: the catalog of exported modules and the Verilog writer.
//! * [`tools`]: lint, cross-simulation and synthesis with the open FPGA tools.
//!
//! The tests are all in `tests/` (one binary per area: `blocks`,
//! `controller`, `host`, `formal`, `tooling`), so that the crate compiles
//! once for them. The few internals they test directly are public but
//! `#[doc(hidden)]`: not part of the API, and free to change.

pub mod blocks;
pub mod export;
pub mod host;
pub mod plots;
pub mod regmap;
pub mod sim;
pub mod tools;
