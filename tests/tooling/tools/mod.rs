//! Unit tests of the report and proof tools (`src/tools`): their parsers
//! and renderers on canned tool output, no tool run.

mod families;
mod formal;
mod gowin;
mod report;
mod scaling;
mod synth;
