//! # `pulse_counter`: up/down counter with clear, load and compare
//!
//! Counts step pulses (commanded position) or encoder counts (actual
//! position) up and down, and detects the end of an interpolation period by
//! comparing the count with a programmable value.
//!
//! ## Ports (`W` = 32 in the exported `pulse_counter`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! `count` is registered: one clock after an edge, it shows the result of
//! that edge's inputs. Priority per edge: `reset`, then `clear`, then `load`,
//! then `up`/`down`. `compare_match` has no latency of its own: it follows
//! `count` and `compare_value` in the same cycle (one equality tree, no
//! register), so a period-end detector sees the match in the cycle the count
//! reaches the value.
//!
//! ## Bad input
//! * `up` and `down` together: the count holds (+1 -1). No pulse is lost.
//! * `clear` or `load` in the same clock as a pulse: the clear or load wins
//!   (the port contract) and that clock's pulse is not counted, but never
//!   silently: `pulse_overridden` strobes one clock later. A design that must
//!   keep such a pulse adds it back (for example with a `load` of the
//!   cleared value ±1) or holds the clear until a clock without a pulse (as
//!   `motion_controller` does).
//! * Overflow wraps (two's complement), as position registers do; the CPU
//!   extends the count in software from successive reads.
//! * `up` and `down` are sampled every clock as levels: a pulse held high for
//!   n clocks counts n times. They are synchronous inputs (from other blocks
//!   of this clock domain); asynchronous pins need a synchronizer first, as
//!   the quadrature decoder has.
//! * `compare_value` tied to 0 flags count == 0; the count is unaffected.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "up/down pulse counter with clear, load and a compare output";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: count <- 0"),
    port("up", "1", "count +1"),
    port("down", "1", "count -1; with `up` in the same clock the count is unchanged and neither pulse is lost"),
    port("clear", "1", "count <- 0; priority over `load` and counting"),
    port("load", "1", "count <- `load_value`; priority over counting"),
    port("load_value", "W", "value for `load`"),
    port("compare_value", "W", "value for `compare_match`"),
    port("count", "W", "two's complement, wrapping; registered"),
    port("compare_match", "1", "`count == compare_value`, combinational from the registered count"),
    port("pulse_overridden", "1", "registered strobe: the previous edge had a net `up` or `down` pulse that `clear` or `load` overrode, so it was not counted"),
];

/// Up/down pulse counter. See the [module documentation](self) for the datasheet.
#[derive(Clone, Debug, LogicBlock)]
pub struct PulseCounter<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Count +1.
    pub up: Signal<In, Bit>,
    /// Count -1.
    pub down: Signal<In, Bit>,
    /// Count <- 0.
    pub clear: Signal<In, Bit>,
    /// Count <- `load_value`.
    pub load: Signal<In, Bit>,
    /// Value for `load`.
    pub load_value: Signal<In, Bits<W>>,
    /// Value for `compare_match`.
    pub compare_value: Signal<In, Bits<W>>,
    /// The count, registered.
    pub count: Signal<Out, Bits<W>>,
    /// `count == compare_value`.
    pub compare_match: Signal<Out, Bit>,
    /// The previous edge's net pulse was overridden (see the port table).
    pub pulse_overridden: Signal<Out, Bit>,
    value: DFF<Bits<W>>,
    overridden: DFF<Bit>,
    /// +1 or -1, as a W-bit two's complement addend.
    delta: Signal<Local, Bits<W>>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    all_ones: Constant<Bits<W>>,
}

impl<const W: usize> Default for PulseCounter<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            up: Default::default(),
            down: Default::default(),
            clear: Default::default(),
            load: Default::default(),
            load_value: Default::default(),
            compare_value: Default::default(),
            count: Default::default(),
            compare_match: Default::default(),
            pulse_overridden: Default::default(),
            value: Default::default(),
            overridden: Default::default(),
            delta: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            all_ones: Constant::new(if W >= 64 { u64::MAX } else { (1u64 << W) - 1 }.into()),
        }
    }
}

impl<const W: usize> Logic for PulseCounter<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, value, overridden);
        self.count.next = self.value.q.val();
        self.pulse_overridden.next = self.overridden.q.val();
        // Reset is not an override: it returns to the power-up state, in
        // which the flag is 0.
        self.overridden.d.next = (self.up.val() ^ self.down.val())
            & (self.load.val() | self.clear.val())
            & !self.reset.val();
        self.compare_match.next = self.value.q.val() == self.compare_value.val();
        // One adder for both directions: +1 or +(-1), applied only on a net pulse.
        if self.down.val() {
            self.delta.next = self.all_ones.val();
        } else {
            self.delta.next = self.one.val();
        }
        if self.up.val() ^ self.down.val() {
            self.value.d.next = self.value.q.val() + self.delta.val();
        }
        if self.load.val() {
            self.value.d.next = self.load_value.val();
        }
        if self.clear.val() | self.reset.val() {
            self.value.d.next = self.zero.val();
        }
    }
}

crate::vector_ports!(impl[const W: usize] PulseCounter<W> {
    inputs: [reset, up, down, clear, load, load_value, compare_value],
    outputs: [count, compare_match, pulse_overridden],
});
