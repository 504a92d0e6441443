//! # `uniform_pulse_gen`: dual-period uniform pulse generator
//!
//! Emits N pulses in an interpolation period of T ticks and fills the
//! period exactly, for every N: N1 pulses of period Tp1 and N2 of period
//! Tp2 = Tp1 + 2 (shared/BACKGROUND.md, section 2). The single-period
//! algorithm, N pulses of Tp1 and then idle, leaves up to almost half of the
//! period empty; this block leaves none. It computes Tp1, N1 and N2 itself
//! with a [`SequentialDivider`], for the next period while the current one
//! runs, so loaded periods follow each other with zero idle ticks.
//!
//! ## Ports
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous, active high: idle, slot empty, output low, flags 0 (the datapath registers are not cleared: they are always loaded before use, and clearing them would cost about 70 LUT4) |
//! | `tick` | in | 1 | time base: one tick is the minimum toggle time (tie high for f_clk) |
//! | `period` | in | 32 | T: the interpolation period in ticks (even) |
//! | `count` | in | 32 | N: pulses in the period, 0 <= N <= T/2 |
//! | `mode` | in | 1 | 0 = paper order (N1 short pulses, then N2 long); 1 = interleaved (Bresenham over the pulse index) |
//! | `load` | in | 1 | strobe: queue (period, count, mode) as the next period; taken only while `ready` is high |
//! | `clear_flags` | in | 1 | clears `underrun`, `overrange` and `overflow` (tie to 0 if unused) |
//! | `pulse` | out | 1 | each pulse is high Tp/2 ticks, then low Tp/2 ticks; registered |
//! | `period_done` | out | 1 | one-clock strobe when a period's T ticks have elapsed |
//! | `ready` | out | 1 | the next-period slot is free: a load now is accepted |
//! | `running` | out | 1 | a period is in progress |
//! | `underrun` | out | 1 | sticky: a period ended with no next period ready; the output stays low and the block waits |
//! | `overrange` | out | 1 | sticky: an odd or too small T, or N > T/2, was corrected |
//! | `overflow` | out | 1 | sticky: a load arrived while `ready` was low and was ignored |
//!
//! ## Formulas (ticks)
//! * Tp1 = 2 * floor(T / 2N), Tp2 = Tp1 + 2.
//! * N1 = (N * Tp2 - T) / 2 short pulses, N2 = (T - N * Tp1) / 2 long ones:
//!   with T/2 = q * N + r (one division), Tp1 = 2q, N2 = r, N1 = N - r.
//!   N1 * Tp1 + N2 * Tp2 = T exactly; N1 >= 1, so the first pulse is short.
//! * Interleaved: pulse i (0-based) is long when floor((i + 1) * N2 / N) >
//!   floor(i * N2 / N). Its rising edge is then at i * Tp1 + 2 * floor(i *
//!   N2 / N) ticks, less than 2 ticks before the ideal i * T / N.
//!
//! ## Load protocol and timing
//! * A load is accepted at an edge where `ready` is high; `ready` falls
//!   after that edge and rises again after the edge that starts the loaded
//!   period. The slot needs [`LOAD_TO_READY`] clocks (a check and a clamp
//!   clock, a 32-clock division, two clocks of precomputation) before its
//!   period can start.
//! * From idle, a computed period starts at the first tick edge after it is
//!   complete: at the earliest LOAD_TO_READY + 1 clocks after the load edge.
//!   The output rises at that edge when N > 0.
//! * Back to back: a period that is complete when the running one ends
//!   starts on the same tick edge, with zero idle ticks, and `period_done`
//!   strobes exactly T ticks apart. For that the next load must come at
//!   least LOAD_TO_READY + 1 clocks before the edge that ends the running
//!   period. Since `ready` rises only when a period starts, a period that
//!   lasts fewer than LOAD_TO_READY + 2 clocks (T ticks at the tick rate)
//!   cannot be followed without a gap: it underruns.
//! * N = 0: the period lasts T ticks with the output low.
//! * `period`, `count` and `mode` are sampled only with an accepted load.
//!
//! ## Bad input
//! * N > T/2: clamped to T/2 (every pulse 2 ticks), `overrange` set.
//! * Odd T: rounded down to even; T below 2: becomes 2. `overrange` set.
//! * No next period at the end of one: the output stays low, `running`
//!   falls, `underrun` is set; the next computed period starts on the first
//!   tick after it is ready.
//! * A load while `ready` is low: ignored, `overflow` set; the queued
//!   period is not disturbed.
//! * A flag set on the same clock as `clear_flags` stays set.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::sequential_divider::SequentialDivider;

pub use model::{load_to_ready, LOAD_TO_READY};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "dual-period uniform pulse generator: N pulses filling T ticks exactly, next period computed in the background";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[(&str, &str)] = &[
    ("clock", "rising-edge clock"),
    (
        "reset",
        "synchronous reset, active high: idle, slot empty, output low, flags 0",
    ),
    (
        "tick",
        "time base: one tick is the minimum toggle time (tie high for f_clk)",
    ),
    ("period", "T: the interpolation period in ticks (even)"),
    ("count", "N: pulses in the period, 0 <= N <= T/2"),
    (
        "mode",
        "0 = paper order (short pulses first), 1 = interleaved (Bresenham)",
    ),
    (
        "load",
        "strobe: queue (period, count, mode) as the next period; taken only while ready",
    ),
    (
        "clear_flags",
        "clears underrun, overrange and overflow (tie to 0 if unused)",
    ),
    ("pulse", "each pulse high Tp/2 ticks, then low Tp/2 ticks"),
    (
        "period_done",
        "one-clock strobe when a period's T ticks have elapsed",
    ),
    (
        "ready",
        "the next-period slot is free: a load now is accepted (gapless if 39+ clocks before the period ends)",
    ),
    ("running", "a period is in progress"),
    (
        "underrun",
        "sticky: a period ended with no next period ready (output low, waiting)",
    ),
    (
        "overrange",
        "sticky: an odd or too small T, or N > T/2, was corrected",
    ),
    (
        "overflow",
        "sticky: a load arrived while ready was low and was ignored",
    ),
];

/// Slot sequencer states.
const SLOT_EMPTY: u64 = 0;
const SLOT_CHECK: u64 = 1;
const SLOT_CLAMP: u64 = 2;
const SLOT_DIVIDE: u64 = 3;
const SLOT_SPLIT: u64 = 4;
const SLOT_STEPS: u64 = 5;
const SLOT_FULL: u64 = 6;

/// Dual-period uniform pulse generator. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct UniformPulseGen<const W: usize> {
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
    divider: SequentialDivider<W, W>,
    // The next-period slot, filled by a small sequencer after a load.
    slot_state: DFF<Bits<3>>,
    /// `slot_state == full`, registered: the start decision is then one
    /// LUT of four flip-flops, in front of the load of every period
    /// register.
    slot_full: DFF<Bit>,
    slot_period: DFF<Bits<W>>,
    slot_count: DFF<Bits<W>>,
    slot_interleaved: DFF<Bit>,
    slot_half: DFF<Bits<W>>,
    slot_half_is_one: DFF<Bit>,
    slot_long_half: DFF<Bits<W>>,
    slot_short_pulses: DFF<Bits<W>>,
    slot_long_pulses: DFF<Bits<W>>,
    slot_step_long: DFF<Bits<W>>,
    slot_step_short: DFF<Bits<W>>,
    slot_first_error: DFF<Bits<W>>,
    slot_has_pulses: DFF<Bit>,
    // The running period.
    running_reg: DFF<Bit>,
    ticks_left: DFF<Bits<W>>,
    /// `ticks_left == 1`: the next tick edge ends the period.
    period_last: DFF<Bit>,
    half_left: DFF<Bits<W>>,
    /// `half_left == 1`: the next tick edge ends the half pulse.
    half_last: DFF<Bit>,
    pulse_reg: DFF<Bit>,
    long: DFF<Bit>,
    /// Bresenham error, signed: the next pulse is long when it is >= 0.
    error: DFF<Bits<W>>,
    half: DFF<Bits<W>>,
    half_is_one: DFF<Bit>,
    long_half: DFF<Bits<W>>,
    step_long: DFF<Bits<W>>,
    step_short: DFF<Bits<W>>,
    has_pulses: DFF<Bit>,
    period_done_reg: DFF<Bit>,
    underrun_reg: DFF<Bit>,
    overrange_reg: DFF<Bit>,
    overflow_reg: DFF<Bit>,
    /// The loaded T and N checked one clock before they are corrected, so
    /// the 32-bit comparison has a clock of its own.
    period_odd: DFF<Bit>,
    period_small: DFF<Bit>,
    count_too_large: DFF<Bit>,
    start: Signal<Local, Bit>,
    next_long: Signal<Local, Bit>,
    period_half: Signal<Local, Bits<W>>,
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

impl<const W: usize> Default for UniformPulseGen<W> {
    fn default() -> Self {
        assert!((4..=32).contains(&W), "UniformPulseGen: W must be 4 to 32 bits");
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
            divider: Default::default(),
            slot_state: Default::default(),
            slot_full: Default::default(),
            slot_period: Default::default(),
            slot_count: Default::default(),
            slot_interleaved: Default::default(),
            slot_half: Default::default(),
            slot_half_is_one: Default::default(),
            slot_long_half: Default::default(),
            slot_short_pulses: Default::default(),
            slot_long_pulses: Default::default(),
            slot_step_long: Default::default(),
            slot_step_short: Default::default(),
            slot_first_error: Default::default(),
            slot_has_pulses: Default::default(),
            running_reg: Default::default(),
            ticks_left: Default::default(),
            period_last: Default::default(),
            half_left: Default::default(),
            half_last: Default::default(),
            pulse_reg: Default::default(),
            long: Default::default(),
            error: Default::default(),
            half: Default::default(),
            half_is_one: Default::default(),
            long_half: Default::default(),
            step_long: Default::default(),
            step_short: Default::default(),
            has_pulses: Default::default(),
            period_done_reg: Default::default(),
            underrun_reg: Default::default(),
            overrange_reg: Default::default(),
            overflow_reg: Default::default(),
            period_odd: Default::default(),
            period_small: Default::default(),
            count_too_large: Default::default(),
            start: Default::default(),
            next_long: Default::default(),
            period_half: Default::default(),
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

impl<const W: usize> Logic for UniformPulseGen<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            slot_state,
            slot_full,
            slot_period,
            slot_count,
            slot_interleaved,
            slot_half,
            slot_half_is_one,
            slot_long_half,
            slot_short_pulses,
            slot_long_pulses,
            slot_step_long,
            slot_step_short,
            slot_first_error,
            slot_has_pulses,
            running_reg,
            ticks_left,
            period_last,
            half_left,
            half_last,
            pulse_reg,
            long,
            error,
            half,
            half_is_one,
            long_half,
            step_long,
            step_short,
            has_pulses,
            period_done_reg,
            underrun_reg,
            overrange_reg,
            overflow_reg,
            period_odd,
            period_small,
            count_too_large
        );
        self.divider.clock.next = self.clock.val();
        self.divider.reset.next = self.reset.val();
        self.divider.start.next = false;
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

        // The slot: load, clamp, divide T/2 by N, then precompute what the
        // first clock of the period needs.
        self.period_half.next = self.slot_period.q.val() >> self.one.val();
        self.period_odd.d.next = self.slot_period.q.val().get_bit(0);
        self.period_small.d.next =
            (self.slot_period.q.val() & self.not_one.val()) == self.zero.val();
        self.count_too_large.d.next = self.slot_count.q.val() > self.period_half.val();
        self.divider.dividend.next = self.period_half.val();
        self.divider.divisor.next = self.slot_count.q.val();
        if self.slot_state.q.val() == self.empty.val() {
            if self.load.val() {
                self.slot_state.d.next = self.check.val();
                self.slot_period.d.next = self.period.val();
                self.slot_count.d.next = self.count.val();
                self.slot_interleaved.d.next = self.mode.val();
            }
        } else if self.load.val() {
            self.overflow_reg.d.next = true;
        }
        if self.slot_state.q.val() == self.check.val() {
            self.slot_state.d.next = self.clamp.val();
        }
        if self.slot_state.q.val() == self.clamp.val() {
            // An odd T is rounded down; a T below 2 becomes 2; N > T/2 is
            // clamped to T/2 (with T corrected first).
            if self.period_odd.q.val() {
                self.overrange_reg.d.next = true;
            }
            self.slot_period.d.next = self.slot_period.q.val() & self.not_one.val();
            if self.period_small.q.val() {
                self.overrange_reg.d.next = true;
                self.slot_period.d.next = self.two.val();
                if self.slot_count.q.val() != self.zero.val() {
                    self.slot_count.d.next = self.one.val();
                }
                if self.slot_count.q.val() > self.one.val() {
                    self.overrange_reg.d.next = true;
                }
            } else if self.count_too_large.q.val() {
                self.overrange_reg.d.next = true;
                self.slot_count.d.next = self.period_half.val();
            }
            self.slot_state.d.next = self.divide.val();
        }
        if self.slot_state.q.val() == self.divide.val() {
            if !self.divider.busy.val() & !self.divider.done.val() {
                self.divider.start.next = true;
            }
            if self.divider.done.val() {
                self.slot_half.d.next = self.divider.quotient.val();
                self.slot_long_pulses.d.next = self.divider.remainder.val();
                self.slot_has_pulses.d.next = self.slot_count.q.val() != self.zero.val();
                self.slot_state.d.next = self.split.val();
            }
        }
        if self.slot_state.q.val() == self.split.val() {
            self.slot_short_pulses.d.next = self.slot_count.q.val() - self.slot_long_pulses.q.val();
            self.slot_long_half.d.next = self.slot_half.q.val() + self.one.val();
            self.slot_half_is_one.d.next = self.slot_half.q.val() == self.one.val();
            self.slot_state.d.next = self.steps.val();
        }
        if self.slot_state.q.val() == self.steps.val() {
            // Error steps: paper order counts the pulse index up from -N1;
            // interleaved adds N2 per short pulse and subtracts N1 per long
            // one. Pulse 0 is short, so the period starts one step in.
            if self.slot_interleaved.q.val() {
                self.slot_step_short.d.next = self.slot_long_pulses.q.val();
                self.slot_step_long.d.next = self.zero.val() - self.slot_short_pulses.q.val();
                self.slot_first_error.d.next =
                    self.slot_long_pulses.q.val() - self.slot_short_pulses.q.val();
            } else {
                self.slot_step_short.d.next = self.one.val();
                self.slot_step_long.d.next = self.one.val();
                self.slot_first_error.d.next = self.one.val() - self.slot_short_pulses.q.val();
            }
            self.slot_state.d.next = self.full.val();
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
                        if self.half_last.q.val() {
                            if self.pulse_reg.q.val() {
                                // The low half of a pulse is as long as its
                                // high half.
                                self.pulse_reg.d.next = false;
                                if self.long.q.val() {
                                    self.half_left.d.next = self.long_half.q.val();
                                    self.half_last.d.next = false;
                                } else {
                                    self.half_left.d.next = self.half.q.val();
                                    self.half_last.d.next = self.half_is_one.q.val();
                                }
                            } else {
                                self.pulse_reg.d.next = true;
                                self.long.d.next = self.next_long.val();
                                if self.next_long.val() {
                                    self.half_left.d.next = self.long_half.q.val();
                                    self.half_last.d.next = false;
                                    self.error.d.next = self.error.q.val() + self.step_long.q.val();
                                } else {
                                    self.half_left.d.next = self.half.q.val();
                                    self.half_last.d.next = self.half_is_one.q.val();
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
            self.pulse_reg.d.next = self.slot_has_pulses.q.val();
            self.long.d.next = false;
            self.error.d.next = self.slot_first_error.q.val();
            self.half.d.next = self.slot_half.q.val();
            self.half_is_one.d.next = self.slot_half_is_one.q.val();
            self.long_half.d.next = self.slot_long_half.q.val();
            self.step_long.d.next = self.slot_step_long.q.val();
            self.step_short.d.next = self.slot_step_short.q.val();
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

crate::vector_ports!(impl[const W: usize] UniformPulseGen<W> {
    inputs: [reset, tick, period, count, mode, load, clear_flags],
    outputs: [pulse, period_done, ready, running, underrun, overrange, overflow],
});
