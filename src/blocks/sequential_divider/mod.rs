//! # `sequential_divider`: unsigned N-bit by D-bit divider, one quotient bit per clock
//!
//! rust-hdl has no `/`, and a combinational 32-bit divider would not close
//! timing anyway. This block computes `dividend / divisor` and
//! `dividend % divisor` by restoring division, one quotient bit per clock,
//! for blocks that need a division now and then: the DDA interpolator
//! splits each period's step count with it, and the uniform pulse generator
//! will compute its pulse periods with it, one period ahead.
//!
//! ## Ports (`N` = `D` = 32 in the exported `sequential_divider`)
//! The dividend and quotient are N bits wide, the divisor and remainder D
//! bits (D <= N). The remainder is below the divisor, so the subtractor is
//! only D bits long: a narrow divisor makes a faster divider.
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! ```text
//! edge:      s   s+1  ...  s+N   s+N+1
//! start    ‾‾‾\______________________        (sampled at edge s, busy low)
//! busy     ____/‾‾‾‾‾‾‾‾‾‾‾‾‾\_______        high after edges s .. s+N-1
//! done     __________________/‾‾‾\___        high for the clock after edge s+N
//! ```
//! `start` is sampled at edge s; `done` is high in the clock after edge
//! s + N, that is N clocks after the start edge (32 for N = 32), with the
//! result valid from then until the next start. `start` may be high in the
//! `done` cycle: the next division begins at once, so back-to-back divisions
//! take N + 1 clocks each.
//!
//! ## Bad input
//! * Divisor 0: the division runs its N clocks as usual and gives the
//!   restoring algorithm's natural result, `quotient` = all ones (the
//!   largest value) and `remainder` = the low D bits of `dividend`, with
//!   `divide_by_zero` set.
//! * `start` while `busy`: ignored; the running division is not disturbed.
//!   `busy` is the handshake: issue `start` only while it is low.
//! * While `busy`, `quotient` and `remainder` show intermediate values.
//!
//! ## Structure
//! Shift registers for the partial remainder (D bits) and the quotient (N
//! bits), one D-bit carry-select subtractor whose carry out is the
//! comparison, and an 8-bit step counter (2 <= D <= N <= 63).

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::carry_select_adder::CarrySelectAdder;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "unsigned N-by-D-bit restoring divider: quotient and remainder N clocks after start";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: idle, outputs 0"),
    port(
        "start",
        "1",
        "start a division of `dividend` by `divisor` (sampled only while `busy` is low)",
    ),
    port("dividend", "N", "unsigned dividend, sampled with `start`"),
    port("divisor", "D", "unsigned divisor, sampled with `start`"),
    port("busy", "1", "a division is running; `start` is ignored"),
    port(
        "done",
        "1",
        "one-clock strobe: `quotient`, `remainder` and `divide_by_zero` are valid",
    ),
    port(
        "quotient",
        "N",
        "`dividend / divisor`; valid from `done` until the next `start`",
    ),
    port(
        "remainder",
        "D",
        "`dividend % divisor`; valid from `done` until the next `start`",
    ),
    port(
        "divide_by_zero",
        "1",
        "the divisor was 0 (quotient all ones, remainder = dividend); valid with the result",
    ),
];

/// Unsigned restoring divider. See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct SequentialDivider<const N: usize, const D: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Start a division.
    pub start: Signal<In, Bit>,
    /// Unsigned dividend.
    pub dividend: Signal<In, Bits<N>>,
    /// Unsigned divisor.
    pub divisor: Signal<In, Bits<D>>,
    /// A division is running.
    pub busy: Signal<Out, Bit>,
    /// The result is valid (one-clock strobe).
    pub done: Signal<Out, Bit>,
    /// `dividend / divisor`.
    pub quotient: Signal<Out, Bits<N>>,
    /// `dividend % divisor`.
    pub remainder: Signal<Out, Bits<D>>,
    /// The divisor was 0.
    pub divide_by_zero: Signal<Out, Bit>,
    /// Dividend bits not yet consumed (high end) and quotient bits (low end).
    shift: DFF<Bits<N>>,
    partial: DFF<Bits<D>>,
    /// The divisor, stored inverted: shifted - d = shifted + !d + 1 needs no
    /// inverters in front of the carry chain.
    denominator_inverted: DFF<Bits<D>>,
    steps_left: DFF<Bits<8>>,
    running: DFF<Bit>,
    finished: DFF<Bit>,
    by_zero: DFF<Bit>,
    /// The partial remainder shifted left with the next dividend bit, low D bits.
    shifted: Signal<Local, Bits<D>>,
    /// Bit D of the shifted remainder: set means it exceeds any divisor.
    shifted_overflows: Signal<Local, Bit>,
    /// shifted + !divisor + 1: the difference, and in its carry out
    /// `shifted >= divisor`; a carry-select adder halves the loop's chain.
    subtractor: CarrySelectAdder<D>,
    zero: Constant<Bits<N>>,
    one: Constant<Bits<N>>,
    msb: Constant<Bits<N>>,
    zero_d: Constant<Bits<D>>,
    one_d: Constant<Bits<D>>,
    msb_d: Constant<Bits<D>>,
    width: Constant<Bits<8>>,
    one_step: Constant<Bits<8>>,
    no_steps: Constant<Bits<8>>,
}

impl<const N: usize, const D: usize> Default for SequentialDivider<N, D> {
    fn default() -> Self {
        // 64 bits would need a 65-bit model; no block needs it.
        assert!(
            2 <= D && D <= N && N <= 63,
            "SequentialDivider needs 2 <= D <= N <= 63"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            dividend: Default::default(),
            divisor: Default::default(),
            busy: Default::default(),
            done: Default::default(),
            quotient: Default::default(),
            remainder: Default::default(),
            divide_by_zero: Default::default(),
            shift: Default::default(),
            partial: Default::default(),
            denominator_inverted: Default::default(),
            steps_left: Default::default(),
            running: Default::default(),
            finished: Default::default(),
            by_zero: Default::default(),
            shifted: Default::default(),
            shifted_overflows: Default::default(),
            subtractor: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            msb: Constant::new((1u64 << (N - 1)).into()),
            zero_d: Constant::new(0u64.into()),
            one_d: Constant::new(1u64.into()),
            msb_d: Constant::new((1u64 << (D - 1)).into()),
            width: Constant::new((N as u64).into()),
            one_step: Constant::new(1u64.into()),
            no_steps: Constant::new(0u64.into()),
        }
    }
}

impl<const N: usize, const D: usize> Logic for SequentialDivider<N, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            shift,
            partial,
            denominator_inverted,
            steps_left,
            running,
            finished,
            by_zero
        );
        self.busy.next = self.running.q.val();
        self.done.next = self.finished.q.val();
        self.quotient.next = self.shift.q.val();
        self.remainder.next = self.partial.q.val();
        self.divide_by_zero.next = self.by_zero.q.val();
        // Shifts are wiring; `x + x` would cost a carry chain each.
        self.shifted.next = self.partial.q.val() << 1;
        if (self.shift.q.val() & self.msb.val()) != self.zero.val() {
            self.shifted.next = (self.partial.q.val() << 1) | self.one_d.val();
        }
        self.shifted_overflows.next =
            (self.partial.q.val() & self.msb_d.val()) != self.zero_d.val();
        self.subtractor.a.next = self.shifted.val();
        self.subtractor.b.next = self.denominator_inverted.q.val();
        self.finished.d.next = false;
        if self.running.q.val() {
            // The subtractor's carry out says whether the divisor fits.
            if self.subtractor.carry_out.val() | self.shifted_overflows.val() {
                self.partial.d.next = self.subtractor.sum.val();
                self.shift.d.next = (self.shift.q.val() << 1) | self.one.val();
            } else {
                self.partial.d.next = self.shifted.val();
                self.shift.d.next = self.shift.q.val() << 1;
            }
            self.steps_left.d.next = self.steps_left.q.val() - self.one_step.val();
            if self.steps_left.q.val() == self.one_step.val() {
                self.running.d.next = false;
                self.finished.d.next = true;
            }
        } else if self.start.val() {
            self.shift.d.next = self.dividend.val();
            self.partial.d.next = self.zero_d.val();
            self.denominator_inverted.d.next = !self.divisor.val();
            self.steps_left.d.next = self.width.val();
            self.running.d.next = true;
            self.by_zero.d.next = self.divisor.val() == self.zero_d.val();
        }
        if self.reset.val() {
            self.shift.d.next = self.zero.val();
            self.partial.d.next = self.zero_d.val();
            self.denominator_inverted.d.next = !self.zero_d.val();
            self.steps_left.d.next = self.no_steps.val();
            self.running.d.next = false;
            self.finished.d.next = false;
            self.by_zero.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const N: usize, const D: usize] SequentialDivider<N, D> {
    inputs: [reset, start, dividend, divisor],
    outputs: [busy, done, quotient, remainder, divide_by_zero],
});
