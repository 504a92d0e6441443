//! # `uniform_pulse_gen`: dual-period uniform pulse generator
//!
//! Emits N pulses in an interpolation period of T ticks and fills the
//! period exactly, for every N: N1 pulses of period Tp1 and N2 of period
//! Tp2 = Tp1 + 2 (shared/BACKGROUND.md, section 2). The single-period
//! algorithm, N pulses of Tp1 and then idle, leaves up to almost half of the
//! period empty; this block leaves none. It computes Tp1, N1 and N2 itself
//! with a [`SequentialDivider`](crate::blocks::sequential_divider::SequentialDivider), for the next period while the current one
//! runs, so loaded periods follow each other with zero idle ticks.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
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
//!   period. The slot needs [`LOAD_TO_READY`] clocks (a check and a correction
//!   clock, the 32-clock plan of the [`PeriodPlanner`] and its start
//!   clock, and two spare clocks where the split once was) before its
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
//! * N > T/2: clamped to T/2 (every pulse 2 ticks), `overrange` set at the
//!   edge the slot takes its plan: LOAD_TO_READY - 2 clocks after the load
//!   edge (later in the motion controller while the shared planner serves
//!   another axis). N is compared with the corrected T.
//! * Odd T: rounded down to even; T below 2: becomes 2. `overrange` set 2
//!   clocks after the load edge.
//! * No next period at the end of one: the output stays low, `running`
//!   falls, `underrun` is set; the next computed period starts on the first
//!   tick after it is ready.
//! * A load while `ready` is low: ignored, `overflow` set; the queued
//!   period is not disturbed.
//! * A flag set on the same clock as `clear_flags` stays set.
//!
//! ## Structure
//! [`UniformPulseCore`] (the slot sequencer and the running period) asks
//! for the plan of (T/2, N) on a planning port, which this block answers
//! with a [`PeriodPlanner`] of its own: a
//! [`SequentialDivider`](crate::blocks::sequential_divider::SequentialDivider)
//! for T/2 / N, whose zero quotient is the clamp of N, and the split into
//! N1 and N2. The motion controller instead answers its axes' cores from
//! one shared planner, in turns, so the comparator, the clamp and the
//! subtractor exist once there. A long pulse's half
//! is a short half plus one tick (`stretch`), so neither Tp2/2 nor the
//! error steps are stored in the slot: the steps are formed when a period
//! starts, from N2, -N1 (as the planner gives it) and the order, with one
//! adder: the first error is the short step plus -N1.

pub mod model;
pub mod period_planner;
pub mod pulse_core;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

pub use period_planner::PeriodPlanner;
pub use pulse_core::UniformPulseCore;

pub use model::{load_to_ready, LOAD_TO_READY};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "dual-period uniform pulse generator: N pulses filling T ticks exactly, next period computed in the background";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: idle, slot empty, output low, flags 0 (the datapath registers are not cleared: they are always loaded before use)"),
    port("tick", "1", "time base: one tick is the minimum toggle time (tie high for f_clk)"),
    port("period", "32", "T: the interpolation period in ticks (even)"),
    port("count", "32", "N: pulses in the period, 0 <= N <= T/2"),
    port("mode", "1", "0 = paper order (N1 short pulses, then N2 long); 1 = interleaved (Bresenham over the pulse index)"),
    port("load", "1", "strobe: queue (period, count, mode) as the next period; taken only while `ready` is high"),
    port("clear_flags", "1", "clears `underrun`, `overrange` and `overflow` (tie to 0 if unused)"),
    port("pulse", "1", "each pulse is high Tp/2 ticks, then low Tp/2 ticks; registered"),
    port("period_done", "1", "one-clock strobe when a period's T ticks have elapsed"),
    port("ready", "1", "the next-period slot is free: a load now is accepted (gapless if 39 or more clocks before the period ends)"),
    port("running", "1", "a period is in progress"),
    port("underrun", "1", "sticky: a period ended with no next period ready; the output stays low and the block waits"),
    port("overrange", "1", "sticky: an odd or too small T, or N > T/2, was corrected"),
    port("overflow", "1", "sticky: a load arrived while `ready` was low and was ignored"),
];

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
    core: UniformPulseCore<W, W>,
    planner: PeriodPlanner<W>,
    zero: Constant<Bits<W>>,
}

impl<const W: usize> Default for UniformPulseGen<W> {
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
            core: Default::default(),
            planner: Default::default(),
            zero: Constant::new(0u64.into()),
        }
    }
}

impl<const W: usize> Logic for UniformPulseGen<W> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, core, planner);
        self.core.reset.next = self.reset.val();
        self.core.tick.next = self.tick.val();
        self.core.period.next = self.period.val();
        self.core.count.next = self.count.val();
        self.core.mode.next = self.mode.val();
        self.core.load.next = self.load.val();
        self.core.clear_flags.next = self.clear_flags.val();
        // No DDA mode: J = 0 leaves the engine to the generator.
        self.core.dda_tick.next = false;
        self.core.dda_reload.next = false;
        self.core.dda_integrand.next = self.zero.val();
        self.core.dda_active.next = false;
        self.core.dda_modulus_negated.next = self.zero.val();
        self.core.dda_clear_overrange.next = false;
        self.pulse.next = self.core.pulse.val();
        self.period_done.next = self.core.period_done.val();
        self.ready.next = self.core.ready.val();
        self.running.next = self.core.running.val();
        self.underrun.next = self.core.underrun.val();
        self.overrange.next = self.core.overrange.val();
        self.overflow.next = self.core.overflow.val();
        // A planner of its own is idle whenever the slot asks: the plan
        // starts in the request's first clock.
        self.planner.reset.next = self.reset.val();
        self.planner.start.next =
            self.core.div_request.val() & !self.planner.busy.val() & !self.planner.done.val();
        self.planner.dividend.next = self.core.div_dividend.val();
        self.planner.divisor.next = self.core.div_divisor.val();
        self.core.div_done.next = self.planner.done.val();
        self.core.div_half.next = self.planner.half.val();
        self.core.div_long_pulses.next = self.planner.long_pulses.val();
        self.core.div_short_negated.next = self.planner.short_negated.val();
        self.core.div_half_is_one.next = self.planner.half_is_one.val();
        self.core.div_has_pulses.next = self.planner.has_pulses.val();
        self.core.div_clamped.next = self.planner.clamped.val();
    }
}

crate::vector_ports!(impl[const W: usize] UniformPulseGen<W> {
    inputs: [reset, tick, period, count, mode, load, clear_flags],
    outputs: [pulse, period_done, ready, running, underrun, overrange, overflow],
});
