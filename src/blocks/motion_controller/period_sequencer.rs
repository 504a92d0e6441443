//! Run control and the period boundary: CONTROL.RUN and FLUSH, the base
//! ticks of each period, and the boundary at which every FIFO pops or the
//! run stops on an underrun.
//!
//! Internal to [`super::MotionController`]; the behavior is the
//! controller's ("Time base and periods" in its datasheet), modelled by
//! [`super::model`].
//!
//! ## Contract (as the controller uses it)
//! * `start`, `halt`, `flush`, `pop`, `underrun` and `period_done` are
//!   combinational, in the clock of their cause.
//! * A start (a CONTROL write with RUN set, not refused) sets RUN; the
//!   first base tick after it is a boundary. A boundary while RUN pops
//!   every FIFO if all have an entry (`all_ready`), else it is an
//!   underrun. A halt (a CONTROL write with RUN clear, or `abort`) wins
//!   over a boundary in the same clock: nothing is popped.
//! * Each popped period lasts PERIOD_TICKS base ticks (0 acting as 1),
//!   taken at its boundary (`period_active`, and one clock later its
//!   negation `modulus_negated`, formed once for every axis's DDA).
//! * PERIOD_COUNT counts pops from reset, wrapping at 2^32.

use rust_hdl::prelude::*;

use super::{ERROR_BITS, PERIOD_BITS};

/// Run control and period boundaries. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct PeriodSequencer {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: stopped, counters 0.
    pub reset: Signal<In, Bit>,
    /// Base tick.
    pub tick: Signal<In, Bit>,
    /// A write to CONTROL in this clock.
    pub control_write: Signal<In, Bit>,
    /// The written CONTROL.RUN.
    pub run_bit: Signal<In, Bit>,
    /// The written CONTROL.FLUSH.
    pub flush_bit: Signal<In, Bit>,
    /// RUN may not start now (a held stop cause, or inputs not ready).
    pub refuse_run: Signal<In, Bit>,
    /// Stop now (a stop cause or the watchdog).
    pub abort: Signal<In, Bit>,
    /// Every axis's FIFO has an entry.
    pub all_ready: Signal<In, Bit>,
    /// PERIOD_TICKS.VALUE.
    pub period_ticks: Signal<In, Bits<PERIOD_BITS>>,
    /// RUN starts in this clock.
    pub start: Signal<Out, Bit>,
    /// RUN is cleared or the run aborted in this clock.
    pub halt: Signal<Out, Bit>,
    /// A FLUSH write in this clock.
    pub flush: Signal<Out, Bit>,
    /// A boundary pops every FIFO in this clock.
    pub pop: Signal<Out, Bit>,
    /// A boundary found an empty FIFO in this clock.
    pub underrun: Signal<Out, Bit>,
    /// A pop ends a period (not the first pop after a start).
    pub period_done: Signal<Out, Bit>,
    /// RUN (CONTROL.RUN, STATE.RUNNING).
    pub running: Signal<Out, Bit>,
    /// The running period's length in base ticks, from its boundary on.
    pub period_active: Signal<Out, Bits<PERIOD_BITS>>,
    /// -`period_active` one clock late, in `ERROR_BITS` two's complement:
    /// the DDAs' -M (the DDA mode of
    /// [`UniformPulseCore`](crate::blocks::uniform_pulse_gen::UniformPulseCore)).
    pub modulus_negated: Signal<Out, Bits<ERROR_BITS>>,
    /// PERIOD_COUNT.
    pub period_count: Signal<Out, Bits<32>>,

    run: DFF<Bit>,
    /// Base ticks left in the running period after the next one.
    ticks_left: DFF<Bits<PERIOD_BITS>>,
    /// The next base tick is a boundary.
    boundary_next: DFF<Bit>,
    /// A period has been popped since the start (so a boundary ends one).
    in_period: DFF<Bit>,
    period_active_reg: DFF<Bits<PERIOD_BITS>>,
    modulus_negated_reg: DFF<Bits<ERROR_BITS>>,
    period_count_reg: DFF<Bits<32>>,
    boundary: Signal<Local, Bit>,
    /// PERIOD_TICKS, 0 acting as 1.
    period_next: Signal<Local, Bits<PERIOD_BITS>>,
    zero_p: Constant<Bits<PERIOD_BITS>>,
    zero_e: Constant<Bits<ERROR_BITS>>,
    one_p: Constant<Bits<PERIOD_BITS>>,
    two_p: Constant<Bits<PERIOD_BITS>>,
    not_one_p: Constant<Bits<PERIOD_BITS>>,
    zero32: Constant<Bits<32>>,
    one32: Constant<Bits<32>>,
}

impl Default for PeriodSequencer {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            control_write: Default::default(),
            run_bit: Default::default(),
            flush_bit: Default::default(),
            refuse_run: Default::default(),
            abort: Default::default(),
            all_ready: Default::default(),
            period_ticks: Default::default(),
            start: Default::default(),
            halt: Default::default(),
            flush: Default::default(),
            pop: Default::default(),
            underrun: Default::default(),
            period_done: Default::default(),
            running: Default::default(),
            period_active: Default::default(),
            modulus_negated: Default::default(),
            period_count: Default::default(),
            run: Default::default(),
            ticks_left: Default::default(),
            boundary_next: Default::default(),
            in_period: Default::default(),
            period_active_reg: Default::default(),
            modulus_negated_reg: Default::default(),
            period_count_reg: Default::default(),
            boundary: Default::default(),
            period_next: Default::default(),
            zero_p: Constant::new(0u64.into()),
            zero_e: Constant::new(0u64.into()),
            one_p: Constant::new(1u64.into()),
            two_p: Constant::new(2u64.into()),
            not_one_p: Constant::new((crate::blocks::width_mask(PERIOD_BITS as u32) & !1).into()),
            zero32: Constant::new(0u64.into()),
            one32: Constant::new(1u64.into()),
        }
    }
}

impl Logic for PeriodSequencer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            run,
            ticks_left,
            boundary_next,
            in_period,
            period_active_reg,
            modulus_negated_reg,
            period_count_reg
        );
        self.running.next = self.run.q.val();
        self.period_active.next = self.period_active_reg.q.val();
        self.modulus_negated.next = self.modulus_negated_reg.q.val();
        self.period_count.next = self.period_count_reg.q.val();

        self.start.next = self.control_write.val() & self.run_bit.val() & !self.refuse_run.val();
        self.halt.next = (self.control_write.val() & !self.run_bit.val()) | self.abort.val();
        self.flush.next = self.control_write.val() & self.flush_bit.val();
        self.boundary.next = self.run.q.val() & self.tick.val() & self.boundary_next.q.val();
        // A stop on the boundary clock wins: nothing is popped.
        self.pop.next = self.boundary.val() & self.all_ready.val() & !self.halt.val();
        self.underrun.next = self.boundary.val() & !self.all_ready.val() & !self.halt.val();
        self.period_done.next = self.pop.val() & self.in_period.q.val();
        self.period_next.next = self.period_ticks.val();
        if self.period_ticks.val() == self.zero_p.val() {
            self.period_next.next = self.one_p.val();
        }
        if self.start.val() {
            self.run.d.next = true;
            self.boundary_next.d.next = true;
            self.in_period.d.next = false;
        }
        if self.run.q.val() & self.tick.val() {
            if self.boundary_next.q.val() {
                self.ticks_left.d.next = self.period_next.val();
                // The next tick is a boundary again when PERIOD_TICKS <= 1.
                self.boundary_next.d.next =
                    (self.period_ticks.val() & self.not_one_p.val()) == self.zero_p.val();
                self.period_active_reg.d.next = self.period_next.val();
            } else {
                self.ticks_left.d.next = self.ticks_left.q.val() - self.one_p.val();
                self.boundary_next.d.next = self.ticks_left.q.val() == self.two_p.val();
            }
        }
        self.modulus_negated_reg.d.next =
            self.zero_e.val() - bit_cast::<ERROR_BITS, PERIOD_BITS>(self.period_active_reg.q.val());
        if self.pop.val() {
            self.in_period.d.next = true;
            self.period_count_reg.d.next = self.period_count_reg.q.val() + self.one32.val();
        }
        if self.underrun.val() | self.halt.val() {
            self.run.d.next = false;
            self.in_period.d.next = false;
        }
        if self.reset.val() {
            self.run.d.next = false;
            self.ticks_left.d.next = self.zero_p.val();
            self.boundary_next.d.next = false;
            self.in_period.d.next = false;
            self.period_active_reg.d.next = self.zero_p.val();
            self.modulus_negated_reg.d.next = self.zero_e.val();
            self.period_count_reg.d.next = self.zero32.val();
        }
    }
}
