//! Reference model of [`super::PulseCounter`], cycle-exact.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PulseCounterInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Count +1.
    pub up: bool,
    /// Count -1.
    pub down: bool,
    /// Count <- 0.
    pub clear: bool,
    /// Count <- `load_value`.
    pub load: bool,
    /// Value for `load` (low `width` bits).
    pub load_value: u64,
    /// Value for `compare_match` (low `width` bits).
    pub compare_value: u64,
}

impl PulseCounterInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.up as u64,
            self.down as u64,
            self.clear as u64,
            self.load as u64,
            self.load_value,
            self.compare_value,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PulseCounterOutputs {
    /// The count (low `width` bits, two's complement).
    pub count: u64,
    /// `count == compare_value`.
    pub compare_match: bool,
    /// The edge's net up/down pulse was overridden by clear or load.
    pub pulse_overridden: bool,
}

impl PulseCounterOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            count: v[0],
            compare_match: v[1] != 0,
            pulse_overridden: v[2] != 0,
        }
    }
}

/// Plain-Rust model of a `width`-bit pulse counter.
#[derive(Clone, Debug)]
pub struct PulseCounterModel {
    mask: u64,
    count: u64,
}

impl PulseCounterModel {
    /// A counter of `width` bits (1 to 64), in its power-up state (count 0).
    pub fn new(width: u32) -> Self {
        let mask = crate::blocks::width_mask(width);
        Self { mask, count: 0 }
    }

    /// The count as a signed number.
    pub fn signed_count(&self) -> i64 {
        crate::blocks::signed_value(self.count, self.mask.count_ones())
    }

    /// One rising clock edge; returns the outputs after it (with the same
    /// `compare_value` still applied).
    pub fn step(&mut self, inputs: PulseCounterInputs) -> PulseCounterOutputs {
        let net_pulse = inputs.up != inputs.down;
        let overridden = net_pulse && !inputs.reset && (inputs.clear || inputs.load);
        if inputs.reset || inputs.clear {
            self.count = 0;
        } else if inputs.load {
            self.count = inputs.load_value & self.mask;
        } else if inputs.up && !inputs.down {
            self.count = self.count.wrapping_add(1) & self.mask;
        } else if inputs.down && !inputs.up {
            self.count = self.count.wrapping_sub(1) & self.mask;
        }
        PulseCounterOutputs {
            count: self.count,
            compare_match: self.count == inputs.compare_value & self.mask,
            pulse_overridden: overridden,
        }
    }
}

crate::lockstep_model!(PulseCounterModel {
    inputs: PulseCounterInputs,
    outputs: PulseCounterOutputs,
    step: |model, inputs| model.step(*inputs),
});
