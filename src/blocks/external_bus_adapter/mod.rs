//! # `external_bus_adapter`: asynchronous external-memory bus to a synchronous register bus
//!
//! A DSP or MCU reaches FPGA registers through its external memory
//! interface (EMIF, XINTF, FSMC): chip select, write and read strobes,
//! address and data, all asynchronous to the FPGA clock. This block
//! synchronizes the strobes (two flip-flops each), samples address and data
//! through the same pipeline, and turns every access into exactly one
//! one-clock strobe on a simple synchronous register bus:
//!
//! * a write becomes `bus_write` (with `bus_address`, `bus_write_data`) once
//!   the write strobe ends, with the address and data sampled a clock
//!   before its last active sample;
//! * a read becomes `bus_read` (with `bus_address`) once the read strobe is
//!   seen active on two samples; the slave answers on `bus_read_data` in
//!   the next clock, and the adapter holds that word on `data_out` for the
//!   rest of the read.
//!
//! It is the [`BusSynchronizer`] at 32 bits, without its `ready` output
//! (the 16- and 8-bit adapters in [`crate::blocks::narrow_bus_adapter`]
//! have it); every timing below is the synchronizer's.
//!
//! ## Ports (`A` = 8-bit address in the exported `external_bus_adapter`)
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
//!
//! ## Formal proof
//! `formal/external_bus_adapter.sv` states the contract above on the ports,
//! with the pins seen as the synchronizer's first flip-flops sample them:
//! one sample per clock edge, a pin changing near an edge sampled either
//! way, a word changing there as any value. A write access (a run of two or
//! more active samples) gives exactly one `bus_write`, two clocks after the
//! edge that first samples its strobe inactive, with the address and data
//! sampled a clock before its last active sample; a read access gives
//! exactly one `bus_read`, two clocks after its second active sample, with
//! the address sampled there, and the slave's answer of the next clock is on
//! `data_out` from the clock after, until the next answer. No other strobe
//! comes: a runt (one active sample) gives none, and never both in one
//! clock. `data_oe` is as stated; an edge in reset ends every access and
//! leaves the outputs 0.
//!
//! The pin timing table is what makes a legal access such a run (3 t_clk
//! of write strobe: two active samples; 2 t_clk of strobe high: an inactive
//! sample between two runs; the setup and hold rows: clean samples where
//! address and data are taken), so the proof assumes none of it: every
//! input, `reset` included, is free at every clock, the bad input of both
//! strobes low together included. Its outcome is proved as "Bad input"
//! states it: the write is taken when it ends, and the read is issued once
//! per run of active read samples, one clock later if the write's
//! `bus_write` takes its clock (the write ends at the edge of the read's
//! second active sample); the put-off read still carries the address
//! sampled at that second active sample, as an on-time read does. Proved by
//! k-induction for A = 2 and for the exported A = 8 (figures in the
//! README's "What is proved").
//!
//! Under that bad input the proof found a bug, since fixed: after a read
//! put off a clock by a write, a read starting one inactive sample later
//! was never issued.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::bus_synchronizer::port_docs::*;
use crate::blocks::bus_synchronizer::BusSynchronizer;
use crate::blocks::port_doc::PortDoc;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "asynchronous external-memory bus (cs_n, we_n, rd_n) to a synchronous register bus, with synchronizers";

/// Meaning of every port, for the export header and the `rtl-out` index
/// (the synchronizer's, without `ready`).
pub const PORT_DOCS: &[PortDoc] = &[
    CLOCK,
    RESET,
    CS_N,
    WE_N,
    RD_N,
    ADDRESS,
    DATA_IN.with_width("32"),
    DATA_OUT.with_width("32"),
    DATA_OE,
    BUS_ADDRESS,
    BUS_WRITE_DATA.with_width("32"),
    BUS_WRITE,
    BUS_READ,
    BUS_READ_DATA.with_width("32"),
];

/// Asynchronous external bus adapter. See the [module documentation](self).
#[derive(Clone, Debug, Default, LogicBlock)]
pub struct ExternalBusAdapter<const A: usize> {
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
    pub data_in: Signal<In, Bits<32>>,
    /// Read data to the pins.
    pub data_out: Signal<Out, Bits<32>>,
    /// Drive the data pins.
    pub data_oe: Signal<Out, Bit>,
    /// Address of the bus strobe.
    pub bus_address: Signal<Out, Bits<A>>,
    /// Data of the write strobe.
    pub bus_write_data: Signal<Out, Bits<32>>,
    /// Write strobe.
    pub bus_write: Signal<Out, Bit>,
    /// Read strobe.
    pub bus_read: Signal<Out, Bit>,
    /// Read data from the slave.
    pub bus_read_data: Signal<In, Bits<32>>,
    pins: BusSynchronizer<A, 32>,
}

impl<const A: usize> Logic for ExternalBusAdapter<A> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pins);
        self.pins.reset.next = self.reset.val();
        self.pins.cs_n.next = self.cs_n.val();
        self.pins.we_n.next = self.we_n.val();
        self.pins.rd_n.next = self.rd_n.val();
        self.pins.address.next = self.address.val();
        self.pins.data_in.next = self.data_in.val();
        self.pins.bus_read_data.next = self.bus_read_data.val();
        self.data_out.next = self.pins.data_out.val();
        self.data_oe.next = self.pins.data_oe.val();
        self.bus_address.next = self.pins.bus_address.val();
        self.bus_write_data.next = self.pins.bus_write_data.val();
        self.bus_write.next = self.pins.bus_write.val();
        self.bus_read.next = self.pins.bus_read.val();
    }
}

crate::vector_ports!(impl[const A: usize] ExternalBusAdapter<A> {
    inputs: [reset, cs_n, we_n, rd_n, address, data_in, bus_read_data],
    outputs: [data_out, data_oe, bus_address, bus_write_data, bus_write, bus_read],
});
