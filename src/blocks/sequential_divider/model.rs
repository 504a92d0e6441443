//! Reference model of [`super::SequentialDivider`], cycle-exact, and the
//! arithmetic it must produce.

/// The result a division must give: `(quotient, remainder, divide_by_zero)`
/// for an N-bit dividend and a D-bit divisor. Divisor 0 gives all ones and
/// the dividend's low D bits (the restoring algorithm's result).
pub fn expected_result(
    dividend: u64,
    divisor: u64,
    dividend_bits: u32,
    divisor_bits: u32,
) -> (u64, u64, bool) {
    let n_mask = crate::blocks::width_mask(dividend_bits);
    let d_mask = crate::blocks::width_mask(divisor_bits);
    let (dividend, divisor) = (dividend & n_mask, divisor & d_mask);
    match dividend.checked_div(divisor) {
        Some(quotient) => (quotient, dividend % divisor, false),
        None => (n_mask, dividend & d_mask, true),
    }
}

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SequentialDividerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Start a division (while not busy).
    pub start: bool,
    /// Unsigned dividend.
    pub dividend: u64,
    /// Unsigned divisor.
    pub divisor: u64,
}

impl SequentialDividerInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.start as u64,
            self.dividend,
            self.divisor,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SequentialDividerOutputs {
    /// A division is running.
    pub busy: bool,
    /// The result is valid (strobe).
    pub done: bool,
    /// Quotient (intermediate while busy).
    pub quotient: u64,
    /// Remainder (intermediate while busy).
    pub remainder: u64,
    /// The divisor was 0.
    pub divide_by_zero: bool,
}

impl SequentialDividerOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            busy: v[0] != 0,
            done: v[1] != 0,
            quotient: v[2],
            remainder: v[3],
            divide_by_zero: v[4] != 0,
        }
    }
}

/// Plain-Rust, cycle-exact model of an N-by-D-bit sequential divider.
#[derive(Clone, Debug)]
pub struct SequentialDividerModel {
    width: u32,
    mask: u64,
    divisor_bits: u32,
    divisor_mask: u64,
    steps_left: u32,
    denominator: u64,
    out: SequentialDividerOutputs,
}

impl SequentialDividerModel {
    /// A divider with an N = `width`-bit dividend and a D = `divisor_bits`
    /// divisor (2 <= D <= N <= 63), idle.
    pub fn new(width: u32, divisor_bits: u32) -> Self {
        assert!(
            2 <= divisor_bits && divisor_bits <= width && width <= 63,
            "need 2 <= D <= N <= 63"
        );
        Self {
            width,
            mask: crate::blocks::width_mask(width),
            divisor_bits,
            divisor_mask: crate::blocks::width_mask(divisor_bits),
            steps_left: 0,
            denominator: 0,
            out: SequentialDividerOutputs::default(),
        }
    }

    /// The outputs after the last edge.
    pub fn outputs(&self) -> SequentialDividerOutputs {
        self.out
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, inputs: SequentialDividerInputs) -> SequentialDividerOutputs {
        let out = &mut self.out;
        out.done = false;
        if out.busy {
            // The partial remainder is kept one bit wider than the ports here,
            // which is what the RTL's overflow bit stands for.
            let next_bit = out.quotient >> (self.width - 1) & 1;
            let shifted = (out.remainder << 1) | next_bit;
            let quotient = (out.quotient << 1) & self.mask;
            if shifted >= self.denominator {
                out.remainder = (shifted - self.denominator) & self.divisor_mask;
                out.quotient = quotient | 1;
            } else {
                out.remainder = shifted & self.divisor_mask;
                out.quotient = quotient;
            }
            self.steps_left -= 1;
            if self.steps_left == 0 {
                out.busy = false;
                out.done = true;
            }
        } else if inputs.start {
            out.quotient = inputs.dividend & self.mask;
            out.remainder = 0;
            self.denominator = inputs.divisor & self.divisor_mask;
            self.steps_left = self.width;
            out.busy = true;
            out.divide_by_zero = self.denominator == 0;
        }
        if inputs.reset {
            *self = Self::new(self.width, self.divisor_bits);
        }
        self.out
    }
}

crate::lockstep_model!(SequentialDividerModel {
    inputs: SequentialDividerInputs,
    outputs: SequentialDividerOutputs,
    step: |model, inputs| model.step(*inputs),
});
