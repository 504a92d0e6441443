//! # `PeriodDda`: the DDA integrator for whole periods, in one error register
//!
//! A [`DdaIntegrator`](super::DdaIntegrator) whose user holds J and M for
//! whole periods of exactly M ticks, and changes them only between two
//! periods. The accumulator is then back at its starting phase at every
//! change: 0, as after reset. So this block keeps no accumulator and no
//! per-tick copy of J and K = M - J. It keeps the Bresenham error
//! e = acc + J - M, signed, and updates it with one adder:
//!
//! * a tick pulses exactly when e >= 0 (acc + J >= M), the sign bit;
//! * then e += J - M after a pulse, e += J otherwise;
//! * at a `reload`, e = J - M (acc = 0), the same adder forming J + (-M),
//!   and the step J - M is stored from it.
//!
//! The motion controller's axes use it for their DDA mode (one per axis,
//! with -M formed once for all of them); it replaces a
//! [`DdaIntegrator`](super::DdaIntegrator) there, cycle for cycle.
//!
//! ## Ports (internal block; `W` data bits, `E` = `W` + 1)
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous, active high: no tick in flight, no pulse, `overrange` 0 (e, its step and the J > M flag are set by the next `reload`) |
//! | `tick` | in | 1 | accumulate enable, sampled with J |
//! | `reload` | in | 1 | the first clock with a new period's J and -M on the inputs |
//! | `integrand` | in | W | J, held from a `reload` clock to the next |
//! | `modulus_negated` | in | E | -M, E-bit two's complement, M from 1 to 2^W - 1, held like J |
//! | `clear_overrange` | in | 1 | clears `overrange` |
//! | `pulse` | out | 1 | one-clock pulse, 2 clocks after its tick (as `DdaIntegrator`) |
//! | `overrange` | out | 1 | sticky: a tick was processed with J > M |
//!
//! ## Contract
//! * J and -M change only in a `reload` clock (the first clock they are
//!   present), and only when the ticks since the last `reload` are a whole
//!   number of periods of M ticks (with J = 0 any number will do). A tick
//!   sampled in the `reload` clock belongs to the new period. The block
//!   then pulses exactly as a `DdaIntegrator` with the same `reset`,
//!   `tick`, J, M and `clear_overrange` (its
//!   [`PeriodDdaModel`](super::model::PeriodDdaModel) is that model, and
//!   checks the phase at every `reload`).
//! * `reset` is followed by J = 0 or by a `reload` before the next tick
//!   with J != 0 (e is not cleared: the reload sets it).
//! * J > M: every tick pulses, e holds, `overrange` is set (as
//!   `DdaIntegrator`). J = 0: no tick is taken, whatever M is.
//!
//! ## Timing
//! A tick sampled at edge t is taken at edge t + 1: its pulse decision
//! reads e, and e is updated (a `reload` at that edge sets e instead: the
//! tick is then the old period's last, and its update would have brought
//! the phase back to 0). The pulse is high in the clock after edge t + 1.
//!
//! ## Width
//! e lies in [-M, M) and the steps in [-M, M], so E = W + 1 bits hold them
//! (M < 2^W).

use rust_hdl::prelude::*;

/// The DDA integrator for whole periods. See the [module
/// documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct PeriodDda<const W: usize, const E: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Accumulate enable.
    pub tick: Signal<In, Bit>,
    /// The first clock of a new J and -M.
    pub reload: Signal<In, Bit>,
    /// J.
    pub integrand: Signal<In, Bits<W>>,
    /// -M, E-bit two's complement.
    pub modulus_negated: Signal<In, Bits<E>>,
    /// Clears `overrange`.
    pub clear_overrange: Signal<In, Bit>,
    /// One pulse per overflow.
    pub pulse: Signal<Out, Bit>,
    /// Sticky: J > M was used.
    pub overrange: Signal<Out, Bit>,
    /// A tick with J != 0 was sampled at the last edge.
    ticked: DFF<Bit>,
    /// e = acc + J - M.
    error: DFF<Bits<E>>,
    /// J - M, the step after a pulse.
    step_long: DFF<Bits<E>>,
    /// J > M: e holds and every tick pulses.
    saturated: DFF<Bit>,
    pulse_reg: DFF<Bit>,
    overrange_reg: DFF<Bit>,
    /// J, E bits wide.
    integrand_wide: Signal<Local, Bits<E>>,
    /// e >= 0: the tick taken now pulses.
    overflows: Signal<Local, Bit>,
    /// The adder's operands and sum: e + step, or -M + J at a reload.
    addend_a: Signal<Local, Bits<E>>,
    addend_b: Signal<Local, Bits<E>>,
    sum: Signal<Local, Bits<E>>,
    zero: Constant<Bits<E>>,
    zero_j: Constant<Bits<W>>,
    sign: Constant<Bits<E>>,
}

impl<const W: usize, const E: usize> Default for PeriodDda<W, E> {
    fn default() -> Self {
        assert!(E == W + 1, "PeriodDda: E must be W + 1");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            reload: Default::default(),
            integrand: Default::default(),
            modulus_negated: Default::default(),
            clear_overrange: Default::default(),
            pulse: Default::default(),
            overrange: Default::default(),
            ticked: Default::default(),
            error: Default::default(),
            step_long: Default::default(),
            saturated: Default::default(),
            pulse_reg: Default::default(),
            overrange_reg: Default::default(),
            integrand_wide: Default::default(),
            overflows: Default::default(),
            addend_a: Default::default(),
            addend_b: Default::default(),
            sum: Default::default(),
            zero: Constant::new(0u64.into()),
            zero_j: Constant::new(0u64.into()),
            sign: Constant::new((1u64 << (E - 1)).into()),
        }
    }
}

impl<const W: usize, const E: usize> Logic for PeriodDda<W, E> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            ticked,
            error,
            step_long,
            saturated,
            pulse_reg,
            overrange_reg
        );
        self.pulse.next = self.pulse_reg.q.val();
        self.overrange.next = self.overrange_reg.q.val();
        // J = 0 takes no tick, as in DdaIntegrator (and so M = 0, before
        // the controller's first period, never pulses).
        self.ticked.d.next = self.tick.val() & (self.integrand.val() != self.zero_j.val());
        self.integrand_wide.next = bit_cast::<E, W>(self.integrand.val());
        self.overflows.next = (self.error.q.val() & self.sign.val()) == self.zero.val();
        // One adder for both uses: at a reload -M + J, else e + (J - M)
        // after a pulse and e + J without one.
        self.addend_a.next = self.error.q.val();
        if self.reload.val() {
            self.addend_a.next = self.modulus_negated.val();
        }
        self.addend_b.next = self.integrand_wide.val();
        if self.overflows.val() & !self.reload.val() {
            self.addend_b.next = self.step_long.q.val();
        }
        self.sum.next = self.addend_a.val() + self.addend_b.val();
        self.pulse_reg.d.next = self.ticked.q.val() & self.overflows.val();
        if self.ticked.q.val() & !self.saturated.q.val() {
            self.error.d.next = self.sum.val();
        }
        if self.ticked.q.val() & self.saturated.q.val() {
            self.overrange_reg.d.next = true;
        }
        if self.reload.val() {
            self.error.d.next = self.sum.val();
            self.step_long.d.next = self.sum.val();
            // J - M > 0.
            self.saturated.d.next = ((self.sum.val() & self.sign.val()) == self.zero.val())
                & (self.sum.val() != self.zero.val());
        }
        if self.clear_overrange.val() {
            self.overrange_reg.d.next = false;
        }
        if self.reset.val() {
            self.ticked.d.next = false;
            self.pulse_reg.d.next = false;
            self.overrange_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize, const E: usize] PeriodDda<W, E> {
    inputs: [reset, tick, reload, integrand, modulus_negated, clear_overrange],
    outputs: [pulse, overrange],
});
