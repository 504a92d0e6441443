//! # `BusSynchronizer`: asynchronous external-memory bus pins to a synchronous register bus
//!
//! A DSP or MCU reaches FPGA registers through its external memory
//! interface (EMIF, XINTF, FSMC): chip select, write and read strobes,
//! address and data, all asynchronous to the FPGA clock. This block
//! synchronizes the strobes (two flip-flops each), samples address and data
//! through the same pipeline, and turns every access into exactly one
//! one-clock strobe on a simple synchronous register bus of the pins' own
//! data width `D`:
//!
//! * a write becomes `bus_write` (with `bus_address`, `bus_write_data`) once
//!   the write strobe ends, with the address and data sampled a clock
//!   before its last active sample;
//! * a read becomes `bus_read` (with `bus_address`) once the read strobe is
//!   seen active on two samples; the slave answers on `bus_read_data` in
//!   the next clock, and the block holds that word on `data_out` for the
//!   rest of the read.
//!
//! It is the pin layer of every external bus adapter:
//! [`crate::blocks::external_bus_adapter`] (32-bit pins) and
//! [`crate::blocks::narrow_bus_adapter`] (8- and 16-bit pins, 32-bit
//! registers). A 16-bit memory such as `dpram_mailbox` can sit directly
//! behind a `BusSynchronizer<A, 16>`.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Synchronous bus timing
//! ```text
//! clock        |  c   | c+1  | c+2  |
//! bus_write    ‾‾‾‾‾‾‾\______________     (with bus_address, bus_write_data)
//! bus_read     ‾‾‾‾‾‾‾\______________     (with bus_address)
//! bus_read_data       |  D   |            slave: registered, the clock after bus_read
//! data_out                   |  D ...     held until the next read
//! ready (read)  ______________/‾‾‾‾‾      rises with data_out while rd_n is low
//! ```
//!
//! ## Minimum timing at the pins, in FPGA clocks (t_clk)
//! An access counts only after two active samples in a row, so runts
//! shorter than that never become bus strobes.
//!
//! | parameter | minimum | why |
//! |---|---|---|
//! | write strobe (cs_n and we_n low) | 3 t_clk | two clean active samples |
//! | address and data stable before we_n (or cs_n) rises | 2 t_clk | the sample taken a clock before the last active one is written |
//! | address and data hold after the write strobe | 0 | that sample is at least a clock old |
//! | write latency: we_n rising to `bus_write` | at most 4 t_clk | |
//! | read access time: rd_n low to data valid at the pins | 6 t_clk + t_su + t_co + pad delays | 1 to the first sure sample, 2 more to qualify, 1 to issue `bus_read`, 1 for the slave, 1 to register `data_out` |
//! | read address stable after rd_n falls | 2 t_clk + t_h | it is sampled with the second active sample (hold it for the whole strobe) |
//! | strobe high between accesses | 2 t_clk | one clean inactive sample separates two accesses |
//!
//! ## With `ready` (XREADY, WAIT, NWAIT)
//! A master that samples `ready` needs no worst-case wait states: it holds
//! the strobe until it sees `ready` high. `ready` falls combinationally
//! with the strobe, and rises on the clock edge that makes the access
//! safe to end: for a write, 2 to 3 t_clk after the strobe falls (its
//! second active sample); for a read, 6 to 7 t_clk after it falls, on the
//! same edge that puts the answer on `data_out`. Rules:
//! * sample `ready` no earlier than 3 t_clk after the strobe falls, and
//!   keep 2 t_clk between strobes: until the end of the previous read has
//!   been sampled (at most 3 t_clk after it), `ready` may still show that
//!   read's answer;
//! * the data and address of a write must be stable from the strobe's
//!   start (as XINTF drives them), since the strobe may end right after
//!   `ready` rises;
//! * `ready` is meaningless (high) while no strobe is active.
//!
//! Without `ready`, program the master's active phase from the table
//! above, plus its own input synchronizer and the board's delays.
//!
//! The `*_meta` flip-flops are synchronizer first stages: give them your
//! tool's ASYNC_REG (or equivalent) attribute and a false path from the
//! pins; rust-hdl cannot emit the attribute itself.
//!
//! ## Bad input
//! * A strobe seen active on only one sample (a runt) is ignored.
//! * we_n and rd_n low together: `data_oe` stays low (the master drives
//!   the pins), the write is taken when it ends, and the read is issued
//!   once, one clock later if the write took its clock; the read may return
//!   the word from before or after the write. Do not do this.
//! * A read whose strobe ends before its data is registered is still issued
//!   (side effects happen once); the master just reads an older `data_out`.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::PortDoc;

/// The meaning of each pin-side and bus-side port, one constant per port,
/// shared by the port tables of every adapter built on the synchronizer
/// (an adapter sets its own width with [`PortDoc::with_width`]).
pub mod port_docs {
    use crate::blocks::port_doc::{port, PortDoc};

    /// `clock`.
    pub const CLOCK: PortDoc = port("clock", "1", "rising-edge clock");
    /// `reset`.
    pub const RESET: PortDoc = port(
        "reset",
        "1",
        "synchronous, active high: no access in progress, outputs 0",
    );
    /// `cs_n`.
    pub const CS_N: PortDoc = port("cs_n", "1", "chip select, active low, asynchronous");
    /// `we_n`.
    pub const WE_N: PortDoc = port("we_n", "1", "write strobe, active low, asynchronous");
    /// `rd_n`.
    pub const RD_N: PortDoc = port(
        "rd_n",
        "1",
        "read strobe (output enable), active low, asynchronous",
    );
    /// `address`.
    pub const ADDRESS: PortDoc = port("address", "A", "word address, asynchronous");
    /// `data_in`.
    pub const DATA_IN: PortDoc = port("data_in", "D", "write data from the pins, asynchronous");
    /// `data_out`.
    pub const DATA_OUT: PortDoc = port("data_out", "D", "read data to the pins, registered");
    /// `data_oe`.
    pub const DATA_OE: PortDoc = port(
        "data_oe",
        "1",
        "drive the data pins: `!cs_n & !rd_n & we_n`, combinational from the pins (for the IO buffer's enable)",
    );
    /// `ready`.
    pub const READY: PortDoc = port(
        "ready",
        "1",
        "the access at the pins may end (the master's wait input, XREADY): low from the moment a strobe falls until a write has two active samples or a read's answer is on `data_out`; combinational from the pins and registered state",
    );
    /// `bus_address`.
    pub const BUS_ADDRESS: PortDoc = port(
        "bus_address",
        "A",
        "address of the current bus strobe, registered",
    );
    /// `bus_write_data`.
    pub const BUS_WRITE_DATA: PortDoc =
        port("bus_write_data", "D", "data of `bus_write`, registered");
    /// `bus_write`.
    pub const BUS_WRITE: PortDoc = port("bus_write", "1", "one-clock write strobe");
    /// `bus_read`.
    pub const BUS_READ: PortDoc = port("bus_read", "1", "one-clock read strobe");
    /// `bus_read_data`.
    pub const BUS_READ_DATA: PortDoc = port(
        "bus_read_data",
        "D",
        "the slave's read data, valid in the clock after `bus_read`",
    );
}

use port_docs::*;

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    CLOCK,
    RESET,
    CS_N,
    WE_N,
    RD_N,
    ADDRESS,
    DATA_IN,
    DATA_OUT,
    DATA_OE,
    READY,
    BUS_ADDRESS,
    BUS_WRITE_DATA,
    BUS_WRITE,
    BUS_READ,
    BUS_READ_DATA,
];

/// Asynchronous external bus pins to a synchronous `D`-bit register bus.
/// See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct BusSynchronizer<const A: usize, const D: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Chip select, active low.
    pub cs_n: Signal<In, Bit>,
    /// Write strobe, active low.
    pub we_n: Signal<In, Bit>,
    /// Read strobe, active low.
    pub rd_n: Signal<In, Bit>,
    /// Word address.
    pub address: Signal<In, Bits<A>>,
    /// Write data from the pins.
    pub data_in: Signal<In, Bits<D>>,
    /// Read data to the pins.
    pub data_out: Signal<Out, Bits<D>>,
    /// Drive the data pins.
    pub data_oe: Signal<Out, Bit>,
    /// The access at the pins may end (wait-state input of the master).
    pub ready: Signal<Out, Bit>,
    /// Address of the bus strobe.
    pub bus_address: Signal<Out, Bits<A>>,
    /// Data of the write strobe.
    pub bus_write_data: Signal<Out, Bits<D>>,
    /// Write strobe.
    pub bus_write: Signal<Out, Bit>,
    /// Read strobe.
    pub bus_read: Signal<Out, Bit>,
    /// Read data from the slave.
    pub bus_read_data: Signal<In, Bits<D>>,
    // Two-flip-flop synchronizers; the address and data go through the same
    // stages, so each stage holds one consistent sample of all pins.
    write_meta: DFF<Bit>,
    write_sync: DFF<Bit>,
    write_prev: DFF<Bit>,
    write_older: DFF<Bit>,
    read_meta: DFF<Bit>,
    read_sync: DFF<Bit>,
    read_prev: DFF<Bit>,
    address_meta: DFF<Bits<A>>,
    address_sync: DFF<Bits<A>>,
    address_prev: DFF<Bits<A>>,
    data_meta: DFF<Bits<D>>,
    data_sync: DFF<Bits<D>>,
    data_prev: DFF<Bits<D>>,
    address_older: DFF<Bits<A>>,
    data_older: DFF<Bits<D>>,
    /// The current read strobe has been issued (or is pending).
    read_served: DFF<Bit>,
    /// A qualified read lost its clock to a write; it is issued next clock.
    read_pending: DFF<Bit>,
    /// `bus_read` was high last clock: capture the slave's answer now.
    read_answer: DFF<Bit>,
    /// `data_out` holds the answer of the read strobe still being sampled.
    read_done: DFF<Bit>,
    bus_address_reg: DFF<Bits<A>>,
    bus_write_data_reg: DFF<Bits<D>>,
    bus_write_reg: DFF<Bit>,
    bus_read_reg: DFF<Bit>,
    data_out_reg: DFF<Bits<D>>,
    write_ends: Signal<Local, Bit>,
    read_wanted: Signal<Local, Bit>,
    zero_a: Constant<Bits<A>>,
    zero_d: Constant<Bits<D>>,
}

impl<const A: usize, const D: usize> Default for BusSynchronizer<A, D> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            cs_n: Default::default(),
            we_n: Default::default(),
            rd_n: Default::default(),
            address: Default::default(),
            data_in: Default::default(),
            data_out: Default::default(),
            data_oe: Default::default(),
            ready: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            bus_read_data: Default::default(),
            write_meta: Default::default(),
            write_sync: Default::default(),
            write_prev: Default::default(),
            write_older: Default::default(),
            read_meta: Default::default(),
            read_sync: Default::default(),
            read_prev: Default::default(),
            address_meta: Default::default(),
            address_sync: Default::default(),
            address_prev: Default::default(),
            data_meta: Default::default(),
            data_sync: Default::default(),
            data_prev: Default::default(),
            address_older: Default::default(),
            data_older: Default::default(),
            read_served: Default::default(),
            read_pending: Default::default(),
            read_answer: Default::default(),
            read_done: Default::default(),
            bus_address_reg: Default::default(),
            bus_write_data_reg: Default::default(),
            bus_write_reg: Default::default(),
            bus_read_reg: Default::default(),
            data_out_reg: Default::default(),
            write_ends: Default::default(),
            read_wanted: Default::default(),
            zero_a: Constant::new(0u64.into()),
            zero_d: Constant::new(0u64.into()),
        }
    }
}

impl<const A: usize, const D: usize> Logic for BusSynchronizer<A, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            write_meta,
            write_sync,
            write_prev,
            write_older,
            read_meta,
            read_sync,
            read_prev,
            address_meta,
            address_sync,
            address_prev,
            data_meta,
            data_sync,
            data_prev,
            address_older,
            data_older,
            read_served,
            read_pending,
            read_answer,
            read_done,
            bus_address_reg,
            bus_write_data_reg,
            bus_write_reg,
            bus_read_reg,
            data_out_reg
        );
        self.data_out.next = self.data_out_reg.q.val();
        // Never drive the pins while the master writes.
        self.data_oe.next = !self.cs_n.val() & !self.rd_n.val() & self.we_n.val();
        self.bus_address.next = self.bus_address_reg.q.val();
        self.bus_write_data.next = self.bus_write_data_reg.q.val();
        self.bus_write.next = self.bus_write_reg.q.val();
        self.bus_read.next = self.bus_read_reg.q.val();

        // Samples of the pins; "active" is cs_n and the strobe both low.
        self.write_meta.d.next = !self.cs_n.val() & !self.we_n.val();
        self.write_sync.d.next = self.write_meta.q.val();
        self.write_prev.d.next = self.write_sync.q.val();
        self.write_older.d.next = self.write_prev.q.val();
        self.read_meta.d.next = !self.cs_n.val() & !self.rd_n.val();
        self.read_sync.d.next = self.read_meta.q.val();
        self.read_prev.d.next = self.read_sync.q.val();
        self.address_meta.d.next = self.address.val();
        self.address_sync.d.next = self.address_meta.q.val();
        self.address_prev.d.next = self.address_sync.q.val();
        self.data_meta.d.next = self.data_in.val();
        self.data_sync.d.next = self.data_meta.q.val();
        self.data_prev.d.next = self.data_sync.q.val();
        self.address_older.d.next = self.address_prev.q.val();
        self.data_older.d.next = self.data_prev.q.val();

        // A strobe counts only after two active samples in a row, so a runt
        // (chip-select skew, a glitch) never becomes an access. A write is
        // taken when its strobe ends, with the address and data of the
        // sample before the last active one: that sample is at least a
        // clock before the strobe's end, so a master with zero hold time
        // cannot corrupt it. A read is issued once per strobe, one clock
        // later if a write takes this clock.
        self.write_ends.next =
            self.write_older.q.val() & self.write_prev.q.val() & !self.write_sync.q.val();
        self.read_wanted.next =
            (self.read_prev.q.val() & self.read_sync.q.val() & !self.read_served.q.val())
                | self.read_pending.q.val();
        self.bus_write_reg.d.next = false;
        self.bus_read_reg.d.next = false;
        if self.write_ends.val() {
            self.bus_write_reg.d.next = true;
            self.bus_address_reg.d.next = self.address_older.q.val();
            self.bus_write_data_reg.d.next = self.data_older.q.val();
            if self.read_wanted.val() {
                self.read_pending.d.next = true;
                self.read_served.d.next = true;
            }
        } else if self.read_wanted.val() {
            self.bus_read_reg.d.next = true;
            self.bus_address_reg.d.next = self.address_sync.q.val();
            if self.read_pending.q.val() {
                // The address as it was on the clock the write took.
                self.bus_address_reg.d.next = self.address_prev.q.val();
            }
            self.read_served.d.next = true;
            self.read_pending.d.next = false;
        }
        // A strobe seen inactive ends its read, even on the clock a
        // put-off read is issued: a read starting right after it is new.
        if !self.read_sync.q.val() {
            self.read_served.d.next = false;
        }
        self.read_answer.d.next = self.bus_read_reg.q.val();
        if self.read_answer.q.val() {
            self.data_out_reg.d.next = self.bus_read_data.val();
        }
        // Set on the edge that registers the answer, so `ready` and the data
        // change together; cleared once the strobe is seen to end.
        self.read_done.d.next =
            (self.read_done.q.val() | self.read_answer.q.val()) & self.read_sync.q.val();
        // Combinational from the pins, so `ready` falls with the strobe and
        // the master never sees a stale high before the strobe is sampled.
        // A write may end once two active samples are in; a read once its
        // answer is on data_out.
        self.ready.next = !(!self.cs_n.val()
            & !self.we_n.val()
            & !(self.write_sync.q.val() & self.write_prev.q.val()))
            & !(!self.cs_n.val() & !self.rd_n.val() & !self.read_done.q.val());

        if self.reset.val() {
            self.write_meta.d.next = false;
            self.write_sync.d.next = false;
            self.write_prev.d.next = false;
            self.write_older.d.next = false;
            self.read_prev.d.next = false;
            self.read_pending.d.next = false;
            self.address_older.d.next = self.zero_a.val();
            self.data_older.d.next = self.zero_d.val();
            self.read_meta.d.next = false;
            self.read_sync.d.next = false;
            self.address_meta.d.next = self.zero_a.val();
            self.address_sync.d.next = self.zero_a.val();
            self.address_prev.d.next = self.zero_a.val();
            self.data_meta.d.next = self.zero_d.val();
            self.data_sync.d.next = self.zero_d.val();
            self.data_prev.d.next = self.zero_d.val();
            self.read_served.d.next = false;
            self.read_answer.d.next = false;
            self.read_done.d.next = false;
            self.bus_address_reg.d.next = self.zero_a.val();
            self.bus_write_data_reg.d.next = self.zero_d.val();
            self.bus_write_reg.d.next = false;
            self.bus_read_reg.d.next = false;
            self.data_out_reg.d.next = self.zero_d.val();
        }
    }
}

crate::vector_ports!(impl[const A: usize, const D: usize] BusSynchronizer<A, D> {
    inputs: [reset, cs_n, we_n, rd_n, address, data_in, bus_read_data],
    outputs: [data_out, data_oe, ready, bus_address, bus_write_data, bus_write, bus_read],
});
