//! # `step_output`: step/dir, up/down and quadrature output with enforced timing
//!
//! Sits between a fine interpolator and the pins. It keeps a signed count of
//! pending steps (forward requests add one, backward requests subtract one,
//! so opposite requests cancel) and emits them as fast as the programmed
//! drive timing allows: it delays steps, it never drops or merges them.
//!
//! ## Ports (`T` = 16-bit timers and `P` = 16-bit pending count in the exported `step_output`)
//! `P` (3 to 32) sets the slack for steps the timing holds back: the count
//! runs from -2^(P-1) to 2^(P-1) - 1; a request beyond it is dropped and
//! flagged (`overrun`). P = 8 saves LUT4 and shortens the emit-to-count
//! adder; `motion_controller` uses it.
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! Step/dir after reset, step_len = 2, step_space = 3, dir_setup = 2,
//! dir_hold = 2; three forward steps requested on clocks 1 to 3, two
//! backward on clocks 14 and 15 (`+`/`-`). Clock 1 loads the timers; `out_b`
//! turns forward at clock 2 and the first pulse rises dir_setup later; the
//! pulses are 2 high and 3 low. The backward requests come while the third
//! pulse is high: `out_b` turns dir_hold after its fall, and the first
//! backward pulse rises dir_setup after that. This diagram is the
//! simulation, checked by a test, not a drawing (`#` = high, one column per
//! clock, outputs after that clock's edge):
//!
#![doc = include_str!("timing.txt")]
//!
//! * A step request is counted at the edge that samples it. A pulse starts
//!   at the earliest edge at which the pulse space, the direction setup and
//!   the pending count all allow it; with every timer 0 the stage emits one
//!   step every 2 clocks (high 1, low 1).
//! * The direction of a pulse is the sign of the pending count when it
//!   starts. In mode 0, when the sign differs from `out_b`, the stage turns
//!   `out_b` dir_hold clocks after the last fall (during the space), and
//!   raises `out_a` once both step_space since the fall and dir_setup since
//!   the turn have passed.
//! * Each setting is sampled when the interval it times starts (step_len at
//!   a rise or quadrature state change, step_space and dir_hold at a fall,
//!   dir_setup at a direction change); a new value applies from the next
//!   interval, and an interval in progress keeps its length.
//! * Mode 1: forward steps pulse `out_a`, backward steps pulse `out_b`; the
//!   length and space rules hold across both outputs (never both high).
//! * Mode 2: each step moves (out_a, out_b) one Gray state forward
//!   (00 -> 10 -> 11 -> 01 -> 00) or backward, and every state is held at
//!   least step_len clocks. step_space, dir_setup and dir_hold do not apply.
//! * After reset and after a mode change the outputs are low; the next
//!   clock (the start clock) loads the timers as if a pulse had just ended
//!   and `out_b` had just turned, so the first pulse rises step_space and
//!   dir_setup clocks later at the earliest (quadrature: step_len). Reset
//!   takes `mode`; after power-up with no reset, the first clock takes it
//!   and the second is the start clock. A `mode` held from time 0
//!   therefore applies to the very first step, whichever clock requests it.
//!
//! ## Implementation
//! Two loadable down-counters, one for the current level (step_len or
//! step_space) and one for the direction (dir_hold or dir_setup), each with
//! a registered "expired" flag computed one clock ahead; the pending count's
//! zero test and its limits are registered flags computed beside the adder.
//! No comparator sits between a register and a step decision, which is
//! what lets the 16-bit stage run above 125 MHz on iCE40 HX8K.
//!
//! ## Bad input
//! * More pending steps than the count holds (it runs from -2^(P-1) to
//!   2^(P-1) - 1; -32768 to 32767 for the exported P = 16): a forward
//!   request that arrives with the count at its maximum, or a backward one
//!   at its minimum, is dropped, even if a step leaves at the same edge, and
//!   the sticky `overrun` is set. No other request is ever lost.
//! * `mode` is taken at reset and in the first clock after power-up
//!   (nothing can be emitted before the start clock that follows), and
//!   after that only while `busy` is low (nothing pending, no pulse, every interval over), so a
//!   change never cuts a pulse, a quadrature state or a direction hold
//!   short; a change resets both outputs to 0 and restarts the timers.
//!   Change it with the drive disabled: the pins' meaning changes with it.
//!   A step requested in those first clocks is counted and waits for its
//!   timers, in the mode taken then.
//! * Timer values of 0 where a minimum of 1 is needed act as 1 (documented
//!   per port above).
//!
//! ## Flush
//! `flush` empties the pending count at its edge: the request of the same
//! clock is dropped too (flagged as an overrun only if it met a saturated
//! count, as without the flush), and `at_max`/`at_min`
//! clear. A step whose pulse the stage decides in the flush clock still
//! leaves (its decision comes from the registered state, so the flush adds
//! no logic to the step path) and is reported by `emitted`; from the next
//! edge on, nothing rises until a new request. A pulse already high keeps
//! its full `step_len`, and the space, hold and setup intervals that follow
//! it still apply to the next step: a flush never makes a runt pulse or
//! breaks a timing rule. Steps dropped by a flush never reached the pins,
//! so a position counted from `emitted` stays the pins' count.
//! `motion_controller` flushes every axis on an abort (E-stop, drive
//! alarm, limit, stop on home, watchdog), and uses `pending_forward` /
//! `pending_backward` to see a step waiting to move toward a limit.
//!
//! ## Formal proof
//! `formal/step_output.sv` states the rules above as assertions on the
//! ports, reading the steps from the pins (mode 0 a rise of `out_a`, its
//! direction `out_b`; mode 1 a rise of `out_a` or `out_b`; mode 2 a Gray
//! move), each setting taken at the edge that starts its interval:
//! * mode 0: `out_a` high exactly max(step_len, 1) clocks; a rise at least
//!   max(step_space, 1) clocks after the last fall and max(dir_setup, 1)
//!   after `out_b` last turned (or after the start clock), never at an edge
//!   that turns `out_b`; `out_b` never turns while `out_a` is high, at its
//!   fall, or within max(dir_hold, 1) clocks after it;
//! * mode 1: the same length and space on `out_a | out_b`, never both
//!   high, a pulse keeps its output; mode 2: one Gray step per move, each
//!   state held at least max(step_len, 1) clocks;
//! * every mode: a request is dropped exactly when it meets the saturated
//!   count, and then sets `overrun` (sticky, cleared as specified); every
//!   pin step goes the way of the pending count (accepted requests minus
//!   pin steps since the last reset or flush), so none is lost or invented;
//!   `pending_forward`/`pending_backward` are its sign and
//!   `emitted`/`emitted_forward` report the pin steps;
//! * the outputs are low after a reset or a mode change and stay low
//!   through the start clock; a mode change never cuts a pulse, a
//!   quadrature state or a direction hold (a reset may: it sets the
//!   outputs low at once); `busy` is high while steps are pending, a pulse
//!   is high, or any of those intervals runs.
//!
//! It assumes nothing: every input, `mode` and the four settings included,
//! is free at every clock. The induction also shows the internal count
//! equal to accepted requests minus pin steps at every clock. Proved by
//! k-induction for T = 3, P = 3 and for the exported T = 16, P = 16
//! (figures in the README's "What is proved").

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Width `P` of the signed pending-step count in the exported `step_output`.
pub const PENDING_BITS: usize = 16;

/// The smallest and largest pending-count widths `StepOutput` accepts.
pub const PENDING_BITS_RANGE: std::ops::RangeInclusive<usize> = 3..=32;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "step output stage: step/dir, up/down or quadrature with hardware-enforced timing";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: nothing pending, outputs low, flags 0; the mode is taken from `mode`"),
    port("step", "1", "request one step (one-clock pulse; a level requests one step per clock)"),
    port("dir", "1", "direction of that request: 1 = forward"),
    port("mode", "2", "0 step/dir, 1 up/down (CW/CCW), 2 quadrature, 3 reserved (acts as 0, `mode_invalid` high)"),
    port("step_len", "T", "step pulse high time in clocks (0 acts as 1); in quadrature, the minimum time per state"),
    port("step_space", "T", "minimum low time between step pulses, in clocks (0 acts as 1)"),
    port("dir_setup", "T", "`out_b` (dir) stable at least this many clocks before a step's rising edge (0 acts as 1)"),
    port("dir_hold", "T", "`out_b` (dir) stable at least this many clocks after a step's falling edge (0 acts as 1)"),
    port("out_a", "1", "step (mode 0), up (mode 1), A (mode 2); registered"),
    port("out_b", "1", "dir (mode 0), down (mode 1), B (mode 2); registered"),
    port("overrun", "1", "sticky: a request arrived with the pending count saturated and was dropped"),
    port("mode_invalid", "1", "`mode` is 3 (reserved); the stage runs as step/dir"),
    port("busy", "1", "steps are pending, a pulse is in progress, or a step_len/step_space/dir_hold/dir_setup interval is still running"),
    port("clear_overrun", "1", "clears `overrun` (a request dropped on the same clock keeps it set); tie to 0 if unused"),
    port("emitted", "1", "a step left the stage at the last edge (its first pin edge is on `out_a`/`out_b` now): one clock per step, registered"),
    port("emitted_forward", "1", "direction of that step: 1 = forward (valid with `emitted`)"),
    port("flush", "1", "drop every pending step and this clock's request; a pulse already high keeps its full `step_len` and the intervals run on; tie to 0 if unused"),
    port("pending_forward", "1", "the next step to leave is forward (the pending count is above 0); from flip-flops"),
    port("pending_backward", "1", "the next step to leave is backward (the pending count is below 0); from flip-flops"),
];

/// Step output stage with `T`-bit timers and a `P`-bit pending count. See
/// the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct StepOutput<const T: usize, const P: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Request one step.
    pub step: Signal<In, Bit>,
    /// Direction of the request.
    pub dir: Signal<In, Bit>,
    /// Output mode.
    pub mode: Signal<In, Bits<2>>,
    /// Pulse high time.
    pub step_len: Signal<In, Bits<T>>,
    /// Minimum low time.
    pub step_space: Signal<In, Bits<T>>,
    /// Direction setup time.
    pub dir_setup: Signal<In, Bits<T>>,
    /// Direction hold time.
    pub dir_hold: Signal<In, Bits<T>>,
    /// Step / up / A.
    pub out_a: Signal<Out, Bit>,
    /// Dir / down / B.
    pub out_b: Signal<Out, Bit>,
    /// Sticky: a request was dropped.
    pub overrun: Signal<Out, Bit>,
    /// Mode 3 selected.
    pub mode_invalid: Signal<Out, Bit>,
    /// Steps pending or a pulse in progress.
    pub busy: Signal<Out, Bit>,
    /// Clears the sticky `overrun`.
    pub clear_overrun: Signal<In, Bit>,
    /// A step left at the last edge.
    pub emitted: Signal<Out, Bit>,
    /// Its direction.
    pub emitted_forward: Signal<Out, Bit>,
    /// Drop every pending step and this clock's request.
    pub flush: Signal<In, Bit>,
    /// The pending count is above 0.
    pub pending_forward: Signal<Out, Bit>,
    /// The pending count is below 0.
    pub pending_backward: Signal<Out, Bit>,
    /// Signed pending steps; its MSB is the sign.
    pending: DFF<Bits<P>>,
    /// `pending != 0`, registered so that no decision waits for a 16-bit
    /// zero test (0 at power-up, like the count).
    nonzero: DFF<Bit>,
    /// `pending` is at its most positive / most negative value.
    at_max: DFF<Bit>,
    at_min: DFF<Bit>,
    a_reg: DFF<Bit>,
    b_reg: DFF<Bit>,
    /// Mode 0/1: a pulse is high.
    high: DFF<Bit>,
    /// Low for the one clock after reset or a mode change, which loads the
    /// timers as if a pulse had just ended and the direction had changed.
    started: DFF<Bit>,
    /// Down-counter of the current level (pulse, space or quadrature
    /// state); loaded with the setting when the level starts.
    phase_count: DFF<Bits<T>>,
    /// The level has lasted long enough: the next edge may come. Registered
    /// from "the counter reaches 1 at this edge", so 0 and 1 both mean one
    /// clock and no comparator sits in the decision path.
    phase_done: DFF<Bit>,
    /// Mode 0 down-counter: dir_hold after a fall, dir_setup after a
    /// direction change.
    dir_count: DFF<Bits<T>>,
    dir_done: DFF<Bit>,
    /// The direction counter times a setup, not a hold.
    timing_setup: DFF<Bit>,
    /// `timing_setup & !dir_done`, registered: a rise must wait. Keeps the
    /// rise decision, and the pending adder behind it, one level shallower.
    setup_wait: DFF<Bit>,
    active_mode: DFF<Bits<2>>,
    /// Low from power-up until the first clock has taken `mode` (reset
    /// takes it too). Keeps the mode input out of the timers' load logic.
    mode_taken: DFF<Bit>,
    overrun_reg: DFF<Bit>,
    /// `emit` and its direction, registered for the `emitted` outputs.
    emitted_reg: DFF<Bit>,
    emitted_forward_reg: DFF<Bit>,
    // Decisions of this clock.
    negative: Signal<Local, Bit>,
    positive: Signal<Local, Bit>,
    quadrature: Signal<Local, Bit>,
    up_down: Signal<Local, Bit>,
    emit: Signal<Local, Bit>,
    fall: Signal<Local, Bit>,
    dir_change: Signal<Local, Bit>,
    /// The phase counter loads step_len (else step_space).
    load_len: Signal<Local, Bit>,
    dir_done_next: Signal<Local, Bit>,
    timing_setup_next: Signal<Local, Bit>,
    request: Signal<Local, Bit>,
    /// This clock's change of the pending count, -2..2.
    change: Signal<Local, Bits<P>>,
    /// `pending` is 1, 2, -1, -2: with this clock's change, the count
    /// reaches 0 exactly from one of these (or stays at 0).
    high_bits_zero: Signal<Local, Bit>,
    high_bits_ones: Signal<Local, Bit>,
    reaches_zero: Signal<Local, Bit>,
    /// `mode` with the reserved value 3 mapped to step/dir.
    requested_mode: Signal<Local, Bits<2>>,
    zero_t: Constant<Bits<T>>,
    one_t: Constant<Bits<T>>,
    /// Clears bit 0: `(v & not_one) == 0` is v <= 1.
    not_one: Constant<Bits<T>>,
    /// Clears bits 1..0: with both low bits checked, v <= 2.
    not_three: Constant<Bits<T>>,
    zero_p: Constant<Bits<P>>,
    one_p: Constant<Bits<P>>,
    minus_one_p: Constant<Bits<P>>,
    two_p: Constant<Bits<P>>,
    minus_two_p: Constant<Bits<P>>,
    low_two_p: Constant<Bits<P>>,
    high_mask_p: Constant<Bits<P>>,
    below_max_p: Constant<Bits<P>>,
    above_min_p: Constant<Bits<P>>,
    min_p: Constant<Bits<P>>,
    /// Low two bits of +1, +-2 and -1.
    low_plus_one: Constant<Bits<2>>,
    low_two: Constant<Bits<2>>,
    low_minus_one: Constant<Bits<2>>,
    mode_step_dir: Constant<Bits<2>>,
    mode_reserved: Constant<Bits<2>>,
}

impl<const T: usize, const P: usize> Default for StepOutput<T, P> {
    fn default() -> Self {
        assert!(
            (2..=32).contains(&T),
            "StepOutput timers must be 2 to 32 bits"
        );
        assert!(
            PENDING_BITS_RANGE.contains(&P),
            "StepOutput pending count must be 3 to 32 bits"
        );
        let t_mask = crate::blocks::width_mask(T as u32);
        let p_mask = crate::blocks::width_mask(P as u32);
        Self {
            clock: Default::default(),
            reset: Default::default(),
            step: Default::default(),
            dir: Default::default(),
            mode: Default::default(),
            step_len: Default::default(),
            step_space: Default::default(),
            dir_setup: Default::default(),
            dir_hold: Default::default(),
            out_a: Default::default(),
            out_b: Default::default(),
            overrun: Default::default(),
            mode_invalid: Default::default(),
            busy: Default::default(),
            clear_overrun: Default::default(),
            emitted: Default::default(),
            emitted_forward: Default::default(),
            flush: Default::default(),
            pending_forward: Default::default(),
            pending_backward: Default::default(),
            pending: Default::default(),
            nonzero: Default::default(),
            at_max: Default::default(),
            at_min: Default::default(),
            a_reg: Default::default(),
            b_reg: Default::default(),
            high: Default::default(),
            started: Default::default(),
            phase_count: Default::default(),
            phase_done: Default::default(),
            dir_count: Default::default(),
            dir_done: Default::default(),
            timing_setup: Default::default(),
            setup_wait: Default::default(),
            active_mode: Default::default(),
            mode_taken: Default::default(),
            overrun_reg: Default::default(),
            emitted_reg: Default::default(),
            emitted_forward_reg: Default::default(),
            negative: Default::default(),
            positive: Default::default(),
            quadrature: Default::default(),
            up_down: Default::default(),
            emit: Default::default(),
            fall: Default::default(),
            dir_change: Default::default(),
            load_len: Default::default(),
            dir_done_next: Default::default(),
            timing_setup_next: Default::default(),
            request: Default::default(),
            change: Default::default(),
            high_bits_zero: Default::default(),
            high_bits_ones: Default::default(),
            reaches_zero: Default::default(),
            requested_mode: Default::default(),
            zero_t: Constant::new(0u64.into()),
            one_t: Constant::new(1u64.into()),
            not_one: Constant::new((t_mask & !1).into()),
            not_three: Constant::new((t_mask & !3).into()),
            zero_p: Constant::new(0u64.into()),
            one_p: Constant::new(1u64.into()),
            minus_one_p: Constant::new(p_mask.into()),
            two_p: Constant::new(2u64.into()),
            minus_two_p: Constant::new((p_mask - 1).into()),
            low_two_p: Constant::new(3u64.into()),
            high_mask_p: Constant::new((p_mask & !3).into()),
            below_max_p: Constant::new(((1u64 << (P - 1)) - 2).into()),
            above_min_p: Constant::new(((1u64 << (P - 1)) + 1).into()),
            min_p: Constant::new((1u64 << (P - 1)).into()),
            low_plus_one: Constant::new(1u64.into()),
            low_two: Constant::new(2u64.into()),
            low_minus_one: Constant::new(3u64.into()),
            mode_step_dir: Constant::new(0u64.into()),
            mode_reserved: Constant::new(3u64.into()),
        }
    }
}

impl<const T: usize, const P: usize> Logic for StepOutput<T, P> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            pending,
            nonzero,
            at_max,
            at_min,
            a_reg,
            b_reg,
            high,
            started,
            phase_count,
            phase_done,
            dir_count,
            dir_done,
            timing_setup,
            setup_wait,
            active_mode,
            mode_taken,
            overrun_reg,
            emitted_reg,
            emitted_forward_reg
        );
        self.out_a.next = self.a_reg.q.val();
        self.out_b.next = self.b_reg.q.val();
        self.overrun.next = self.overrun_reg.q.val();
        self.emitted.next = self.emitted_reg.q.val();
        self.emitted_forward.next = self.emitted_forward_reg.q.val();
        self.mode_invalid.next = self.mode.val() == self.mode_reserved.val();
        // Busy until the last interval's timers have run out too, so that a
        // mode change (taken only while not busy) never cuts an interval.
        self.busy.next = self.nonzero.q.val()
            | self.high.q.val()
            | !self.phase_done.q.val()
            | !self.dir_done.q.val();
        self.started.d.next = true;

        self.negative.next = (self.pending.q.val() & self.min_p.val()) != self.zero_p.val();
        self.positive.next = self.nonzero.q.val() & !self.negative.val();
        self.pending_forward.next = self.positive.val();
        self.pending_backward.next = self.negative.val();
        self.requested_mode.next = self.mode.val();
        if self.mode.val() == self.mode_reserved.val() {
            self.requested_mode.next = self.mode_step_dir.val();
        }
        // The active mode is never 3, so each of its bits is one mode.
        self.quadrature.next = self.active_mode.q.val().get_bit(1);
        self.up_down.next = self.active_mode.q.val().get_bit(0);

        // Events. After reset or a mode change, phase_done, dir_done,
        // timing_setup and high are all 0, so no event fires in the clock
        // that loads the timers.
        self.emit.next = false;
        self.fall.next = false;
        self.dir_change.next = false;
        if self.quadrature.val() {
            if self.nonzero.q.val() & self.phase_done.q.val() {
                self.emit.next = true;
                if self.positive.val() {
                    self.a_reg.d.next = !self.b_reg.q.val();
                    self.b_reg.d.next = self.a_reg.q.val();
                } else {
                    self.a_reg.d.next = self.b_reg.q.val();
                    self.b_reg.d.next = !self.a_reg.q.val();
                }
            }
        } else if self.high.q.val() {
            if self.phase_done.q.val() {
                self.fall.next = true;
                self.high.d.next = false;
                self.a_reg.d.next = false;
                if self.up_down.val() {
                    self.b_reg.d.next = false;
                }
            }
        } else if self.nonzero.q.val()
            & self.phase_done.q.val()
            & (self.up_down.val()
                | ((self.b_reg.q.val() == self.positive.val()) & !self.setup_wait.q.val()))
        {
            self.emit.next = true;
            self.high.d.next = true;
            if self.up_down.val() {
                self.a_reg.d.next = self.positive.val();
                self.b_reg.d.next = !self.positive.val();
            } else {
                self.a_reg.d.next = true;
            }
        } else if !self.up_down.val()
            & self.nonzero.q.val()
            & (self.b_reg.q.val() != self.positive.val())
            & (self.dir_done.q.val() | self.timing_setup.q.val())
        {
            self.dir_change.next = true;
            self.b_reg.d.next = self.positive.val();
        }

        // Timers: a counter loaded with v at an edge lets its event happen
        // max(v, 1) clocks later.
        self.load_len.next = self.quadrature.val() | (self.started.q.val() & !self.high.q.val());
        // Once done, a counter runs on freely (its value is unused until
        // the next load): no clock enable, which nextpnr would route through
        // a slow global buffer.
        self.phase_count.d.next = self.phase_count.q.val() - self.one_t.val();
        self.phase_done.d.next = self.phase_done.q.val()
            | (((self.phase_count.q.val() & self.not_three.val()) == self.zero_t.val())
                & !(self.phase_count.q.val().get_bit(0) & self.phase_count.q.val().get_bit(1)));
        if !self.started.q.val() | self.emit.val() | self.fall.val() {
            if self.load_len.val() {
                self.phase_count.d.next = self.step_len.val();
                self.phase_done.d.next =
                    (self.step_len.val() & self.not_one.val()) == self.zero_t.val();
            } else {
                self.phase_count.d.next = self.step_space.val();
                self.phase_done.d.next =
                    (self.step_space.val() & self.not_one.val()) == self.zero_t.val();
            }
        }
        self.timing_setup_next.next = self.timing_setup.q.val();
        self.dir_count.d.next = self.dir_count.q.val() - self.one_t.val();
        self.dir_done_next.next = self.dir_done.q.val()
            | (((self.dir_count.q.val() & self.not_three.val()) == self.zero_t.val())
                & !(self.dir_count.q.val().get_bit(0) & self.dir_count.q.val().get_bit(1)));
        if !self.started.q.val() | self.fall.val() | self.dir_change.val() {
            self.timing_setup_next.next = !self.high.q.val();
            if self.high.q.val() {
                self.dir_count.d.next = self.dir_hold.val();
                self.dir_done_next.next =
                    (self.dir_hold.val() & self.not_one.val()) == self.zero_t.val();
            } else {
                self.dir_count.d.next = self.dir_setup.val();
                self.dir_done_next.next =
                    (self.dir_setup.val() & self.not_one.val()) == self.zero_t.val();
            }
        }
        self.dir_done.d.next = self.dir_done_next.val();
        self.timing_setup.d.next = self.timing_setup_next.val();
        self.setup_wait.d.next = self.timing_setup_next.val() & !self.dir_done_next.val();

        // The pending count: + request, - emitted step. A request that meets
        // the count at its limit is dropped even if a step leaves at the
        // same edge: the emit decision stays off the request path.
        self.emitted_reg.d.next = self.emit.val();
        self.emitted_forward_reg.d.next = self.positive.val();
        if self.clear_overrun.val() {
            self.overrun_reg.d.next = false;
        }
        self.request.next = self.step.val();
        if self.step.val()
            & ((self.dir.val() & self.at_max.q.val()) | (!self.dir.val() & self.at_min.q.val()))
        {
            self.request.next = false;
            self.overrun_reg.d.next = true;
        }
        // The limits are registered like `nonzero`: the count reaches its
        // limit from one step below with a request and no emitted step, and
        // stays there with neither (a request beyond it is dropped).
        self.at_max.d.next = !self.emit.val()
            & ((self.at_max.q.val() & !self.request.val())
                | ((self.pending.q.val() == self.below_max_p.val())
                    & self.request.val()
                    & self.dir.val()));
        self.at_min.d.next = !self.emit.val()
            & ((self.at_min.q.val() & !self.request.val())
                | ((self.pending.q.val() == self.above_min_p.val())
                    & self.request.val()
                    & !self.dir.val()));
        // One adder: the change is -2..2 (emitted step and request).
        self.change.next = self.zero_p.val();
        if self.request.val() & self.dir.val() {
            self.change.next = self.one_p.val();
        }
        if self.request.val() & !self.dir.val() {
            self.change.next = self.minus_one_p.val();
        }
        if self.emit.val() {
            if self.positive.val() {
                self.change.next = self.minus_one_p.val();
                if self.request.val() & self.dir.val() {
                    self.change.next = self.zero_p.val();
                }
                if self.request.val() & !self.dir.val() {
                    self.change.next = self.minus_two_p.val();
                }
            } else {
                self.change.next = self.one_p.val();
                if self.request.val() & self.dir.val() {
                    self.change.next = self.two_p.val();
                }
                if self.request.val() & !self.dir.val() {
                    self.change.next = self.zero_p.val();
                }
            }
        }
        self.pending.d.next = self.pending.q.val() + self.change.val();
        // The next count is 0 exactly when the change cancels a count of
        // 0, +-1 or +-2: decided from the current count beside the adder,
        // not after it.
        self.high_bits_zero.next =
            (self.pending.q.val() & self.high_mask_p.val()) == self.zero_p.val();
        self.high_bits_ones.next =
            (self.pending.q.val() | self.low_two_p.val()) == self.minus_one_p.val();
        self.reaches_zero.next = !self.nonzero.q.val() & !self.request.val();
        if self.high_bits_zero.val() {
            if self.pending.q.val().get_bits::<2>(0) == self.low_plus_one.val() {
                // +1: an emitted step alone, or a backward request alone.
                self.reaches_zero.next = (self.emit.val() & !self.request.val())
                    | (!self.emit.val() & self.request.val() & !self.dir.val());
            }
            if self.pending.q.val().get_bits::<2>(0) == self.low_two.val() {
                self.reaches_zero.next = self.emit.val() & self.request.val() & !self.dir.val();
            }
        }
        if self.high_bits_ones.val() {
            if self.pending.q.val().get_bits::<2>(0) == self.low_minus_one.val() {
                // -1: an emitted step alone, or a forward request alone.
                self.reaches_zero.next = (self.emit.val() & !self.request.val())
                    | (!self.emit.val() & self.request.val() & self.dir.val());
            }
            if self.pending.q.val().get_bits::<2>(0) == self.low_two.val() {
                self.reaches_zero.next = self.emit.val() & self.request.val() & self.dir.val();
            }
        }
        self.nonzero.d.next = !self.reaches_zero.val();
        // A flush empties the count like a reset of the count alone: a step
        // emitted in this clock has already left, and the request of this
        // clock is dropped with the rest.
        if self.flush.val() {
            self.pending.d.next = self.zero_p.val();
            self.nonzero.d.next = false;
            self.at_max.d.next = false;
            self.at_min.d.next = false;
        }

        // The mode is taken at reset and in the first clock after power-up
        // (a mode change: the start clock follows), so a mode tied from
        // time 0 holds from the first step. After that it is taken only
        // while idle; a change resets the outputs and restarts the timers.
        self.mode_taken.d.next = true;
        if !self.mode_taken.q.val()
            | (!self.nonzero.q.val()
                & !self.high.q.val()
                & self.phase_done.q.val()
                & self.dir_done.q.val()
                & (self.requested_mode.val() != self.active_mode.q.val()))
        {
            self.active_mode.d.next = self.requested_mode.val();
            self.a_reg.d.next = false;
            self.b_reg.d.next = false;
            self.high.d.next = false;
            self.started.d.next = false;
            self.phase_done.d.next = false;
            self.dir_done.d.next = false;
            self.timing_setup.d.next = false;
            self.setup_wait.d.next = false;
        }
        if self.reset.val() {
            self.pending.d.next = self.zero_p.val();
            self.nonzero.d.next = false;
            self.at_max.d.next = false;
            self.at_min.d.next = false;
            self.a_reg.d.next = false;
            self.b_reg.d.next = false;
            self.high.d.next = false;
            self.started.d.next = false;
            self.phase_count.d.next = self.zero_t.val();
            self.phase_done.d.next = false;
            self.dir_count.d.next = self.zero_t.val();
            self.dir_done.d.next = false;
            self.timing_setup.d.next = false;
            self.setup_wait.d.next = false;
            self.active_mode.d.next = self.requested_mode.val();
            self.mode_taken.d.next = true;
            self.overrun_reg.d.next = false;
            self.emitted_reg.d.next = false;
            self.emitted_forward_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const T: usize, const P: usize] StepOutput<T, P> {
    inputs: [reset, step, dir, mode, step_len, step_space, dir_setup, dir_hold, clear_overrun, flush],
    outputs: [out_a, out_b, overrun, mode_invalid, busy, emitted, emitted_forward, pending_forward, pending_backward],
});
