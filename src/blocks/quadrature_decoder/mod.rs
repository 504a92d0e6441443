//! # `quadrature_decoder`: 4x quadrature or step/dir counter with glitch filter, error flag, index and timestamp
//!
//! Reads an incremental encoder (A, B, index Z) into a signed position, the
//! actual-position half of a closed loop. Every input is synchronized by two
//! flip-flops, then filtered: a change of a level counts only after it has
//! been seen on `filter` consecutive samples, at a programmable sample rate.
//! A and B changing on the same sample means the encoder outran the
//! decoder and counts were lost: nothing is counted for it and the sticky
//! `error` is set. No count is ever lost to a `clear` or an index clear on
//! the same clock (see "Collisions").
//!
//! ## Ports (`W` = 32-bit count, `S` = 8-bit sample rate, `TS` = 16-bit timestamp in the exported `quadrature_decoder`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Counting
//! Quadrature: forward is A leading B, (a,b) = 00 -> 10 -> 11 -> 01 -> 00,
//! +1 per transition; the reverse sequence counts -1. Counter mode: +1 on a
//! rising edge of `a` with `b` high, -1 with `b` low (as sampled with that
//! edge).
//!
//! ## Timing
//! * Latency: with the filter off and `sample_rate` = 0, `count` shows a
//!   pin change after the 5th edge that samples it ([`PIN_TO_COUNT_EDGES`]:
//!   two synchronizer flip-flops, the filter, the decode register, the
//!   count). A filter of k adds max(k, 1) - 1 samples, and a slower sample
//!   rate up to `sample_rate` clocks before the first sample.
//! * Rate: each level must be held at least max(k, 1) samples, and A and B
//!   edges must be at least that far apart, or both are accepted on the same
//!   sample (`error`). With k <= 1 and `sample_rate` = 0 the decoder counts
//!   one state change per clock. In general the maximum count rate is
//!   f_clock / (max(k, 1) * (sample_rate + 1)).
//! * The index options are taken at every clock. A new `sample_rate`
//!   applies from the next sample (the running sample interval finishes
//!   first); a new `filter` length from the next change of each input.
//! * Start-up: after reset (and power-up) the first three clocks fill the
//!   synchronizers and load the filters with the pins' levels, without
//!   counting, so an encoder resting at any state does not count on
//!   start-up.
//!
//! ## Index
//! An index event is an accepted change of the filtered index to its active
//! level (`index_invert` = 0: rising). It is acted on when `index_once` is
//! 0, or when `index_seen` is 0. An acted-on event sets `index_seen`,
//! latches the count (with `index_latch`) and clears it (with
//! `index_clear`). `index_rearm` clears `index_seen` and re-arms a
//! once-only index; an event on the same clock as `index_rearm` is acted on
//! and sets `index_seen` again.
//!
//! ## Collisions
//! * A count and a `clear` (or an index clear) on the same clock: the count
//!   becomes 0 at that edge, and the count that arrived with it is added at
//!   the next edge. A count is never lost to a clear: after a clear the
//!   position is the movement from the clear on, including the transition
//!   on the clear's own clock.
//! * An index latch on the same clock as a count latches the count before
//!   that transition.
//! * An error event on the clock of a `clear`: `error` is set (the new
//!   error is not cleared).
//!
//! ## Bad input
//! * A and B changing on the same sample (quadrature): no count, `error`
//!   set, and the decoder continues from the new state.
//! * Counter mode, b changing on the sample where a rises: counted with the
//!   new b, and `error` set (the direction was ambiguous).
//! * Glitches shorter than k samples are ignored; glitches shorter than a
//!   clock may or may not be seen by the synchronizer.
//! * Motion faster than the rate limit above: A and B edges closer than k
//!   samples are accepted on one sample (`error`, no count) or, if a level
//!   is held for fewer than k samples, dropped as a glitch pair. The count
//!   can then be off by a multiple of 4 without `error` (no filter can tell
//!   a fast move from a glitch): keep the encoder below the rate limit.
//!
//! ## Formal proof
//! `formal/quadrature_decoder.sv` states the count's contract above as
//! assertions on the ports, with the filter off, following each pin through
//! the documented stages: the two synchronizer flip-flops, the sample that
//! accepts the change, the decode and the count ([`PIN_TO_COUNT_EDGES`] = 5
//! edges at `sample_rate` = 0; a slower rate waits for its sample). It
//! proves, at every clock: each legal transition changes `count` once, in
//! its direction, 5 edges after the pin change is first sampled (quadrature
//! and counter mode); at most one count per sample; a double change counts
//! nothing and sets `error`; a `clear` or an index clear on a counting clock
//! leaves the count 0 and adds the step at the next edge, so no count is
//! lost; nothing counts for the pins' resting levels after reset and the
//! start-up clocks; and `error`, `dir`, `index_seen`, `index_count` (the
//! count before a transition on the same clock) and `timestamp` (+1 per
//! sample) as specified.
//!
//! The environment it assumes:
//! * the filter is off: `filter` <= 1 at every clock. Filtering (k >= 2)
//!   is not covered by the proof;
//! * `counter_mode` and `index_invert` are configuration: each holds one
//!   value (either) through the run. Changing either while the encoder
//!   moves is not covered.
//!
//! Every other input (`reset`, the pins, `clear`, `clear_error`,
//! `sample_rate`, the index options) is free at every clock. Two timing
//! points the proof takes as part of the contract, where the sections
//! above are silent: the first sample comes at the first clock after reset
//! (then every `sample_rate` + 1 clocks, the rate taken at each sample);
//! and the index takes the same path as a and b, so an index event is
//! acted on (latch, clear, `index_seen`) on the clock that a transition
//! sampled with it reaches the count.
//!
//! Proved by k-induction (depth 5) for W = 4, S = 2, TS = 2 and for W = 32,
//! S = 2, TS = 16 (the exported count and timestamp widths). The exported
//! S = 8 is not proved: the filters' run counters are out of the property
//! file's reach, so the induction must span the longest sample interval,
//! 2^S clocks. Figures in the README's "What is proved".
//!
//! ## Implementation
//! Each input has its own [`GlitchFilter`] with registered level and
//! change flags, so the decode stage starts from flip-flops. The count's
//! change (-2..2, a transition plus one carried over a clear) is itself
//! registered, which leaves the 32-bit carry chain alone between two
//! registers; `clear` drives the count flip-flops' synchronous reset.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::glitch_filter::GlitchFilter;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "quadrature decoder: 4x or step/dir counting, glitch filter, error flag, index latch/clear, timestamp";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: everything 0; then 3 start-up clocks without counting"),
    port("a", "1", "encoder channel A, asynchronous to `clock`"),
    port("b", "1", "encoder channel B, asynchronous to `clock`"),
    port("index", "1", "index (Z) channel, asynchronous to `clock`"),
    port("filter", "4", "k: a change of a, b or index is accepted after k consecutive samples of the new level; 0 and 1: at the first sample (synchronizer only)"),
    port("clear", "1", "count <- 0 and error <- 0 (a count on the same clock is kept, added after the clear)"),
    port("sample_rate", "S", "a sample every `sample_rate` + 1 clocks; 0 = every clock"),
    port("counter_mode", "1", "0 = 4x quadrature; 1 = count rising edges of `a`, `b` high = up (step/dir input)"),
    port("index_invert", "1", "0 = the index is active high, 1 = active low"),
    port("index_clear", "1", "an index event clears the count"),
    port("index_latch", "1", "an index event latches the count into `index_count`"),
    port("index_once", "1", "act on the first index event only, until `index_rearm`"),
    port("index_rearm", "1", "clears `index_seen` (re-arms a once-only index)"),
    port("clear_error", "1", "clears `error` alone, keeping the count (an error on the same clock keeps it set); tie to 0 if unused"),
    port("count", "W", "signed position, two's complement, wrapping; 4 counts per line in quadrature"),
    port("dir", "1", "1 when the last count was up"),
    port("error", "1", "sticky: a and b changed on the same sample (quadrature), or b changed on the sample where a rose (counter mode); cleared by `clear` and `clear_error`"),
    port("index_seen", "1", "sticky: an index event was acted on since `index_rearm` or reset"),
    port("index_count", "W", "the count latched at the last acted-on index event (with `index_latch`)"),
    port("count_time", "TS", "`timestamp` latched at the last count"),
    port("timestamp", "TS", "free-running, wrapping, +1 per sample"),
];

/// Clocks after reset in which the filters take the pins' levels without
/// counting.
pub use model::STARTUP_CLOCKS;

/// Edges from the one that first samples a pin change to the one after
/// which `count` shows it, with the filter off and `sample_rate` = 0.
pub const PIN_TO_COUNT_EDGES: u64 = 5;

/// Quadrature decoder. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct QuadratureDecoder<const W: usize, const S: usize, const TS: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Channel A.
    pub a: Signal<In, Bit>,
    /// Channel B.
    pub b: Signal<In, Bit>,
    /// Index (Z).
    pub index: Signal<In, Bit>,
    /// Filter length k.
    pub filter: Signal<In, Bits<4>>,
    /// Count and error <- 0.
    pub clear: Signal<In, Bit>,
    /// A sample every `sample_rate` + 1 clocks.
    pub sample_rate: Signal<In, Bits<S>>,
    /// Step/dir counting instead of quadrature.
    pub counter_mode: Signal<In, Bit>,
    /// Index active low.
    pub index_invert: Signal<In, Bit>,
    /// Clear on index.
    pub index_clear: Signal<In, Bit>,
    /// Latch on index.
    pub index_latch: Signal<In, Bit>,
    /// First index only.
    pub index_once: Signal<In, Bit>,
    /// Clear `index_seen`.
    pub index_rearm: Signal<In, Bit>,
    /// Clear `error` alone (the count is kept).
    pub clear_error: Signal<In, Bit>,
    /// Signed position.
    pub count: Signal<Out, Bits<W>>,
    /// The last count was up.
    pub dir: Signal<Out, Bit>,
    /// Sticky double change.
    pub error: Signal<Out, Bit>,
    /// Sticky index seen.
    pub index_seen: Signal<Out, Bit>,
    /// Count at the last index event.
    pub index_count: Signal<Out, Bits<W>>,
    /// Timestamp of the last count.
    pub count_time: Signal<Out, Bits<TS>>,
    /// Free-running timestamp.
    pub timestamp: Signal<Out, Bits<TS>>,
    // Synchronizers: no logic between the two flip-flops of each.
    a_meta: DFF<Bit>,
    a_sync: DFF<Bit>,
    b_meta: DFF<Bit>,
    b_sync: DFF<Bit>,
    index_meta: DFF<Bit>,
    index_sync: DFF<Bit>,
    /// Counts the start-up clocks to 3.
    startup: DFF<Bits<2>>,
    sample_left: DFF<Bits<S>>,
    /// `sample_left != 0`, registered (0 at power-up, like the counter).
    sample_wait: DFF<Bit>,
    filter_a: GlitchFilter,
    filter_b: GlitchFilter,
    filter_index: GlitchFilter,
    // Decode stage.
    up: DFF<Bit>,
    down: DFF<Bit>,
    double: DFF<Bit>,
    index_event: DFF<Bit>,
    // Count stage.
    position: DFF<Bits<W>>,
    /// The change the count takes at the next edge, -2..2 (yosys keeps
    /// one flip-flop per distinct bit).
    delta: DFF<Bits<W>>,
    dir_reg: DFF<Bit>,
    error_reg: DFF<Bit>,
    index_seen_reg: DFF<Bit>,
    index_position: DFF<Bits<W>>,
    samples: DFF<Bits<TS>>,
    count_time_reg: DFF<Bits<TS>>,
    sample: Signal<Local, Bit>,
    priming: Signal<Local, Bit>,
    forward: Signal<Local, Bit>,
    index_act: Signal<Local, Bit>,
    clear_now: Signal<Local, Bit>,
    up_next: Signal<Local, Bit>,
    down_next: Signal<Local, Bit>,
    /// A count on the clock of a clear, carried to the next clock.
    carry_up: Signal<Local, Bit>,
    carry_down: Signal<Local, Bit>,
    zero_w: Constant<Bits<W>>,
    one_w: Constant<Bits<W>>,
    two_w: Constant<Bits<W>>,
    minus_one_w: Constant<Bits<W>>,
    minus_two_w: Constant<Bits<W>>,
    zero_s: Constant<Bits<S>>,
    one_s: Constant<Bits<S>>,
    one_ts: Constant<Bits<TS>>,
    zero_ts: Constant<Bits<TS>>,
    startup_done: Constant<Bits<2>>,
    one_2: Constant<Bits<2>>,
    zero_2: Constant<Bits<2>>,
}

impl<const W: usize, const S: usize, const TS: usize> Default for QuadratureDecoder<W, S, TS> {
    fn default() -> Self {
        assert!((3..=64).contains(&W), "count width must be 3..=64");
        assert!((1..=32).contains(&S), "sample-rate width must be 1..=32");
        assert!((1..=64).contains(&TS), "timestamp width must be 1..=64");
        let w_mask = crate::blocks::width_mask(W as u32);
        Self {
            clock: Default::default(),
            reset: Default::default(),
            a: Default::default(),
            b: Default::default(),
            index: Default::default(),
            filter: Default::default(),
            clear: Default::default(),
            sample_rate: Default::default(),
            counter_mode: Default::default(),
            index_invert: Default::default(),
            index_clear: Default::default(),
            index_latch: Default::default(),
            index_once: Default::default(),
            index_rearm: Default::default(),
            clear_error: Default::default(),
            count: Default::default(),
            dir: Default::default(),
            error: Default::default(),
            index_seen: Default::default(),
            index_count: Default::default(),
            count_time: Default::default(),
            timestamp: Default::default(),
            a_meta: Default::default(),
            a_sync: Default::default(),
            b_meta: Default::default(),
            b_sync: Default::default(),
            index_meta: Default::default(),
            index_sync: Default::default(),
            startup: Default::default(),
            sample_left: Default::default(),
            sample_wait: Default::default(),
            filter_a: Default::default(),
            filter_b: Default::default(),
            filter_index: Default::default(),
            up: Default::default(),
            down: Default::default(),
            double: Default::default(),
            index_event: Default::default(),
            position: Default::default(),
            delta: Default::default(),
            dir_reg: Default::default(),
            error_reg: Default::default(),
            index_seen_reg: Default::default(),
            index_position: Default::default(),
            samples: Default::default(),
            count_time_reg: Default::default(),
            sample: Default::default(),
            priming: Default::default(),
            forward: Default::default(),
            index_act: Default::default(),
            clear_now: Default::default(),
            up_next: Default::default(),
            down_next: Default::default(),
            carry_up: Default::default(),
            carry_down: Default::default(),
            zero_w: Constant::new(0u64.into()),
            one_w: Constant::new(1u64.into()),
            two_w: Constant::new(2u64.into()),
            minus_one_w: Constant::new(w_mask.into()),
            minus_two_w: Constant::new((w_mask - 1).into()),
            zero_s: Constant::new(0u64.into()),
            one_s: Constant::new(1u64.into()),
            one_ts: Constant::new(1u64.into()),
            zero_ts: Constant::new(0u64.into()),
            startup_done: Constant::new((STARTUP_CLOCKS as u64).into()),
            one_2: Constant::new(1u64.into()),
            zero_2: Constant::new(0u64.into()),
        }
    }
}

impl<const W: usize, const S: usize, const TS: usize> Logic for QuadratureDecoder<W, S, TS> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            a_meta,
            a_sync,
            b_meta,
            b_sync,
            index_meta,
            index_sync,
            startup,
            sample_left,
            sample_wait,
            up,
            down,
            double,
            index_event,
            position,
            delta,
            dir_reg,
            error_reg,
            index_seen_reg,
            index_position,
            samples,
            count_time_reg
        );
        self.filter_a.clock.next = self.clock.val();
        self.filter_b.clock.next = self.clock.val();
        self.filter_index.clock.next = self.clock.val();
        self.count.next = self.position.q.val();
        self.dir.next = self.dir_reg.q.val();
        self.error.next = self.error_reg.q.val();
        self.index_seen.next = self.index_seen_reg.q.val();
        self.index_count.next = self.index_position.q.val();
        self.count_time.next = self.count_time_reg.q.val();
        self.timestamp.next = self.samples.q.val();

        // Synchronizers.
        self.a_meta.d.next = self.a.val();
        self.a_sync.d.next = self.a_meta.q.val();
        self.b_meta.d.next = self.b.val();
        self.b_sync.d.next = self.b_meta.q.val();
        self.index_meta.d.next = self.index.val();
        self.index_sync.d.next = self.index_meta.q.val();

        // Sampling: a down-counter with its zero test registered one clock
        // ahead, and the timestamp counting samples.
        self.sample.next = !self.sample_wait.q.val();
        if self.sample.val() {
            self.sample_left.d.next = self.sample_rate.val();
            self.sample_wait.d.next = self.sample_rate.val() != self.zero_s.val();
            self.samples.d.next = self.samples.q.val() + self.one_ts.val();
        } else {
            self.sample_left.d.next = self.sample_left.q.val() - self.one_s.val();
            self.sample_wait.d.next = self.sample_left.q.val() != self.one_s.val();
        }

        // Filters, primed with the pins' levels during start-up.
        self.priming.next = self.startup.q.val() != self.startup_done.val();
        if self.priming.val() {
            self.startup.d.next = self.startup.q.val() + self.one_2.val();
        }
        self.filter_a.reset.next = self.reset.val();
        self.filter_a.raw.next = self.a_sync.q.val();
        self.filter_a.sample.next = self.sample.val();
        self.filter_a.length.next = self.filter.val();
        self.filter_a.prime.next = self.priming.val();
        self.filter_b.reset.next = self.reset.val();
        self.filter_b.raw.next = self.b_sync.q.val();
        self.filter_b.sample.next = self.sample.val();
        self.filter_b.length.next = self.filter.val();
        self.filter_b.prime.next = self.priming.val();
        self.filter_index.reset.next = self.reset.val();
        self.filter_index.raw.next = self.index_sync.q.val();
        self.filter_index.sample.next = self.sample.val();
        self.filter_index.length.next = self.filter.val();
        self.filter_index.prime.next = self.priming.val();

        // Decode stage, from the filters' registered levels and change
        // flags: forward is 00 -> 10 -> 11 -> 01, that is A changing into
        // a != b, or B changing into b == a.
        self.forward.next = !(self.filter_a.changed.val()
            ^ (self.filter_a.filtered.val() != self.filter_b.filtered.val()));
        if self.counter_mode.val() {
            self.up_next.next = self.filter_a.changed.val()
                & self.filter_a.filtered.val()
                & self.filter_b.filtered.val();
            self.down_next.next = self.filter_a.changed.val()
                & self.filter_a.filtered.val()
                & !self.filter_b.filtered.val();
            self.double.d.next = self.filter_a.changed.val()
                & self.filter_a.filtered.val()
                & self.filter_b.changed.val();
        } else {
            self.up_next.next =
                (self.filter_a.changed.val() ^ self.filter_b.changed.val()) & self.forward.val();
            self.down_next.next =
                (self.filter_a.changed.val() ^ self.filter_b.changed.val()) & !self.forward.val();
            self.double.d.next = self.filter_a.changed.val() & self.filter_b.changed.val();
        }
        self.up.d.next = self.up_next.val();
        self.down.d.next = self.down_next.val();
        self.index_event.d.next = self.filter_index.changed.val()
            & (self.filter_index.filtered.val() != self.index_invert.val());

        // Count stage. A count that meets a clear is carried into the next
        // clock's change, so the change register holds -2..2: the next
        // count plus the carried one. Registering it keeps the count's
        // carry chain the only logic between two registers.
        // A re-arm on the clock of an index event arms it: the event is
        // acted on and sets index_seen again.
        self.index_act.next = self.index_event.q.val()
            & (!self.index_once.val() | !self.index_seen_reg.q.val() | self.index_rearm.val());
        self.clear_now.next = self.clear.val() | (self.index_act.val() & self.index_clear.val());
        if self.index_act.val() & self.index_latch.val() {
            self.index_position.d.next = self.position.q.val();
        }
        self.index_seen_reg.d.next =
            (self.index_seen_reg.q.val() & !self.index_rearm.val()) | self.index_act.val();
        self.carry_up.next = self.clear_now.val() & self.up.q.val();
        self.carry_down.next = self.clear_now.val() & self.down.q.val();
        self.delta.d.next = self.zero_w.val();
        if (self.up_next.val() & !self.carry_down.val())
            | (self.carry_up.val() & !self.down_next.val())
        {
            self.delta.d.next = self.one_w.val();
        }
        if (self.down_next.val() & !self.carry_up.val())
            | (self.carry_down.val() & !self.up_next.val())
        {
            self.delta.d.next = self.minus_one_w.val();
        }
        if self.up_next.val() & self.carry_up.val() {
            self.delta.d.next = self.two_w.val();
        }
        if self.down_next.val() & self.carry_down.val() {
            self.delta.d.next = self.minus_two_w.val();
        }
        if self.clear_now.val() {
            self.position.d.next = self.zero_w.val();
        } else {
            self.position.d.next = self.position.q.val() + self.delta.q.val();
        }
        if self.up.q.val() {
            self.dir_reg.d.next = true;
        }
        if self.down.q.val() {
            self.dir_reg.d.next = false;
        }
        self.error_reg.d.next =
            (self.error_reg.q.val() & !self.clear.val() & !self.clear_error.val())
                | self.double.q.val();
        if self.up.q.val() | self.down.q.val() {
            self.count_time_reg.d.next = self.samples.q.val();
        }

        if self.reset.val() {
            self.a_meta.d.next = false;
            self.a_sync.d.next = false;
            self.b_meta.d.next = false;
            self.b_sync.d.next = false;
            self.index_meta.d.next = false;
            self.index_sync.d.next = false;
            self.startup.d.next = self.zero_2.val();
            self.sample_left.d.next = self.zero_s.val();
            self.sample_wait.d.next = false;
            self.up.d.next = false;
            self.down.d.next = false;
            self.double.d.next = false;
            self.index_event.d.next = false;
            self.position.d.next = self.zero_w.val();
            self.delta.d.next = self.zero_w.val();
            self.dir_reg.d.next = false;
            self.error_reg.d.next = false;
            self.index_seen_reg.d.next = false;
            self.index_position.d.next = self.zero_w.val();
            self.samples.d.next = self.zero_ts.val();
            self.count_time_reg.d.next = self.zero_ts.val();
        }
    }
}

crate::vector_ports!(impl[const W: usize, const S: usize, const TS: usize] QuadratureDecoder<W, S, TS> {
    inputs: [reset, a, b, index, filter, clear, sample_rate, counter_mode, index_invert, index_clear, index_latch, index_once, index_rearm, clear_error],
    outputs: [count, dir, error, index_seen, index_count, count_time, timestamp],
});
