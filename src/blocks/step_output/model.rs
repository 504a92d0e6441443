//! Reference model of [`super::StepOutput`], cycle-exact.
//!
//! The model keeps each timer as "clocks still to wait" and gates every
//! event on an explicit `started` state; the RTL uses loadable down-counters
//! with registered "expired" flags instead. The two representations are
//! proven equal by the cycle-by-cycle comparison in `tests/blocks/step_output.rs`.

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepOutputInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Request one step.
    pub step: bool,
    /// Direction of the request: true = forward.
    pub dir: bool,
    /// 0 step/dir, 1 up/down, 2 quadrature, 3 reserved.
    pub mode: u8,
    /// Pulse high time (0 acts as 1).
    pub step_len: u64,
    /// Minimum low time (0 acts as 1).
    pub step_space: u64,
    /// Direction setup time (0 acts as 1).
    pub dir_setup: u64,
    /// Direction hold time (0 acts as 1).
    pub dir_hold: u64,
    /// Clears the sticky overrun.
    pub clear_overrun: bool,
    /// Drop every pending step and this clock's request.
    pub flush: bool,
}

impl StepOutputInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.step as u64,
            self.dir as u64,
            self.mode as u64,
            self.step_len,
            self.step_space,
            self.dir_setup,
            self.dir_hold,
            self.clear_overrun as u64,
            self.flush as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepOutputOutputs {
    /// Step / up / A.
    pub out_a: bool,
    /// Dir / down / B.
    pub out_b: bool,
    /// Sticky overrun.
    pub overrun: bool,
    /// Mode 3 selected.
    pub mode_invalid: bool,
    /// Steps pending or a pulse in progress.
    pub busy: bool,
    /// A step left at the last edge.
    pub emitted: bool,
    /// Its direction: true = forward.
    pub emitted_forward: bool,
    /// The pending count is above 0.
    pub pending_forward: bool,
    /// The pending count is below 0.
    pub pending_backward: bool,
}

impl StepOutputOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            out_a: v[0] != 0,
            out_b: v[1] != 0,
            overrun: v[2] != 0,
            mode_invalid: v[3] != 0,
            busy: v[4] != 0,
            emitted: v[5] != 0,
            emitted_forward: v[6] != 0,
            pending_forward: v[7] != 0,
            pending_backward: v[8] != 0,
        }
    }
}

/// The most positive pending count of the exported 16-bit count, 2^15 - 1.
pub const PENDING_MAX: i32 = (1 << 15) - 1;
/// The most negative pending count of the exported 16-bit count, -2^15.
pub const PENDING_MIN: i32 = -(1 << 15);

/// (most negative, most positive) pending count of a `bits`-wide count.
pub fn pending_limits(bits: u32) -> (i64, i64) {
    (-(1i64 << (bits - 1)), (1i64 << (bits - 1)) - 1)
}

/// Plain-Rust, cycle-exact model of the step output stage with
/// `timer_bits` timers and a `pending_bits` pending count.
#[derive(Clone, Debug)]
pub struct StepOutputModel {
    timer_mask: u64,
    pending_bits: u32,
    pending: i64,
    a: bool,
    b: bool,
    /// Mode 0/1: a pulse is high.
    high: bool,
    /// False for the one clock after reset or a mode change, in which the
    /// timers are loaded as if a pulse had just ended and the direction
    /// had just changed.
    started: bool,
    /// Clocks the current level (pulse, space or quadrature state) must
    /// still last before the next edge of `out_a`/state may come.
    phase_left: u64,
    /// Mode 0: clocks until `out_b` may change (hold) or, while
    /// `timing_setup`, until a pulse may rise (setup).
    dir_left: u64,
    /// The direction timer times a setup (after a direction change), not a
    /// hold (after a fall).
    timing_setup: bool,
    active_mode: u8,
    /// False from power-up until the first clock has taken the mode input
    /// (reset takes it too).
    mode_taken: bool,
    overrun: bool,
    emitted: bool,
    emitted_forward: bool,
}

impl StepOutputModel {
    /// A stage with `timer_bits`-bit timers and a `pending_bits` count, in
    /// its power-up state.
    pub fn new(timer_bits: u32, pending_bits: u32) -> Self {
        Self {
            timer_mask: crate::blocks::width_mask(timer_bits),
            pending_bits,
            pending: 0,
            a: false,
            b: false,
            high: false,
            started: false,
            phase_left: 0,
            dir_left: 0,
            timing_setup: false,
            active_mode: 0,
            mode_taken: false,
            overrun: false,
            emitted: false,
            emitted_forward: false,
        }
    }

    /// Steps requested but not yet emitted (signed).
    pub fn pending(&self) -> i64 {
        self.pending
    }

    /// Steps pending, a pulse high, or an interval still running (the
    /// start clock after reset or a mode change counts as running).
    fn busy(&self) -> bool {
        self.pending != 0 || self.high || !self.started || self.phase_left > 0 || self.dir_left > 0
    }

    /// The outputs of the present state (before the next edge), with the
    /// `mode` input at `mode`.
    pub fn outputs(&self, mode: u8) -> StepOutputOutputs {
        StepOutputOutputs {
            out_a: self.a,
            out_b: self.b,
            overrun: self.overrun,
            mode_invalid: mode == 3,
            busy: self.busy(),
            emitted: self.emitted,
            emitted_forward: self.emitted_forward,
            pending_forward: self.pending > 0,
            pending_backward: self.pending < 0,
        }
    }

    /// One rising clock edge; returns the outputs after it (with the same
    /// `mode` input still applied).
    pub fn step(&mut self, i: StepOutputInputs) -> StepOutputOutputs {
        // A timer loaded with v lets its event happen max(v, 1) clocks later.
        let wait = |v: u64| (v & self.timer_mask).max(1) - 1;
        let positive = self.pending > 0;
        let nonzero = self.pending != 0;
        let requested_mode = if i.mode == 3 { 0 } else { i.mode };
        let quadrature = self.active_mode == 2;
        let up_down = self.active_mode == 1;
        let phase_done = self.phase_left == 0;
        let dir_done = self.dir_left == 0;
        let mut next = self.clone();
        next.phase_left = self.phase_left.saturating_sub(1);
        next.dir_left = self.dir_left.saturating_sub(1);
        next.started = true;
        next.mode_taken = true;

        let (mut emit, mut fall, mut dir_change) = (false, false, false);
        if !self.started {
            // Only the timers load (below).
        } else if quadrature {
            if nonzero && phase_done {
                emit = true;
                (next.a, next.b) = if positive {
                    (!self.b, self.a)
                } else {
                    (self.b, !self.a)
                };
            }
        } else if self.high {
            if phase_done {
                fall = true;
                next.high = false;
                next.a = false;
                if up_down {
                    next.b = false;
                }
            }
        } else if nonzero
            && phase_done
            && (up_down || (self.b == positive && (dir_done || !self.timing_setup)))
        {
            emit = true;
            next.high = true;
            if up_down {
                (next.a, next.b) = (positive, !positive);
            } else {
                next.a = true;
            }
        } else if !up_down && nonzero && self.b != positive && (dir_done || self.timing_setup) {
            // A direction change once the hold after the last fall has
            // passed; during a setup (no pulse since the last change) it
            // may change back at once.
            dir_change = true;
            next.b = positive;
        }

        if !self.started || emit || fall {
            // A rise or a quadrature state times step_len; a fall or the
            // start times step_space (quadrature: step_len).
            let len = quadrature || (self.started && !self.high);
            next.phase_left = wait(if len { i.step_len } else { i.step_space });
        }
        if !self.started || fall || dir_change {
            // After a fall: hold; after a direction change or the start:
            // setup.
            next.timing_setup = !self.high;
            next.dir_left = wait(if self.high { i.dir_hold } else { i.dir_setup });
        }

        let (min, max) = pending_limits(self.pending_bits);
        next.emitted = emit;
        next.emitted_forward = positive;
        if i.clear_overrun {
            next.overrun = false;
        }
        let mut request = i.step;
        if i.step && ((i.dir && self.pending == max) || (!i.dir && self.pending == min)) {
            request = false;
            next.overrun = true;
        }
        let emitted = match (emit, positive) {
            (false, _) => 0,
            (true, true) => -1,
            (true, false) => 1,
        };
        let requested = match (request, i.dir) {
            (false, _) => 0,
            (true, true) => 1,
            (true, false) => -1,
        };
        next.pending = self.pending + emitted + requested;
        if i.flush {
            next.pending = 0;
        }

        // The first clock after power-up takes the mode as a change does.
        if !self.mode_taken || (!self.busy() && requested_mode != self.active_mode) {
            next.active_mode = requested_mode;
            next.a = false;
            next.b = false;
            next.high = false;
            next.started = false;
        }
        if i.reset {
            next = Self::new(self.timer_mask.count_ones(), self.pending_bits);
            next.active_mode = requested_mode;
            next.mode_taken = true;
        }
        *self = next;
        self.outputs(i.mode)
    }
}

crate::lockstep_model!(StepOutputModel {
    inputs: StepOutputInputs,
    outputs: StepOutputOutputs,
    step: |model, inputs| model.step(*inputs),
});
