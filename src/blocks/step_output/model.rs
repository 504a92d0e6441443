//! Reference model of [`super::StepOutput`], cycle-exact.

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
    /// Direction setup time.
    pub dir_setup: u64,
    /// Direction hold time (0 acts as 1).
    pub dir_hold: u64,
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
}

/// Plain-Rust, cycle-exact model of the step output stage with `timer_bits`
/// timers and a 16-bit pending count.
#[derive(Clone, Debug)]
pub struct StepOutputModel {
    timer_max: u64,
    pending: i32,
    a: bool,
    b: bool,
    high: bool,
    elapsed: u64,
    dir_elapsed: u64,
    active_mode: u8,
    overrun: bool,
}

/// The pending count's limit: ±(2^15 - 1) forward, -2^15 backward.
pub const PENDING_MAX: i32 = (1 << 15) - 1;
/// The most negative pending count.
pub const PENDING_MIN: i32 = -(1 << 15);

impl StepOutputModel {
    /// A stage with `timer_bits`-bit timers, in its power-up state.
    pub fn new(timer_bits: u32) -> Self {
        Self {
            timer_max: crate::blocks::width_mask(timer_bits),
            pending: 0,
            a: false,
            b: false,
            high: false,
            elapsed: 0,
            dir_elapsed: 0,
            active_mode: 0,
            overrun: false,
        }
    }

    /// Steps requested but not yet emitted (signed).
    pub fn pending(&self) -> i32 {
        self.pending
    }

    fn outputs(&self, mode: u8) -> StepOutputOutputs {
        StepOutputOutputs {
            out_a: self.a,
            out_b: self.b,
            overrun: self.overrun,
            mode_invalid: mode == 3,
            busy: !(self.pending == 0 && !self.high),
        }
    }

    /// One rising clock edge; returns the outputs after it (with the same
    /// `mode` input still applied).
    pub fn step(&mut self, i: StepOutputInputs) -> StepOutputOutputs {
        let mask = self.timer_max;
        let at_least_one = |x: u64| if x & mask == 0 { 1 } else { x & mask };
        let (len, space, hold, setup) = (
            at_least_one(i.step_len),
            at_least_one(i.step_space),
            at_least_one(i.dir_hold),
            i.dir_setup & mask,
        );
        let positive = self.pending > 0;
        let negative = self.pending < 0;
        let idle = self.pending == 0 && !self.high;
        let mut next = self.clone();
        next.elapsed = (self.elapsed + 1).min(mask);
        next.dir_elapsed = (self.dir_elapsed + 1).min(mask);
        let mut emit = false;
        if self.active_mode == 2 {
            if (positive || negative) && self.elapsed >= len {
                emit = true;
                next.elapsed = 1;
                if positive {
                    (next.a, next.b) = (!self.b, self.a);
                } else {
                    (next.a, next.b) = (self.b, !self.a);
                }
            }
        } else if self.high {
            if self.elapsed >= len {
                next.high = false;
                next.a = false;
                if self.active_mode == 1 {
                    next.b = false;
                }
                next.elapsed = 1;
            }
        } else if (positive || negative) && self.elapsed >= space {
            if self.active_mode == 1 {
                emit = true;
                next.high = true;
                next.elapsed = 1;
                if positive {
                    next.a = true;
                } else {
                    next.b = true;
                }
            } else if self.b == positive {
                if self.dir_elapsed >= setup {
                    emit = true;
                    next.high = true;
                    next.a = true;
                    next.elapsed = 1;
                }
            } else if self.elapsed >= hold {
                next.b = positive;
                next.dir_elapsed = 1;
            }
        }
        let mut request = i.step;
        if i.step
            && !emit
            && ((i.dir && self.pending == PENDING_MAX) || (!i.dir && self.pending == PENDING_MIN))
        {
            request = false;
            next.overrun = true;
        }
        let emitted = if emit {
            if positive {
                -1
            } else {
                1
            }
        } else {
            0
        };
        let requested = if request {
            if i.dir {
                1
            } else {
                -1
            }
        } else {
            0
        };
        next.pending = self.pending + emitted + requested;
        let requested_mode = if i.mode == 3 { 0 } else { i.mode };
        if idle && requested_mode != self.active_mode {
            next.active_mode = requested_mode;
            next.a = false;
            next.b = false;
            next.high = false;
            next.elapsed = 0;
            next.dir_elapsed = 0;
        }
        if i.reset {
            next = Self::new(mask.count_ones());
        }
        *self = next;
        self.outputs(i.mode)
    }
}
