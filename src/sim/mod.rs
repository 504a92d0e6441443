//! Fast cycle-by-cycle simulation of rust-hdl blocks.
//!
//! rust-hdl's threaded `Simulation` hands the circuit between threads on every
//! event and runs at about 10k cycles/s. [`Harness`] steps a block directly on
//! the calling thread (about 200x faster). [`CompiledModel`] runs the block's
//! Verilog compiled by Verilator, another 70 times faster on the whole
//! controller. [`Stepper`] drives either, chosen at run time ([`Backend`]).

mod ad669;
mod backend;
pub mod compiled;
mod encoder;
mod harness;
mod lockstep;
mod ports;
mod waveform;

pub use ad669::Ad669Bank;
pub use backend::{stepper, Backend, CompiledStepper, SimError, Stepper, BACKEND_VARIABLE};
pub use compiled::{CompiledError, CompiledModel};

pub use encoder::{quadrature_state, SimulatedEncoder};
pub use harness::{Harness, HarnessError};
pub use lockstep::{Lockstep, LockstepError, LockstepModel, Sample};
pub use ports::{port_words, push_port, set_port, PortValue, VectorPorts};
pub use waveform::{render_svg, WaveformError};
