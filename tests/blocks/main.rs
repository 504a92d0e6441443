//! Every block's tests, one module per block (`tests/blocks/<block>.rs`):
//! RTL against its model in lockstep, the contract at the pins,
//! cross-simulation of its exported Verilog. One binary, so that the
//! crate's simulation code is compiled once for all of them.

mod support;
mod command_fifo;
mod dac_interface;
mod dda_integrator;
mod dda_interpolator;
mod external_bus_adapter;
mod narrow_bus_adapter;
mod word_assembler;
mod dpram_mailbox;
mod host_links;
mod freq_divider;
mod glitch_filter;
mod input_conditioner;
mod interrupt_controller;
mod pulse_counter;
mod quadrature_decoder;
mod sequential_divider;
mod step_channel;
mod step_output;
mod uniform_pulse_gen;
mod watchdog;
mod sync_fifo_bridge;
