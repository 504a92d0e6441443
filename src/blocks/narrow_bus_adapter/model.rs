//! Reference model of [`super::NarrowBusAdapter`], cycle-exact: the
//! synchronizer's model and the word assembler's model, wired as the RTL.

use crate::blocks::bus_synchronizer::model::{
    BusPinInputs, BusSynchronizerModel, BusSynchronizerOutputs,
};
use crate::blocks::word_assembler::model::{PartGeometry, WordAssemblerInputs, WordAssemblerModel};

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NarrowBusOutputs {
    /// Read data to the pins.
    pub data_out: u64,
    /// Drive the data pins.
    pub data_oe: bool,
    /// The access may end.
    pub ready: bool,
    /// Register address of the bus strobe.
    pub bus_address: u64,
    /// Whole word of the write strobe.
    pub bus_write_data: u64,
    /// Write strobe.
    pub bus_write: bool,
    /// Read strobe.
    pub bus_read: bool,
    /// Access-order violation.
    pub order_error: bool,
}

impl NarrowBusOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            data_out: v[0],
            data_oe: v[1] != 0,
            ready: v[2] != 0,
            bus_address: v[3],
            bus_write_data: v[4],
            bus_write: v[5] != 0,
            bus_read: v[6] != 0,
            order_error: v[7] != 0,
        }
    }
}

/// Cycle-exact model of the narrow adapter. Its inputs are the
/// synchronizer's ([`BusPinInputs`]), with `bus_read_data` the wide word.
#[derive(Clone, Debug)]
pub struct NarrowBusModel {
    pins: BusSynchronizerModel,
    words: WordAssemblerModel,
    /// The synchronizer's registered outputs, as shown this clock.
    shown: BusSynchronizerOutputs,
}

impl NarrowBusModel {
    /// An adapter in its power-up state.
    pub fn new(geometry: PartGeometry) -> Self {
        let narrow_address_bits = geometry.address_bits + geometry.part_bits();
        Self {
            pins: BusSynchronizerModel::new(narrow_address_bits, geometry.narrow_bits),
            words: WordAssemblerModel::new(geometry),
            shown: BusSynchronizerOutputs::default(),
        }
    }

    /// The exported 16-bit adapter's geometry.
    pub const fn geometry_16() -> PartGeometry {
        PartGeometry {
            narrow_bits: 16,
            wide_bits: 32,
            address_bits: 8,
        }
    }

    /// The exported 8-bit adapter's geometry.
    pub const fn geometry_8() -> PartGeometry {
        PartGeometry {
            narrow_bits: 8,
            wide_bits: 32,
            address_bits: 8,
        }
    }

    fn assembler_inputs(&self, i: &BusPinInputs) -> WordAssemblerInputs {
        WordAssemblerInputs {
            reset: i.reset,
            narrow_address: self.shown.bus_address,
            narrow_write_data: self.shown.bus_write_data,
            narrow_write: self.shown.bus_write,
            narrow_read: self.shown.bus_read,
            bus_read_data: i.bus_read_data,
        }
    }

    /// One rising clock edge; returns the outputs after it (`data_oe`,
    /// `ready` and the bus strobes with this clock's inputs still applied).
    pub fn step(&mut self, i: BusPinInputs) -> NarrowBusOutputs {
        let before = self.assembler_inputs(&i);
        let answer = self.words.outputs(&before).narrow_read_data;
        self.shown = self.pins.step(BusPinInputs {
            bus_read_data: answer,
            ..i
        });
        self.words.clock(&before);
        let words = self.words.outputs(&self.assembler_inputs(&i));
        NarrowBusOutputs {
            data_out: self.shown.data_out,
            data_oe: self.shown.data_oe,
            ready: self.shown.ready,
            bus_address: words.bus_address,
            bus_write_data: words.bus_write_data,
            bus_write: words.bus_write,
            bus_read: words.bus_read,
            order_error: words.order_error,
        }
    }
}

crate::lockstep_model!(NarrowBusModel {
    inputs: BusPinInputs,
    outputs: NarrowBusOutputs,
    step: |model, inputs| model.step(*inputs),
});
