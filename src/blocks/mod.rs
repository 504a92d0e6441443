//! The hardware blocks. Each block lives in its own folder: `mod.rs` holds
//! the rust-hdl implementation and its datasheet, `model.rs` the plain-Rust
//! reference model the RTL is proven against (in `tests/<block>.rs`).

pub mod dda_integrator;
pub mod dda_interpolator;
pub mod freq_divider;
pub mod pulse_counter;
pub mod sequential_divider;
