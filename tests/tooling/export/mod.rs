//! Unit tests of the export (`src/export`): the datasheet renderer and the
//! Verilog clean-up.

mod datasheet;
mod verilog;
