//! Reference model of [`super::GlitchFilter`], cycle-exact.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GlitchFilterInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The unfiltered level.
    pub raw: bool,
    /// Sample `raw` on this edge.
    pub sample: bool,
    /// Samples a new level must hold (0 and 1 both mean one).
    pub length: u8,
    /// Take `raw` as the accepted level at once.
    pub prime: bool,
}

impl GlitchFilterInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.raw as u64,
            self.sample as u64,
            self.length as u64,
            self.prime as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GlitchFilterOutputs {
    /// The accepted level.
    pub filtered: bool,
    /// `filtered` changed at this edge.
    pub changed: bool,
}

impl GlitchFilterOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            filtered: v[0] != 0,
            changed: v[1] != 0,
        }
    }
}

/// Plain-Rust model of one glitch filter.
#[derive(Clone, Debug, Default)]
pub struct GlitchFilterModel {
    filtered: bool,
    /// Consecutive samples of a level different from `filtered` so far.
    run: u8,
    /// The threshold taken when the current run began.
    length: u8,
    changed: bool,
}

impl GlitchFilterModel {
    /// A filter in its power-up state.
    pub fn new() -> Self {
        Self::default()
    }

    /// The accepted level.
    pub fn filtered(&self) -> bool {
        self.filtered
    }

    /// `filtered` changed at the last edge.
    pub fn changed(&self) -> bool {
        self.changed
    }

    /// Whether the edge with these inputs will accept a change.
    pub fn accepts(&self, raw: bool, sample: bool, prime: bool) -> bool {
        !prime && sample && raw != self.filtered && self.run + 1 >= self.length
    }

    /// One rising edge. Returns whether it accepted a change.
    pub fn step(&mut self, reset: bool, raw: bool, sample: bool, length: u8, prime: bool) -> bool {
        let accept = self.accepts(raw, sample, prime);
        if reset {
            *self = Self::new();
        } else if prime || (sample && (raw == self.filtered || accept)) {
            self.filtered = raw;
            self.run = 0;
            self.length = length & 15;
        } else if sample {
            self.run += 1;
        }
        self.changed = accept && !reset;
        accept
    }
}

crate::lockstep_model!(GlitchFilterModel {
    inputs: GlitchFilterInputs,
    outputs: GlitchFilterOutputs,
    step: |model, i| {
        model.step(i.reset, i.raw, i.sample, i.length, i.prime);
        GlitchFilterOutputs {
            filtered: model.filtered(),
            changed: model.changed(),
        }
    },
});
