//! # `freq_divider`: runtime clock-enable generator
//!
//! Divides the system clock by a divisor written at run time and emits a
//! one-clock `strobe`: the time base (tick) of the DDA and of the other
//! interpolators. It is a clock *enable*, never a derived clock, so everything
//! downstream stays in the one clock domain.
//!
//! ## Ports (`W` = 32 in the exported `freq_divider`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! The divider counts enabled clocks (clock edges with `enable` high). The
//! strobe is registered: it is high during the clock after the enabled edge
//! that completes an interval. So a strobe can still be high in the first
//! clock in which `enable` is low (it belongs to the last enabled edge); no
//! edge with `enable` low ever produces one.
//!
//! Reset and power-up are the same state as seen from the ports (the two
//! control flip-flops are 0; the count and the latched D are not read again
//! before the next enabled edge reloads them), so a design that ties `reset`
//! low and relies on the FPGA's initial values behaves exactly like one that
//! resets.
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
//! ## Formal proof
//! `formal/freq_divider.sv` states the timing above as assertions on the
//! ports: no strobe after an edge in reset or with `enable` low; after
//! reset, a strobe at the first enabled edge with D != 0; then the next
//! strobe exactly D enabled edges later (D latched at the strobe), or, if
//! D = 0 there, at the first later enabled edge with D != 0. It assumes
//! nothing: every input is free at every clock. Proved by k-induction for
//! W = 4 and for the exported W = 32 (figures in the README's "What is
//! proved").
//!
//! ## Resources
//! The D of the interval in progress is latched at the interval's first edge
//! and compared for equality with an up-counter that restarts at 2. That
//! makes the end-of-interval flag a registered equality of two flip-flop
//! vectors (a LUT tree, no carry chain), and the restart the counter's own
//! synchronous set/reset, so the count needs one LUT per bit. A loadable
//! down-counter, the obvious design, needs two on iCE40 (the load
//! multiplexer cannot share the carry cell's LUT).
//!
//! The trade: the latched D is W flip-flops with no logic in front of them.
//! On iCE40 each takes a logic cell of its own (with a pass-through LUT that
//! yosys does not count as a LUT4): fewer LUT4 than the down-counter
//! design, a few more logic cells. The exported 32-bit module's figures
//! are its row in `rtl-out/synthesis-report.md`.

pub mod model;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "runtime clock-enable generator: one strobe every D enabled clocks";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: back to the power-up state after one clock",
    ),
    port(
        "enable",
        "1",
        "counting runs while high; while low the phase holds and no new strobe comes",
    ),
    port(
        "divisor",
        "W",
        "D: one strobe every D enabled clocks; 1 = every clock; 0 = stopped",
    ),
    port("strobe", "1", "one-clock pulse, registered"),
];

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Runtime clock-enable generator: one `strobe` every `divisor` enabled clocks.
/// See the [module documentation](self) for the datasheet.
///
/// `W` must be at least 2 (the count restarts at 2).
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
    /// The D of the interval in progress, taken at its first edge.
    latched_divisor: DFF<Bits<W>>,
    /// Enabled edges of the interval in progress, plus 1. It restarts at 2
    /// rather than 0 so that `count == latched_divisor` one edge early is
    /// exactly "the next edge ends the interval": the end test then reads
    /// only flip-flops, and the restart is the flip-flops' own synchronous
    /// set/reset (no load multiplexer in front of the increment).
    count: DFF<Bits<W>>,
    /// Registered "the next enabled edge does not end the interval". Stored in
    /// this sense so that power-up (all flip-flops 0) and reset give the same
    /// state: the next enabled edge starts an interval.
    mid_interval: DFF<Bit>,
    strobe_reg: DFF<Bit>,
    /// D <= 1: an interval starting now is a single clock (or none, D = 0).
    divisor_at_most_one: Signal<Local, Bit>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    two: Constant<Bits<W>>,
    /// All bits but bit 0: an equality test maps to a LUT tree, where `<=`
    /// would cost a second carry chain.
    high_bits: Constant<Bits<W>>,
}

impl<const W: usize> Default for FreqDivider<W> {
    fn default() -> Self {
        assert!(W >= 2, "FreqDivider needs W >= 2");
        let all_ones = if W >= 64 { u64::MAX } else { (1u64 << W) - 1 };
        Self {
            clock: Default::default(),
            reset: Default::default(),
            enable: Default::default(),
            divisor: Default::default(),
            strobe: Default::default(),
            latched_divisor: Default::default(),
            count: Default::default(),
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
        dff_setup!(
            self,
            clock,
            latched_divisor,
            count,
            mid_interval,
            strobe_reg
        );
        self.strobe.next = self.strobe_reg.q.val();
        self.divisor_at_most_one.next =
            (self.divisor.val() & self.high_bits.val()) == self.zero.val();
        self.strobe_reg.d.next = false;
        if self.enable.val() {
            if !self.mid_interval.q.val() {
                self.latched_divisor.d.next = self.divisor.val();
                self.count.d.next = self.two.val();
                self.mid_interval.d.next = !self.divisor_at_most_one.val();
                // D != 0, from the D <= 1 tree rather than a second one.
                self.strobe_reg.d.next =
                    !self.divisor_at_most_one.val() | self.divisor.val().get_bit(0);
            } else {
                self.count.d.next = self.count.q.val() + self.one.val();
                self.mid_interval.d.next = self.count.q.val() != self.latched_divisor.q.val();
            }
        }
        // count and latched_divisor are left alone: with mid_interval low
        // they are not read before the next edge reloads them.
        if self.reset.val() {
            self.mid_interval.d.next = false;
            self.strobe_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize] FreqDivider<W> {
    inputs: [reset, enable, divisor],
    outputs: [strobe],
});
