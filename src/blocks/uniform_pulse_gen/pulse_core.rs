//! The uniform pulse generator's slot and running period, without the
//! per-period work: see [`super::UniformPulseGen`] for the behavior, which
//! this block has whenever its planning port is answered as
//! [`super::UniformPulseGen`] answers it, by a
//! [`super::PeriodPlanner`] (a start in the first clock of the request,
//! the plan `W` clocks later).
//!
//! ## DDA mode: one interpolator engine
//! The core's Bresenham engine (the signed error, its long and short
//! steps and the adder that adds one of them per pulse) also runs a DDA
//! integrator, on the `dda_` ports, for a user that holds J and M for
//! whole periods of exactly M ticks (the motion controller's DDA axes).
//! The DDA's phase is then 0 whenever J changes, so it needs no
//! accumulator: the error e = acc + J - M, with
//! * a tick pulsing exactly when e >= 0 (the sign bit, as a uniform
//!   pulse's long/short choice);
//! * e += J - M after a pulse, e += J otherwise (the long and the short
//!   step);
//! * at a `dda_reload`, e = J - M (acc = 0), formed by the period-start
//!   adder from J and -M, and stored as the long step too.
//!
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `dda_tick` | in | 1 | accumulate enable, sampled with J |
//! | `dda_reload` | in | 1 | the first clock with a new J and -M (ignored with J = 0) |
//! | `dda_integrand` | in | W | J, held from one reload to the next; 0 = the DDA is idle |
//! | `dda_active` | in | 1 | J != 0, from a register beside J's: the tick, the reload and the engine's owner are decided from it, not from a W-input OR |
//! | `dda_modulus_negated` | in | E | -M, E-bit two's complement, M from 1 to 2^W - 1 |
//! | `dda_clear_overrange` | in | 1 | clears `dda_overrange` |
//! | `dda_pulse` | out | 1 | one-clock pulse, 2 clocks after its tick (as `DdaIntegrator`) |
//! | `dda_overrange` | out | 1 | sticky: a tick was processed with J > M |
//!
//! Contract, as [`PeriodDdaModel`](crate::blocks::dda_integrator::model::PeriodDdaModel)
//! checks it: J and -M change only in a reload clock, when the ticks
//! since the last reload are a whole number of periods (with J = 0 any
//! number will do); a tick sampled in the reload clock is the new
//! period's. The engine is the DDA's while J != 0: the uniform generator
//! neither loads nor steps it then, so J != 0 and a uniform period whose
//! pulses are used must not overlap. J > M: every tick pulses, e holds,
//! `dda_overrange` is set (J > M is read from the stored J - M, not
//! after the reload's adder). `reset` clears the DDA's tick in flight, its
//! pulse and its flag; e is set by the next reload. A tick sampled at edge
//! t is taken at edge t + 1, and its pulse is high in the clock after.
//! The error and the steps are E = W + 1 bits wide for the DDA (e lies in
//! [-M, M)); a core without the DDA has E = W.

use rust_hdl::prelude::*;

/// Slot sequencer states.
const SLOT_EMPTY: u64 = 0;
const SLOT_CHECK: u64 = 1;
const SLOT_CLAMP: u64 = 2;
const SLOT_DIVIDE: u64 = 3;
const SLOT_SPLIT: u64 = 4;
const SLOT_STEPS: u64 = 5;
const SLOT_FULL: u64 = 6;

/// The generator without its per-period work: the slot asks for the plan
/// of (T/2, N) on its planning port (the `div_` ports).
/// [`super::UniformPulseGen`] gives it a [`super::PeriodPlanner`] of its
/// own; the motion controller shares one among its axes.
#[derive(Clone, Debug, LogicBlock)]
pub struct UniformPulseCore<const W: usize, const E: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Time base.
    pub tick: Signal<In, Bit>,
    /// T.
    pub period: Signal<In, Bits<W>>,
    /// N.
    pub count: Signal<In, Bits<W>>,
    /// Interleaved order.
    pub mode: Signal<In, Bit>,
    /// Queue the next period.
    pub load: Signal<In, Bit>,
    /// Clear the sticky flags.
    pub clear_flags: Signal<In, Bit>,
    /// Pulse train.
    pub pulse: Signal<Out, Bit>,
    /// End of a period.
    pub period_done: Signal<Out, Bit>,
    /// The slot is free.
    pub ready: Signal<Out, Bit>,
    /// A period is running.
    pub running: Signal<Out, Bit>,
    /// Sticky underrun.
    pub underrun: Signal<Out, Bit>,
    /// Sticky overrange.
    pub overrange: Signal<Out, Bit>,
    /// Sticky overflow.
    pub overflow: Signal<Out, Bit>,
    /// The slot waits for its plan: `div_dividend` / `div_divisor` are
    /// stable while it is high, until the clock after `div_done`.
    pub div_request: Signal<Out, Bit>,
    /// T/2 of the slot's corrected period (at least 1).
    pub div_dividend: Signal<Out, Bits<W>>,
    /// N as loaded.
    pub div_divisor: Signal<Out, Bits<W>>,
    /// One-clock strobe: this slot's plan is on the `div_` inputs.
    pub div_done: Signal<In, Bit>,
    /// The plan's Tp1 / 2 ([`super::PeriodPlanner`]'s `half`).
    pub div_half: Signal<In, Bits<W>>,
    /// The plan's N2 (ignored when `div_clamped`: N2 = 0).
    pub div_long_pulses: Signal<In, Bits<W>>,
    /// The plan's -N1 (if `div_clamped`, in the clock after `div_done`).
    pub div_short_negated: Signal<In, Bits<W>>,
    /// `div_half` == 1.
    pub div_half_is_one: Signal<In, Bit>,
    /// N > 0.
    pub div_has_pulses: Signal<In, Bit>,
    /// N > T/2 was clamped: `overrange`.
    pub div_clamped: Signal<In, Bit>,
    /// DDA mode: accumulate enable.
    pub dda_tick: Signal<In, Bit>,
    /// DDA mode: the first clock of a new J and -M.
    pub dda_reload: Signal<In, Bit>,
    /// DDA mode: J (0: idle).
    pub dda_integrand: Signal<In, Bits<W>>,
    /// DDA mode: J != 0.
    pub dda_active: Signal<In, Bit>,
    /// DDA mode: -M, E-bit two's complement.
    pub dda_modulus_negated: Signal<In, Bits<E>>,
    /// DDA mode: clears `dda_overrange`.
    pub dda_clear_overrange: Signal<In, Bit>,
    /// DDA mode: one pulse per overflow.
    pub dda_pulse: Signal<Out, Bit>,
    /// DDA mode: sticky, J > M was used.
    pub dda_overrange: Signal<Out, Bit>,
    // The next-period slot, filled by a small sequencer after a load.
    slot_state: DFF<Bits<3>>,
    /// `slot_state == full`, registered: the start decision is then one
    /// LUT of four flip-flops, in front of the load of every period
    /// register.
    slot_full: DFF<Bit>,
    slot_period: DFF<Bits<W>>,
    slot_interleaved: DFF<Bit>,
    slot_half: DFF<Bits<W>>,
    slot_half_is_one: DFF<Bit>,
    /// N as loaded until the plan arrives, then -N1: the step of a long
    /// interleaved pulse as it is, and one adder from the first error.
    slot_short_negated: DFF<Bits<W>>,
    slot_long_pulses: DFF<Bits<W>>,
    slot_has_pulses: DFF<Bit>,
    /// The plan clamped N: -N1 is taken again in the split clock.
    slot_clamped: DFF<Bit>,
    // The running period.
    running_reg: DFF<Bit>,
    ticks_left: DFF<Bits<W>>,
    /// `ticks_left == 1`: the next tick edge ends the period.
    period_last: DFF<Bit>,
    half_left: DFF<Bits<W>>,
    /// `half_left == 1`: the next tick edge ends the half pulse (unless
    /// `stretch` adds its tick).
    half_last: DFF<Bit>,
    /// The running half belongs to a long pulse and has not had its extra
    /// tick yet: a long half is a short one plus one tick at its end, so
    /// no `half + 1` is stored or loaded.
    stretch: DFF<Bit>,
    pulse_reg: DFF<Bit>,
    long: DFF<Bit>,
    /// Bresenham error, signed: the next pulse is long when it is >= 0
    /// (in DDA mode: the tick pulses).
    error: DFF<Bits<E>>,
    half: DFF<Bits<W>>,
    half_is_one: DFF<Bit>,
    step_long: DFF<Bits<E>>,
    step_short: DFF<Bits<E>>,
    has_pulses: DFF<Bit>,
    period_done_reg: DFF<Bit>,
    underrun_reg: DFF<Bit>,
    overrange_reg: DFF<Bit>,
    overflow_reg: DFF<Bit>,
    /// The loaded T checked one clock before it is corrected.
    period_odd: DFF<Bit>,
    period_small: DFF<Bit>,
    start: Signal<Local, Bit>,
    next_long: Signal<Local, Bit>,
    /// DDA mode: a tick with J != 0 was sampled at the last edge.
    dda_ticked: DFF<Bit>,
    dda_pulse_reg: DFF<Bit>,
    dda_overrange_reg: DFF<Bit>,
    /// The slot's short step: N2 interleaved, 1 in paper order.
    short_step: Signal<Local, Bits<E>>,
    /// The slot's -N1, sign-extended to E bits.
    short_negated_wide: Signal<Local, Bits<E>>,
    /// The period-start adder's operands and sum: short step + (-N1), or
    /// J + (-M) at a DDA reload.
    start_a: Signal<Local, Bits<E>>,
    start_b: Signal<Local, Bits<E>>,
    start_sum: Signal<Local, Bits<E>>,
    /// The short step as the pulse adders see it.
    pulse_step: Signal<Local, Bits<E>>,
    /// error + the long or the short step.
    step_sum: Signal<Local, Bits<E>>,
    dda_reloading: Signal<Local, Bit>,
    /// J > M: the stored J - M is above 0; e holds and every tick pulses.
    dda_too_large: Signal<Local, Bit>,
    empty: Constant<Bits<3>>,
    check: Constant<Bits<3>>,
    clamp: Constant<Bits<3>>,
    divide: Constant<Bits<3>>,
    split: Constant<Bits<3>>,
    steps: Constant<Bits<3>>,
    full: Constant<Bits<3>>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    two: Constant<Bits<W>>,
    not_one: Constant<Bits<W>>,
    /// The core has its generator; without it (`without_generator`) only
    /// the DDA mode is left and synthesis removes the rest.
    has_generator: Constant<Bit>,
    /// Bit W - 1: the sign of a W-bit -N1.
    sign_w: Constant<Bits<W>>,
    zero_e: Constant<Bits<E>>,
    one_e: Constant<Bits<E>>,
    /// Bit E - 1: the error's sign.
    sign: Constant<Bits<E>>,
    /// The bits a W-bit value lacks in E bits (0 when E = W).
    extension: Constant<Bits<E>>,
}

impl<const W: usize, const E: usize> Default for UniformPulseCore<W, E> {
    fn default() -> Self {
        assert!(
            (4..=32).contains(&W),
            "UniformPulseGen: W must be 4 to 32 bits"
        );
        assert!(
            E == W || E == W + 1,
            "UniformPulseCore: E must be W (no DDA) or W + 1"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            period: Default::default(),
            count: Default::default(),
            mode: Default::default(),
            load: Default::default(),
            clear_flags: Default::default(),
            pulse: Default::default(),
            period_done: Default::default(),
            ready: Default::default(),
            running: Default::default(),
            underrun: Default::default(),
            overrange: Default::default(),
            overflow: Default::default(),
            div_request: Default::default(),
            div_dividend: Default::default(),
            div_divisor: Default::default(),
            div_done: Default::default(),
            div_half: Default::default(),
            div_long_pulses: Default::default(),
            div_short_negated: Default::default(),
            div_half_is_one: Default::default(),
            div_has_pulses: Default::default(),
            div_clamped: Default::default(),
            dda_tick: Default::default(),
            dda_reload: Default::default(),
            dda_integrand: Default::default(),
            dda_active: Default::default(),
            dda_modulus_negated: Default::default(),
            dda_clear_overrange: Default::default(),
            dda_pulse: Default::default(),
            dda_overrange: Default::default(),
            slot_state: Default::default(),
            slot_full: Default::default(),
            slot_period: Default::default(),
            slot_interleaved: Default::default(),
            slot_half: Default::default(),
            slot_half_is_one: Default::default(),
            slot_short_negated: Default::default(),
            slot_long_pulses: Default::default(),
            slot_has_pulses: Default::default(),
            slot_clamped: Default::default(),
            running_reg: Default::default(),
            ticks_left: Default::default(),
            period_last: Default::default(),
            half_left: Default::default(),
            half_last: Default::default(),
            stretch: Default::default(),
            pulse_reg: Default::default(),
            long: Default::default(),
            error: Default::default(),
            half: Default::default(),
            half_is_one: Default::default(),
            step_long: Default::default(),
            step_short: Default::default(),
            has_pulses: Default::default(),
            period_done_reg: Default::default(),
            underrun_reg: Default::default(),
            overrange_reg: Default::default(),
            overflow_reg: Default::default(),
            period_odd: Default::default(),
            period_small: Default::default(),
            start: Default::default(),
            next_long: Default::default(),
            dda_ticked: Default::default(),
            dda_pulse_reg: Default::default(),
            dda_overrange_reg: Default::default(),
            short_step: Default::default(),
            short_negated_wide: Default::default(),
            start_a: Default::default(),
            start_b: Default::default(),
            start_sum: Default::default(),
            pulse_step: Default::default(),
            step_sum: Default::default(),
            dda_reloading: Default::default(),
            dda_too_large: Default::default(),
            empty: Constant::new(SLOT_EMPTY.into()),
            check: Constant::new(SLOT_CHECK.into()),
            clamp: Constant::new(SLOT_CLAMP.into()),
            divide: Constant::new(SLOT_DIVIDE.into()),
            split: Constant::new(SLOT_SPLIT.into()),
            steps: Constant::new(SLOT_STEPS.into()),
            full: Constant::new(SLOT_FULL.into()),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            two: Constant::new(2u64.into()),
            not_one: Constant::new((crate::blocks::width_mask(W as u32) & !1).into()),
            has_generator: Constant::new(true),
            sign_w: Constant::new((1u64 << (W - 1)).into()),
            zero_e: Constant::new(0u64.into()),
            one_e: Constant::new(1u64.into()),
            sign: Constant::new((1u64 << (E - 1)).into()),
            extension: Constant::new(
                (crate::blocks::width_mask(E as u32) & !crate::blocks::width_mask(W as u32)).into(),
            ),
        }
    }
}

impl<const W: usize, const E: usize> UniformPulseCore<W, E> {
    /// The core in DDA mode only: its generator's inputs are to be tied
    /// off (no `tick`, no `load`), and nothing of it is left in the
    /// netlist but the engine the DDA uses.
    pub fn without_generator() -> Self {
        Self {
            has_generator: Constant::new(false),
            ..Default::default()
        }
    }
}

impl<const W: usize, const E: usize> Logic for UniformPulseCore<W, E> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            slot_state,
            slot_full,
            slot_period,
            slot_interleaved,
            slot_half,
            slot_half_is_one,
            slot_short_negated,
            slot_long_pulses,
            slot_has_pulses,
            slot_clamped,
            running_reg,
            ticks_left,
            period_last,
            half_left,
            half_last,
            stretch,
            pulse_reg,
            long,
            error,
            half,
            half_is_one,
            step_long,
            step_short,
            has_pulses,
            period_done_reg,
            underrun_reg,
            overrange_reg,
            overflow_reg,
            period_odd,
            period_small,
            dda_ticked,
            dda_pulse_reg,
            dda_overrange_reg
        );
        self.pulse.next = self.pulse_reg.q.val();
        self.period_done.next = self.period_done_reg.q.val();
        self.ready.next = self.slot_state.q.val() == self.empty.val();
        self.running.next = self.running_reg.q.val();
        self.underrun.next = self.underrun_reg.q.val();
        self.overrange.next = self.overrange_reg.q.val();
        self.overflow.next = self.overflow_reg.q.val();

        // Sticky flags: cleared first, so that an event on the same clock
        // sets them again.
        if self.clear_flags.val() {
            self.underrun_reg.d.next = false;
            self.overrange_reg.d.next = false;
            self.overflow_reg.d.next = false;
        }

        // The slot: load, correct T, then ask for the plan of (T/2, N): the
        // clamp of N and the split are the planner's.
        self.period_odd.d.next = self.slot_period.q.val().get_bit(0);
        self.period_small.d.next =
            (self.slot_period.q.val() & self.not_one.val()) == self.zero.val();
        self.div_dividend.next = self.slot_period.q.val() >> self.one.val();
        self.div_divisor.next = self.slot_short_negated.q.val();
        self.div_request.next = self.slot_state.q.val() == self.divide.val();
        if self.slot_state.q.val() == self.empty.val() {
            if self.load.val() {
                self.slot_state.d.next = self.check.val();
                self.slot_period.d.next = self.period.val();
                self.slot_short_negated.d.next = self.count.val();
                self.slot_interleaved.d.next = self.mode.val();
            }
        } else if self.load.val() {
            self.overflow_reg.d.next = true;
        }
        if self.slot_state.q.val() == self.check.val() {
            self.slot_state.d.next = self.clamp.val();
        }
        if self.slot_state.q.val() == self.clamp.val() {
            // An odd T is rounded down; a T below 2 becomes 2. N > T/2 is
            // the planner's, flagged when the plan arrives.
            if self.period_odd.q.val() {
                self.overrange_reg.d.next = true;
            }
            self.slot_period.d.next = self.slot_period.q.val() & self.not_one.val();
            if self.period_small.q.val() {
                self.overrange_reg.d.next = true;
                self.slot_period.d.next = self.two.val();
            }
            self.slot_state.d.next = self.divide.val();
        }
        if self.slot_state.q.val() == self.divide.val() {
            if self.div_done.val() {
                self.slot_half.d.next = self.div_half.val();
                self.slot_long_pulses.d.next = self.div_long_pulses.val();
                self.slot_short_negated.d.next = self.div_short_negated.val();
                self.slot_half_is_one.d.next = self.div_half_is_one.val();
                self.slot_has_pulses.d.next = self.div_has_pulses.val();
                self.slot_clamped.d.next = self.div_clamped.val();
                if self.div_clamped.val() {
                    self.overrange_reg.d.next = true;
                    self.slot_long_pulses.d.next = self.zero.val();
                }
                self.slot_state.d.next = self.split.val();
            }
        }
        // Two clocks kept so that the slot's timing stays LOAD_TO_READY:
        // the split they once did is now the planner's (but for a clamped
        // N's -N1, which it gives one clock late), and the error steps
        // they once stored are formed when the period starts.
        if self.slot_state.q.val() == self.split.val() {
            if self.slot_clamped.q.val() {
                self.slot_short_negated.d.next = self.div_short_negated.val();
            }
            self.slot_state.d.next = self.steps.val();
        }
        if self.slot_state.q.val() == self.steps.val() {
            self.slot_state.d.next = self.full.val();
        }

        self.short_step.next = self.one_e.val();
        if self.slot_interleaved.q.val() {
            self.short_step.next = bit_cast::<E, W>(self.slot_long_pulses.q.val());
        }
        self.short_negated_wide.next = bit_cast::<E, W>(self.slot_short_negated.q.val());
        if (self.slot_short_negated.q.val() & self.sign_w.val()) != self.zero.val() {
            self.short_negated_wide.next = self.short_negated_wide.val() | self.extension.val();
        }

        // The engine: one adder per pulse (or DDA tick), one at a period
        // start (or DDA reload). The DDA owns it while J != 0.
        self.dda_reloading.next = self.dda_reload.val() & self.dda_active.val();
        self.start_a.next = self.short_step.val();
        self.start_b.next = self.short_negated_wide.val();
        // Without the generator the start adder only reloads the DDA.
        if self.dda_reloading.val() | !self.has_generator.val() {
            self.start_a.next = bit_cast::<E, W>(self.dda_integrand.val());
            self.start_b.next = self.dda_modulus_negated.val();
        }
        self.start_sum.next = self.start_a.val() + self.start_b.val();
        self.next_long.next = (self.error.q.val() & self.sign.val()) == self.zero_e.val();
        // J stays on `dda_integrand` from one reload to the next: without
        // the generator the short step is read there, not stored again.
        self.pulse_step.next = self.step_short.q.val();
        if !self.has_generator.val() {
            self.pulse_step.next = bit_cast::<E, W>(self.dda_integrand.val());
        }
        // Two adders and the sign's choice after them: the sign bit then
        // selects a sum, not the operand of a carry chain (one adder
        // behind a multiplexer measured 98 MHz for uniform_pulse_gen, two
        // 102.6, median of 5 seeds).
        self.step_sum.next = self.error.q.val() + self.pulse_step.val();
        if self.next_long.val() {
            self.step_sum.next = self.error.q.val() + self.step_long.q.val();
        }

        // The running period, advanced on tick edges.
        self.period_done_reg.d.next = false;
        self.start.next = false;
        if self.tick.val() {
            if self.running_reg.q.val() {
                if self.period_last.q.val() {
                    self.period_done_reg.d.next = true;
                    if self.slot_full.q.val() {
                        self.start.next = true;
                    } else {
                        self.running_reg.d.next = false;
                        self.pulse_reg.d.next = false;
                        self.underrun_reg.d.next = true;
                    }
                } else {
                    self.ticks_left.d.next = self.ticks_left.q.val() - self.one.val();
                    self.period_last.d.next = self.ticks_left.q.val() == self.two.val();
                    if self.has_pulses.q.val() {
                        if self.half_last.q.val() & self.stretch.q.val() {
                            // A long half's extra tick.
                            self.stretch.d.next = false;
                        } else if self.half_last.q.val() {
                            self.half_left.d.next = self.half.q.val();
                            self.half_last.d.next = self.half_is_one.q.val();
                            if self.pulse_reg.q.val() {
                                // The low half of a pulse is as long as its
                                // high half.
                                self.pulse_reg.d.next = false;
                                self.stretch.d.next = self.long.q.val();
                            } else {
                                self.pulse_reg.d.next = true;
                                self.long.d.next = self.next_long.val();
                                self.stretch.d.next = self.next_long.val();
                                if !self.dda_active.val() {
                                    self.error.d.next = self.step_sum.val();
                                }
                            }
                        } else {
                            self.half_left.d.next = self.half_left.q.val() - self.one.val();
                            self.half_last.d.next = self.half_left.q.val() == self.two.val();
                        }
                    }
                }
            } else if self.slot_full.q.val() {
                self.start.next = true;
            }
        }
        if self.start.val() {
            self.running_reg.d.next = true;
            self.ticks_left.d.next = self.slot_period.q.val();
            self.period_last.d.next = false;
            self.half_left.d.next = self.slot_half.q.val();
            self.half_last.d.next = self.slot_half_is_one.q.val();
            self.stretch.d.next = false;
            self.pulse_reg.d.next = self.slot_has_pulses.q.val();
            self.long.d.next = false;
            self.half.d.next = self.slot_half.q.val();
            self.half_is_one.d.next = self.slot_half_is_one.q.val();
            // Error steps: paper order counts the pulse index up from -N1;
            // interleaved adds N2 per short pulse and adds -N1 per long
            // one. Pulse 0 is short, so the period starts one short step
            // in: error = short step - N1, one adder for both orders.
            if !self.dda_active.val() {
                self.step_short.d.next = self.short_step.val();
                self.step_long.d.next = self.one_e.val();
                if self.slot_interleaved.q.val() {
                    self.step_long.d.next = self.short_negated_wide.val();
                }
                self.error.d.next = self.start_sum.val();
            }
            self.has_pulses.d.next = self.slot_has_pulses.q.val();
            self.slot_state.d.next = self.empty.val();
        }

        // DDA mode: the tick taken now pulses when e >= 0; e holds when J
        // > M. A reload sets e and the long step to J - M (acc = 0) and
        // the short step to J.
        self.dda_pulse.next = self.dda_pulse_reg.q.val();
        self.dda_overrange.next = self.dda_overrange_reg.q.val();
        self.dda_ticked.d.next = self.dda_tick.val() & self.dda_active.val();
        self.dda_pulse_reg.d.next = self.dda_ticked.q.val() & self.next_long.val();
        self.dda_too_large.next = ((self.step_long.q.val() & self.sign.val()) == self.zero_e.val())
            & (self.step_long.q.val() != self.zero_e.val());
        if self.dda_ticked.q.val() & !self.dda_too_large.val() {
            self.error.d.next = self.step_sum.val();
        }
        if self.dda_ticked.q.val() & self.dda_too_large.val() {
            self.dda_overrange_reg.d.next = true;
        }
        if self.dda_reloading.val() {
            self.error.d.next = self.start_sum.val();
            self.step_long.d.next = self.start_sum.val();
            self.step_short.d.next = self.start_a.val();
        }
        if self.dda_clear_overrange.val() {
            self.dda_overrange_reg.d.next = false;
        }

        if self.reset.val() {
            self.slot_state.d.next = self.empty.val();
            self.running_reg.d.next = false;
            self.pulse_reg.d.next = false;
            self.period_done_reg.d.next = false;
            self.underrun_reg.d.next = false;
            self.overrange_reg.d.next = false;
            self.overflow_reg.d.next = false;
            self.dda_ticked.d.next = false;
            self.dda_pulse_reg.d.next = false;
            self.dda_overrange_reg.d.next = false;
        }
        // Last: it follows every assignment of the slot state above.
        self.slot_full.d.next = self.slot_state.d.val() == self.full.val();
    }
}

crate::vector_ports!(impl[const W: usize, const E: usize] UniformPulseCore<W, E> {
    inputs: [reset, tick, period, count, mode, load, clear_flags, div_done, div_half, div_long_pulses, div_short_negated, div_half_is_one, div_has_pulses, div_clamped, dda_tick, dda_reload, dda_integrand, dda_active, dda_modulus_negated, dda_clear_overrange],
    outputs: [pulse, period_done, ready, running, underrun, overrange, overflow, div_request, div_dividend, div_divisor, dda_pulse, dda_overrange],
});
