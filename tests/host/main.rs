//! The host (DSP) side's tests, one module per `src/host` file it tests
//! (`tests/host/<path>.rs` for `src/host/<path>.rs`): the G-code
//! interpreter against hand-made programs, LinuxCNC's golden traces and
//! random text; the hexapod's kinematics and card program; the servo, hold,
//! soft-limit, laser and threading helpers. Kept out of the library's own
//! build (`[lib] test = false`) so that the crate compiles once for the tests.

mod gcode;
mod geometry;
mod hexapod;
mod hold_window;
mod laser_log;
mod laser_run;
mod servo;
mod soft_window;
mod thread_log;
mod tool_table;
