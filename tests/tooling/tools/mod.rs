//! Unit tests of the report and proof tools (`src/tools`): their parsers
//! and renderers on canned tool output, no tool run.

mod families;
mod formal;
mod report;
mod scaling;
mod synth;
