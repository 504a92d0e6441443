//! Fast cycle-by-cycle simulation of rust-hdl blocks.
//!
//! rust-hdl's threaded `Simulation` hands the circuit between threads on every
//! event. [`Harness`] steps a block directly on the calling thread, far
//! faster. [`CompiledModel`] runs the block's Verilog compiled by Verilator,
//! faster again by more than an order of magnitude on the whole controller
//! (`cargo bench --bench simulation_speed` measures all three).
//! [`Stepper`] drives either, chosen at run time ([`Backend`]).
//! [`Lockstep`] runs one of them against a block's reference model, and
//! [`plant`] holds the models of what hangs on the pins.

mod backend;
pub mod compiled;
mod harness;
mod lockstep;
pub mod plant;
mod ports;

pub use backend::{stepper, Backend, CompiledStepper, SimError, Stepper, BACKEND_VARIABLE};
pub use compiled::{CompiledError, CompiledModel};

pub use harness::{Harness, HarnessError, CLOCK_PERIOD_PS};
pub use lockstep::{Lockstep, LockstepError, LockstepModel, Sample};
pub use plant::{quadrature_state, Ad669Bank, ServoMotor, SimulatedEncoder};
pub use ports::{port_words, push_port, set_port, PortValue, VectorPorts};
