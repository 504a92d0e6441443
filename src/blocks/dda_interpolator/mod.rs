//! # `dda_interpolator`: K-axis DDA fine interpolator with exact fractional steps
//!
//! The FPGA half of a two-level interpolator: every interpolation period the
//! CPU gives each axis a signed step count (Q16.16 fixed point, so fractional
//! steps are allowed) and the period length P in ticks. The block spreads each
//! axis's steps evenly over the P ticks, all axes in lockstep, and carries
//! every fractional remainder into the next period: over any sequence of
//! periods, the steps emitted equal the floor of the summed deltas exactly,
//! whatever P does from one period to the next.
//!
//! ## Ports (`K` = 3 in the exported `dda_interpolator`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Load protocol
//! Write `next_period` and `next_delta_*`, then pulse `load` while `ready` is
//! high. The block then divides each |delta| by P with one shared
//! [`SequentialDivider`] (35 clocks per axis, 35 * K in all, during
//! which `ready` is low) and holds the result in the pending slot. At the
//! end of the current period, on the clock edge of its last tick, every axis
//! switches to the pending command at once; `ready` rises again and the next
//! period can be loaded. The CPU therefore loads period n+1 during period n,
//! at least 35 * K + 2 clocks before it ends.
//!
//! From idle (after reset or an underrun), a completed load starts the
//! period on the next clock edge; its first tick is the first tick after.
//!
//! ## Timing
//! A step caused by the tick sampled at edge t is high in the clock after
//! edge t + 3 (latency 4, the same on every axis). `dir` changes only in a
//! clock in which a step in the new direction starts, so it is stable during
//! every step pulse; the step output stage enforces setup and hold towards
//! the drive. `period_done` is high in the clock after the edge of a
//! period's last tick. Steps of the last ticks of a period appear after
//! `period_done`, within the latency.
//!
//! ## Arithmetic: exact, drift-free
//! With d the delta in 2^-16 steps, the divider gives d = q * P + r with
//! 0 <= r < P (floor division, also for negative d). Each tick adds q to the
//! axis's position fraction, plus one more unit when a [`DdaIntegrator`](crate::blocks::dda_integrator::DdaIntegrator)
//! with J = r and M = P overflows (exactly r times per period, evenly). So
//! t ticks into a period the position is exactly `base + floor(d * t / P)`
//! units, and a step comes on the first tick at which the ideal linear
//! position `base + d * t / P` reaches the next whole step: every step is at
//! its ideal Bresenham position, rounded up to the next tick. Nothing is
//! cleared at period boundaries except the remainder DDA, whose accumulator
//! is back at 0 after every full period anyway.
//!
//! ## Bad input
//! * Underrun (a period ends with nothing queued): ticks stop being used, no
//!   step is invented, `running` falls and the sticky `underrun` is set. The
//!   position fractions are kept, so the next `load` resumes cleanly.
//! * |delta| > P steps (more than one step per tick): clamped to one step per
//!   tick in the delta's direction, sticky `overrange` set. Those steps are
//!   lost to the clamp: the flag is the report.
//! * `load` while not `ready`, or with P = 0 or P >= 2^24: refused, sticky
//!   `load_error` set; the queued period is not disturbed.

mod axis;
pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

pub use axis::{InterpolatorAxis, PERIOD_BITS, Q_BITS};

use crate::blocks::sequential_divider::SequentialDivider;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "K-axis DDA fine interpolator: Q16.16 steps per period, double-buffered, drift-free";

/// Meaning of every port, for the export header and the `rtl-out` index.
/// Array ports are documented once, as `name__i`.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: idle, nothing queued, position fractions 0, flags 0"),
    port("tick", "1", "time base, for example a `freq_divider` strobe"),
    port("load", "1", "strobe: queue `next_period` and `next_delta_*` as the next period (taken only while `ready`)"),
    port("next_period", "32", "P, the next period's length in ticks: 1 to 2^24-1 (167 ms at a 100 MHz tick)"),
    port("next_delta__i", "32", "axis i's steps for the next period, signed Q16.16 (-32768.0 to 32767.99998), at most one step per tick"),
    port("clear_status", "1", "clears `underrun`, `overrange` and `load_error`"),
    port("step__i", "1", "axis i's one-clock step pulse"),
    port("dir__i", "1", "axis i's direction: 1 = positive; set with each step"),
    port("period_done", "1", "one-clock strobe after the last tick of every period"),
    port("ready", "1", "the next-period slot is free: a `load` now is taken"),
    port("running", "1", "a period is in progress (ticks are being used)"),
    port("underrun", "1", "sticky: a period ended with no next period queued"),
    port("overrange", "1", "sticky: a delta asked for more than one step per tick and was clamped"),
    port("load_error", "1", "sticky: a `load` was refused (not `ready`, or P out of range)"),
];

/// K-axis DDA fine interpolator. See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct DdaInterpolator<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Time base.
    pub tick: Signal<In, Bit>,
    /// Queue the next period.
    pub load: Signal<In, Bit>,
    /// P of the next period, in ticks (1 to 2^24 - 1).
    pub next_period: Signal<In, Bits<32>>,
    /// Per axis: signed Q16.16 steps of the next period.
    pub next_delta: [Signal<In, Bits<32>>; K],
    /// Clears the sticky flags.
    pub clear_status: Signal<In, Bit>,
    /// Per axis: step pulse.
    pub step: [Signal<Out, Bit>; K],
    /// Per axis: direction.
    pub dir: [Signal<Out, Bit>; K],
    /// Strobe after each period's last tick.
    pub period_done: Signal<Out, Bit>,
    /// The next-period slot is free.
    pub ready: Signal<Out, Bit>,
    /// A period is in progress.
    pub running: Signal<Out, Bit>,
    /// Sticky: a period ended with nothing queued.
    pub underrun: Signal<Out, Bit>,
    /// Sticky: a delta was clamped.
    pub overrange: Signal<Out, Bit>,
    /// Sticky: a load was refused.
    pub load_error: Signal<Out, Bit>,
    axes: [InterpolatorAxis; K],
    /// |delta| (32 bits) by P (24 bits): the remainder is below P, so the
    /// divider's subtractor is only 24 bits long.
    divider: SequentialDivider<32, PERIOD_BITS>,
    staged_period: DFF<Bits<32>>,
    pending_period: DFF<Bits<PERIOD_BITS>>,
    active_period: DFF<Bits<PERIOD_BITS>>,
    /// Used ticks left in the active period after the next one.
    ticks_left: DFF<Bits<PERIOD_BITS>>,
    /// Registered `ticks_left == 0`: the next used tick ends the period.
    /// A flip-flop keeps the period-end test off the commit fan-out path.
    at_last: DFF<Bit>,
    is_running: DFF<Bit>,
    pending_valid: DFF<Bit>,
    computing: DFF<Bit>,
    division_issued: DFF<Bit>,
    axis_index: DFF<Bits<8>>,
    period_done_reg: DFF<Bit>,
    underrun_reg: DFF<Bit>,
    overrange_reg: DFF<Bit>,
    load_error_reg: DFF<Bit>,
    /// The divider's result, one clock after `done`: the clamp test is
    /// registered with it, so no divider output reaches the axes' pending
    /// registers through more than one carry chain.
    result_ready: DFF<Bit>,
    result_clamped: DFF<Bit>,
    over_limit: Signal<Local, Bit>,
    used_tick: Signal<Local, Bit>,
    last_tick: Signal<Local, Bit>,
    commit: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
    slot_free: Signal<Local, Bit>,
    zero: Constant<Bits<32>>,
    zero_p: Constant<Bits<PERIOD_BITS>>,
    /// Bits 24 and up of a period: set means P does not fit.
    period_too_long: Constant<Bits<32>>,
    one_p: Constant<Bits<PERIOD_BITS>>,
    first_axis: Constant<Bits<8>>,
    next_axis: Constant<Bits<8>>,
    last_axis: Constant<Bits<8>>,
    one_step: Constant<Bits<32>>,
    above_one_step: Constant<Bits<32>>,
    below_one_step: Constant<Bits<32>>,
}

impl<const K: usize> Default for DdaInterpolator<K> {
    fn default() -> Self {
        assert!(
            (1..=64).contains(&K),
            "DdaInterpolator supports 1 to 64 axes"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            load: Default::default(),
            next_period: Default::default(),
            next_delta: array_init::array_init(|_| Default::default()),
            clear_status: Default::default(),
            step: array_init::array_init(|_| Default::default()),
            dir: array_init::array_init(|_| Default::default()),
            period_done: Default::default(),
            ready: Default::default(),
            running: Default::default(),
            underrun: Default::default(),
            overrange: Default::default(),
            load_error: Default::default(),
            axes: array_init::array_init(|_| Default::default()),
            divider: Default::default(),
            staged_period: Default::default(),
            pending_period: Default::default(),
            active_period: Default::default(),
            ticks_left: Default::default(),
            at_last: Default::default(),
            is_running: Default::default(),
            pending_valid: Default::default(),
            computing: Default::default(),
            division_issued: Default::default(),
            axis_index: Default::default(),
            period_done_reg: Default::default(),
            underrun_reg: Default::default(),
            overrange_reg: Default::default(),
            load_error_reg: Default::default(),
            result_ready: Default::default(),
            result_clamped: Default::default(),
            over_limit: Default::default(),
            used_tick: Default::default(),
            last_tick: Default::default(),
            commit: Default::default(),
            accept: Default::default(),
            slot_free: Default::default(),
            zero: Constant::new(0u64.into()),
            zero_p: Constant::new(0u64.into()),
            period_too_long: Constant::new((0xffff_ffffu64 & !((1u64 << PERIOD_BITS) - 1)).into()),
            one_p: Constant::new(1u64.into()),
            first_axis: Constant::new(0u64.into()),
            next_axis: Constant::new(1u64.into()),
            last_axis: Constant::new(((K - 1) as u64).into()),
            one_step: Constant::new((1u64 << 16).into()),
            above_one_step: Constant::new((0xffff_ffffu64 & !0x1_ffff).into()),
            below_one_step: Constant::new(0xffffu64.into()),
        }
    }
}

impl<const K: usize> Logic for DdaInterpolator<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            staged_period,
            pending_period,
            active_period,
            ticks_left,
            at_last,
            is_running,
            pending_valid,
            computing,
            division_issued,
            axis_index,
            period_done_reg,
            underrun_reg,
            overrange_reg,
            load_error_reg,
            result_ready,
            result_clamped
        );
        self.divider.clock.next = self.clock.val();
        self.divider.reset.next = self.reset.val();
        self.period_done.next = self.period_done_reg.q.val();
        self.running.next = self.is_running.q.val();
        self.underrun.next = self.underrun_reg.q.val();
        self.overrange.next = self.overrange_reg.q.val();
        self.load_error.next = self.load_error_reg.q.val();
        self.slot_free.next = !self.computing.q.val() & !self.pending_valid.q.val();
        self.ready.next = self.slot_free.val();

        // Period timing: ticks count only while a period runs.
        self.used_tick.next = self.tick.val() & self.is_running.q.val();
        self.last_tick.next = self.used_tick.val() & self.at_last.q.val();
        self.commit.next =
            self.pending_valid.q.val() & (self.last_tick.val() | !self.is_running.q.val());
        self.period_done_reg.d.next = self.last_tick.val();
        if self.used_tick.val() {
            self.ticks_left.d.next = self.ticks_left.q.val() - self.one_p.val();
            self.at_last.d.next = self.ticks_left.q.val() == self.one_p.val();
        }
        if self.last_tick.val() {
            self.is_running.d.next = false;
            if !self.pending_valid.q.val() {
                self.underrun_reg.d.next = true;
            }
        }
        if self.commit.val() {
            self.active_period.d.next = self.pending_period.q.val();
            self.ticks_left.d.next = self.pending_period.q.val() - self.one_p.val();
            self.at_last.d.next = self.pending_period.q.val() == self.one_p.val();
            self.is_running.d.next = true;
            self.pending_valid.d.next = false;
        }

        // Load: stage the command, then divide each axis's |delta| by P.
        // P must be 1 to 2^24 - 1: zero and wider values are refused.
        self.accept.next = self.load.val()
            & self.slot_free.val()
            & (self.next_period.val() != self.zero.val())
            & ((self.next_period.val() & self.period_too_long.val()) == self.zero.val());
        if self.load.val() & !self.accept.val() {
            self.load_error_reg.d.next = true;
        }
        if self.accept.val() {
            self.staged_period.d.next = self.next_period.val();
            self.computing.d.next = true;
            self.division_issued.d.next = false;
            self.axis_index.d.next = self.first_axis.val();
        }
        self.divider.start.next = self.computing.q.val() & !self.division_issued.q.val();
        self.divider.divisor.next = self.staged_period.q.val().get_bits::<PERIOD_BITS>(0);
        self.divider.dividend.next = self.zero.val();
        if self.divider.start.val() {
            self.division_issued.d.next = true;
        }
        // |d| = q'P + r' exceeds one step per tick when q' > 2^16, or q' = 2^16
        // with r' != 0: bit tests, no carry chain.
        self.over_limit.next = ((self.divider.quotient.val() & self.above_one_step.val())
            != self.zero.val())
            | (((self.divider.quotient.val() & self.one_step.val()) != self.zero.val())
                & (((self.divider.quotient.val() & self.below_one_step.val()) != self.zero.val())
                    | (self.divider.remainder.val() != self.zero_p.val())));
        self.result_ready.d.next = self.divider.done.val();
        self.result_clamped.d.next = self.over_limit.val();
        if self.result_ready.q.val() & self.result_clamped.q.val() {
            self.overrange_reg.d.next = true;
        }
        if self.result_ready.q.val() {
            self.division_issued.d.next = false;
            self.axis_index.d.next = self.axis_index.q.val() + self.next_axis.val();
            if self.axis_index.q.val() == self.last_axis.val() {
                self.computing.d.next = false;
                self.pending_valid.d.next = true;
                self.pending_period.d.next = self.staged_period.q.val().get_bits::<PERIOD_BITS>(0);
            }
        }
        for i in 0..K {
            self.axes[i].clock.next = self.clock.val();
            self.axes[i].reset.next = self.reset.val();
            self.axes[i].stage.next = self.accept.val();
            self.axes[i].delta.next = self.next_delta[i].val();
            self.axes[i].quotient.next = self.divider.quotient.val().get_bits::<Q_BITS>(0);
            self.axes[i].remainder.next = self.divider.remainder.val();
            self.axes[i].staged_period.next = self.staged_period.q.val().get_bits::<PERIOD_BITS>(0);
            self.axes[i].write_result.next =
                self.result_ready.q.val() & (self.axis_index.q.val().index() == i);
            self.axes[i].clamp.next = self.result_clamped.q.val();
            if self.axis_index.q.val().index() == i {
                self.divider.dividend.next = self.axes[i].magnitude.val();
            }
            self.axes[i].commit.next = self.commit.val();
            self.axes[i].tick.next = self.used_tick.val();
            self.axes[i].active_period.next = self.active_period.q.val();
            self.step[i].next = self.axes[i].step.val();
            self.dir[i].next = self.axes[i].dir.val();
        }

        if self.clear_status.val() {
            self.underrun_reg.d.next = false;
            self.overrange_reg.d.next = false;
            self.load_error_reg.d.next = false;
        }
        if self.reset.val() {
            self.staged_period.d.next = self.zero.val();
            self.pending_period.d.next = self.zero_p.val();
            self.active_period.d.next = self.zero_p.val();
            self.ticks_left.d.next = self.zero_p.val();
            self.at_last.d.next = false;
            self.is_running.d.next = false;
            self.pending_valid.d.next = false;
            self.computing.d.next = false;
            self.division_issued.d.next = false;
            self.axis_index.d.next = self.first_axis.val();
            self.period_done_reg.d.next = false;
            self.underrun_reg.d.next = false;
            self.overrange_reg.d.next = false;
            self.load_error_reg.d.next = false;
            self.result_ready.d.next = false;
            self.result_clamped.d.next = false;
        }
    }
}

impl<const K: usize> crate::sim::VectorPorts for DdaInterpolator<K> {
    fn input_names() -> Vec<String> {
        let mut names: Vec<String> = ["reset", "tick", "load", "next_period"]
            .map(String::from)
            .to_vec();
        names.extend((0..K).map(|i| format!("next_delta__{i}")));
        names.push("clear_status".into());
        names
    }
    fn output_names() -> Vec<String> {
        let mut names: Vec<String> = (0..K).map(|i| format!("step__{i}")).collect();
        names.extend((0..K).map(|i| format!("dir__{i}")));
        names.extend(
            [
                "period_done",
                "ready",
                "running",
                "underrun",
                "overrange",
                "load_error",
            ]
            .map(String::from),
        );
        names
    }
    fn clock_mut(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }
    fn set_inputs(&mut self, values: &[u64]) {
        use crate::sim::PortValue;
        self.reset.next = PortValue::from_vector(values[0]);
        self.tick.next = PortValue::from_vector(values[1]);
        self.load.next = PortValue::from_vector(values[2]);
        self.next_period.next = PortValue::from_vector(values[3]);
        for (i, delta) in self.next_delta.iter_mut().enumerate() {
            delta.next = PortValue::from_vector(values[4 + i]);
        }
        self.clear_status.next = PortValue::from_vector(values[4 + K]);
    }
    fn outputs(&self) -> Vec<u64> {
        use crate::sim::PortValue;
        let mut out: Vec<u64> = self.step.iter().map(|s| s.val().to_vector()).collect();
        out.extend(self.dir.iter().map(|s| s.val().to_vector()));
        out.extend(
            [
                &self.period_done,
                &self.ready,
                &self.running,
                &self.underrun,
                &self.overrange,
                &self.load_error,
            ]
            .iter()
            .map(|s| s.val().to_vector()),
        );
        out
    }
}
