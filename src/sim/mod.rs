//! Fast cycle-by-cycle simulation of rust-hdl blocks.
//!
//! rust-hdl's threaded `Simulation` hands the circuit between threads on every
//! event and runs at about 10k cycles/s. [`Harness`] steps a block directly on
//! the calling thread (about 200x faster) and is the one way every test and
//! tool in this crate drives RTL.

mod encoder;
mod harness;
mod ports;
mod waveform;

pub use encoder::{quadrature_state, SimulatedEncoder};
pub use harness::{Harness, HarnessError};
pub use ports::{PortValue, VectorPorts};
pub use waveform::{render_svg, WaveformError};
