//! Reference model of [`super::FreqDivider`], cycle-exact.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FreqDividerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Counting runs while high.
    pub enable: bool,
    /// D, the divisor (only the low `width` bits count).
    pub divisor: u64,
}

impl FreqDividerInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![self.reset as u64, self.enable as u64, self.divisor]
    }
}

/// Plain-Rust model of a `width`-bit frequency divider.
#[derive(Clone, Debug)]
pub struct FreqDividerModel {
    mask: u64,
    remaining: u64,
    strobe: bool,
}

impl FreqDividerModel {
    /// A divider of `width` bits (1 to 64), in its power-up state.
    pub fn new(width: u32) -> Self {
        let mask = crate::blocks::width_mask(width);
        Self {
            mask,
            remaining: 0,
            strobe: false,
        }
    }

    /// The registered strobe output.
    pub fn strobe(&self) -> bool {
        self.strobe
    }

    /// One rising clock edge; returns the strobe output after it.
    pub fn step(&mut self, inputs: FreqDividerInputs) -> bool {
        let divisor = inputs.divisor & self.mask;
        self.strobe = false;
        if inputs.enable {
            if self.remaining <= 1 {
                self.remaining = divisor;
                self.strobe = divisor != 0;
            } else {
                self.remaining -= 1;
            }
        }
        if inputs.reset {
            self.remaining = 0;
            self.strobe = false;
        }
        self.strobe
    }
}

/// The model's one output, `strobe`, read from the RTL's output vector.
impl crate::sim::LockstepModel for FreqDividerModel {
    type Inputs = FreqDividerInputs;
    type Outputs = bool;
    fn input_vector(inputs: &FreqDividerInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> bool {
        vector[0] != 0
    }
    fn expected(&mut self, inputs: &FreqDividerInputs) -> bool {
        self.step(*inputs)
    }
}
