//! Reference model of [`super::WordAssembler`], cycle-exact.

use crate::blocks::width_mask;

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WordAssemblerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Narrow word address.
    pub narrow_address: u64,
    /// Data of the narrow write.
    pub narrow_write_data: u64,
    /// Narrow write strobe.
    pub narrow_write: bool,
    /// Narrow read strobe.
    pub narrow_read: bool,
    /// The wide slave's read data.
    pub bus_read_data: u64,
}

impl WordAssemblerInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.narrow_address,
            self.narrow_write_data,
            self.narrow_write as u64,
            self.narrow_read as u64,
            self.bus_read_data,
        ]
    }
}

/// Outputs after one clock edge (the combinational ones with this clock's
/// inputs still applied).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WordAssemblerOutputs {
    /// The part read a clock ago.
    pub narrow_read_data: u64,
    /// Wide address.
    pub bus_address: u64,
    /// Assembled word.
    pub bus_write_data: u64,
    /// Wide write strobe.
    pub bus_write: bool,
    /// Wide read strobe.
    pub bus_read: bool,
    /// Access-order violation.
    pub order_error: bool,
}

impl WordAssemblerOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            narrow_read_data: v[0],
            bus_address: v[1],
            bus_write_data: v[2],
            bus_write: v[3] != 0,
            bus_read: v[4] != 0,
            order_error: v[5] != 0,
        }
    }
}

/// The split of a narrow bus into parts of a wide word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartGeometry {
    /// Narrow data width N.
    pub narrow_bits: u32,
    /// Wide data width W.
    pub wide_bits: u32,
    /// Wide address width A.
    pub address_bits: u32,
}

impl PartGeometry {
    /// Parts per wide word (W / N).
    pub fn parts(&self) -> u64 {
        (self.wide_bits / self.narrow_bits) as u64
    }

    /// log2(W / N): the part bits at the bottom of a narrow address.
    pub fn part_bits(&self) -> u32 {
        self.parts().trailing_zeros()
    }

    /// The narrow address of `part` of the wide register at `address`.
    pub fn narrow_address(&self, address: u64, part: u64) -> u64 {
        (address << self.part_bits()) | part
    }

    /// Part `part` of a wide word.
    pub fn part_of(&self, word: u64, part: u64) -> u64 {
        (word >> (part as u32 * self.narrow_bits)) & width_mask(self.narrow_bits)
    }

    /// `word` with part `part` replaced by `value`.
    pub fn with_part(&self, word: u64, part: u64, value: u64) -> u64 {
        let shift = part as u32 * self.narrow_bits;
        let mask = width_mask(self.narrow_bits) << shift;
        (word & !mask) | ((value << shift) & mask)
    }
}

/// Cycle-exact model of the word assembler.
#[derive(Clone, Debug)]
pub struct WordAssemblerModel {
    geometry: PartGeometry,
    latch: u64,
    latch_address: u64,
    latch_valid: bool,
    answer_from_bus: bool,
    answer_part: u64,
    holding: u64,
    held_parts: u64,
    holding_address: u64,
    error: bool,
}

impl WordAssemblerModel {
    /// An assembler in its power-up state.
    pub fn new(geometry: PartGeometry) -> Self {
        Self {
            geometry,
            latch: 0,
            latch_address: 0,
            latch_valid: false,
            answer_from_bus: false,
            answer_part: 0,
            holding: 0,
            held_parts: 0,
            holding_address: 0,
            error: false,
        }
    }

    /// The outputs during a clock with inputs `i`, before its edge: the
    /// wide strobes and data are combinational from `i` and the state.
    pub fn outputs(&self, i: &WordAssemblerInputs) -> WordAssemblerOutputs {
        let d = self.decide(i);
        let g = self.geometry;
        let answered = if self.answer_from_bus {
            i.bus_read_data
        } else {
            self.latch
        };
        WordAssemblerOutputs {
            narrow_read_data: g.part_of(answered, self.answer_part),
            bus_address: d.address,
            bus_write_data: d.merged,
            bus_write: d.write,
            bus_read: d.read,
            order_error: self.error,
        }
    }

    /// The rising edge at the end of a clock with inputs `i`.
    pub fn clock(&mut self, i: &WordAssemblerInputs) {
        let g = self.geometry;
        let d = self.decide(i);
        if self.answer_from_bus {
            self.latch = i.bus_read_data & width_mask(g.wide_bits);
        }
        self.error = false;
        self.answer_from_bus = false;
        if i.narrow_read {
            self.answer_part = d.part;
            if d.read {
                self.answer_from_bus = true;
                self.latch_address = d.address;
                self.latch_valid = true;
                self.error = d.part != 0;
            }
        }
        if i.narrow_write {
            if d.part == g.parts() - 1 {
                self.error |= !d.write;
                self.held_parts = 0;
            } else {
                self.holding = d.merged;
                self.holding_address = d.address;
                if d.holding_hit {
                    self.held_parts |= 1 << d.part;
                } else {
                    // Parts of another register are abandoned.
                    self.error = self.held_parts != 0;
                    self.held_parts = 1 << d.part;
                }
            }
        }
        if i.reset {
            *self = Self::new(g);
        }
    }

    fn decide(&self, i: &WordAssemblerInputs) -> Decision {
        let g = self.geometry;
        let part = i.narrow_address & (g.parts() - 1);
        let address = (i.narrow_address >> g.part_bits()) & width_mask(g.address_bits);
        let data = i.narrow_write_data & width_mask(g.narrow_bits);
        let top = g.parts() - 1;
        let latch_hit = self.latch_valid && self.latch_address == address;
        let holding_hit = self.holding_address == address;
        let whole = holding_hit && self.held_parts == (1 << top) - 1;
        Decision {
            part,
            address,
            merged: g.with_part(self.holding, part, data),
            read: i.narrow_read && (part == 0 || !latch_hit),
            write: i.narrow_write && part == top && whole,
            holding_hit,
        }
    }
}

/// What the combinational logic makes of one clock's inputs.
struct Decision {
    part: u64,
    address: u64,
    merged: u64,
    read: bool,
    write: bool,
    /// The holding register holds parts of this register.
    holding_hit: bool,
}

/// The wide strobes are combinational from the narrow ones: the model
/// gives the outputs during the clock, before its edge.
impl crate::sim::LockstepModel for WordAssemblerModel {
    type Inputs = WordAssemblerInputs;
    type Outputs = WordAssemblerOutputs;
    const SAMPLE: crate::sim::Sample = crate::sim::Sample::BeforeEdge;
    fn input_vector(inputs: &WordAssemblerInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> WordAssemblerOutputs {
        WordAssemblerOutputs::from_vector(vector)
    }
    fn expected(&mut self, inputs: &WordAssemblerInputs) -> WordAssemblerOutputs {
        let outputs = self.outputs(inputs);
        self.clock(inputs);
        outputs
    }
}
