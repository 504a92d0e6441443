//! The FIFO entry as the axes store it, and the converter that makes it.
//!
//! The bus writes a 32-bit signed entry w. The interpolators use only |w|
//! saturated to 16 bits and its sign, and the DAC uses w as a 16-bit signed
//! code. So the controller converts each written word once, for every
//! axis, before the FIFOs ([`EntryConverter`]), and the axes store
//! [`ENTRY_BITS`] instead of 32:
//!
//! | bits | meaning |
//! |------|---------|
//! | 15..0 | \|w\| saturated to 2^16 - 1 |
//! | 16 ([`ENTRY_TOO_LARGE`]) | \|w\| > 2^16 - 1 (bits 15..0 saturated) |
//! | 17 ([`ENTRY_SIGN`]) | w < 0 |
//! | 18 ([`ENTRY_CODE_WIDE`]) | w does not fit 16 bits signed (the DAC code saturates) |
//! | 19 ([`ENTRY_NONZERO`]) | w != 0 |
//!
//! The DAC code is the magnitude with the sign put back, once for all
//! axes, after the controller's DAC walk.
//!
//! Internal to [`super::MotionController`]: its behavior at the pins is the
//! controller's, modelled by [`super::model`]; [`entry_of`] is the format's
//! model, which the converter's tests compare it with.
//!
//! ## Converter timing
//! Combinational: `entry` follows `word` in the same clock (no flip-flop).
//! Every 32-bit word has a defined entry; none is refused here.

use rust_hdl::prelude::*;

use crate::blocks::motion_controller::PERIOD_BITS;

/// Width of a FIFO entry as the axes store it (see the table above).
pub const ENTRY_BITS: usize = 20;
/// Entry flag: |w| > 2^16 - 1 (the magnitude is saturated).
pub const ENTRY_TOO_LARGE: usize = 16;
/// Entry flag: w < 0.
pub const ENTRY_SIGN: usize = 17;
/// Entry flag: w does not fit 16 bits signed (the DAC code saturates).
pub const ENTRY_CODE_WIDE: usize = 18;
/// Entry flag: w != 0.
pub const ENTRY_NONZERO: usize = 19;

// The literal bit numbers in the axis's `update()` and in the converter's.
const _: () = {
    assert!(PERIOD_BITS == 16);
    assert!(ENTRY_TOO_LARGE == 16 && ENTRY_SIGN == 17);
    assert!(ENTRY_CODE_WIDE == 18 && ENTRY_NONZERO == 19 && ENTRY_BITS == 20);
};

/// The format's model: the entry the axes store for the bus word `w`.
pub fn entry_of(w: i32) -> u32 {
    let magnitude = w.unsigned_abs();
    let mut entry = magnitude.min(0xffff);
    if magnitude > 0xffff {
        entry |= 1 << ENTRY_TOO_LARGE;
    }
    if w < 0 {
        entry |= 1 << ENTRY_SIGN;
    }
    if i16::try_from(w).is_err() {
        entry |= 1 << ENTRY_CODE_WIDE;
    }
    if w != 0 {
        entry |= 1 << ENTRY_NONZERO;
    }
    entry
}

/// Converts a bus word to a FIFO entry. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct EntryConverter {
    /// The bus word, a 32-bit signed entry.
    pub word: Signal<In, Bits<32>>,
    /// Its FIFO entry.
    pub entry: Signal<Out, Bits<ENTRY_BITS>>,
    /// Bits 31..16 all 0 / all 1, bits 15..0 and whether they are 0, too
    /// large for 16 bits unsigned, and the magnitude saturated.
    upper_zero: Signal<Local, Bit>,
    upper_ones: Signal<Local, Bit>,
    low: Signal<Local, Bits<PERIOD_BITS>>,
    low_nonzero: Signal<Local, Bit>,
    too_large: Signal<Local, Bit>,
    magnitude: Signal<Local, Bits<PERIOD_BITS>>,
    /// Bits 31..16 of a bus word.
    upper_half: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    zero_p: Constant<Bits<PERIOD_BITS>>,
    max_p: Constant<Bits<PERIOD_BITS>>,
    zero_entry: Constant<Bits<ENTRY_BITS>>,
    /// `entry_bit[b]` = 1 << b.
    entry_bit: [Constant<Bits<ENTRY_BITS>>; ENTRY_BITS],
}

impl Default for EntryConverter {
    fn default() -> Self {
        Self {
            word: Default::default(),
            entry: Default::default(),
            upper_zero: Default::default(),
            upper_ones: Default::default(),
            low: Default::default(),
            low_nonzero: Default::default(),
            too_large: Default::default(),
            magnitude: Default::default(),
            upper_half: Constant::new(0xffff_0000u64.into()),
            zero32: Constant::new(0u64.into()),
            zero_p: Constant::new(0u64.into()),
            max_p: Constant::new(crate::blocks::width_mask(PERIOD_BITS as u32).into()),
            zero_entry: Constant::new(0u64.into()),
            entry_bit: array_init::array_init(|b| Constant::new((1u64 << b).into())),
        }
    }
}

impl Logic for EntryConverter {
    #[hdl_gen]
    fn update(&mut self) {
        // Too large is decided on the upper half alone (and -2^16 itself),
        // and only the lower half is negated.
        self.upper_zero.next = (self.word.val() & self.upper_half.val()) == self.zero32.val();
        self.upper_ones.next = (self.word.val() & self.upper_half.val()) == self.upper_half.val();
        self.low.next = self.word.val().get_bits::<PERIOD_BITS>(0);
        self.low_nonzero.next = self.low.val() != self.zero_p.val();
        if self.word.val().get_bit(31) {
            self.too_large.next = !self.upper_ones.val() | !self.low_nonzero.val();
            self.magnitude.next = self.zero_p.val() - self.low.val();
        } else {
            self.too_large.next = !self.upper_zero.val();
            self.magnitude.next = self.low.val();
        }
        if self.too_large.val() {
            self.magnitude.next = self.max_p.val();
        }
        // (Bit by bit: rust-hdl has no widening that Verilator reads
        // without a width warning.)
        self.entry.next = self.zero_entry.val();
        for b in 0..PERIOD_BITS {
            if self.magnitude.val().get_bit(b) {
                self.entry.next = self.entry.val() | self.entry_bit[b].val();
            }
        }
        if self.too_large.val() {
            self.entry.next = self.entry.val() | self.entry_bit[16].val();
        }
        if self.word.val().get_bit(31) {
            self.entry.next = self.entry.val() | self.entry_bit[17].val();
        }
        // Bits 31..15 not all equal.
        if !((self.upper_zero.val() & !self.low.val().get_bit(15))
            | (self.upper_ones.val() & self.low.val().get_bit(15)))
        {
            self.entry.next = self.entry.val() | self.entry_bit[18].val();
        }
        if !self.upper_zero.val() | self.low_nonzero.val() {
            self.entry.next = self.entry.val() | self.entry_bit[19].val();
        }
    }
}
