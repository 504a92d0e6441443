//! # `dpram_mailbox`: block-RAM dual-port memory with mailbox interrupts
//!
//! A memory shared by two masters (a PC bridge and a DSP, say), each on its
//! own synchronous register bus, normally behind its own
//! `external_bus_adapter`. 2^AW words of D bits (exported: 1024 x 16).
//! Two words are mailboxes: port A writing `MAILBOX_TO_B` (the last word)
//! raises `irq_b`, and any port-B access to it clears `irq_b`; port B
//! writing `MAILBOX_TO_A` (the word before it) raises `irq_a`, and any
//! port-A access to it clears `irq_a`. By convention the mailbox word holds
//! 1 = in use, 0 = done; the block gives the words no meaning of its own.
//!
//! ## Ports (AW = 10, D = 16 in the exported `dpram_mailbox`)
//!
#![doc = include_str!("ports.md")]
//!
//! Both ports follow the project's register-bus convention (the bus side of
//! `external_bus_adapter`): `address` with a one-clock `write` or `read`
//! strobe, and `read_data` registered, valid in the clock after `read`.
//!
//! ## Mailbox words
//! | word | address (AW = 10) | raised by | cleared by |
//! |---|---|---|---|
//! | `MAILBOX_TO_B` = 2^AW - 1 | 1023 (0x3ff) | an A write of it: `irq_b` | any B read or write of it |
//! | `MAILBOX_TO_A` = 2^AW - 2 | 1022 (0x3fe) | a B write of it: `irq_a` | any A read or write of it |
//!
//! Both are ordinary memory words too: they hold what was written. An A
//! access of `MAILBOX_TO_B` (and a B access of `MAILBOX_TO_A`) does not touch
//! an irq. When a raising write and a clearing access come on the same
//! clock, the raise wins: a new message is never lost. [`mailbox_to_b`] and
//! [`mailbox_to_a`] give the addresses for any AW.
//!
//! ## Timing (a strobe is high for one clock, here clock c)
//! ```text
//! clock        |  c   | c+1  | c+2  | c+3  |
//! a_read       |‾‾‾‾‾‾|      |      |      |   a_address = X
//! a_read_data  |      | X's word, held until the next answer
//! a_write      |‾‾‾‾‾‾|      |      |      |   a_address = MAILBOX_TO_B
//! irq_b        |      |‾‾‾‾‾‾|‾‾‾‾‾‾|      |   up the clock after the write
//! b_read       |      |      |‾‾‾‾‾‾|      |   b_address = MAILBOX_TO_B: clears irq_b
//! b_read_data  |      |      |      | the message
//! ```
//! | latency | clocks |
//! |---|---|
//! | read strobe to `read_data` | 1 (the next clock), then held |
//! | mailbox write strobe to its irq high | 1 |
//! | clearing access strobe to its irq low | 1 |
//! | both ports write the same word to `collision` high | 1 (for one clock) |
//! | refused B write to `overrun` high | 1 (for one clock) |
//! | write strobe to the word visible to either port's read | 0: a read strobed on any later clock returns it |
//!
//! ## Ordering and collision rules
//! The memory behaves as one memory whose writes take effect in strobe
//! order: clock by clock, and within one clock port A's write before port
//! B's. A read strobed on clock c returns the word as left by every write
//! strobed before clock c:
//!
//! * **Read-first.** A read of a word on the clock either port (the other
//!   port, or the reading port itself) writes it returns the old word; a
//!   read on any later clock returns the new one.
//! * **Both ports write the same word on the same clock:** B's data stays
//!   (A's write lands first, B's after it) and `collision` pulses.
//! * A port always reads back what it wrote, and the other port reads it
//!   too from the next clock on, even while the write is still queued.
//!
//! A read and a write on the same port in the same clock are both done
//! (the read returns the old word).
//!
//! ## Write rate
//! Block RAM has one write port, so one write lands per clock. A write
//! that cannot land on its own clock waits in a two-entry queue, oldest
//! first; reads of a queued word are answered from the queue. No write is
//! refused as long as, in every run of n consecutive clocks, the two ports
//! strobe at most n + 2 writes together: for example each port writing at
//! most every other clock, or both ports writing on two clocks in a row
//! and then pausing. An `external_bus_adapter` writes at most once every 5
//! clocks or so, far below this.
//!
//! Beyond that rate a write must be refused. It is always port B's: when
//! the queue is full and both ports write on one clock, A's write is
//! queued and B's is dropped; `overrun` pulses, that write does not reach
//! the memory, and it raises no `irq_a` (it still clears `irq_b` if it was
//! to `MAILBOX_TO_B`: it is an access). Port A's writes are never refused.
//!
//! ## Reset and power-up
//! `reset` (synchronous, active high, for one clock or more): irqs low,
//! queued writes dropped, both `read_data` 0, `collision` and `overrun` 0;
//! strobes during reset are ignored (no write lands, no read is answered).
//! The RAM keeps its words: reset does not clear them. At power-up every
//! word is 0 (block RAM initialization).
//!
//! ## Bad input
//! There is none at the ports: every combination of strobes is defined
//! above. Writing faster than the write rate loses B's writes, flagged by
//! `overrun`. `read_data` changes only the clock after a read strobe.
//!
//! ## Implementation and resources
//! iCE40 block RAM (SB_RAM40_4K), like rust-hdl's `RAM`, has one read port
//! and one write port. The block keeps two copies of the memory, each read
//! by one port, written identically through one shared write port: 2 x
//! 2^AW x D bits. A write that lands at once goes to the RAM on its own
//! clock; the others wait in the queue (two entries of address and data),
//! and a read of a queued word is answered from the queue (the newest
//! entry for that word). Each port's answer is the RAM copy's output on
//! the clock after the read, and a hold register after that.
//!
//! The exported AW = 10, D = 16 on iCE40 HX8K is its row in
//! `rtl-out/synthesis-report.md` (8 SB_RAM40_4K). Part of its flip-flops
//! and LUT4 are yosys's emulation of the Verilog's read-first RAM on
//! SB_RAM40_4K, whose read-during-write result is undefined
//! (`emulate_read_first`: the write is delayed a clock and bypassed).

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "block-RAM dual-port memory (two synchronous register-bus ports) with mailbox interrupts, read-first, collision and overrun flags";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: irqs low, pending writes dropped, read data 0; the RAM keeps its words"),
    port("a_address", "AW", "port A word address, with `a_write` or `a_read`"),
    port("a_write_data", "D", "port A write data"),
    port("a_write", "1", "port A one-clock write strobe"),
    port("a_read", "1", "port A one-clock read strobe"),
    port("a_read_data", "D", "port A read data: valid the clock after `a_read`, held until the next answer"),
    port("irq_a", "1", "level: port B wrote `MAILBOX_TO_A` (2^AW - 2), and port A has not accessed it since"),
    port("b_address", "AW", "port B word address, with `b_write` or `b_read`"),
    port("b_write_data", "D", "port B write data"),
    port("b_write", "1", "port B one-clock write strobe"),
    port("b_read", "1", "port B one-clock read strobe"),
    port("b_read_data", "D", "port B read data: valid the clock after `b_read`, held until the next answer"),
    port("irq_b", "1", "level: port A wrote `MAILBOX_TO_B` (2^AW - 1), and port B has not accessed it since"),
    port("collision", "1", "one-clock pulse the clock after both ports wrote the same word on the same clock (B's data stays)"),
    port("overrun", "1", "one-clock pulse the clock after a port-B write was refused (its write queue was full: more writes than the block can land)"),
];

/// `MAILBOX_TO_B` for a 2^`aw`-word memory: port A writes it to raise `irq_b`.
pub const fn mailbox_to_b(aw: usize) -> u64 {
    (1u64 << aw) - 1
}

/// `MAILBOX_TO_A` for a 2^`aw`-word memory: port B writes it to raise `irq_a`.
pub const fn mailbox_to_a(aw: usize) -> u64 {
    (1u64 << aw) - 2
}

/// The exported configuration: 1024 words of 16 bits.
pub type DpramMailbox1024x16 = DpramMailbox<10, 16>;

/// Dual-port block-RAM mailbox of 2^AW words of D bits. See the
/// [module documentation](self).
#[derive(LogicBlock)]
pub struct DpramMailbox<const AW: usize, const D: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Port A word address.
    pub a_address: Signal<In, Bits<AW>>,
    /// Port A write data.
    pub a_write_data: Signal<In, Bits<D>>,
    /// Port A write strobe.
    pub a_write: Signal<In, Bit>,
    /// Port A read strobe.
    pub a_read: Signal<In, Bit>,
    /// Port A read data, the clock after `a_read`, held.
    pub a_read_data: Signal<Out, Bits<D>>,
    /// Port B wrote `MAILBOX_TO_A`.
    pub irq_a: Signal<Out, Bit>,
    /// Port B word address.
    pub b_address: Signal<In, Bits<AW>>,
    /// Port B write data.
    pub b_write_data: Signal<In, Bits<D>>,
    /// Port B write strobe.
    pub b_write: Signal<In, Bit>,
    /// Port B read strobe.
    pub b_read: Signal<In, Bit>,
    /// Port B read data, the clock after `b_read`, held.
    pub b_read_data: Signal<Out, Bits<D>>,
    /// Port A wrote `MAILBOX_TO_B`.
    pub irq_b: Signal<Out, Bit>,
    /// Both ports wrote the same word on the last clock.
    pub collision: Signal<Out, Bit>,
    /// A port-B write was refused on the last clock.
    pub overrun: Signal<Out, Bit>,
    /// The copy port A reads.
    ram_a: RAM<Bits<D>, AW>,
    /// The copy port B reads.
    ram_b: RAM<Bits<D>, AW>,
    /// The write queue, oldest first (`queue1_valid` implies `queue0_valid`).
    queue0_valid: DFF<Bit>,
    queue0_address: DFF<Bits<AW>>,
    queue0_data: DFF<Bits<D>>,
    queue1_valid: DFF<Bit>,
    queue1_address: DFF<Bits<AW>>,
    queue1_data: DFF<Bits<D>>,
    /// `a_read_data` comes from `ram_a` this clock (a fresh answer), else
    /// from `a_hold`.
    a_from_ram: DFF<Bit>,
    a_hold: DFF<Bits<D>>,
    b_from_ram: DFF<Bit>,
    b_hold: DFF<Bits<D>>,
    irq_a_reg: DFF<Bit>,
    irq_b_reg: DFF<Bit>,
    collision_reg: DFF<Bit>,
    overrun_reg: DFF<Bit>,
    /// This clock's first new write: A's if A writes, else B's.
    first_address: Signal<Local, Bits<AW>>,
    first_data: Signal<Local, Bits<D>>,
    /// The write that lands at this edge: the queue head, else the first new one.
    land_address: Signal<Local, Bits<AW>>,
    land_data: Signal<Local, Bits<D>>,
    /// The queue is full and both ports write: B's write is refused.
    refuse_b: Signal<Local, Bit>,
    a_match0: Signal<Local, Bit>,
    a_match1: Signal<Local, Bit>,
    b_match0: Signal<Local, Bit>,
    b_match1: Signal<Local, Bit>,
    mailbox_a: Constant<Bits<AW>>,
    mailbox_b: Constant<Bits<AW>>,
    zero_a: Constant<Bits<AW>>,
    zero_d: Constant<Bits<D>>,
}

impl<const AW: usize, const D: usize> DpramMailbox<AW, D> {
    /// Port A writes this word to raise `irq_b`.
    pub const MAILBOX_TO_B: u64 = mailbox_to_b(AW);
    /// Port B writes this word to raise `irq_a`.
    pub const MAILBOX_TO_A: u64 = mailbox_to_a(AW);
}

impl<const AW: usize, const D: usize> Default for DpramMailbox<AW, D> {
    fn default() -> Self {
        assert!((2..=14).contains(&AW), "4 to 16384 words");
        assert!((1..=32).contains(&D), "1 to 32 data bits");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            a_address: Default::default(),
            a_write_data: Default::default(),
            a_write: Default::default(),
            a_read: Default::default(),
            a_read_data: Default::default(),
            irq_a: Default::default(),
            b_address: Default::default(),
            b_write_data: Default::default(),
            b_write: Default::default(),
            b_read: Default::default(),
            b_read_data: Default::default(),
            irq_b: Default::default(),
            collision: Default::default(),
            overrun: Default::default(),
            // Zero-initialized (block RAM INIT): the Verilog reads 0, not X,
            // from a word never written, as the simulation does.
            ram_a: RAM::from((0..1usize << AW).map(|_| Bits::<D>::default())),
            ram_b: RAM::from((0..1usize << AW).map(|_| Bits::<D>::default())),
            queue0_valid: Default::default(),
            queue0_address: Default::default(),
            queue0_data: Default::default(),
            queue1_valid: Default::default(),
            queue1_address: Default::default(),
            queue1_data: Default::default(),
            a_from_ram: Default::default(),
            a_hold: Default::default(),
            b_from_ram: Default::default(),
            b_hold: Default::default(),
            irq_a_reg: Default::default(),
            irq_b_reg: Default::default(),
            collision_reg: Default::default(),
            overrun_reg: Default::default(),
            first_address: Default::default(),
            first_data: Default::default(),
            land_address: Default::default(),
            land_data: Default::default(),
            refuse_b: Default::default(),
            a_match0: Default::default(),
            a_match1: Default::default(),
            b_match0: Default::default(),
            b_match1: Default::default(),
            mailbox_a: Constant::new(mailbox_to_a(AW).into()),
            mailbox_b: Constant::new(mailbox_to_b(AW).into()),
            zero_a: Constant::new(0u64.into()),
            zero_d: Constant::new(0u64.into()),
        }
    }
}

impl<const AW: usize, const D: usize> Logic for DpramMailbox<AW, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            queue0_valid,
            queue0_address,
            queue0_data,
            queue1_valid,
            queue1_address,
            queue1_data,
            a_from_ram,
            a_hold,
            b_from_ram,
            b_hold,
            irq_a_reg,
            irq_b_reg,
            collision_reg,
            overrun_reg
        );
        self.ram_a.read_clock.next = self.clock.val();
        self.ram_a.write_clock.next = self.clock.val();
        self.ram_b.read_clock.next = self.clock.val();
        self.ram_b.write_clock.next = self.clock.val();

        // Read data: the fresh RAM word the clock after a read, else the
        // held answer (a forwarded queue word, or the last RAM word).
        self.a_read_data.next = self.a_hold.q.val();
        if self.a_from_ram.q.val() {
            self.a_read_data.next = self.ram_a.read_data.val();
        }
        self.b_read_data.next = self.b_hold.q.val();
        if self.b_from_ram.q.val() {
            self.b_read_data.next = self.ram_b.read_data.val();
        }
        self.irq_a.next = self.irq_a_reg.q.val();
        self.irq_b.next = self.irq_b_reg.q.val();
        self.collision.next = self.collision_reg.q.val();
        self.overrun.next = self.overrun_reg.q.val();

        // One write lands per clock, oldest first: the queue head, else
        // this clock's A write, else its B write. The rest are queued.
        self.first_address.next = self.b_address.val();
        self.first_data.next = self.b_write_data.val();
        if self.a_write.val() {
            self.first_address.next = self.a_address.val();
            self.first_data.next = self.a_write_data.val();
        }
        self.land_address.next = self.first_address.val();
        self.land_data.next = self.first_data.val();
        if self.queue0_valid.q.val() {
            self.land_address.next = self.queue0_address.q.val();
            self.land_data.next = self.queue0_data.q.val();
        }
        self.ram_a.write_address.next = self.land_address.val();
        self.ram_a.write_data.next = self.land_data.val();
        self.ram_a.write_enable.next =
            self.queue0_valid.q.val() | self.a_write.val() | self.b_write.val();
        self.ram_b.write_address.next = self.land_address.val();
        self.ram_b.write_data.next = self.land_data.val();
        self.ram_b.write_enable.next =
            self.queue0_valid.q.val() | self.a_write.val() | self.b_write.val();

        self.refuse_b.next = self.queue1_valid.q.val() & self.a_write.val() & self.b_write.val();
        if self.queue0_valid.q.val() {
            if self.queue1_valid.q.val() {
                // The head lands; the second moves up; the first new write
                // takes its place (a second new one, B's, is refused).
                self.queue0_address.d.next = self.queue1_address.q.val();
                self.queue0_data.d.next = self.queue1_data.q.val();
                self.queue1_valid.d.next = self.a_write.val() | self.b_write.val();
                self.queue1_address.d.next = self.first_address.val();
                self.queue1_data.d.next = self.first_data.val();
            } else {
                self.queue0_valid.d.next = self.a_write.val() | self.b_write.val();
                self.queue0_address.d.next = self.first_address.val();
                self.queue0_data.d.next = self.first_data.val();
                self.queue1_valid.d.next = self.a_write.val() & self.b_write.val();
                self.queue1_address.d.next = self.b_address.val();
                self.queue1_data.d.next = self.b_write_data.val();
            }
        } else {
            // A's write (if any) lands now; B's waits if A took the clock.
            self.queue0_valid.d.next = self.a_write.val() & self.b_write.val();
            self.queue0_address.d.next = self.b_address.val();
            self.queue0_data.d.next = self.b_write_data.val();
            self.queue1_valid.d.next = false;
        }
        self.overrun_reg.d.next = self.refuse_b.val();
        self.collision_reg.d.next = self.a_write.val()
            & self.b_write.val()
            & (self.a_address.val() == self.b_address.val());

        // Reads: the RAM copy answers (read-first), unless a queued write
        // to the word has not landed yet; the newest queued one answers then.
        self.ram_a.read_address.next = self.a_address.val();
        self.ram_b.read_address.next = self.b_address.val();
        self.a_match0.next =
            self.queue0_valid.q.val() & (self.queue0_address.q.val() == self.a_address.val());
        self.a_match1.next =
            self.queue1_valid.q.val() & (self.queue1_address.q.val() == self.a_address.val());
        self.b_match0.next =
            self.queue0_valid.q.val() & (self.queue0_address.q.val() == self.b_address.val());
        self.b_match1.next =
            self.queue1_valid.q.val() & (self.queue1_address.q.val() == self.b_address.val());
        self.a_hold.d.next = self.a_read_data.val();
        self.a_from_ram.d.next = false;
        if self.a_read.val() {
            self.a_from_ram.d.next = !(self.a_match0.val() | self.a_match1.val());
            if self.a_match0.val() {
                self.a_hold.d.next = self.queue0_data.q.val();
            }
            if self.a_match1.val() {
                self.a_hold.d.next = self.queue1_data.q.val();
            }
        }
        self.b_hold.d.next = self.b_read_data.val();
        self.b_from_ram.d.next = false;
        if self.b_read.val() {
            self.b_from_ram.d.next = !(self.b_match0.val() | self.b_match1.val());
            if self.b_match0.val() {
                self.b_hold.d.next = self.queue0_data.q.val();
            }
            if self.b_match1.val() {
                self.b_hold.d.next = self.queue1_data.q.val();
            }
        }

        // Mailboxes: a clearing access first, so that a raise on the same
        // clock wins.
        if (self.a_read.val() | self.a_write.val()) & (self.a_address.val() == self.mailbox_a.val())
        {
            self.irq_a_reg.d.next = false;
        }
        if self.b_write.val()
            & !self.refuse_b.val()
            & (self.b_address.val() == self.mailbox_a.val())
        {
            self.irq_a_reg.d.next = true;
        }
        if (self.b_read.val() | self.b_write.val()) & (self.b_address.val() == self.mailbox_b.val())
        {
            self.irq_b_reg.d.next = false;
        }
        if self.a_write.val() & (self.a_address.val() == self.mailbox_b.val()) {
            self.irq_b_reg.d.next = true;
        }

        if self.reset.val() {
            self.ram_a.write_enable.next = false;
            self.ram_b.write_enable.next = false;
            self.queue0_valid.d.next = false;
            self.queue0_address.d.next = self.zero_a.val();
            self.queue0_data.d.next = self.zero_d.val();
            self.queue1_valid.d.next = false;
            self.queue1_address.d.next = self.zero_a.val();
            self.queue1_data.d.next = self.zero_d.val();
            self.a_from_ram.d.next = false;
            self.a_hold.d.next = self.zero_d.val();
            self.b_from_ram.d.next = false;
            self.b_hold.d.next = self.zero_d.val();
            self.irq_a_reg.d.next = false;
            self.irq_b_reg.d.next = false;
            self.collision_reg.d.next = false;
            self.overrun_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const AW: usize, const D: usize] DpramMailbox<AW, D> {
    inputs: [
        reset, a_address, a_write_data, a_write, a_read,
        b_address, b_write_data, b_write, b_read
    ],
    outputs: [a_read_data, irq_a, b_read_data, irq_b, collision, overrun],
});
