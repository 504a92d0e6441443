//! # `CommandFifo`: a block-RAM FIFO with flush, level, low-water and sticky error flags
//!
//! An internal building block for the motion controller's per-axis command
//! queues. rust-hdl's `SynchronousFIFO` has no reset (a controller must be
//! able to flush its queues) and no sticky error flags, so this FIFO wraps
//! a [`HoldingRam`] (iCE40 block RAM, read at every clock) with its own
//! pointers. The head entry is always on `head` while `empty` is low
//! (first-word fall-through); nothing is ever overwritten or invented.
//!
//! ## Ports (2^N entries of W bits)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A write at edge e is counted in `level` after e and is on `head` after e
//! if the FIFO was empty. A pop at edge e shows the next entry on `head`
//! after e. Write and pop may come on every clock, together. A flag set on
//! the clock of `clear_flags` stays set.
//!
//! ## Implementation
//! The RAM reads synchronously at the address the head will have after the
//! edge. A write to that same address on the same edge (into an empty FIFO,
//! or into the slot a pop is about to expose) is caught by a bypass
//! register, which `head` shows instead of the RAM's word in the clock
//! after: the FIFO never looks at a word read during a write of it. So its
//! RAM is [`HoldingRam::collisions_unobserved`], and yosys adds no
//! read-first logic of its own (it did, beside this bypass, with rust-hdl's
//! `RAM`). The formal proof below checks the
//! claim: a non-empty FIFO's head never comes from a colliding read.
//!
//! ## Formal proof
//! `formal/command_fifo.sv` states the ports and timing above as
//! assertions: `level` never exceeds 2^N, and `empty`, `full` and `low`
//! follow it; reset (and power-up) empties the FIFO and clears both flags;
//! `level` moves by one per write taken and per pop taken, so a refused
//! write or pop changes nothing; a refused write sets `overflow`, a
//! refused pop `underflow`, each held until `clear_flags` (a flag set on
//! its clock stays set) and set by nothing else; a refused write leaves
//! `head` as it was; `head` is 0 until the first write taken since
//! power-up; and entries come out in order with their data: a freely
//! chosen write taken is followed, stays held while the entries written
//! before it are popped, then is on `head` with its data until it is
//! popped. It assumes nothing of the environment: every input, `reset`
//! included, is free at every clock. Proved by k-induction for N = 1 and
//! for the motion controller's N = 4 (figures in the README's "What is
//! proved").
//!
//! One limit. The RAM's array is in the [`HoldingRam`] submodule, which
//! the proof cannot name, while an entry behind the head is held only
//! there: the induction therefore takes the RAM's own contract as a
//! premise (a read returns the word last written to its address before the
//! read's edge, read-first), and `formal/command_fifo_ram.sv` proves that
//! contract on the same RAM, built as the FIFO builds it, at both depths
//! (assume-guarantee). The premise is never needed for a colliding read,
//! whose word is undefined on iCE40 (see Implementation). The bounded
//! checks from power-up of the mutation
//! tests run on the real RAM, without the premise.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::holding_ram::HoldingRam;
use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: flush (empty), flags 0"),
    port("write", "1", "push `write_data` (refused when full, unless a pop frees a slot on the same clock)"),
    port("write_data", "W", "the entry to push"),
    port("pop", "1", "remove the head entry (refused when empty)"),
    port("head", "W", "the oldest entry, valid while `empty` is low (while empty: 0 after power-up, else a stale word)"),
    port("empty", "1", "no entry (registered)"),
    port("full", "1", "2^N entries (registered)"),
    port("level", "N+1", "entries held"),
    port("low_water", "N+1", "threshold for `low`"),
    port("low", "1", "`level` <= `low_water` (combinational from the registered level)"),
    port("clear_flags", "1", "clears `overflow` and `underflow`"),
    port("overflow", "1", "sticky: a write was refused (FIFO full); the FIFO is unchanged"),
    port("underflow", "1", "sticky: a pop was refused (FIFO empty)"),
];

/// Block-RAM FIFO of 2^N W-bit entries with flush and sticky flags. See the
/// [module documentation](self).
#[derive(LogicBlock)]
pub struct CommandFifo<const N: usize, const NP1: usize, const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: flush.
    pub reset: Signal<In, Bit>,
    /// Push.
    pub write: Signal<In, Bit>,
    /// Entry to push.
    pub write_data: Signal<In, Bits<W>>,
    /// Remove the head.
    pub pop: Signal<In, Bit>,
    /// The oldest entry.
    pub head: Signal<Out, Bits<W>>,
    /// No entry.
    pub empty: Signal<Out, Bit>,
    /// No free slot.
    pub full: Signal<Out, Bit>,
    /// Entries held.
    pub level: Signal<Out, Bits<NP1>>,
    /// Threshold for `low`.
    pub low_water: Signal<In, Bits<NP1>>,
    /// `level <= low_water`.
    pub low: Signal<Out, Bit>,
    /// Clear the sticky flags.
    pub clear_flags: Signal<In, Bit>,
    /// Sticky: a write was refused.
    pub overflow: Signal<Out, Bit>,
    /// Sticky: a pop was refused.
    pub underflow: Signal<Out, Bit>,
    ram: HoldingRam<Bits<W>, N>,
    read_pointer: DFF<Bits<N>>,
    write_pointer: DFF<Bits<N>>,
    count: DFF<Bits<NP1>>,
    /// The head comes from `bypass_data`, not from the RAM, this clock.
    bypass: DFF<Bit>,
    bypass_data: DFF<Bits<W>>,
    overflow_reg: DFF<Bit>,
    underflow_reg: DFF<Bit>,
    /// `count != 0` and `count == 2^N`, kept beside the count so that
    /// `empty` and `full` come straight from flip-flops: in a top they
    /// feed decisions (all FIFOs ready to pop) that fan back into every
    /// FIFO's write. Stored as non-empty so power-up (all 0) means empty.
    /// Each is set or cleared by the clock's net change and a compare of
    /// the *registered* count (`count_is_one`, `count_is_almost_full`), not
    /// by comparing the next count: the pop that arrives late in the clock
    /// then passes two LUTs to these flip-flops, not the count's carry
    /// chain and a wide compare (the controller's critical path).
    not_empty_reg: DFF<Bit>,
    full_reg: DFF<Bit>,
    count_is_one: Signal<Local, Bit>,
    count_is_almost_full: Signal<Local, Bit>,
    grows: Signal<Local, Bit>,
    shrinks: Signal<Local, Bit>,
    is_empty: Signal<Local, Bit>,
    is_full: Signal<Local, Bit>,
    write_taken: Signal<Local, Bit>,
    pop_taken: Signal<Local, Bit>,
    next_read: Signal<Local, Bits<N>>,
    one_n: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    one_c: Constant<Bits<NP1>>,
    zero_c: Constant<Bits<NP1>>,
    almost_full: Constant<Bits<NP1>>,
}

impl<const N: usize, const NP1: usize, const W: usize> Default for CommandFifo<N, NP1, W> {
    fn default() -> Self {
        assert_eq!(NP1, N + 1, "NP1 must be N + 1");
        assert!((1..=12).contains(&N), "2 to 4096 entries");
        assert!((1..=64).contains(&W), "entries of 1 to 64 bits");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            pop: Default::default(),
            head: Default::default(),
            empty: Default::default(),
            full: Default::default(),
            level: Default::default(),
            low_water: Default::default(),
            low: Default::default(),
            clear_flags: Default::default(),
            overflow: Default::default(),
            underflow: Default::default(),
            // Zero-initialized (block RAM INIT), so the Verilog's head
            // is 0, not X, before the first write, as in the simulation.
            ram: HoldingRam::collisions_unobserved(),
            read_pointer: Default::default(),
            write_pointer: Default::default(),
            count: Default::default(),
            bypass: Default::default(),
            bypass_data: Default::default(),
            overflow_reg: Default::default(),
            underflow_reg: Default::default(),
            not_empty_reg: Default::default(),
            full_reg: Default::default(),
            count_is_one: Default::default(),
            count_is_almost_full: Default::default(),
            grows: Default::default(),
            shrinks: Default::default(),
            is_empty: Default::default(),
            is_full: Default::default(),
            write_taken: Default::default(),
            pop_taken: Default::default(),
            next_read: Default::default(),
            one_n: Constant::new(1u64.into()),
            zero_n: Constant::new(0u64.into()),
            one_c: Constant::new(1u64.into()),
            zero_c: Constant::new(0u64.into()),
            almost_full: Constant::new(((1u64 << N) - 1).into()),
        }
    }
}

impl<const N: usize, const NP1: usize, const W: usize> Logic for CommandFifo<N, NP1, W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            read_pointer,
            write_pointer,
            count,
            bypass,
            bypass_data,
            overflow_reg,
            underflow_reg,
            not_empty_reg,
            full_reg
        );
        self.ram.clock.next = self.clock.val();
        self.ram.read_enable.next = true;
        self.is_empty.next = !self.not_empty_reg.q.val();
        self.is_full.next = self.full_reg.q.val();
        self.empty.next = self.is_empty.val();
        self.full.next = self.is_full.val();
        self.level.next = self.count.q.val();
        self.low.next = self.count.q.val() <= self.low_water.val();
        self.overflow.next = self.overflow_reg.q.val();
        self.underflow.next = self.underflow_reg.q.val();
        self.head.next = self.ram.read_data.val();
        if self.bypass.q.val() {
            self.head.next = self.bypass_data.q.val();
        }

        self.pop_taken.next = self.pop.val() & !self.is_empty.val();
        self.write_taken.next = self.write.val() & (!self.is_full.val() | self.pop_taken.val());
        if self.clear_flags.val() {
            self.overflow_reg.d.next = false;
            self.underflow_reg.d.next = false;
        }
        if self.write.val() & !self.write_taken.val() {
            self.overflow_reg.d.next = true;
        }
        if self.pop.val() & !self.pop_taken.val() {
            self.underflow_reg.d.next = true;
        }

        // The RAM reads where the head will be after this edge.
        self.next_read.next = self.read_pointer.q.val();
        if self.pop_taken.val() {
            self.next_read.next = self.read_pointer.q.val() + self.one_n.val();
            self.read_pointer.d.next = self.next_read.val();
        }
        self.ram.read_address.next = self.next_read.val();
        self.ram.write_address.next = self.write_pointer.q.val();
        self.ram.write_data.next = self.write_data.val();
        self.ram.write_enable.next = self.write_taken.val();
        if self.write_taken.val() {
            self.write_pointer.d.next = self.write_pointer.q.val() + self.one_n.val();
        }
        // Read-during-write of the head's next address: take the new word.
        self.bypass.d.next =
            self.write_taken.val() & (self.write_pointer.q.val() == self.next_read.val());
        self.bypass_data.d.next = self.write_data.val();

        self.grows.next = self.write_taken.val() & !self.pop_taken.val();
        self.shrinks.next = self.pop_taken.val() & !self.write_taken.val();
        self.count_is_one.next = self.count.q.val() == self.one_c.val();
        self.count_is_almost_full.next = self.count.q.val() == self.almost_full.val();
        if self.grows.val() {
            self.count.d.next = self.count.q.val() + self.one_c.val();
            self.not_empty_reg.d.next = true;
            self.full_reg.d.next = self.count_is_almost_full.val();
        }
        if self.shrinks.val() {
            self.count.d.next = self.count.q.val() - self.one_c.val();
            self.not_empty_reg.d.next = !self.count_is_one.val();
            self.full_reg.d.next = false;
        }
        if self.reset.val() {
            self.read_pointer.d.next = self.zero_n.val();
            self.write_pointer.d.next = self.zero_n.val();
            self.count.d.next = self.zero_c.val();
            self.bypass.d.next = false;
            self.overflow_reg.d.next = false;
            self.underflow_reg.d.next = false;
            self.not_empty_reg.d.next = false;
            self.full_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const N: usize, const NP1: usize, const W: usize] CommandFifo<N, NP1, W> {
    inputs: [reset, write, write_data, pop, low_water, clear_flags],
    outputs: [head, empty, full, level, low, overflow, underflow],
});
