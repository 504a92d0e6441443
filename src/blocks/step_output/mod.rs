//! # `step_output`: step/dir, up/down and quadrature output with enforced timing
//!
//! Sits between a fine interpolator and the pins. It keeps a signed count of
//! pending steps (forward requests add one, backward requests subtract one,
//! so opposite requests cancel) and emits them as fast as the programmed
//! drive timing allows: it delays steps, it never drops or merges them.
//!
//! ## Ports (`T` = 16-bit timers in the exported `step_output`)
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous, active high: nothing pending, outputs low, timers 0, flags 0 |
//! | `step` | in | 1 | request one step (one-clock pulse; a level requests one step per clock) |
//! | `dir` | in | 1 | direction of that request: 1 = forward |
//! | `mode` | in | 2 | 0 step/dir, 1 up/down (CW/CCW), 2 quadrature, 3 reserved (acts as 0, `mode_invalid` high) |
//! | `step_len` | in | T | step pulse high time in clocks (0 acts as 1); in quadrature, the minimum time per state |
//! | `step_space` | in | T | minimum low time between step pulses, in clocks (0 acts as 1) |
//! | `dir_setup` | in | T | `out_b` (dir) stable at least this many clocks before a step's rising edge |
//! | `dir_hold` | in | T | `out_b` (dir) stable at least this many clocks after a step's falling edge (0 acts as 1) |
//! | `out_a` | out | 1 | step (mode 0), up (mode 1), A (mode 2); registered |
//! | `out_b` | out | 1 | dir (mode 0), down (mode 1), B (mode 2); registered |
//! | `overrun` | out | 1 | sticky: a request arrived with the pending count saturated and was dropped |
//! | `mode_invalid` | out | 1 | `mode` is 3 (reserved); the stage runs as step/dir |
//! | `busy` | out | 1 | steps are pending or a pulse is in progress |
//!
//! ## Timing
//! Step/dir, step_len = 2, step_space = 3, dir_setup = 2, dir_hold = 2; three
//! forward steps requested on clocks 1 to 3, two backward on clocks 14 and 15
//! (`+`/`-`). Two forward steps are emitted; the third forward request and
//! one backward request cancel; one backward step follows the direction
//! change. This diagram is the simulation, checked by a test, not a drawing
//! (`#` = high, one column per clock, outputs after that clock's edge):
//!
#![doc = include_str!("timing.txt")]
//!
//! * A step request is counted at the edge that samples it. A pulse starts
//!   at the earliest edge at which the pulse space, the direction setup and
//!   the pending count all allow it; with every timer 0 the stage emits one
//!   step every 2 clocks (high 1, low 1).
//! * The direction of a pulse is the sign of the pending count when it
//!   starts. In mode 0 the stage first sets `out_b` (at least dir_hold after
//!   the last fall), then waits dir_setup, then raises `out_a`.
//! * Mode 1: forward steps pulse `out_a`, backward steps pulse `out_b`; the
//!   length and space rules hold across both outputs (never both high).
//! * Mode 2: each step moves (out_a, out_b) one Gray state forward
//!   (00 -> 10 -> 11 -> 01 -> 00) or backward, and every state is held at
//!   least step_len clocks. step_space, dir_setup and dir_hold do not apply.
//! * After reset the outputs are low and the first pulse waits step_space
//!   (and dir_setup) clocks, as if a pulse had just ended.
//!
//! ## Bad input
//! * More pending steps than the count holds (±(2^15 - 1) for the exported
//!   16-bit count): the request that does not fit is dropped and the sticky
//!   `overrun` is set. No other request is ever lost.
//! * `mode` is taken only while the stage is idle (nothing pending, no pulse);
//!   a change resets both outputs to 0 and restarts the timers. Change it
//!   with the drive disabled: the pins' meaning changes with it.
//! * Timer values of 0 where a minimum of 1 is needed act as 1 (documented
//!   per port above).

pub mod model;

use rust_hdl::prelude::*;

/// Width of the signed pending-step count.
pub const PENDING_BITS: usize = 16;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "step output stage: step/dir, up/down or quadrature with hardware-enforced timing";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[(&str, &str)] = &[
    ("clock", "rising-edge clock"),
    (
        "reset",
        "synchronous reset, active high: nothing pending, outputs low, flags 0",
    ),
    ("step", "request one step (one-clock pulse)"),
    ("dir", "direction of that request: 1 = forward"),
    (
        "mode",
        "0 step/dir, 1 up/down, 2 quadrature, 3 reserved (acts as 0)",
    ),
    (
        "step_len",
        "step pulse high time in clocks (0 acts as 1); quadrature: minimum time per state",
    ),
    (
        "step_space",
        "minimum low time between step pulses in clocks (0 acts as 1)",
    ),
    (
        "dir_setup",
        "dir stable at least this many clocks before a step's rising edge",
    ),
    (
        "dir_hold",
        "dir stable at least this many clocks after a step's falling edge (0 acts as 1)",
    ),
    ("out_a", "step (mode 0), up (mode 1), A (mode 2)"),
    ("out_b", "dir (mode 0), down (mode 1), B (mode 2)"),
    (
        "overrun",
        "sticky: a request arrived with the pending count saturated and was dropped",
    ),
    (
        "mode_invalid",
        "mode is 3 (reserved); the stage runs as step/dir",
    ),
    ("busy", "steps are pending or a pulse is in progress"),
];

/// Step output stage with enforced timing. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct StepOutput<const T: usize> {
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
    pending: DFF<Bits<PENDING_BITS>>,
    a_reg: DFF<Bit>,
    b_reg: DFF<Bit>,
    /// Mode 0/1: a pulse is high.
    high: DFF<Bit>,
    /// Clocks since the current level (pulse, space, or quadrature state)
    /// began, saturating.
    elapsed: DFF<Bits<T>>,
    /// Clocks since `out_b` last changed in mode 0, saturating.
    dir_elapsed: DFF<Bits<T>>,
    active_mode: DFF<Bits<2>>,
    overrun_reg: DFF<Bit>,
    // Decisions of this clock.
    positive: Signal<Local, Bit>,
    negative: Signal<Local, Bit>,
    idle: Signal<Local, Bit>,
    emit: Signal<Local, Bit>,
    len: Signal<Local, Bits<T>>,
    space: Signal<Local, Bits<T>>,
    hold: Signal<Local, Bits<T>>,
    elapsed_next: Signal<Local, Bits<T>>,
    dir_elapsed_next: Signal<Local, Bits<T>>,
    request: Signal<Local, Bit>,
    /// This clock's change of the pending count, -2..2.
    change: Signal<Local, Bits<PENDING_BITS>>,
    /// `mode` with the reserved value 3 mapped to step/dir.
    requested_mode: Signal<Local, Bits<2>>,
    zero_t: Constant<Bits<T>>,
    one_t: Constant<Bits<T>>,
    max_t: Constant<Bits<T>>,
    zero_p: Constant<Bits<PENDING_BITS>>,
    one_p: Constant<Bits<PENDING_BITS>>,
    minus_one_p: Constant<Bits<PENDING_BITS>>,
    two_p: Constant<Bits<PENDING_BITS>>,
    minus_two_p: Constant<Bits<PENDING_BITS>>,
    sign_p: Constant<Bits<PENDING_BITS>>,
    max_p: Constant<Bits<PENDING_BITS>>,
    min_p: Constant<Bits<PENDING_BITS>>,
    mode_step_dir: Constant<Bits<2>>,
    mode_up_down: Constant<Bits<2>>,
    mode_quadrature: Constant<Bits<2>>,
    mode_reserved: Constant<Bits<2>>,
}

impl<const T: usize> Default for StepOutput<T> {
    fn default() -> Self {
        assert!(
            (2..=32).contains(&T),
            "StepOutput timers must be 2 to 32 bits"
        );
        let p_mask = crate::blocks::width_mask(PENDING_BITS as u32);
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
            pending: Default::default(),
            a_reg: Default::default(),
            b_reg: Default::default(),
            high: Default::default(),
            elapsed: Default::default(),
            dir_elapsed: Default::default(),
            active_mode: Default::default(),
            overrun_reg: Default::default(),
            positive: Default::default(),
            negative: Default::default(),
            idle: Default::default(),
            emit: Default::default(),
            len: Default::default(),
            space: Default::default(),
            hold: Default::default(),
            elapsed_next: Default::default(),
            dir_elapsed_next: Default::default(),
            request: Default::default(),
            change: Default::default(),
            requested_mode: Default::default(),
            zero_t: Constant::new(0u64.into()),
            one_t: Constant::new(1u64.into()),
            max_t: Constant::new(crate::blocks::width_mask(T as u32).into()),
            zero_p: Constant::new(0u64.into()),
            one_p: Constant::new(1u64.into()),
            minus_one_p: Constant::new(p_mask.into()),
            two_p: Constant::new(2u64.into()),
            minus_two_p: Constant::new((p_mask - 1).into()),
            sign_p: Constant::new((1u64 << (PENDING_BITS - 1)).into()),
            max_p: Constant::new(((1u64 << (PENDING_BITS - 1)) - 1).into()),
            min_p: Constant::new((p_mask & !((1u64 << (PENDING_BITS - 1)) - 1)).into()),
            mode_step_dir: Constant::new(0u64.into()),
            mode_up_down: Constant::new(1u64.into()),
            mode_quadrature: Constant::new(2u64.into()),
            mode_reserved: Constant::new(3u64.into()),
        }
    }
}

impl<const T: usize> Logic for StepOutput<T> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            pending,
            a_reg,
            b_reg,
            high,
            elapsed,
            dir_elapsed,
            active_mode,
            overrun_reg
        );
        self.out_a.next = self.a_reg.q.val();
        self.out_b.next = self.b_reg.q.val();
        self.overrun.next = self.overrun_reg.q.val();
        self.mode_invalid.next = self.mode.val() == self.mode_reserved.val();

        // Timer minimums: 0 acts as 1.
        self.len.next = self.step_len.val();
        if self.step_len.val() == self.zero_t.val() {
            self.len.next = self.one_t.val();
        }
        self.space.next = self.step_space.val();
        if self.step_space.val() == self.zero_t.val() {
            self.space.next = self.one_t.val();
        }
        self.hold.next = self.dir_hold.val();
        if self.dir_hold.val() == self.zero_t.val() {
            self.hold.next = self.one_t.val();
        }
        // Saturating counters.
        self.elapsed_next.next = self.elapsed.q.val();
        if self.elapsed.q.val() != self.max_t.val() {
            self.elapsed_next.next = self.elapsed.q.val() + self.one_t.val();
        }
        self.dir_elapsed_next.next = self.dir_elapsed.q.val();
        if self.dir_elapsed.q.val() != self.max_t.val() {
            self.dir_elapsed_next.next = self.dir_elapsed.q.val() + self.one_t.val();
        }
        self.elapsed.d.next = self.elapsed_next.val();
        self.dir_elapsed.d.next = self.dir_elapsed_next.val();

        self.negative.next = (self.pending.q.val() & self.sign_p.val()) != self.zero_p.val();
        self.positive.next = !self.negative.val() & (self.pending.q.val() != self.zero_p.val());
        self.idle.next = (self.pending.q.val() == self.zero_p.val()) & !self.high.q.val();
        self.busy.next = !self.idle.val();

        // Emission: one step leaves the pending count when its pulse (or
        // quadrature state change) starts.
        self.emit.next = false;
        if self.active_mode.q.val() == self.mode_quadrature.val() {
            if (self.positive.val() | self.negative.val())
                & (self.elapsed.q.val() >= self.len.val())
            {
                self.emit.next = true;
                self.elapsed.d.next = self.one_t.val();
                if self.positive.val() {
                    self.a_reg.d.next = !self.b_reg.q.val();
                    self.b_reg.d.next = self.a_reg.q.val();
                } else {
                    self.a_reg.d.next = self.b_reg.q.val();
                    self.b_reg.d.next = !self.a_reg.q.val();
                }
            }
        } else if self.high.q.val() {
            // A pulse ends after exactly `len` clocks.
            if self.elapsed.q.val() >= self.len.val() {
                self.high.d.next = false;
                self.a_reg.d.next = false;
                if self.active_mode.q.val() == self.mode_up_down.val() {
                    self.b_reg.d.next = false;
                }
                self.elapsed.d.next = self.one_t.val();
            }
        } else if (self.positive.val() | self.negative.val())
            & (self.elapsed.q.val() >= self.space.val())
        {
            if self.active_mode.q.val() == self.mode_up_down.val() {
                self.emit.next = true;
                self.high.d.next = true;
                self.elapsed.d.next = self.one_t.val();
                if self.positive.val() {
                    self.a_reg.d.next = true;
                } else {
                    self.b_reg.d.next = true;
                }
            } else if self.b_reg.q.val() == self.positive.val() {
                // Step/dir with the direction already right: wait for setup.
                if self.dir_elapsed.q.val() >= self.dir_setup.val() {
                    self.emit.next = true;
                    self.high.d.next = true;
                    self.a_reg.d.next = true;
                    self.elapsed.d.next = self.one_t.val();
                }
            } else if self.elapsed.q.val() >= self.hold.val() {
                // Step/dir needing the other direction: change it once the
                // hold time after the last fall has passed.
                self.b_reg.d.next = self.positive.val();
                self.dir_elapsed.d.next = self.one_t.val();
            }
        }

        // The pending count: + request, - emitted step, saturating requests.
        self.request.next = self.step.val();
        if self.step.val()
            & self.dir.val()
            & (self.pending.q.val() == self.max_p.val())
            & !self.emit.val()
        {
            self.request.next = false;
            self.overrun_reg.d.next = true;
        }
        if self.step.val()
            & !self.dir.val()
            & (self.pending.q.val() == self.min_p.val())
            & !self.emit.val()
        {
            self.request.next = false;
            self.overrun_reg.d.next = true;
        }
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

        // The mode is taken only while idle; a change resets the outputs.
        self.requested_mode.next = self.mode.val();
        if self.mode.val() == self.mode_reserved.val() {
            self.requested_mode.next = self.mode_step_dir.val();
        }
        if self.idle.val() & (self.requested_mode.val() != self.active_mode.q.val()) {
            self.active_mode.d.next = self.requested_mode.val();
            self.a_reg.d.next = false;
            self.b_reg.d.next = false;
            self.high.d.next = false;
            self.elapsed.d.next = self.zero_t.val();
            self.dir_elapsed.d.next = self.zero_t.val();
        }
        if self.reset.val() {
            self.pending.d.next = self.zero_p.val();
            self.a_reg.d.next = false;
            self.b_reg.d.next = false;
            self.high.d.next = false;
            self.elapsed.d.next = self.zero_t.val();
            self.dir_elapsed.d.next = self.zero_t.val();
            self.active_mode.d.next = self.mode_step_dir.val();
            self.overrun_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const T: usize] StepOutput<T> {
    inputs: [reset, step, dir, mode, step_len, step_space, dir_setup, dir_hold],
    outputs: [out_a, out_b, overrun, mode_invalid, busy],
});
