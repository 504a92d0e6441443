//! Reference model of [`super::QuadratureDecoder`], cycle-exact.

use crate::blocks::glitch_filter::model::GlitchFilterModel;

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadratureDecoderInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Encoder channel A (asynchronous).
    pub a: bool,
    /// Encoder channel B (asynchronous).
    pub b: bool,
    /// Index (Z) channel (asynchronous).
    pub index: bool,
    /// Glitch filter length k, 0..15.
    pub filter: u8,
    /// Count <- 0 and error <- 0.
    pub clear: bool,
    /// Error <- 0 (the count is kept).
    pub clear_error: bool,
    /// A sample every sample_rate + 1 clocks.
    pub sample_rate: u64,
    /// Count rising edges of `a`, `b` = direction (1 = up).
    pub counter_mode: bool,
    /// The index is active low.
    pub index_invert: bool,
    /// Clear the count on an index event.
    pub index_clear: bool,
    /// Latch the count on an index event.
    pub index_latch: bool,
    /// Act on the first index event only, until re-armed.
    pub index_once: bool,
    /// Clear `index_seen` (re-arms a once-only index).
    pub index_rearm: bool,
}

impl QuadratureDecoderInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.a as u64,
            self.b as u64,
            self.index as u64,
            self.filter as u64,
            self.clear as u64,
            self.sample_rate,
            self.counter_mode as u64,
            self.index_invert as u64,
            self.index_clear as u64,
            self.index_latch as u64,
            self.index_once as u64,
            self.index_rearm as u64,
            self.clear_error as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadratureDecoderOutputs {
    /// Signed position (two's complement, `count_bits` wide).
    pub count: u64,
    /// The last count was up.
    pub dir: bool,
    /// Sticky: a double change (counts lost).
    pub error: bool,
    /// Sticky: an index event was seen since re-arm.
    pub index_seen: bool,
    /// The count latched at the last index event.
    pub index_count: u64,
    /// The timestamp latched at the last count.
    pub count_time: u64,
    /// The free-running timestamp (samples).
    pub timestamp: u64,
}

impl QuadratureDecoderOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            count: v[0],
            dir: v[1] != 0,
            error: v[2] != 0,
            index_seen: v[3] != 0,
            index_count: v[4],
            count_time: v[5],
            timestamp: v[6],
        }
    }
}

/// Clocks after reset in which the filters take the pins' levels without
/// counting (the synchronizer fills in two of them).
pub const STARTUP_CLOCKS: u8 = 3;

/// Plain-Rust, cycle-exact model of the quadrature decoder.
#[derive(Clone, Debug)]
pub struct QuadratureDecoderModel {
    count_mask: u64,
    sample_mask: u64,
    time_mask: u64,
    /// Two-flip-flop synchronizers: (first, second) for a, b, index.
    sync: [(bool, bool); 3],
    startup: u8,
    sample_left: u64,
    filters: [GlitchFilterModel; 3],
    /// Decoded at the last edge, applied at the next: up, down, double
    /// change, index event.
    up: bool,
    down: bool,
    double: bool,
    index_event: bool,
    /// A count held over a clear at the last edge: +1, -1 or 0.
    deferred: i64,
    out: QuadratureDecoderOutputs,
}

impl QuadratureDecoderModel {
    /// A decoder with a `count_bits` count, a `sample_bits` sample-rate
    /// input and a `time_bits` timestamp, in its power-up state.
    pub fn new(count_bits: u32, sample_bits: u32, time_bits: u32) -> Self {
        Self {
            count_mask: crate::blocks::width_mask(count_bits),
            sample_mask: crate::blocks::width_mask(sample_bits),
            time_mask: crate::blocks::width_mask(time_bits),
            sync: [(false, false); 3],
            startup: 0,
            sample_left: 0,
            filters: Default::default(),
            up: false,
            down: false,
            double: false,
            index_event: false,
            deferred: 0,
            out: QuadratureDecoderOutputs::default(),
        }
    }

    /// The outputs after the last edge.
    pub fn outputs(&self) -> QuadratureDecoderOutputs {
        self.out
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: QuadratureDecoderInputs) -> QuadratureDecoderOutputs {
        if i.reset {
            *self = Self::new(
                self.count_mask.count_ones(),
                self.sample_mask.count_ones(),
                self.time_mask.count_ones(),
            );
            return self.out;
        }
        let prev = self.clone();
        let o = &mut self.out;

        // Count stage: applies what the decode stage registered last edge.
        let armed = !i.index_once || !prev.out.index_seen || i.index_rearm;
        let index_act = prev.index_event && armed;
        let clear_now = i.clear || (index_act && i.index_clear);
        if index_act && i.index_latch {
            o.index_count = prev.out.count;
        }
        o.index_seen = (prev.out.index_seen && !i.index_rearm) || index_act;
        let event = prev.up as i64 - prev.down as i64;
        if clear_now {
            o.count = 0;
            self.deferred = event;
        } else {
            o.count = (prev.out.count as i64 + event + prev.deferred) as u64 & self.count_mask;
            self.deferred = 0;
        }
        if prev.up {
            o.dir = true;
        }
        if prev.down {
            o.dir = false;
        }
        o.error = (prev.out.error && !i.clear && !i.clear_error) || prev.double;
        if prev.up || prev.down {
            o.count_time = prev.out.timestamp;
        }

        // Sampling and the free-running timestamp.
        let sample = prev.sample_left == 0;
        self.sample_left = if sample {
            i.sample_rate & self.sample_mask
        } else {
            prev.sample_left - 1
        };
        if sample {
            o.timestamp = (prev.out.timestamp + 1) & self.time_mask;
        }

        // Decode, from the filters' registered levels and change flags.
        let [a, b, index] = [0, 1, 2].map(|n| prev.filters[n].filtered());
        let [changed_a, changed_b, changed_index] = [0, 1, 2].map(|n| prev.filters[n].changed());
        if i.counter_mode {
            let rise = changed_a && a;
            self.up = rise && b;
            self.down = rise && !b;
            self.double = rise && changed_b;
        } else {
            let single = changed_a != changed_b;
            // Forward is 00 -> 10 -> 11 -> 01: A changing into a != b, or B
            // changing into b == a.
            let forward = if changed_a { a != b } else { a == b };
            self.up = single && forward;
            self.down = single && !forward;
            self.double = changed_a && changed_b;
        }
        self.index_event = changed_index && (index != i.index_invert);

        // Filters, from the synchronized levels before this edge.
        let priming = prev.startup < STARTUP_CLOCKS;
        for (filter, sync) in self.filters.iter_mut().zip(prev.sync) {
            filter.step(false, sync.1, sample, i.filter, priming);
        }
        if priming {
            self.startup += 1;
        }

        // Synchronizers.
        for (s, pin) in self.sync.iter_mut().zip([i.a, i.b, i.index]) {
            *s = (pin, s.0);
        }
        self.out
    }
}

crate::lockstep_model!(QuadratureDecoderModel {
    inputs: QuadratureDecoderInputs,
    outputs: QuadratureDecoderOutputs,
    step: |model, inputs| model.step(*inputs),
});
