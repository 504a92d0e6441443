//! Every block's tests, one module per block (`tests/blocks/<block>.rs`):
//! RTL against its model in lockstep, the contract at the pins,
//! cross-simulation of its exported Verilog. One binary, so that the
//! crate's simulation code is compiled once for all of them.

mod carry_select_adder;
mod command_fifo;
mod dac_interface;
mod dda_integrator;
mod dda_interpolator;
mod dpram_mailbox;
mod electronic_gearbox;
mod external_bus_adapter;
mod freq_divider;
mod glitch_filter;
mod hold_ramp;
mod holding_ram;
mod host_links;
mod input_conditioner;
mod interrupt_controller;
mod laser_pwm;
mod laser_pwm_model;
mod narrow_bus_adapter;
mod parallel_card;
mod port_doc;
mod pulse_counter;
mod quadrature_decoder;
mod sequential_divider;
mod sim;
mod soft_limits;
mod spi_bus_adapter;
mod step_channel;
mod step_output;
mod support;
mod sync_fifo_bridge;
mod uniform_dda_mode;
mod uniform_pulse_gen;
mod watchdog;
mod word_assembler;
