//! # `NarrowBusAdapter`: an 8- or 16-bit external bus to 32-bit registers, without tearing
//!
//! The seed board's DSP (TMS320F28335, XINTF: `XD[15:0]`) and PC bridge
//! (CH365: 8 data bits) have narrower data buses than the controller's
//! 32-bit registers. This adapter is the [`BusSynchronizer`] at the pins'
//! width followed by a [`WordAssembler`]: each 32-bit register is 2 (16-bit
//! bus) or 4 (8-bit bus) consecutive narrow addresses, lowest part first,
//! and
//! * **reads never tear**: reading the lowest part latches the whole
//!   register in one `bus_read`; the higher parts return the latched word;
//! * **writes are atomic**: the lower parts are held, and writing the
//!   highest part commits the whole word as one `bus_write`.
//!
//! Exported as `external_bus_adapter_16` (`A` = 8, `NA` = 9, `N` = 16) and
//! `external_bus_adapter_8` (`A` = 8, `NA` = 10, `N` = 8), both with `W` = 32
//! ([`ExternalBusAdapter16`], [`ExternalBusAdapter8`]). The register
//! header's `<REG>_ADDR16` and `<REG>_ADDR8` macros give each register's
//! lowest-part pin address (`INDEX * 2` and `INDEX * 4`).
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! Every narrow access has the [`BusSynchronizer`]'s pin timing, with or
//! without `ready`: 3 t_clk write strobes, 6 t_clk read access, 2 t_clk
//! between strobes. The bus strobes come on the same clocks as the
//! synchronizer's (the assembler adds no latency): a register write
//! reaches the bus at most 4 t_clk after the highest part's strobe ends;
//! `order_error` pulses one clock after the offending bus strobe.
//!
//! A 32-bit register access by a 16-bit master therefore takes two bus
//! cycles: with XINTF at 150 MHz and the FPGA at 48 MHz, about 2 × 140 ns
//! for reads without `ready`, or whatever `ready` allows.
//!
//! ## What firmware must do
//! Read the lowest part first, then the higher parts; write the lower parts
//! first (any order), then the highest part, and let nothing else write
//! another register's parts in between (an interrupt handler that only
//! reads is harmless: reads and writes have separate latches). Broken
//! orders have the outcomes in [`WordAssembler`]'s table: a torn word is
//! never written, an out-of-order read reads the register fresh, and
//! `order_error` pulses (wire it to a sticky status bit or an interrupt).
//!
//! ## Formal proof
//! `formal/narrow_bus_adapter.sv` states the contract on the ports, with the
//! pins seen as in [`crate::blocks::external_bus_adapter`]'s proof (one
//! sample per clock edge, either value near a change): a narrow write or
//! read takes effect in the clock the synchronizer's strobe would, with the
//! address and data that proof names. Then, in that clock:
//! * a highest-part write gives exactly one `bus_write`, of the register's
//!   whole word (each lower part as last written, the highest part from
//!   this write), if and only if every lower part of that register was
//!   written since the last highest-part write, reset or lower-part write
//!   of another register; any other write gives none;
//! * a part-0 read, or a higher-part read of a register other than the one
//!   latched by the last `bus_read`, gives exactly one `bus_read`; a
//!   higher-part read of the latched register gives none; `data_out` then
//!   holds the part of the slave's answer (latched) or of the latched word;
//! * `order_error` pulses the clock after, exactly on the broken orders of
//!   the [`WordAssembler`] table;
//! * `ready` is high with no strobe active; with the strobe sampled active
//!   at the last two edges (the "3 t_clk after the fall" rule), a write's
//!   `ready` is high exactly from its third active sample, and a read's
//!   exactly from its sixth, with its answer on `data_out`, provided every
//!   earlier read since reset lasted until its answer (as a master that
//!   waits for `ready` does; the proof observes this, it does not assume
//!   it);
//! * an edge in reset ends every access, empties the latch and the holding
//!   register, and leaves the outputs 0.
//!
//! Nothing is assumed: every input, `reset` included, is free at every
//! clock, and firmware's order is free (broken orders have the outcomes
//! above). All but `data_oe` is proved while no clock edge since reset has
//! sampled both strobes active: unlike the 32-bit adapter's proof, this one
//! does not cover the bad input of we_n and rd_n low together. Proved by
//! k-induction for A = 1, NA = 2, N = 2, W = 4 and for both exported
//! adapters (figures in the README's "What is proved").

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::bus_synchronizer::port_docs::*;
use crate::blocks::bus_synchronizer::BusSynchronizer;
use crate::blocks::port_doc::{port, PortDoc};
use crate::blocks::word_assembler::WordAssembler;

/// One line for the export header and the `rtl-out` index (16-bit pins).
pub const SUMMARY_16: &str =
    "16-bit asynchronous external bus (F28335 XINTF) to 32-bit registers: tear-free reads, atomic writes, XREADY";

/// One line for the export header and the `rtl-out` index (8-bit pins).
pub const SUMMARY_8: &str =
    "8-bit asynchronous external bus (CH365) to 32-bit registers: tear-free reads, atomic writes, ready";

/// Meaning of every port, for the export header and the `rtl-out` index:
/// the synchronizer's pins, and the register bus as the assembler makes it.
pub const PORT_DOCS: &[PortDoc] = &[
    CLOCK,
    RESET.with_meaning(
        "synchronous, active high: no access in progress, latch and holding register empty, outputs 0",
    ),
    CS_N,
    WE_N,
    RD_N,
    port(
        "address",
        "NA",
        "narrow word address: register address * (W/N) + part, asynchronous",
    ),
    DATA_IN.with_width("N"),
    DATA_OUT.with_width("N"),
    DATA_OE,
    READY,
    port(
        "bus_address",
        "A",
        "register address of the current bus strobe",
    ),
    port("bus_write_data", "W", "the whole word of `bus_write`"),
    port(
        "bus_write",
        "1",
        "one-clock write strobe: the highest part completed a word",
    ),
    port(
        "bus_read",
        "1",
        "one-clock read strobe: the lowest part was read",
    ),
    BUS_READ_DATA.with_width("W"),
    port(
        "order_error",
        "1",
        "one-clock pulse: firmware broke the access order (torn write dropped, out-of-order read)",
    ),
];

/// The exported 16-bit adapter: 8-bit register address, 9-bit pin address.
pub type ExternalBusAdapter16 = NarrowBusAdapter<8, 9, 16, 32>;

/// The exported 8-bit adapter: 8-bit register address, 10-bit pin address.
pub type ExternalBusAdapter8 = NarrowBusAdapter<8, 10, 8, 32>;

/// Narrow external bus to wide registers. See the [module documentation](self).
#[derive(Clone, Debug, Default, LogicBlock)]
pub struct NarrowBusAdapter<const A: usize, const NA: usize, const N: usize, const W: usize> {
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
    /// Narrow word address.
    pub address: Signal<In, Bits<NA>>,
    /// Write data from the pins.
    pub data_in: Signal<In, Bits<N>>,
    /// Read data to the pins.
    pub data_out: Signal<Out, Bits<N>>,
    /// Drive the data pins.
    pub data_oe: Signal<Out, Bit>,
    /// The access may end.
    pub ready: Signal<Out, Bit>,
    /// Register address of the bus strobe.
    pub bus_address: Signal<Out, Bits<A>>,
    /// Whole word of the write strobe.
    pub bus_write_data: Signal<Out, Bits<W>>,
    /// Write strobe.
    pub bus_write: Signal<Out, Bit>,
    /// Read strobe.
    pub bus_read: Signal<Out, Bit>,
    /// Read data from the slave.
    pub bus_read_data: Signal<In, Bits<W>>,
    /// Access-order violation.
    pub order_error: Signal<Out, Bit>,
    pins: BusSynchronizer<NA, N>,
    words: WordAssembler<A, NA, N, W>,
}

impl<const A: usize, const NA: usize, const N: usize, const W: usize> Logic
    for NarrowBusAdapter<A, NA, N, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pins, words);
        self.pins.reset.next = self.reset.val();
        self.pins.cs_n.next = self.cs_n.val();
        self.pins.we_n.next = self.we_n.val();
        self.pins.rd_n.next = self.rd_n.val();
        self.pins.address.next = self.address.val();
        self.pins.data_in.next = self.data_in.val();
        self.pins.bus_read_data.next = self.words.narrow_read_data.val();
        self.data_out.next = self.pins.data_out.val();
        self.data_oe.next = self.pins.data_oe.val();
        self.ready.next = self.pins.ready.val();

        self.words.reset.next = self.reset.val();
        self.words.narrow_address.next = self.pins.bus_address.val();
        self.words.narrow_write_data.next = self.pins.bus_write_data.val();
        self.words.narrow_write.next = self.pins.bus_write.val();
        self.words.narrow_read.next = self.pins.bus_read.val();
        self.words.bus_read_data.next = self.bus_read_data.val();
        self.bus_address.next = self.words.bus_address.val();
        self.bus_write_data.next = self.words.bus_write_data.val();
        self.bus_write.next = self.words.bus_write.val();
        self.bus_read.next = self.words.bus_read.val();
        self.order_error.next = self.words.order_error.val();
    }
}

crate::vector_ports!(impl[const A: usize, const NA: usize, const N: usize, const W: usize] NarrowBusAdapter<A, NA, N, W> {
    inputs: [reset, cs_n, we_n, rd_n, address, data_in, bus_read_data],
    outputs: [data_out, data_oe, ready, bus_address, bus_write_data, bus_write, bus_read, order_error],
});
