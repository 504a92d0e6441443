//! The G-code interpreter (`src/host/gcode`): one module per interpreter
//! file, through its public `interpret*` functions.

mod canon;
mod cutter_comp;
mod cycles;
mod flow;
mod fuzz;
mod golden;
mod interpreter;
mod laser;
mod lexer;
mod non_modal;
mod param_store;
mod parameters;
mod polar;
mod probing;
mod rotary;
mod support;
mod text;
mod threading;
mod tool_calls;
