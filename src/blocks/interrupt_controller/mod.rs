//! # `InterruptController`: sticky status bits, enable mask, write-1-to-clear, level interrupt
//!
//! An internal building block (the motion controller's interrupt logic).
//! Each of N status bits is set by its event input and stays set until
//! software writes a 1 to it; `irq` is high while any enabled status bit is
//! set. No event is ever lost to a clear: an event on the clock of the
//! clear that would remove it leaves the bit set.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! An event at edge e shows in `status` after edge e; `irq` follows one
//! clock later (it is registered from `status` and `enable`). Masking or
//! unmasking takes effect on `irq` one clock after `enable` changes. A
//! clear at edge e removes the bit after edge e unless its event is high at
//! edge e.
//!
//! ## Formal proof
//! `formal/interrupt_controller.sv` states the timing above as assertions
//! on the ports, for every bit, at every edge: after reset (and power-up)
//! `status` is 0 and `irq` low; an event sets its bit, even on the clock of
//! a W1C of it (no event is lost to a clear); a set bit is cleared only by
//! a W1C of it, and a W1C without the event clears it; a bit is set only by
//! its event; `irq` after an edge is the OR of the status before the edge
//! and the enable at the edge. It assumes nothing: every input, `reset`
//! included, is free at every clock. Proved by k-induction (k = 1) for
//! N = 3 and for the motion controller's N = 12 (figures in the README's
//! "What is proved").

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: status 0, irq low"),
    port(
        "events",
        "N",
        "bit i high sets status bit i (a pulse or a level; a level keeps it set)",
    ),
    port("clear", "1", "write strobe of the status register"),
    port(
        "clear_bits",
        "N",
        "with `clear`: each 1 clears that status bit (write 1 to clear)",
    ),
    port("enable", "N", "interrupt enable mask"),
    port("status", "N", "the sticky status bits, registered"),
    port(
        "irq",
        "1",
        "level interrupt: any status bit set and enabled, registered",
    ),
];

/// Sticky status with a level interrupt. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct InterruptController<const N: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Set inputs.
    pub events: Signal<In, Bits<N>>,
    /// Status write strobe.
    pub clear: Signal<In, Bit>,
    /// Write-1-to-clear data.
    pub clear_bits: Signal<In, Bits<N>>,
    /// Interrupt enable mask.
    pub enable: Signal<In, Bits<N>>,
    /// Sticky status.
    pub status: Signal<Out, Bits<N>>,
    /// Level interrupt.
    pub irq: Signal<Out, Bit>,
    status_reg: DFF<Bits<N>>,
    irq_reg: DFF<Bit>,
    zero: Constant<Bits<N>>,
}

impl<const N: usize> Default for InterruptController<N> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            events: Default::default(),
            clear: Default::default(),
            clear_bits: Default::default(),
            enable: Default::default(),
            status: Default::default(),
            irq: Default::default(),
            status_reg: Default::default(),
            irq_reg: Default::default(),
            zero: Constant::new(0u64.into()),
        }
    }
}

impl<const N: usize> Logic for InterruptController<N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, status_reg, irq_reg);
        self.status.next = self.status_reg.q.val();
        self.irq.next = self.irq_reg.q.val();
        // The clear applies first; a simultaneous event sets its bit again.
        if self.clear.val() {
            self.status_reg.d.next =
                (self.status_reg.q.val() & !self.clear_bits.val()) | self.events.val();
        } else {
            self.status_reg.d.next = self.status_reg.q.val() | self.events.val();
        }
        self.irq_reg.d.next = (self.status_reg.q.val() & self.enable.val()) != self.zero.val();
        if self.reset.val() {
            self.status_reg.d.next = self.zero.val();
            self.irq_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const N: usize] InterruptController<N> {
    inputs: [reset, events, clear, clear_bits, enable],
    outputs: [status, irq],
});
