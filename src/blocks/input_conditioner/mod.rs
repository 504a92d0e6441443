//! # `InputConditioner`: W asynchronous switch inputs, synchronized, filtered, polarity-corrected
//!
//! An internal building block of `motion_controller` (not exported on its
//! own): limit and home switches, drive alarms, the E-stop chain and the
//! general inputs each pass one. Per bit: a two-flip-flop synchronizer, a
//! [`GlitchFilter`](crate::blocks::glitch_filter) and a polarity inversion.
//!
//! ## Ports (`W` bits)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A pin change that settles before clock edge e is in the second
//! synchronizer flip-flop after edge e + 1. The filter samples that flip-flop:
//! with a sample every clock and `length` = k, a change held from edge e on
//! is accepted at edge e + 1 + max(k, 1), and `active`, `rise` and `fall`
//! show it after that edge. The latency from the pin to `active` is
//! therefore max(k, 1) + 1 clocks after the first edge that sees it, i.e.
//! at most max(k, 1) + 2 clocks, and a pulse shorter than k samples is
//! never seen. With a slower `sample`, multiply k by the sample interval
//! and add up to one interval.
//!
//! ## Reset and priming
//! The synchronizer flip-flops are not reset: they follow the pins through
//! a reset. After reset (and after power-up) the filters are primed for
//! three clocks: each loads its synchronized pin directly, with no edge,
//! so a switch already closed at reset reads closed without a `rise`, and
//! a level held through reset never interrupts. `ready` rises with the
//! third priming edge; `active` reads 0 before it, so the consumer must
//! treat `!ready` as "not known yet" (`motion_controller` refuses RUN).
//!
//! ## Bad input
//! * A pin that changes on every sample (a broken wire that chatters, or a
//!   `length` too short for the bounce) produces one `rise`/`fall` pair per
//!   accepted change, never two changes at one edge.
//! * Changing `invert` flips `active` at once without a `rise` or `fall`:
//!   a polarity change is a configuration change, not an event.
//! * Changing `length` applies from the next change of the pin (the filter's
//!   own rule).

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::glitch_filter::GlitchFilter;

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: every `active` bit 0, no edges, `ready` 0 until primed again"),
    port("raw", "W", "the pins, asynchronous"),
    port("invert", "W", "per bit, 1 = active low (normally-open wiring); applied after the filter"),
    port("sample", "1", "this edge is a filter sample (tie high to sample every clock)"),
    port("length", "4", "samples a new level must hold to be accepted; 0 and 1 accept at the first sample"),
    port("active", "W", "the accepted level, inverted where `invert` is set (0 while priming); from flip-flops through one LUT"),
    port("rise", "W", "`active` rose at the last edge (one clock per accepted change)"),
    port("fall", "W", "`active` fell at the last edge"),
    port("ready", "1", "primed: `active` shows the pins (low for 3 clocks after reset or power-up)"),
];

/// Priming edges after reset before `ready`: two fill the synchronizer,
/// the third loads the filters from it.
pub const PRIME_CLOCKS: u64 = 3;

/// Synchronizer, glitch filter and polarity for `W` pins. See the
/// [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct InputConditioner<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// The pins (asynchronous).
    pub raw: Signal<In, Bits<W>>,
    /// Per bit: active low.
    pub invert: Signal<In, Bits<W>>,
    /// This edge is a filter sample.
    pub sample: Signal<In, Bit>,
    /// Samples a new level must hold.
    pub length: Signal<In, Bits<4>>,
    /// Accepted level, polarity applied.
    pub active: Signal<Out, Bits<W>>,
    /// `active` rose at the last edge.
    pub rise: Signal<Out, Bits<W>>,
    /// `active` fell at the last edge.
    pub fall: Signal<Out, Bits<W>>,
    /// The filters are primed.
    pub ready: Signal<Out, Bit>,

    filters: [GlitchFilter; W],
    /// The two synchronizer stages (not reset).
    sync_1: DFF<Bits<W>>,
    sync_2: DFF<Bits<W>>,
    /// Priming edges done, saturating at 3.
    primed: DFF<Bits<2>>,
    filtered: Signal<Local, Bits<W>>,
    changed: Signal<Local, Bits<W>>,
    priming: Signal<Local, Bit>,
    bit_mask: [Constant<Bits<W>>; W],
    zero_w: Constant<Bits<W>>,
    zero_2: Constant<Bits<2>>,
    one_2: Constant<Bits<2>>,
    three_2: Constant<Bits<2>>,
}

impl<const W: usize> Default for InputConditioner<W> {
    fn default() -> Self {
        assert!(
            (1..=32).contains(&W),
            "InputConditioner takes 1 to 32 inputs"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            raw: Default::default(),
            invert: Default::default(),
            sample: Default::default(),
            length: Default::default(),
            active: Default::default(),
            rise: Default::default(),
            fall: Default::default(),
            ready: Default::default(),
            filters: array_init::array_init(|_| GlitchFilter::default()),
            sync_1: Default::default(),
            sync_2: Default::default(),
            primed: Default::default(),
            filtered: Default::default(),
            changed: Default::default(),
            priming: Default::default(),
            bit_mask: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            zero_w: Constant::new(0u64.into()),
            zero_2: Constant::new(0u64.into()),
            one_2: Constant::new(1u64.into()),
            three_2: Constant::new(3u64.into()),
        }
    }
}

impl<const W: usize> Logic for InputConditioner<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, sync_1, sync_2, primed);

        // Synchronizer: two flip-flops, free-running through reset.
        self.sync_1.d.next = self.raw.val();
        self.sync_2.d.next = self.sync_1.q.val();

        // Priming: three edges after reset.
        self.priming.next = self.primed.q.val() != self.three_2.val();
        if self.priming.val() {
            self.primed.d.next = self.primed.q.val() + self.one_2.val();
        }
        if self.reset.val() {
            self.primed.d.next = self.zero_2.val();
        }
        self.ready.next = !self.priming.val();

        self.filtered.next = self.zero_w.val();
        self.changed.next = self.zero_w.val();
        for i in 0..W {
            self.filters[i].clock.next = self.clock.val();
            self.filters[i].reset.next = self.reset.val();
            // A mask, not a bit select: rust-hdl declares a 1-bit vector
            // without a range, where `x[0]` is illegal Verilog.
            self.filters[i].raw.next =
                (self.sync_2.q.val() & self.bit_mask[i].val()) != self.zero_w.val();
            self.filters[i].sample.next = self.sample.val();
            self.filters[i].length.next = self.length.val();
            self.filters[i].prime.next = self.priming.val();
            if self.filters[i].filtered.val() {
                self.filtered.next = self.filtered.val() | self.bit_mask[i].val();
            }
            if self.filters[i].changed.val() {
                self.changed.next = self.changed.val() | self.bit_mask[i].val();
            }
        }
        // Nothing is known before the filters are primed: read inactive.
        self.active.next = self.filtered.val() ^ self.invert.val();
        if self.priming.val() {
            self.active.next = self.zero_w.val();
        }
        self.rise.next = self.changed.val() & (self.filtered.val() ^ self.invert.val());
        self.fall.next = self.changed.val() & !(self.filtered.val() ^ self.invert.val());
    }
}

crate::vector_ports!(impl[const W: usize] InputConditioner<W> {
    inputs: [reset, raw, invert, sample, length],
    outputs: [active, rise, fall, ready],
});
