//! The simulation support (`src/sim`): the lockstep runner, port packing,
//! the plant models and the compiled backend's Verilog rewrite.

mod compiled;
mod lockstep;
mod plant;
mod ports;
