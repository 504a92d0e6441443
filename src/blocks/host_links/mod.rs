//! # `host_links`: the seed card's DSP and PC buses, the controller's registers and the mailbox
//!
//! The seed card has two masters on the FPGA: a TMS320F28335 on its 16-bit
//! external interface (XINTF: one zone chip select, XWE, XRD, XA, XD\[15:0\],
//! XREADY) and a CH365 PCI bridge with an 8-bit data bus. The DSP drives
//! the motion controller's 32-bit registers and shares a dual-port RAM
//! mailbox with the PC. This block is that whole host side, composed of the
//! project's blocks:
//!
//! ```text
//! DSP pins --> BusSynchronizer<DA, 16> --+-- address[MA] = 0 --> WordAssembler<CA, CNA, 16, 32> --> reg_* (the controller's bus)
//!  (XINTF)          ready -> XREADY      +-- address[MA] = 1 --> DpramMailbox<MA, 16> port B
//! PC pins  --> NarrowBusAdapter<MA, DA, 8, 16> ----------------> DpramMailbox<MA, 16> port A
//!  (CH365)
//! ```
//!
//! One DSP zone serves both targets through one synchronizer: the top
//! address bit chooses the mailbox, so the DSP needs one chip select and
//! the FPGA one set of synchronizers. The PC side is the seed's CH365
//! byte-split scheme made atomic: each 16-bit mailbox word is two byte
//! addresses, low byte first (reading the low byte latches the whole
//! word; writing the high byte commits it).
//!
//! Exported as `host_links` with CA = 8, CNA = 9, MA = 10, DA = 11
//! ([`SeedHostLinks`]): 256 controller registers and a 1024 x 16 mailbox.
//!
//! ## Address maps
//! | master | pin word address | target |
//! |---|---|---|
//! | DSP (16-bit words) | 0x000 to 0x1FF | controller register `a / 2`, part `a % 2` (low half first): the `<REG>_ADDR16` macros of `motion_controller_regs.h` |
//! | DSP | 0x200 to 0x3FF | the same registers again (bit 9 is not decoded) |
//! | DSP | 0x400 to 0x7FF | mailbox word `a - 0x400` (`MAILBOX_TO_B` = 0x7FF, `MAILBOX_TO_A` = 0x7FE) |
//! | PC (bytes) | 0x000 to 0x7FF | mailbox word `a / 2`, byte `a % 2` (low byte first): `MAILBOX_TO_B` at 0x7FE/0x7FF, `MAILBOX_TO_A` at 0x7FC/0x7FD |
//!
//! The PC writes `MAILBOX_TO_B` to interrupt the DSP (`irq_dsp`); the DSP's
//! access to it clears that interrupt. The DSP writes `MAILBOX_TO_A` to
//! interrupt the PC (`irq_pc`); the PC's access to it clears it. The other
//! mailbox rules (read-first, a write on both ports at once, the write
//! queue) are [`DpramMailbox`]'s.
//!
//! ## Ports (exported: CA = 8, CNA = 9, MA = 10, DA = 11)
//!
#![doc = include_str!("ports.md")]
//!
//! `reg_*` is the project's synchronous register bus: connect it to
//! `motion_controller`'s `bus_*` ports.
//!
//! ## Timing, in FPGA clocks (t_clk)
//! Both masters see the [`BusSynchronizer`]'s pin timing: write strobes of
//! at least 3 t_clk, a read access of 6 t_clk (plus pad delays) or until
//! `ready`, 2 t_clk between strobes. The assembler and the address decode
//! add no clock: a DSP register write reaches `reg_write` at most 4 t_clk
//! after the high half's strobe ends, and a mailbox write reaches the
//! memory at the same moment (visible to the other master's next read).
//! A mailbox write raises the other side's irq 1 clock after it reaches
//! the memory, so at most 5 t_clk after the writing strobe ends.
//!
//! Each master strobes at most one mailbox write every 5 clocks, far below
//! the mailbox's write rate, so `mailbox_overrun` stays low at the pins'
//! timing; it is brought out so that no flag of the mailbox is hidden.
//!
//! ## What firmware must do
//! * DSP, controller registers: the [`NarrowBusAdapter`] rules: read the
//!   low half first, write the low half then the high half, and let no
//!   other register write come between the halves.
//! * PC, mailbox words: the same per word: read the low byte first, write
//!   the low byte then the high byte. A high byte written alone writes
//!   nothing (a torn word never reaches the memory) and pulses
//!   `pc_order_error`.
//! * DSP, mailbox words: plain 16-bit accesses, no order.
//!
//! ## Bad input
//! Every pin sequence has the outcome of the block that takes it: the
//! synchronizer's for strobes (runts ignored, a read and write together
//! taken as documented there), the assembler's for broken part orders
//! (flagged), the mailbox's for concurrent writes (flagged). A DSP access
//! to 0x200-0x3FF reaches the controller's registers (partial decode).

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::bus_synchronizer::BusSynchronizer;
use crate::blocks::dpram_mailbox::DpramMailbox;
use crate::blocks::narrow_bus_adapter::NarrowBusAdapter;
use crate::blocks::word_assembler::WordAssembler;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "the seed card's host side: a 16-bit DSP bus (XINTF, XREADY) onto the controller's 32-bit registers and a 1024 x 16 mailbox, and an 8-bit PC bus (CH365) onto the mailbox's other port";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: no access in progress, latches and holding registers empty, irqs low, outputs 0; the mailbox RAM keeps its words"),
    port("dsp_cs_n", "1", "DSP zone chip select, active low, asynchronous"),
    port("dsp_we_n", "1", "DSP write strobe (XWE), active low, asynchronous"),
    port("dsp_rd_n", "1", "DSP read strobe (XRD), active low, asynchronous"),
    port("dsp_address", "DA", "DSP word address (XA), asynchronous: 0x000-0x3FF controller registers (register * 2 + half), 0x400-0x7FF mailbox words"),
    port("dsp_data_in", "16", "DSP write data (XD), asynchronous"),
    port("dsp_data_out", "16", "DSP read data, registered"),
    port("dsp_data_oe", "1", "drive XD: `!dsp_cs_n & !dsp_rd_n & dsp_we_n`, combinational from the pins"),
    port("dsp_ready", "1", "XREADY: low from the strobe's fall until a write has two active samples or a read's answer is on `dsp_data_out`"),
    port("dsp_order_error", "1", "one-clock pulse: the DSP broke a 32-bit register's half order (torn write dropped, out-of-order read)"),
    port("pc_cs_n", "1", "PC bridge chip select, active low, asynchronous"),
    port("pc_we_n", "1", "PC bridge write strobe, active low, asynchronous"),
    port("pc_rd_n", "1", "PC bridge read strobe, active low, asynchronous"),
    port("pc_address", "DA", "PC byte address: mailbox word * 2 + byte (low byte first), asynchronous"),
    port("pc_data_in", "8", "PC write data, asynchronous"),
    port("pc_data_out", "8", "PC read data, registered"),
    port("pc_data_oe", "1", "drive the PC data pins: `!pc_cs_n & !pc_rd_n & pc_we_n`, combinational from the pins"),
    port("pc_ready", "1", "the PC's access may end (for a bridge with a wait input; the CH365 has none)"),
    port("pc_order_error", "1", "one-clock pulse: the PC broke a mailbox word's byte order (torn write dropped, out-of-order read)"),
    port("reg_address", "CA", "the controller's register address, with `reg_write` or `reg_read`"),
    port("reg_write_data", "32", "the whole 32-bit word of `reg_write`"),
    port("reg_write", "1", "one-clock register write strobe"),
    port("reg_read", "1", "one-clock register read strobe"),
    port("reg_read_data", "32", "the controller's read data, valid in the clock after `reg_read`"),
    port("irq_dsp", "1", "level: the PC wrote `MAILBOX_TO_B`, the DSP has not accessed it since; registered"),
    port("irq_pc", "1", "level: the DSP wrote `MAILBOX_TO_A`, the PC has not accessed it since; registered"),
    port("mailbox_collision", "1", "one-clock pulse: both masters' writes reached the same mailbox word on one clock (the DSP's word stays)"),
    port("mailbox_overrun", "1", "one-clock pulse: a DSP mailbox write was refused; cannot happen at the pins' timing"),
];

/// The exported configuration: 256 controller registers (CA = 8, DSP
/// half-word address 9 bits) and a 1024 x 16 mailbox (MA = 10), 11-bit
/// DSP and PC pin addresses.
pub type SeedHostLinks = HostLinks<8, 9, 10, 11>;

/// The seed card's host side. See the [module documentation](self).
///
/// `CA`: controller register address bits; `CNA` = CA + 1 (16-bit halves);
/// `MA`: mailbox word address bits, at least `CNA`; `DA` = MA + 1, the
/// DSP's and PC's pin address width.
#[derive(LogicBlock)]
pub struct HostLinks<const CA: usize, const CNA: usize, const MA: usize, const DA: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// DSP chip select, active low.
    pub dsp_cs_n: Signal<In, Bit>,
    /// DSP write strobe, active low.
    pub dsp_we_n: Signal<In, Bit>,
    /// DSP read strobe, active low.
    pub dsp_rd_n: Signal<In, Bit>,
    /// DSP word address.
    pub dsp_address: Signal<In, Bits<DA>>,
    /// DSP write data.
    pub dsp_data_in: Signal<In, Bits<16>>,
    /// DSP read data.
    pub dsp_data_out: Signal<Out, Bits<16>>,
    /// Drive the DSP data pins.
    pub dsp_data_oe: Signal<Out, Bit>,
    /// XREADY.
    pub dsp_ready: Signal<Out, Bit>,
    /// The DSP broke a register's half order.
    pub dsp_order_error: Signal<Out, Bit>,
    /// PC chip select, active low.
    pub pc_cs_n: Signal<In, Bit>,
    /// PC write strobe, active low.
    pub pc_we_n: Signal<In, Bit>,
    /// PC read strobe, active low.
    pub pc_rd_n: Signal<In, Bit>,
    /// PC byte address.
    pub pc_address: Signal<In, Bits<DA>>,
    /// PC write data.
    pub pc_data_in: Signal<In, Bits<8>>,
    /// PC read data.
    pub pc_data_out: Signal<Out, Bits<8>>,
    /// Drive the PC data pins.
    pub pc_data_oe: Signal<Out, Bit>,
    /// The PC's access may end.
    pub pc_ready: Signal<Out, Bit>,
    /// The PC broke a mailbox word's byte order.
    pub pc_order_error: Signal<Out, Bit>,
    /// Controller register address.
    pub reg_address: Signal<Out, Bits<CA>>,
    /// Controller register write data.
    pub reg_write_data: Signal<Out, Bits<32>>,
    /// Controller register write strobe.
    pub reg_write: Signal<Out, Bit>,
    /// Controller register read strobe.
    pub reg_read: Signal<Out, Bit>,
    /// Controller read data.
    pub reg_read_data: Signal<In, Bits<32>>,
    /// The PC wrote `MAILBOX_TO_B`.
    pub irq_dsp: Signal<Out, Bit>,
    /// The DSP wrote `MAILBOX_TO_A`.
    pub irq_pc: Signal<Out, Bit>,
    /// Both masters wrote one mailbox word on one clock.
    pub mailbox_collision: Signal<Out, Bit>,
    /// A DSP mailbox write was refused.
    pub mailbox_overrun: Signal<Out, Bit>,
    dsp: BusSynchronizer<DA, 16>,
    registers: WordAssembler<CA, CNA, 16, 32>,
    // Not `mailbox`: a SystemVerilog built-in class, which Verilator rejects as an instance name.
    memory: DpramMailbox<MA, 16>,
    pc: NarrowBusAdapter<MA, DA, 8, 16>,
    /// The DSP's bus strobe this clock is for the mailbox.
    to_mailbox: Signal<Local, Bit>,
    /// The DSP's last read went to the mailbox: its answer comes from there.
    answer_from_mailbox: DFF<Bit>,
    /// Shifts the DSP address's top (window) bit down to bit 0.
    window_shift: Constant<Bits<DA>>,
    zero_da: Constant<Bits<DA>>,
}

impl<const CA: usize, const CNA: usize, const MA: usize, const DA: usize> Default
    for HostLinks<CA, CNA, MA, DA>
{
    /// Panics on a parameter set that does not fit together (a build-time
    /// error): `CNA != CA + 1`, `DA != MA + 1` or `MA < CNA`.
    fn default() -> Self {
        assert!(
            CNA == CA + 1,
            "HostLinks: CNA must be CA + 1 (16-bit halves)"
        );
        assert!(
            DA == MA + 1,
            "HostLinks: DA must be MA + 1 (the window bit)"
        );
        assert!(
            MA >= CNA,
            "HostLinks: the mailbox window must cover the register window"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            dsp_cs_n: Default::default(),
            dsp_we_n: Default::default(),
            dsp_rd_n: Default::default(),
            dsp_address: Default::default(),
            dsp_data_in: Default::default(),
            dsp_data_out: Default::default(),
            dsp_data_oe: Default::default(),
            dsp_ready: Default::default(),
            dsp_order_error: Default::default(),
            pc_cs_n: Default::default(),
            pc_we_n: Default::default(),
            pc_rd_n: Default::default(),
            pc_address: Default::default(),
            pc_data_in: Default::default(),
            pc_data_out: Default::default(),
            pc_data_oe: Default::default(),
            pc_ready: Default::default(),
            pc_order_error: Default::default(),
            reg_address: Default::default(),
            reg_write_data: Default::default(),
            reg_write: Default::default(),
            reg_read: Default::default(),
            reg_read_data: Default::default(),
            irq_dsp: Default::default(),
            irq_pc: Default::default(),
            mailbox_collision: Default::default(),
            mailbox_overrun: Default::default(),
            dsp: Default::default(),
            registers: Default::default(),
            memory: Default::default(),
            pc: Default::default(),
            to_mailbox: Default::default(),
            answer_from_mailbox: Default::default(),
            window_shift: Constant::new((MA as u64).into()),
            zero_da: Constant::new(0u64.into()),
        }
    }
}

impl<const CA: usize, const CNA: usize, const MA: usize, const DA: usize> Logic
    for HostLinks<CA, CNA, MA, DA>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, dsp, registers, memory, pc);
        dff_setup!(self, clock, answer_from_mailbox);

        // DSP pins.
        self.dsp.reset.next = self.reset.val();
        self.dsp.cs_n.next = self.dsp_cs_n.val();
        self.dsp.we_n.next = self.dsp_we_n.val();
        self.dsp.rd_n.next = self.dsp_rd_n.val();
        self.dsp.address.next = self.dsp_address.val();
        self.dsp.data_in.next = self.dsp_data_in.val();
        self.dsp_data_out.next = self.dsp.data_out.val();
        self.dsp_data_oe.next = self.dsp.data_oe.val();
        self.dsp_ready.next = self.dsp.ready.val();

        // The window bit splits the DSP's strobes (a shift, not an indexed
        // bit: rust-hdl would print the parameter's name as the index).
        self.to_mailbox.next =
            (self.dsp.bus_address.val() >> self.window_shift.val()) != self.zero_da.val();

        // Controller registers, through the word assembler.
        self.registers.reset.next = self.reset.val();
        self.registers.narrow_address.next = self.dsp.bus_address.val().get_bits::<CNA>(0);
        self.registers.narrow_write_data.next = self.dsp.bus_write_data.val();
        self.registers.narrow_write.next = self.dsp.bus_write.val() & !self.to_mailbox.val();
        self.registers.narrow_read.next = self.dsp.bus_read.val() & !self.to_mailbox.val();
        self.registers.bus_read_data.next = self.reg_read_data.val();
        self.reg_address.next = self.registers.bus_address.val();
        self.reg_write_data.next = self.registers.bus_write_data.val();
        self.reg_write.next = self.registers.bus_write.val();
        self.reg_read.next = self.registers.bus_read.val();
        self.dsp_order_error.next = self.registers.order_error.val();

        // Mailbox port B: the DSP's plain 16-bit words.
        self.memory.reset.next = self.reset.val();
        self.memory.b_address.next = self.dsp.bus_address.val().get_bits::<MA>(0);
        self.memory.b_write_data.next = self.dsp.bus_write_data.val();
        self.memory.b_write.next = self.dsp.bus_write.val() & self.to_mailbox.val();
        self.memory.b_read.next = self.dsp.bus_read.val() & self.to_mailbox.val();

        // The answer to the DSP's last read: both targets answer in the
        // clock after their read strobe and hold it.
        if self.dsp.bus_read.val() {
            self.answer_from_mailbox.d.next = self.to_mailbox.val();
        }
        self.dsp.bus_read_data.next = self.registers.narrow_read_data.val();
        if self.answer_from_mailbox.q.val() {
            self.dsp.bus_read_data.next = self.memory.b_read_data.val();
        }
        if self.reset.val() {
            self.answer_from_mailbox.d.next = false;
        }

        // PC pins onto mailbox port A, bytes assembled into words.
        self.pc.reset.next = self.reset.val();
        self.pc.cs_n.next = self.pc_cs_n.val();
        self.pc.we_n.next = self.pc_we_n.val();
        self.pc.rd_n.next = self.pc_rd_n.val();
        self.pc.address.next = self.pc_address.val();
        self.pc.data_in.next = self.pc_data_in.val();
        self.pc.bus_read_data.next = self.memory.a_read_data.val();
        self.pc_data_out.next = self.pc.data_out.val();
        self.pc_data_oe.next = self.pc.data_oe.val();
        self.pc_ready.next = self.pc.ready.val();
        self.pc_order_error.next = self.pc.order_error.val();
        self.memory.a_address.next = self.pc.bus_address.val();
        self.memory.a_write_data.next = self.pc.bus_write_data.val();
        self.memory.a_write.next = self.pc.bus_write.val();
        self.memory.a_read.next = self.pc.bus_read.val();

        self.irq_dsp.next = self.memory.irq_b.val();
        self.irq_pc.next = self.memory.irq_a.val();
        self.mailbox_collision.next = self.memory.collision.val();
        self.mailbox_overrun.next = self.memory.overrun.val();
    }
}

crate::vector_ports!(impl[const CA: usize, const CNA: usize, const MA: usize, const DA: usize] HostLinks<CA, CNA, MA, DA> {
    inputs: [
        reset, dsp_cs_n, dsp_we_n, dsp_rd_n, dsp_address, dsp_data_in,
        pc_cs_n, pc_we_n, pc_rd_n, pc_address, pc_data_in, reg_read_data
    ],
    outputs: [
        dsp_data_out, dsp_data_oe, dsp_ready, dsp_order_error,
        pc_data_out, pc_data_oe, pc_ready, pc_order_error,
        reg_address, reg_write_data, reg_write, reg_read,
        irq_dsp, irq_pc, mailbox_collision, mailbox_overrun
    ],
});
