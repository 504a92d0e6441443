//! # `Watchdog`: stop everything when the host stops kicking
//!
//! An internal building block (the motion controller's host watchdog). A
//! down-counter is reloaded with `timeout` by every `kick` and counts the
//! `tick`s in between; if it runs out before the next kick, the sticky
//! `expired` output is set (the controller stops all stepping on it). Axes
//! that keep running after the host disconnects is a real field failure;
//! this is the defence.
//!
//! ## Ports (`W` bits of timeout)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A kick at edge k arms the watchdog with T = `timeout`; `expired` is set
//! at the T-th tick edge after k if no kick comes before or at that edge (a
//! kick on the expiring edge wins: it reloads). After reset the watchdog
//! is disarmed: the first kick arms it, so a host that never starts cannot
//! trip it, and a host that starts and stops always does.
//!
//! ## Bad input
//! * `timeout` = 0 at a kick: disarmed (no expiry). Changing `timeout`
//!   while armed affects the next kick only.
//! * `kick` and `clear` on one clock: `expired` is cleared and the counter
//!   re-armed.
//!
//! ## Formal proof
//! `formal/watchdog.sv` states the timing above as assertions on the ports.
//! After a kick with T = `timeout` != 0, `expired` is set at exactly the
//! T-th tick edge after the kick if no kick comes before or at that edge,
//! and at no other edge: not early, not while kicked in time, never with
//! T = 0, never after reset or an expiry until a kick arms the watchdog
//! again. It stays set until `clear`. `armed` is 1 from such a kick up to
//! the expiry. The proof assumes nothing: every input is free at every
//! clock. It also proves two points of `clear`: it clears `expired` only
//! and leaves a running countdown armed (the ports table); and an expiry on
//! the clock of a `clear` sets `expired`: the new expiry wins over the
//! clear of the old one.
//! Proved by k-induction (depth 1) for W = 4 and for the motion
//! controller's W = 32 (figures in the README's "What is proved").

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: disarmed, `expired` 0"),
    port("tick", "1", "time base: the counter counts ticks (tie high to count clocks)"),
    port("timeout", "W", "ticks allowed between kicks; 0 disarms the watchdog"),
    port("kick", "1", "reload the counter with `timeout` (and arm it)"),
    port("clear", "1", "clear `expired` (a countdown in progress goes on; after an expiry the counter stays disarmed until the next kick)"),
    port("expired", "1", "sticky: `timeout` ticks passed without a kick"),
    port("armed", "1", "the counter is running"),
];

/// Host watchdog. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct Watchdog<const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Time base.
    pub tick: Signal<In, Bit>,
    /// Ticks allowed between kicks; 0 disarms.
    pub timeout: Signal<In, Bits<W>>,
    /// Reload and arm.
    pub kick: Signal<In, Bit>,
    /// Clear `expired`.
    pub clear: Signal<In, Bit>,
    /// Sticky expiry.
    pub expired: Signal<Out, Bit>,
    /// The counter runs.
    pub armed: Signal<Out, Bit>,
    left: DFF<Bits<W>>,
    /// `left == 1`: the next tick expires, registered a tick ahead.
    last: DFF<Bit>,
    armed_reg: DFF<Bit>,
    expired_reg: DFF<Bit>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    two: Constant<Bits<W>>,
}

impl<const W: usize> Default for Watchdog<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            timeout: Default::default(),
            kick: Default::default(),
            clear: Default::default(),
            expired: Default::default(),
            armed: Default::default(),
            left: Default::default(),
            last: Default::default(),
            armed_reg: Default::default(),
            expired_reg: Default::default(),
            zero: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
            two: Constant::new(2u64.into()),
        }
    }
}

impl<const W: usize> Logic for Watchdog<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, left, last, armed_reg, expired_reg);
        self.expired.next = self.expired_reg.q.val();
        self.armed.next = self.armed_reg.q.val();
        if self.clear.val() {
            self.expired_reg.d.next = false;
        }
        if self.kick.val() {
            self.left.d.next = self.timeout.val();
            self.last.d.next = self.timeout.val() == self.one.val();
            self.armed_reg.d.next = self.timeout.val() != self.zero.val();
        } else if self.tick.val() & self.armed_reg.q.val() {
            if self.last.q.val() {
                self.expired_reg.d.next = true;
                self.armed_reg.d.next = false;
            } else {
                self.left.d.next = self.left.q.val() - self.one.val();
                self.last.d.next = self.left.q.val() == self.two.val();
            }
        }
        if self.reset.val() {
            self.left.d.next = self.zero.val();
            self.last.d.next = false;
            self.armed_reg.d.next = false;
            self.expired_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const W: usize] Watchdog<W> {
    inputs: [reset, tick, timeout, kick, clear],
    outputs: [expired, armed],
});
