//! # `sequential_divider`: unsigned W-bit divider, one quotient bit per clock
//!
//! rust-hdl has no `/`, and a combinational 32-bit divider would not close
//! timing anyway. This block computes `dividend / divisor` and
//! `dividend % divisor` by restoring division in W clocks, for blocks that
//! need a division now and then (the uniform pulse generator computes its
//! pulse periods with it, one period ahead).
//!
//! ## Ports (`W` = 32 in the exported `sequential_divider`)
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous, active high: idle, outputs 0 |
//! | `start` | in | 1 | start a division of `dividend` by `divisor` (sampled only while `busy` is low) |
//! | `dividend` | in | W | unsigned dividend, sampled with `start` |
//! | `divisor` | in | W | unsigned divisor, sampled with `start` |
//! | `busy` | out | 1 | a division is running; `start` is ignored |
//! | `done` | out | 1 | one-clock strobe: `quotient`, `remainder` and `divide_by_zero` are valid |
//! | `quotient` | out | W | `dividend / divisor`; valid from `done` until the next `start` |
//! | `remainder` | out | W | `dividend % divisor`; valid from `done` until the next `start` |
//! | `divide_by_zero` | out | 1 | the divisor was 0; valid with the result |
//!
//! ## Timing
//! ```text
//! edge:      s   s+1  ...  s+W   s+W+1
//! start    ‾‾‾\______________________        (sampled at edge s, busy low)
//! busy     ____/‾‾‾‾‾‾‾‾‾‾‾‾‾\_______        high after edges s .. s+W-1
//! done     __________________/‾‾‾\___        high for the clock after edge s+W
//! ```
//! Latency from the start edge to `done`: W + 1 clocks (33 for W = 32).
//! `start` may be high in the `done` cycle: the next division begins at once,
//! so back-to-back divisions take W + 1 clocks each.
//!
//! ## Bad input
//! * Divisor 0: the division runs its W clocks as usual and gives the
//!   restoring algorithm's natural result, `quotient` = all ones (the
//!   largest value) and `remainder` = `dividend`, with `divide_by_zero` set.
//! * `start` while `busy`: ignored; the running division is not disturbed.
//!   `busy` is the handshake: issue `start` only while it is low.
//! * While `busy`, `quotient` and `remainder` show intermediate values.
//!
//! ## Structure
//! Shift registers for the partial remainder and the quotient, one W-bit
//! subtractor and comparator, and an 8-bit step counter (W <= 64).

pub mod model;

use rust_hdl::prelude::*;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "unsigned W-bit restoring divider: quotient and remainder in W+1 clocks";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[(&str, &str)] = &[
    ("clock", "rising-edge clock"),
    ("reset", "synchronous reset, active high: idle, outputs 0"),
    ("start", "start a division (sampled only while busy is low)"),
    ("dividend", "unsigned dividend, sampled with start"),
    ("divisor", "unsigned divisor, sampled with start"),
    ("busy", "a division is running; start is ignored"),
    (
        "done",
        "one-clock strobe: quotient, remainder and divide_by_zero are valid",
    ),
    (
        "quotient",
        "dividend / divisor; valid from done until the next start",
    ),
    (
        "remainder",
        "dividend % divisor; valid from done until the next start",
    ),
    (
        "divide_by_zero",
        "the divisor was 0 (quotient all ones, remainder = dividend)",
    ),
];

/// Unsigned restoring divider. See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct SequentialDivider<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Start a division.
    pub start: Signal<In, Bit>,
    /// Unsigned dividend.
    pub dividend: Signal<In, Bits<W>>,
    /// Unsigned divisor.
    pub divisor: Signal<In, Bits<W>>,
    /// A division is running.
    pub busy: Signal<Out, Bit>,
    /// The result is valid (one-clock strobe).
    pub done: Signal<Out, Bit>,
    /// `dividend / divisor`.
    pub quotient: Signal<Out, Bits<W>>,
    /// `dividend % divisor`.
    pub remainder: Signal<Out, Bits<W>>,
    /// The divisor was 0.
    pub divide_by_zero: Signal<Out, Bit>,
    /// Dividend bits not yet consumed (high end) and quotient bits (low end).
    shift: DFF<Bits<W>>,
    partial: DFF<Bits<W>>,
    denominator: DFF<Bits<W>>,
    steps_left: DFF<Bits<8>>,
    running: DFF<Bit>,
    finished: DFF<Bit>,
    by_zero: DFF<Bit>,
    /// The partial remainder shifted left with the next dividend bit, low W bits.
    shifted: Signal<Local, Bits<W>>,
    /// Bit W of the shifted remainder: set means it exceeds any divisor.
    shifted_overflows: Signal<Local, Bit>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    msb: Constant<Bits<W>>,
    width: Constant<Bits<8>>,
    one_step: Constant<Bits<8>>,
    no_steps: Constant<Bits<8>>,
}

impl<const W: usize> Default for SequentialDivider<W> {
    fn default() -> Self {
        assert!(
            (2..=64).contains(&W),
            "SequentialDivider width must be 2..=64"
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
            denominator: Default::default(),
            steps_left: Default::default(),
            running: Default::default(),
            finished: Default::default(),
            by_zero: Default::default(),
            shifted: Default::default(),
            shifted_overflows: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            msb: Constant::new((1u64 << (W - 1)).into()),
            width: Constant::new((W as u64).into()),
            one_step: Constant::new(1u64.into()),
            no_steps: Constant::new(0u64.into()),
        }
    }
}

impl<const W: usize> Logic for SequentialDivider<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            shift,
            partial,
            denominator,
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
            self.shifted.next = (self.partial.q.val() << 1) | self.one.val();
        }
        self.shifted_overflows.next = (self.partial.q.val() & self.msb.val()) != self.zero.val();
        self.finished.d.next = false;
        if self.running.q.val() {
            // `shifted < denominator` keeps the operand order of the
            // subtraction, so yosys computes both on one carry chain.
            if !self.shifted_overflows.val() & (self.shifted.val() < self.denominator.q.val()) {
                self.partial.d.next = self.shifted.val();
                self.shift.d.next = self.shift.q.val() << 1;
            } else {
                self.partial.d.next = self.shifted.val() - self.denominator.q.val();
                self.shift.d.next = (self.shift.q.val() << 1) | self.one.val();
            }
            self.steps_left.d.next = self.steps_left.q.val() - self.one_step.val();
            if self.steps_left.q.val() == self.one_step.val() {
                self.running.d.next = false;
                self.finished.d.next = true;
            }
        } else if self.start.val() {
            self.shift.d.next = self.dividend.val();
            self.partial.d.next = self.zero.val();
            self.denominator.d.next = self.divisor.val();
            self.steps_left.d.next = self.width.val();
            self.running.d.next = true;
            self.by_zero.d.next = self.divisor.val() == self.zero.val();
        }
        if self.reset.val() {
            self.shift.d.next = self.zero.val();
            self.partial.d.next = self.zero.val();
            self.denominator.d.next = self.zero.val();
            self.steps_left.d.next = self.no_steps.val();
            self.running.d.next = false;
            self.finished.d.next = false;
            self.by_zero.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize] SequentialDivider<W> {
    inputs: [reset, start, dividend, divisor],
    outputs: [busy, done, quotient, remainder, divide_by_zero],
});
