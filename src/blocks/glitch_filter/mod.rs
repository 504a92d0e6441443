//! # `GlitchFilter`: accept a level change only after k stable samples
//!
//! An internal building block (not exported on its own; the
//! `quadrature_decoder` uses one per input). It holds a filtered copy of a
//! synchronized input and accepts a change of the input only when the new
//! level has been seen on `length` consecutive samples. A shorter excursion
//! (a glitch, a bounce) is forgotten as soon as a sample sees the old level
//! again.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A new level that is first sampled at sample s is accepted at sample
//! s + max(k, 1) - 1, if every sample in between saw it: `filtered` shows
//! the new level after that edge, and `changed` is high for the clock
//! after it. With k <= 1 a change is accepted at the first sample that sees
//! it. Both outputs come straight from flip-flops, so a consumer of the
//! change starts a new logic stage.
//!
//! `length` is taken when a run of the old level is sampled (and at each
//! acceptance and prime); a change of `length` applies from the next change
//! of the input.
//!
//! After reset the threshold is not loaded yet, so the first change would
//! be accepted at its first sample: prime the filter (one clock is enough)
//! before its `changed` is used, as the `quadrature_decoder` does.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: `filtered` 0, run count 0",
    ),
    port("raw", "1", "the input, already synchronized to `clock`"),
    port(
        "sample",
        "1",
        "this edge is a sample (tie high to sample every clock)",
    ),
    port(
        "length",
        "4",
        "k: consecutive samples a new level needs; 0 and 1 both accept at the first sample",
    ),
    port(
        "prime",
        "1",
        "load `raw` into `filtered` at once, with no `accept` (start-up)",
    ),
    port("filtered", "1", "the accepted level, registered"),
    port(
        "changed",
        "1",
        "registered: `filtered` changed at the last edge (high one clock per change)",
    ),
];

/// Level filter with a run-length threshold. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct GlitchFilter {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Synchronized input.
    pub raw: Signal<In, Bit>,
    /// This edge is a sample.
    pub sample: Signal<In, Bit>,
    /// k, the samples a new level needs.
    pub length: Signal<In, Bits<4>>,
    /// Load `raw` without an `accept`.
    pub prime: Signal<In, Bit>,
    /// Accepted level.
    pub filtered: Signal<Out, Bit>,
    /// `filtered` changed at the last edge.
    pub changed: Signal<Out, Bit>,
    level: DFF<Bit>,
    changed_reg: DFF<Bit>,
    /// Samples the new level still needs, counting down; 0 and 1 both mean
    /// "the next sample of the new level is accepted".
    left: DFF<Bits<4>>,
    differs: Signal<Local, Bit>,
    ready: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
    zero: Constant<Bits<4>>,
    one: Constant<Bits<4>>,
    not_one: Constant<Bits<4>>,
}

impl Default for GlitchFilter {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            raw: Default::default(),
            sample: Default::default(),
            length: Default::default(),
            prime: Default::default(),
            filtered: Default::default(),
            changed: Default::default(),
            level: Default::default(),
            changed_reg: Default::default(),
            left: Default::default(),
            differs: Default::default(),
            ready: Default::default(),
            accept: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            not_one: Constant::new(14u64.into()),
        }
    }
}

impl Logic for GlitchFilter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, level, left, changed_reg);
        self.filtered.next = self.level.q.val();
        self.changed.next = self.changed_reg.q.val();
        self.differs.next = self.raw.val() != self.level.q.val();
        self.ready.next = (self.left.q.val() & self.not_one.val()) == self.zero.val();
        self.accept.next =
            !self.prime.val() & self.sample.val() & self.differs.val() & self.ready.val();
        self.changed_reg.d.next = self.accept.val();
        if self.sample.val() {
            if !self.differs.val() | self.ready.val() {
                self.left.d.next = self.length.val();
                self.level.d.next = self.raw.val();
            } else {
                self.left.d.next = self.left.q.val() - self.one.val();
            }
        }
        if self.prime.val() {
            self.left.d.next = self.length.val();
            self.level.d.next = self.raw.val();
        }
        if self.reset.val() {
            self.left.d.next = self.zero.val();
            self.level.d.next = false;
            self.changed_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[] GlitchFilter {
    inputs: [reset, raw, sample, length, prime],
    outputs: [filtered, changed],
});
