//! The per-period work of the uniform pulse generator, done once for every
//! generator that shares it: T/2 / N by a [`SequentialDivider`], then the
//! clamp of N to T/2 and the split into short and long pulses.
//!
//! ## Contract
//! * `start` (sampled while `busy` is low) takes T/2 on `dividend` and the
//!   requested N on `divisor`; `done` is high `W` clocks later, for one
//!   clock, with the plan on the other outputs (valid from `done` until
//!   the next `start`, except `short_negated`: see `clamped`, and it is
//!   N2 - N only in the `done` clock). The user starts the next plan no
//!   earlier than the clock after `done`.
//! * The plan is that of [`super::model::PulsePlan`] for a corrected T
//!   (even, at least 2): `half` = floor(T/2 / N'), `long_pulses` = N2 =
//!   T/2 mod N', `short_negated` = -N1 = N2 - N' (W-bit two's
//!   complement), where N' = min(N, T/2). The generator forms its
//!   Bresenham error and steps from N2 and -N1 with one adder and
//!   multiplexers: -N1 is the step of a long pulse as it is.
//! * `clamped`: N > T/2 (then N' = T/2: `half` = 1, N2 = 0, N1 = T/2).
//!   N > T/2 exactly when the quotient is 0, so no comparator is needed:
//!   the remainder is then T/2. `long_pulses` is the remainder (T/2) even
//!   then: the generator clears its N2 when `clamped` is set, in its slot
//!   register's synchronous clear. `short_negated` is N2 - N in the `done`
//!   clock and -T/2 in the next one, and the generator takes the second
//!   when `clamped` was set: the subtractor's operand is then chosen by a
//!   register, not by the quotient's zero test, which would put a
//!   W-input OR in front of its carry chain.
//! * N = 0: `has_pulses` is low, `clamped` is low and the other outputs are
//!   don't-care (the generator emits nothing).
//! * A `dividend` of 0 is outside the contract: the generator always asks
//!   with T/2 >= 1.
//!
//! ## Why it is apart from the generator
//! The motion controller's axes take turns at one planner, so each axis's
//! generator keeps only the registers of its slot: the comparator, the
//! clamp, the subtractor and the divider exist once.

use rust_hdl::prelude::*;

use crate::blocks::sequential_divider::SequentialDivider;

/// The shared per-period work of [`super::UniformPulseCore`]s. See the
/// [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct PeriodPlanner<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high: idle.
    pub reset: Signal<In, Bit>,
    /// Plan a period (sampled while `busy` is low).
    pub start: Signal<In, Bit>,
    /// T/2 of the corrected period (at least 1).
    pub dividend: Signal<In, Bits<W>>,
    /// N as requested.
    pub divisor: Signal<In, Bits<W>>,
    /// A plan is being computed.
    pub busy: Signal<Out, Bit>,
    /// One-clock strobe: the plan is valid.
    pub done: Signal<Out, Bit>,
    /// Tp1 / 2.
    pub half: Signal<Out, Bits<W>>,
    /// N2 (T/2 when `clamped`: the user clears it).
    pub long_pulses: Signal<Out, Bits<W>>,
    /// -N1.
    pub short_negated: Signal<Out, Bits<W>>,
    /// `half` == 1.
    pub half_is_one: Signal<Out, Bit>,
    /// N > 0.
    pub has_pulses: Signal<Out, Bit>,
    /// N > T/2 was clamped to T/2.
    pub clamped: Signal<Out, Bit>,
    divider: SequentialDivider<W, W>,
    /// N from the start: -N1 = N2 - N.
    count: DFF<Bits<W>>,
    /// The clock after `done`: -N1 subtracts T (twice the remainder).
    after_done: DFF<Bit>,
    /// What -N1 subtracts: N in the `done` clock, T in the next.
    subtrahend: Signal<Local, Bits<W>>,
    /// `half` before it is driven: every output is assigned once (see
    /// `update`).
    plan_half: Signal<Local, Bits<W>>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
}

impl<const W: usize> Default for PeriodPlanner<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            dividend: Default::default(),
            divisor: Default::default(),
            busy: Default::default(),
            done: Default::default(),
            half: Default::default(),
            long_pulses: Default::default(),
            short_negated: Default::default(),
            half_is_one: Default::default(),
            has_pulses: Default::default(),
            clamped: Default::default(),
            divider: Default::default(),
            count: Default::default(),
            after_done: Default::default(),
            subtrahend: Default::default(),
            plan_half: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
        }
    }
}

impl<const W: usize> Logic for PeriodPlanner<W> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, divider);
        dff_setup!(self, clock, count, after_done);
        self.divider.reset.next = self.reset.val();
        self.divider.start.next = self.start.val();
        self.divider.dividend.next = self.dividend.val();
        self.divider.divisor.next = self.divisor.val();
        // N follows `divisor` whenever the divider is idle, so it holds the
        // started one through the division: its enable is then a register,
        // not the start (in the controller, the end of the arbiter's grant
        // chain). It changes at the edge after `done`, and the `done` clock
        // is the only one that reads it.
        if !self.divider.busy.val() {
            self.count.d.next = self.divisor.val();
        }
        self.busy.next = self.divider.busy.val();
        self.done.next = self.divider.done.val();
        self.has_pulses.next = !self.divider.divide_by_zero.val();
        self.clamped.next =
            (self.divider.quotient.val() == self.zero.val()) & !self.divider.divide_by_zero.val();
        // A quotient of 0 (clamped) or 1 both give a half of one tick.
        self.half_is_one.next = (self.divider.quotient.val() >> self.one.val()) == self.zero.val();
        // Outputs are assigned once, never a default and then an
        // override: in the controller, the plan, the axes and the arbiter
        // form a cycle of always blocks, and a glitch on an output keeps
        // Icarus re-evaluating it forever.
        self.plan_half.next = self.divider.quotient.val();
        if self.clamped.val() {
            self.plan_half.next = self.divider.quotient.val() | self.one.val();
        }
        self.after_done.d.next = self.divider.done.val();
        self.subtrahend.next = self.count.q.val();
        if self.after_done.q.val() {
            self.subtrahend.next = self.divider.remainder.val() << self.one.val();
        }
        self.half.next = self.plan_half.val();
        self.long_pulses.next = self.divider.remainder.val();
        self.short_negated.next = self.divider.remainder.val() - self.subtrahend.val();
    }
}

crate::vector_ports!(impl[const W: usize] PeriodPlanner<W> {
    inputs: [reset, start, dividend, divisor],
    outputs: [busy, done, half, long_pulses, short_negated, half_is_one, has_pulses, clamped],
});
