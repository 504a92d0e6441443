//! Reference model of [`super::ExternalBusAdapter`], cycle-exact: the
//! [`BusSynchronizerModel`] at 32 bits, without `ready`.

use crate::blocks::bus_synchronizer::model::{BusSynchronizerModel, BusSynchronizerOutputs};

/// Inputs of one clock cycle (the synchronizer's).
pub use crate::blocks::bus_synchronizer::model::BusPinInputs as ExternalBusInputs;

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExternalBusOutputs {
    /// Read data to the pins.
    pub data_out: u64,
    /// Drive the data pins.
    pub data_oe: bool,
    /// Address of the bus strobe.
    pub bus_address: u64,
    /// Data of the write strobe.
    pub bus_write_data: u64,
    /// Write strobe.
    pub bus_write: bool,
    /// Read strobe.
    pub bus_read: bool,
}

impl ExternalBusOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            data_out: v[0],
            data_oe: v[1] != 0,
            bus_address: v[2],
            bus_write_data: v[3],
            bus_write: v[4] != 0,
            bus_read: v[5] != 0,
        }
    }
}

impl From<BusSynchronizerOutputs> for ExternalBusOutputs {
    fn from(o: BusSynchronizerOutputs) -> Self {
        Self {
            data_out: o.data_out,
            data_oe: o.data_oe,
            bus_address: o.bus_address,
            bus_write_data: o.bus_write_data,
            bus_write: o.bus_write,
            bus_read: o.bus_read,
        }
    }
}

/// Cycle-exact model of the adapter with an `address_bits` address.
#[derive(Clone, Debug)]
pub struct ExternalBusModel {
    pins: BusSynchronizerModel,
}

impl ExternalBusModel {
    /// An adapter in its power-up state.
    pub fn new(address_bits: u32) -> Self {
        Self {
            pins: BusSynchronizerModel::new(address_bits, 32),
        }
    }

    /// One rising clock edge; returns the outputs after it (`data_oe` with
    /// this clock's pins still applied).
    pub fn step(&mut self, i: ExternalBusInputs) -> ExternalBusOutputs {
        self.pins.step(i).into()
    }
}

crate::lockstep_model!(ExternalBusModel {
    inputs: ExternalBusInputs,
    outputs: ExternalBusOutputs,
    step: |model, inputs| model.step(*inputs),
});
