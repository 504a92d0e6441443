//! The export and its tools: `rtl-out/` freshness and lint, the datasheets'
//! port tables, register maps,
//! cross-simulation, the harness, plots, and synthesis of every exported
//! module and the board example.

mod cross_simulation;
mod datasheets;
mod harness;
mod plots;
mod regmap;
mod rtl_out;
mod synthesis;
