//! The hardware blocks. Each block lives in its own folder: `mod.rs` holds
//! the rust-hdl implementation and its datasheet, `model.rs` the plain-Rust
//! reference model the RTL is proven against (in `tests/blocks/<block>.rs`).

pub mod bus_synchronizer;
pub mod carry_select_adder;
pub mod command_fifo;
pub mod dac_interface;
pub mod dda_integrator;
pub mod dda_interpolator;
pub mod dpram_mailbox;
pub mod external_bus_adapter;
pub mod freq_divider;
pub mod glitch_filter;
pub mod host_links;
pub mod input_conditioner;
pub mod interrupt_controller;
pub mod motion_controller;
pub mod narrow_bus_adapter;
pub mod port_doc;
pub mod pulse_counter;
pub mod quadrature_decoder;
pub mod sequential_divider;
pub mod step_channel;
pub mod step_output;
pub mod sync_fifo_bridge;
pub mod uniform_pulse_gen;
pub mod watchdog;
pub mod word_assembler;

/// All ones in the low `width` bits (1 to 64): the value range of a
/// `width`-bit port, for models and stimulus.
pub fn width_mask(width: u32) -> u64 {
    assert!((1..=64).contains(&width), "width must be 1..=64");
    u64::MAX >> (64 - width)
}
