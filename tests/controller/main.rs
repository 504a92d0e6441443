//! The motion controller's tests: the controller bench (`bench.rs`), the
//! controller against its model, its DDA-only build, machine I/O, the host driver and
//! simulation, the compiled backend, the controller behind the bus adapter.
//! One binary, so that the controller's simulation is compiled (and
//! monomorphized) once.

#[allow(dead_code)] // each test module uses part of the bench
mod bench;
mod motion_controller;
mod dda_only;
mod machine_io;
mod host;
mod arcs;
mod gcode;
mod compiled_backend;
mod controller_behind_bus_adapter;
mod analog_servo;
mod analog_axes;
