//! Reference model of [`super::DpramMailbox`], cycle-exact: one memory in
//! which every accepted write takes effect at its strobe (reads answer from
//! it), and the queue of writes not landed yet, for `overrun` and for what
//! a reset drops. It knows nothing of the RAM copies or of forwarding.

use std::collections::VecDeque;

use super::{mailbox_to_a, mailbox_to_b};
use crate::blocks::width_mask;

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DpramMailboxInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Port A word address.
    pub a_address: u64,
    /// Port A write data.
    pub a_write_data: u64,
    /// Port A write strobe.
    pub a_write: bool,
    /// Port A read strobe.
    pub a_read: bool,
    /// Port B word address.
    pub b_address: u64,
    /// Port B write data.
    pub b_write_data: u64,
    /// Port B write strobe.
    pub b_write: bool,
    /// Port B read strobe.
    pub b_read: bool,
}

impl DpramMailboxInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.a_address,
            self.a_write_data,
            self.a_write as u64,
            self.a_read as u64,
            self.b_address,
            self.b_write_data,
            self.b_write as u64,
            self.b_read as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DpramMailboxOutputs {
    /// Port A read data.
    pub a_read_data: u64,
    /// Port B wrote `MAILBOX_TO_A`.
    pub irq_a: bool,
    /// Port B read data.
    pub b_read_data: u64,
    /// Port A wrote `MAILBOX_TO_B`.
    pub irq_b: bool,
    /// Both ports wrote the same word on the last clock.
    pub collision: bool,
    /// A port-B write was refused on the last clock.
    pub overrun: bool,
}

impl DpramMailboxOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            a_read_data: v[0],
            irq_a: v[1] != 0,
            b_read_data: v[2],
            irq_b: v[3] != 0,
            collision: v[4] != 0,
            overrun: v[5] != 0,
        }
    }
}

/// Writes the block can hold without landing them (its queue).
pub const QUEUE_DEPTH: usize = 2;

/// Cycle-exact model of a 2^`address_bits`-word, `data_bits`-wide mailbox.
#[derive(Clone, Debug)]
pub struct DpramMailboxModel {
    address_mask: u64,
    data_mask: u64,
    mailbox_to_a: u64,
    mailbox_to_b: u64,
    /// The memory as the ports see it: every accepted write applied at its
    /// strobe. Reads answer from this.
    memory: Vec<u64>,
    /// The memory as the RAM holds it: only the writes that have landed.
    /// A reset drops the others.
    landed: Vec<u64>,
    /// Accepted writes not landed yet, oldest first: (address, data).
    queue: VecDeque<(u64, u64)>,
    out: DpramMailboxOutputs,
}

impl DpramMailboxModel {
    /// A mailbox in its power-up state (every word 0).
    pub fn new(address_bits: usize, data_bits: u32) -> Self {
        Self {
            address_mask: width_mask(address_bits as u32),
            data_mask: width_mask(data_bits),
            mailbox_to_a: mailbox_to_a(address_bits),
            mailbox_to_b: mailbox_to_b(address_bits),
            memory: vec![0; 1 << address_bits],
            landed: vec![0; 1 << address_bits],
            queue: VecDeque::with_capacity(QUEUE_DEPTH + 2),
            out: DpramMailboxOutputs::default(),
        }
    }

    /// The word a read strobed now would return.
    pub fn word(&self, address: u64) -> u64 {
        self.memory[(address & self.address_mask) as usize]
    }

    /// A write to `address` has been accepted but has not landed in the
    /// RAM yet: a read of it now is answered by forwarding.
    pub fn is_queued(&self, address: u64) -> bool {
        let address = address & self.address_mask;
        self.queue.iter().any(|&(queued, _)| queued == address)
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: DpramMailboxInputs) -> DpramMailboxOutputs {
        let a_address = i.a_address & self.address_mask;
        let b_address = i.b_address & self.address_mask;
        if i.reset {
            // Queued writes are dropped, the RAM keeps the landed ones.
            self.queue.clear();
            self.memory.clone_from(&self.landed);
            self.out = DpramMailboxOutputs::default();
            return self.out;
        }
        let mut out = self.out;
        // Read-first: answers from the memory before this clock's writes.
        if i.a_read {
            out.a_read_data = self.memory[a_address as usize];
        }
        if i.b_read {
            out.b_read_data = self.memory[b_address as usize];
        }
        // Writes take effect in strobe order, A before B. One lands per
        // clock, oldest first; B's write is refused when the rest would
        // not fit in the queue.
        if i.a_write {
            let data = i.a_write_data & self.data_mask;
            self.memory[a_address as usize] = data;
            self.queue.push_back((a_address, data));
        }
        let refuse_b = i.b_write && self.queue.len() > QUEUE_DEPTH;
        if i.b_write && !refuse_b {
            let data = i.b_write_data & self.data_mask;
            self.memory[b_address as usize] = data;
            self.queue.push_back((b_address, data));
        }
        if let Some((address, data)) = self.queue.pop_front() {
            self.landed[address as usize] = data;
        }
        out.collision = i.a_write && i.b_write && a_address == b_address;
        out.overrun = refuse_b;
        // Clear, then raise: a raise on the same clock wins.
        if (i.a_read || i.a_write) && a_address == self.mailbox_to_a {
            out.irq_a = false;
        }
        if i.b_write && !refuse_b && b_address == self.mailbox_to_a {
            out.irq_a = true;
        }
        if (i.b_read || i.b_write) && b_address == self.mailbox_to_b {
            out.irq_b = false;
        }
        if i.a_write && a_address == self.mailbox_to_b {
            out.irq_b = true;
        }
        self.out = out;
        out
    }
}

crate::lockstep_model!(DpramMailboxModel {
    inputs: DpramMailboxInputs,
    outputs: DpramMailboxOutputs,
    step: |model, inputs| model.step(*inputs),
});
