//! # `freq_divider`: runtime clock-enable generator
//!
//! Divides the system clock by a divisor written at run time and emits a
//! one-clock `strobe`: the time base (tick) of the DDA and of the other
//! interpolators. It is a clock *enable*, never a derived clock, so everything
//! downstream stays in the one clock domain.
//!
//! ## Ports (`W` = 32 in the exported `freq_divider`)
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous, active high: back to the power-up state after one clock |
//! | `enable` | in | 1 | counting runs while high; while low the phase holds and no new strobe comes |
//! | `divisor` | in | W | D: one strobe every D enabled clocks; 1 = every clock; 0 = stopped |
//! | `strobe` | out | 1 | one-clock pulse, registered |
//!
//! ## Timing
//! The divider counts enabled clocks (clock edges with `enable` high). The
//! strobe is registered: it is high during the clock after the enabled edge
//! that completes an interval. So a strobe can still be high in the first
//! clock in which `enable` is low (it belongs to the last enabled edge); no
//! edge with `enable` low ever produces one.
//!
//! Reset and power-up are the same state (every flip-flop 0), so a design
//! that ties `reset` low and relies on the FPGA's initial values behaves
//! exactly like one that resets.
//!
//! ```text
//! D = 3       edge:  1   2   3   4   5   6   7
//! enable       ____/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//! strobe       ________/‾‾‾\___________/‾‾‾\_______   (after edges 1, 4, 7)
//! ```
//!
//! * After reset (or after the divider was stopped with D = 0 and has run
//!   out), the first enabled edge with D != 0 strobes at once. Then strobes
//!   come every D enabled edges: with D constant and `enable` high they are
//!   exactly D clocks apart.
//! * A new D is loaded at each strobe, so it takes effect at the next strobe
//!   at the latest; the interval in progress keeps the old D. No interval is
//!   therefore shorter than the smaller of the old and the new D.
//! * `enable` low freezes the phase: the interval resumes where it stopped.
//!
//! ## Bad input
//! There is none: every divisor value is legal. D = 0 stops the strobes; the
//! interval in progress runs out silently and the divider then waits, parked,
//! for a non-zero D (which strobes at the next enabled edge).
//!
//! An interval in progress always completes with the D it started with. A
//! mistakenly huge D (up to 2^W - 1 clocks, 43 s at 100 MHz for W = 32) can
//! therefore only be cut short by `reset`.
//!
//! ## Resources
//! A W-bit down-counter with a reload mux and a registered end-of-interval
//! flag, so the reload select comes straight from a flip-flop and the only
//! carry chain is the decrement. D is never compared by magnitude: the
//! control needs only equality tests (D <= 1, D != 0, counter == 2), which
//! map to LUT trees. Figures for the exported 32-bit module are in
//! `rtl-out/synthesis-report.md`.

pub mod model;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "runtime clock-enable generator: one strobe every D enabled clocks";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[(&str, &str)] = &[
    ("clock", "rising-edge clock"),
    ("reset", "synchronous reset, active high"),
    (
        "enable",
        "counting runs while high; while low the phase holds and no strobe comes",
    ),
    (
        "divisor",
        "D: one strobe every D enabled clocks; 1 = every clock; 0 = stopped",
    ),
    ("strobe", "one-clock strobe, registered"),
];

use rust_hdl::prelude::*;

/// Runtime clock-enable generator: one `strobe` every `divisor` enabled clocks.
/// See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct FreqDivider<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Counting runs while high.
    pub enable: Signal<In, Bit>,
    /// D: one strobe every D enabled clocks; 0 stops the divider.
    pub divisor: Signal<In, Bits<W>>,
    /// One-clock strobe.
    pub strobe: Signal<Out, Bit>,
    /// Enabled clocks left in the current interval, counting down to 1.
    remaining: DFF<Bits<W>>,
    /// Registered `remaining > 1`: the next enabled clock does not end the
    /// interval. A flip-flop takes the zero test off the reload path; it is
    /// stored in this sense so that power-up (all flip-flops 0) and reset
    /// give the same state.
    mid_interval: DFF<Bit>,
    strobe_reg: DFF<Bit>,
    /// D <= 1 (the next interval is a single clock).
    divisor_at_most_one: Signal<Local, Bit>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    two: Constant<Bits<W>>,
    /// All bits but bit 0: equality tests map to LUT trees, where `<=`
    /// would cost a second carry chain.
    high_bits: Constant<Bits<W>>,
}

impl<const W: usize> Default for FreqDivider<W> {
    fn default() -> Self {
        let all_ones = if W >= 64 { u64::MAX } else { (1u64 << W) - 1 };
        Self {
            clock: Default::default(),
            reset: Default::default(),
            enable: Default::default(),
            divisor: Default::default(),
            strobe: Default::default(),
            remaining: Default::default(),
            mid_interval: Default::default(),
            strobe_reg: Default::default(),
            divisor_at_most_one: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            two: Constant::new(2u64.into()),
            high_bits: Constant::new((all_ones & !1).into()),
        }
    }
}

impl<const W: usize> Logic for FreqDivider<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, remaining, mid_interval, strobe_reg);
        self.strobe.next = self.strobe_reg.q.val();
        self.divisor_at_most_one.next =
            (self.divisor.val() & self.high_bits.val()) == self.zero.val();
        self.strobe_reg.d.next = false;
        if self.enable.val() {
            if !self.mid_interval.q.val() {
                self.remaining.d.next = self.divisor.val();
                self.mid_interval.d.next = !self.divisor_at_most_one.val();
                self.strobe_reg.d.next = self.divisor.val() != self.zero.val();
            } else {
                self.remaining.d.next = self.remaining.q.val() - self.one.val();
                self.mid_interval.d.next = self.remaining.q.val() != self.two.val();
            }
        }
        if self.reset.val() {
            self.remaining.d.next = self.zero.val();
            self.mid_interval.d.next = false;
            self.strobe_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize] FreqDivider<W> {
    inputs: [reset, enable, divisor],
    outputs: [strobe],
});
