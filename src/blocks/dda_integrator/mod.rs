//! # `dda_integrator`: one DDA axis (integrand J, modulus M)
//!
//! The classic digital differential analyzer: on each `tick` the accumulator
//! adds J; each time it reaches the modulus M it wraps (subtracts M) and
//! emits one `pulse`. After t ticks exactly floor(t * J / M) pulses have come
//! out (from reset), spaced floor(M/J) or ceil(M/J) ticks apart: a Bresenham
//! distribution. The accumulator is never cleared by the block itself, so a
//! fractional remainder carries over from one use to the next.
//!
//! ## Ports (`W` = 32 in the exported `dda_integrator`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! J and M are sampled together with `tick` at the same rising edge, so a
//! tick always uses the J and M present with it. The pulse of a tick sampled
//! at edge t is high in the clock after edge t + 1 (latency 2, fixed, for
//! every tick). Ticks may come on every clock.
//!
//! ```text
//! edge:    t    t+1   t+2
//! tick   _/‾‾\_______________
//! pulse  __________/‾‾‾\_____      (if that tick overflows)
//! ```
//!
//! ## Arithmetic
//! On each tick, with s = acc + J computed without losing the carry: if
//! s >= M then acc <- s - M and a pulse is emitted, else acc <- s. The RTL
//! computes this as `acc >= M - J` (the input stage registers K = M - J, and
//! a flag for J > M), so the input stage and the accumulator loop are each
//! one carry chain deep.
//!
//! ## Bad input
//! * J > M (M != 0): J is treated as M, so every tick pulses, and the sticky
//!   `overrange` is set. It stays set until `clear_overrange` or `reset`.
//! * J = 0: never pulses (also with M = 0, which would otherwise mean
//!   "J = 2^W - 0").
//! * M lowered below the accumulator: the accumulated phase is not thrown
//!   away. Ticks pulse and remove M - J each until the accumulator is below
//!   M - J again, then the normal distribution resumes.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::carry_select_adder::CarrySelectAdder;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "DDA integrator: exactly floor(t*J/M) evenly spread pulses after t ticks";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: accumulator 0, flags 0, pipeline empty",
    ),
    port(
        "tick",
        "1",
        "accumulate enable (for example a `freq_divider` strobe)",
    ),
    port("integrand", "W", "J, sampled with `tick`"),
    port(
        "modulus",
        "W",
        "M, sampled with `tick`; 0 means 2^W (the binary DDA)",
    ),
    port(
        "clear_overrange",
        "1",
        "clears `overrange` (tie to 0 if unused)",
    ),
    port(
        "pulse",
        "1",
        "one-clock pulse per accumulator overflow, 2 clocks after its tick",
    ),
    port(
        "overrange",
        "1",
        "sticky: a tick was processed with J > M (M != 0)",
    ),
];

/// DDA integrator. See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct DdaIntegrator<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Accumulate enable.
    pub tick: Signal<In, Bit>,
    /// J.
    pub integrand: Signal<In, Bits<W>>,
    /// M; 0 means 2^W.
    pub modulus: Signal<In, Bits<W>>,
    /// Clears `overrange`.
    pub clear_overrange: Signal<In, Bit>,
    /// One pulse per overflow.
    pub pulse: Signal<Out, Bit>,
    /// Sticky: J > M was used.
    pub overrange: Signal<Out, Bit>,
    // Input stage: the tick with its J and K = M - J.
    ticked: DFF<Bit>,
    step: DFF<Bits<W>>,
    /// !K = !(M - J): stored inverted so that acc - K = acc + !K + 1 needs
    /// no inverter in front of the accumulator's carry chain.
    back_inverted: DFF<Bits<W>>,
    /// J > M: every tick pulses and the accumulator holds. A flag instead
    /// of muxing M into J keeps the input stage one carry chain deep.
    saturated: DFF<Bit>,
    // Accumulator stage.
    acc: DFF<Bits<W>>,
    pulse_reg: DFF<Bit>,
    overrange_reg: DFF<Bit>,
    /// M - J (wrapping: 2^W - J when M = 0).
    headroom: Signal<Local, Bits<W>>,
    /// J > M with M != 0.
    too_large: Signal<Local, Bit>,
    /// acc - K, the accumulator after an overflow.
    wrapped: Signal<Local, Bits<W>>,
    /// acc + !K + 1 = acc - K, with the carry out meaning acc >= K; a
    /// carry-select adder halves the loop's carry chain.
    subtractor: CarrySelectAdder<W>,
    /// The accumulator stays below K: no pulse on this tick.
    below: Signal<Local, Bit>,
    zero: Constant<Bits<W>>,
    msb: Constant<Bits<W>>,
}

impl<const W: usize> Default for DdaIntegrator<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            integrand: Default::default(),
            modulus: Default::default(),
            clear_overrange: Default::default(),
            pulse: Default::default(),
            overrange: Default::default(),
            ticked: Default::default(),
            step: Default::default(),
            back_inverted: Default::default(),
            saturated: Default::default(),
            acc: Default::default(),
            pulse_reg: Default::default(),
            overrange_reg: Default::default(),
            headroom: Default::default(),
            too_large: Default::default(),
            wrapped: Default::default(),
            subtractor: Default::default(),
            below: Default::default(),
            zero: Constant::new(0u64.into()),
            msb: Constant::new((1u64 << (W - 1)).into()),
        }
    }
}

impl<const W: usize> Logic for DdaIntegrator<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            ticked,
            step,
            back_inverted,
            saturated,
            acc,
            pulse_reg,
            overrange_reg
        );
        self.pulse.next = self.pulse_reg.q.val();
        self.overrange.next = self.overrange_reg.q.val();
        // Each comparison is the borrow of the subtraction beside it, taken
        // from the most significant bits (borrow = ~a&b | ~(a^b)&d), so
        // every subtract-and-compare costs one carry chain whatever yosys
        // decides about merging.
        self.headroom.next = self.modulus.val() - self.integrand.val();
        // rust-hdl prints operators flat: without the outer parentheses,
        // Verilog would read `x & msb != 0` as `x & (msb != 0)`.
        self.too_large.next = (((!self.modulus.val() & self.integrand.val())
            | (!(self.modulus.val() ^ self.integrand.val()) & self.headroom.val()))
            & self.msb.val())
            != self.zero.val();
        self.too_large.next = self.too_large.val() & (self.modulus.val() != self.zero.val());
        // A tick with J = 0 changes nothing; dropping it here keeps the
        // "never pulse" case (J = 0, M = 0 means K = 2^W) off the
        // accumulator's critical path.
        self.ticked.d.next = self.tick.val() & (self.integrand.val() != self.zero.val());
        self.saturated.d.next = self.too_large.val();
        self.step.d.next = self.integrand.val();
        self.back_inverted.d.next = !self.headroom.val();
        // Accumulator stage: s = acc + J >= M  <=>  acc >= M - J.
        // No pulse when acc + !K + 1 does not carry out of the MSB.
        self.subtractor.a.next = self.acc.q.val();
        self.subtractor.b.next = self.back_inverted.q.val();
        self.wrapped.next = self.subtractor.sum.val();
        self.below.next = !self.subtractor.carry_out.val();
        self.pulse_reg.d.next = self.ticked.q.val() & (self.saturated.q.val() | !self.below.val());
        if self.ticked.q.val() & !self.saturated.q.val() {
            if self.below.val() {
                self.acc.d.next = self.acc.q.val() + self.step.q.val();
            } else {
                self.acc.d.next = self.wrapped.val();
            }
        }
        if self.ticked.q.val() & self.saturated.q.val() {
            self.overrange_reg.d.next = true;
        }
        if self.clear_overrange.val() {
            self.overrange_reg.d.next = false;
        }
        if self.reset.val() {
            self.ticked.d.next = false;
            self.saturated.d.next = false;
            self.acc.d.next = self.zero.val();
            self.pulse_reg.d.next = false;
            self.overrange_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize] DdaIntegrator<W> {
    inputs: [reset, tick, integrand, modulus, clear_overrange],
    outputs: [pulse, overrange],
});
