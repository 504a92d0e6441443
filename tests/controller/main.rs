//! The motion controller's tests: the controller bench (`bench.rs`), the
//! controller against its model, its DDA-only build, machine I/O, the host driver and
//! simulation, the compiled backend, the controller behind the bus adapter.
//! One binary, so that the controller's simulation is compiled (and
//! monomorphized) once.

mod analog_axes;
mod analog_hold;
mod analog_model;
mod analog_servo;
mod arcs;
#[allow(dead_code)] // each test module uses part of the bench
mod bench;
mod compiled_backend;
mod controller_behind_bus_adapter;
mod dda_only;
mod entry_converter;
mod feed_hold;
mod gcode;
mod gcode_corpus;
mod hexapod_program;
mod host;
mod host_feed_hold;
mod host_laser;
mod host_probing;
mod host_soft_limits;
mod host_spi;
mod host_threading;
mod laser;
mod machine_io;
mod motion_controller;
mod parallel_machine;
mod position_range;
mod probe;
mod soft_limits;
mod spindle;
