//! Formal proofs of the blocks' port contracts (`formal/`, run by
//! `motion_hdl::tools::formal`): each proof, and for each property file a
//! deliberate bug that its proof must catch with a counterexample.

mod readme;
mod support;

mod command_fifo;
mod external_bus_adapter;
mod freq_divider;
mod interrupt_controller;
mod motion_controller;
mod quadrature_decoder;
mod spi_bus_adapter;
mod step_output;
mod watchdog;
