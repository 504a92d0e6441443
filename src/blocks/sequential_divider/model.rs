//! Reference model of [`super::SequentialDivider`], cycle-exact, and the
//! arithmetic it must produce.

/// The result a division must give: `(quotient, remainder, divide_by_zero)`.
/// Divisor 0 gives all ones and the dividend (the restoring algorithm's result).
pub fn expected_result(dividend: u64, divisor: u64, width: u32) -> (u64, u64, bool) {
    let mask = if width == 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    let (dividend, divisor) = (dividend & mask, divisor & mask);
    if divisor == 0 {
        (mask, dividend, true)
    } else {
        (dividend / divisor, dividend % divisor, false)
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

/// Plain-Rust, cycle-exact model of a `width`-bit sequential divider.
#[derive(Clone, Debug)]
pub struct SequentialDividerModel {
    width: u32,
    mask: u64,
    steps_left: u32,
    denominator: u64,
    out: SequentialDividerOutputs,
}

impl SequentialDividerModel {
    /// A divider of `width` bits (2 to 63), idle.
    pub fn new(width: u32) -> Self {
        assert!((2..=63).contains(&width), "model width must be 2..=63");
        Self {
            width,
            mask: (1u64 << width) - 1,
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
                out.remainder = (shifted - self.denominator) & self.mask;
                out.quotient = quotient | 1;
            } else {
                out.remainder = shifted & self.mask;
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
            self.denominator = inputs.divisor & self.mask;
            self.steps_left = self.width;
            out.busy = true;
            out.divide_by_zero = self.denominator == 0;
        }
        if inputs.reset {
            *self = Self::new(self.width);
        }
        self.out
    }
}
