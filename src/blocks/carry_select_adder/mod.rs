//! # `CarrySelectAdder`: a + b + 1 with its carry out, in half the chain delay
//!
//! An internal building block (not exported on its own): the accumulator of
//! the DDA and the partial remainder of the divider each decide on the carry
//! out of a W-bit `a + !c + 1` (that is, `a - c` and `a >= c`) every clock,
//! and that carry chain is their critical path. This block splits the sum at
//! bit W/2: the low half and the high half for both possible carries out of
//! the low half are computed in parallel, and the low half's carry selects
//! one. The longest carry chain is then about W/2 bits, for about W/2 extra
//! LUT4s.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! Purely combinational: no clock, no state, defined for every input.

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("a", "W", "first operand"),
    port("b", "W", "second operand (for a subtraction a - c, b = !c)"),
    port("sum", "W", "(a + b + 1) mod 2^W, combinational"),
    port(
        "carry_out",
        "1",
        "carry out of bit W - 1; for b = !c it is `a >= c`",
    ),
];

/// `a + b + 1` with its carry out, as a carry-select adder split at W/2.
#[derive(Clone, Debug, LogicBlock)]
pub struct CarrySelectAdder<const W: usize> {
    /// First operand.
    pub a: Signal<In, Bits<W>>,
    /// Second operand.
    pub b: Signal<In, Bits<W>>,
    /// (a + b + 1) mod 2^W.
    pub sum: Signal<Out, Bits<W>>,
    /// Carry out of the most significant bit.
    pub carry_out: Signal<Out, Bit>,
    low_sum: Signal<Local, Bits<W>>,
    high_sum_carry0: Signal<Local, Bits<W>>,
    high_sum_carry1: Signal<Local, Bits<W>>,
    carry_mid: Signal<Local, Bit>,
    carry_out0: Signal<Local, Bit>,
    carry_out1: Signal<Local, Bit>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    msb: Constant<Bits<W>>,
    low_half: Constant<Bits<W>>,
    high_half: Constant<Bits<W>>,
    mid_bit: Constant<Bits<W>>,
}

impl<const W: usize> Default for CarrySelectAdder<W> {
    fn default() -> Self {
        assert!(
            (2..=63).contains(&W),
            "CarrySelectAdder supports 2 to 63 bits"
        );
        let low_half = (1u64 << (W / 2)) - 1;
        Self {
            a: Default::default(),
            b: Default::default(),
            sum: Default::default(),
            carry_out: Default::default(),
            low_sum: Default::default(),
            high_sum_carry0: Default::default(),
            high_sum_carry1: Default::default(),
            carry_mid: Default::default(),
            carry_out0: Default::default(),
            carry_out1: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            msb: Constant::new((1u64 << (W - 1)).into()),
            low_half: Constant::new(low_half.into()),
            high_half: Constant::new((crate::blocks::width_mask(W as u32) & !low_half).into()),
            mid_bit: Constant::new((1u64 << (W / 2)).into()),
        }
    }
}

impl<const W: usize> Logic for CarrySelectAdder<W> {
    #[hdl_gen]
    fn update(&mut self) {
        // The low half, with the carry into bit W/2 left in that bit.
        self.low_sum.next = (self.a.val() & self.low_half.val())
            + (self.b.val() & self.low_half.val())
            + self.one.val();
        self.carry_mid.next = (self.low_sum.val() & self.mid_bit.val()) != self.zero.val();
        self.high_sum_carry0.next =
            (self.a.val() & self.high_half.val()) + (self.b.val() & self.high_half.val());
        // Low bits all ones plus one: the same high half with a carry in,
        // written differently so that synthesis does not chain it behind
        // the carry-0 sum.
        self.high_sum_carry1.next = (self.a.val() | self.low_half.val())
            + (self.b.val() & self.high_half.val())
            + self.one.val();
        // Carry out of the MSB: a&b | (a^b)&!sum. (rust-hdl prints operators
        // flat, so every mixed expression is fully parenthesized.)
        self.carry_out0.next = (((self.a.val() & self.b.val())
            | ((self.a.val() ^ self.b.val()) & !self.high_sum_carry0.val()))
            & self.msb.val())
            != self.zero.val();
        self.carry_out1.next = (((self.a.val() & self.b.val())
            | ((self.a.val() ^ self.b.val()) & !self.high_sum_carry1.val()))
            & self.msb.val())
            != self.zero.val();
        if self.carry_mid.val() {
            self.sum.next = (self.low_sum.val() & self.low_half.val()) | self.high_sum_carry1.val();
            self.carry_out.next = self.carry_out1.val();
        } else {
            self.sum.next = (self.low_sum.val() & self.low_half.val()) | self.high_sum_carry0.val();
            self.carry_out.next = self.carry_out0.val();
        }
    }
}
