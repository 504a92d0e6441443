//! The uniform pulse generator's slot and running period, without the
//! per-period work: see [`super::UniformPulseGen`] for the behavior, which
//! this block has whenever its planning port is answered as
//! [`super::UniformPulseGen`] answers it, by a
//! [`super::PeriodPlanner`] (a start in the first clock of the request,
//! the plan `W` clocks later).

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
pub struct UniformPulseCore<const W: usize> {
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
    /// Bresenham error, signed: the next pulse is long when it is >= 0.
    error: DFF<Bits<W>>,
    half: DFF<Bits<W>>,
    half_is_one: DFF<Bit>,
    step_long: DFF<Bits<W>>,
    step_short: DFF<Bits<W>>,
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
    /// The slot's short step: N2 interleaved, 1 in paper order.
    short_step: Signal<Local, Bits<W>>,
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
    sign: Constant<Bits<W>>,
}

impl<const W: usize> Default for UniformPulseCore<W> {
    fn default() -> Self {
        assert!(
            (4..=32).contains(&W),
            "UniformPulseGen: W must be 4 to 32 bits"
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
            short_step: Default::default(),
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
            sign: Constant::new((1u64 << (W - 1)).into()),
        }
    }
}

impl<const W: usize> Logic for UniformPulseCore<W> {
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
            period_small
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

        self.short_step.next = self.one.val();
        if self.slot_interleaved.q.val() {
            self.short_step.next = self.slot_long_pulses.q.val();
        }

        // The running period, advanced on tick edges.
        self.period_done_reg.d.next = false;
        self.start.next = false;
        self.next_long.next = (self.error.q.val() & self.sign.val()) == self.zero.val();
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
                                if self.next_long.val() {
                                    self.error.d.next = self.error.q.val() + self.step_long.q.val();
                                } else {
                                    self.error.d.next =
                                        self.error.q.val() + self.step_short.q.val();
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
            self.step_short.d.next = self.short_step.val();
            self.step_long.d.next = self.one.val();
            if self.slot_interleaved.q.val() {
                self.step_long.d.next = self.slot_short_negated.q.val();
            }
            self.error.d.next = self.short_step.val() + self.slot_short_negated.q.val();
            self.has_pulses.d.next = self.slot_has_pulses.q.val();
            self.slot_state.d.next = self.empty.val();
        }

        if self.reset.val() {
            self.slot_state.d.next = self.empty.val();
            self.running_reg.d.next = false;
            self.pulse_reg.d.next = false;
            self.period_done_reg.d.next = false;
            self.underrun_reg.d.next = false;
            self.overrange_reg.d.next = false;
            self.overflow_reg.d.next = false;
        }
        // Last: it follows every assignment of the slot state above.
        self.slot_full.d.next = self.slot_state.d.val() == self.full.val();
    }
}

crate::vector_ports!(impl[const W: usize] UniformPulseCore<W> {
    inputs: [reset, tick, period, count, mode, load, clear_flags, div_done, div_half, div_long_pulses, div_short_negated, div_half_is_one, div_has_pulses, div_clamped],
    outputs: [pulse, period_done, ready, running, underrun, overrange, overflow, div_request, div_dividend, div_divisor],
});
