//! # `SpiBusAdapter`: an SPI slave (mode 0) onto the 32-bit register bus, in CRC-checked frames
//!
//! The host of most hobby and small-shop motion cards is a Raspberry Pi or
//! a microcontroller on SPI (Mesa 7C80/7C81, Remora, RAPcores). This block
//! puts the controller's register bus (`motion_controller`'s `bus_*`
//! ports) behind four SPI pins. Every transaction is one **frame** between
//! CS falling and rising: a command, an address, a burst of 1 to 16 words
//! at consecutive addresses, and a CRC-8. The frame's layout is in
//! [`frame`]; the host side is [`crate::host::spi::SpiBus`] (and `simulate --bus spi`).
//!
//! * **Nothing of a bad frame reaches the bus.** The header (command and
//!   address) has a CRC-8 of its own, so a corrupted count never lays the
//!   frame out wrong: a write frame whose header fails writes nothing,
//!   whatever its later bytes. A write frame's words wait
//!   in a 16-word buffer (one block RAM) until its CRC byte has been
//!   checked; only a frame whose CRC matches, with every SCLK phase at
//!   least 2 clocks long, writes, and then all its words, one a clock. A
//!   CRC mismatch, CS rising before the CRC byte ends, or a too-fast SCLK
//!   write nothing. A read frame's header is checked the same way before
//!   any read is issued.
//! * **The status comes back in the same frame**: the byte after the CRC
//!   byte carries the frame's verdict on MISO, and the first byte of every
//!   frame carries the last frame's (with `ABORTED` for a frame cut short).
//! * **Coherent burst reads**: a read frame's words are read on
//!   consecutive clocks into the buffer before the first is shifted out;
//!   with the command's `SNAPSHOT` bit the adapter first writes the
//!   controller's `SNAPSHOT` register, so the positions read come from one
//!   clock (the snapshot the controller already has).
//! * Read data carry their own CRC-8, so the host sees a corrupted MISO.
//!
//! Exported as `spi_bus_adapter` (`A` = 8 address bits, 32-bit words,
//! `SNAPSHOT` at 0x0b, the controller's).
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing at the pins, in FPGA clocks (t_clk)
//! SCLK, CS and MOSI pass two flip-flops each (give the `*_meta`
//! flip-flops your tool's ASYNC_REG attribute and a false path from the
//! pins). SPI mode 0: SCLK idles low, both sides sample on the rising edge,
//! and MISO changes 3 t_clk after a rising edge at the pins (not on the
//! falling edge), so it is valid at the next rising edge when SCLK's
//! period is at least 4 t_clk.
//!
//! | parameter | limit | why |
//! |---|---|---|
//! | SCLK high, SCLK low | at least 2 t_clk each (SCLK at most f_clk / 4) | every phase needs two samples; a shorter one sets `OVERSPEED` |
//! | MOSI setup and hold around SCLK's rising edge | t_clk each | sampled through the same two stages as SCLK |
//! | CS falling to the first SCLK rise | at least 3 t_clk | MISO's first bit is out 3 t_clk after CS falls |
//! | last SCLK rise to CS rising | at least 2 t_clk (CS may rise with SCLK's last fall) | the last bit's rise is taken 2 t_clk after it happens |
//! | CS high between frames | at least 2 t_clk | one clean deselected sample ends a frame |
//! | MISO after SCLK's rising edge | 3 t_clk + t_co | two synchronizer stages and the shift register |
//!
//! A write's bus strobes start 4 t_clk after the CRC byte's last rising
//! edge at the pins, one word a clock. A read frame's reads start there
//! too (after the `SNAPSHOT` write when asked); the last of 16 is issued
//! 20 t_clk after that edge (21 with `SNAPSHOT`), well inside the
//! turnaround byte (32 t_clk at the fastest SCLK). At 48 MHz, SCLK may be
//! 12 MHz: a 4-word read frame (3 header, 1 status, 16 data, 1 CRC bytes)
//! takes 14 µs.
//!
//! ## Bad input
//! | input | outcome |
//! |---|---|
//! | a CRC that does not match | nothing written or read; `CRC_ERROR` in the status; `frame_error` pulses at CS rising |
//! | CS rising before the CRC byte's last bit | nothing written or read; `ABORTED` in the next frame's first byte; `frame_error` |
//! | CS rising later (mid status, mid word of a read) | the frame is complete: its writes all happen, its reads were all issued |
//! | an SCLK phase shorter than 2 samples | `OVERSPEED`; before the CRC byte ends, nothing written or read; `frame_error` |
//! | SCLK far above f_clk / 2 | edges alias: caught by the CRC (or the bit count), not always by `OVERSPEED` |
//! | bytes after the frame's last | ignored; MISO 0 |
//! | an unknown register address | the slave's answer, as on the other buses: the controller reads 0 and ignores the write |
//! | a burst past 0xff | the address wraps to 0x00 |
//! | reset during a frame | the frame and the bus strobes stop; the rest of the frame up to CS rising is ignored |
//! | SCLK high when CS falls (mode 1, 3) | the first falling edge is ignored; the bits are taken on rising edges, so mode 3 works, mode 1 and 2 do not |
//!
//! Reads have no side effects on the controller, so a read frame cut short
//! after its header does no harm.
//!
//! ## Latency
//! * Write: the first `bus_write` 4 t_clk after the CRC byte's last SCLK
//!   rise at the pins, word k k t_clk later.
//! * Read: the first `bus_read` 4 t_clk after the header CRC's last SCLK
//!   rise (5 with `SNAPSHOT`, whose write takes the 4th); the words are on
//!   MISO from the status byte's end on.
//! * The status byte is on MISO for the SCLK rise right after the CRC byte.
//!
//! ## Verification
//! **Formal proof** (`formal/spi_bus_adapter.sv`, proof `spi_bus_adapter`
//! in the README's "What is proved"): with every input free at every clock
//! (any SCLK rate, CS released anywhere, `reset`, `bus_read_data`), every
//! bus strobe belongs to a frame that passed (its CRC byte ended with CS
//! low, the header and frame CRCs left 0, no SCLK phase shorter than 2
//! samples), and a frame that passed gets, from the second clock after its
//! CRC byte's last sampled rise, its `SNAPSHOT` write (a read frame that
//! asked) and all its N strobes at consecutive addresses, one a clock,
//! each written word the frame's, all 32 bits. No other clock has a
//! strobe. The proof follows one word place, any of the 16, and takes the
//! buffer's RAM contract as a premise, proved on the RAM itself
//! (`spi_bus_adapter_ram`). It found one bug, fixed: a write frame whose
//! header CRC failed was checked again at its frame CRC, so a frame CRC
//! matching the bytes as received wrote it (a corrupted count lays that
//! CRC on a data byte, 1 time in 256). Not proved: MISO (status bytes, read
//! words and their CRC), `frame_error`, and the read words' data.
//!
//! Simulation: the lockstep against [`model::SpiBusModel`] under random
//! framed traffic with garbage, cut frames, single-clock SCLK phases and
//! resets; an independent monitor at the pins with a register file behind
//! the bus (every good frame's words written once, whole, on consecutive
//! clocks; no strobe for a bad or cut frame; reads, status bytes and the
//! read CRC as the frame says), shown by mutation to fail; the exhaustive
//! cut point and single-bit error sweeps of a frame; and frames whose
//! header CRC fails while their frame CRC matches.
//!
//! ## Model
//! [`model::SpiBusModel`], cycle-exact.

pub mod frame;
pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::holding_ram::HoldingRam;
use crate::blocks::konst;
use crate::blocks::motion_controller::registers::global;
use crate::blocks::port_doc::{port, PortDoc};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "SPI slave (mode 0, SCLK to f_clk/4) to 32-bit registers: CRC-8 framed bursts, no write on a bad frame, status in the same frame";

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: no frame, no bus strobe, status clear",
    ),
    port(
        "sclk",
        "1",
        "SPI clock from the master, mode 0 (idle low, sampled on the rising edge), asynchronous",
    ),
    port("cs_n", "1", "chip select, active low, asynchronous: a frame lasts while it is low"),
    port("mosi", "1", "master out, slave in: sampled at SCLK's rising edge, asynchronous"),
    port(
        "miso",
        "1",
        "master in, slave out: registered, the next bit 3 clocks after each SCLK rise",
    ),
    port(
        "miso_oe",
        "1",
        "drive MISO: `!cs_n`, combinational from the pin (for a shared MISO line's buffer)",
    ),
    port("bus_address", "8", "register address of the current bus strobe, registered"),
    port(
        "bus_write_data",
        "32",
        "the word of `bus_write`, registered (0 for the `SNAPSHOT` write)",
    ),
    port(
        "bus_write",
        "1",
        "one-clock write strobe: a word of a frame that passed its CRC, or a read frame's `SNAPSHOT` write",
    ),
    port(
        "bus_read",
        "1",
        "one-clock read strobe: a word of a read frame that passed its CRC (consecutive clocks for a burst)",
    ),
    port(
        "bus_read_data",
        "32",
        "the slave's read data, valid in the clock after `bus_read`",
    ),
    port(
        "frame_error",
        "1",
        "one-clock pulse the clock after CS rises on a frame with a flag in its status (CRC error, too-fast SCLK, cut short)",
    ),
];

/// The address the `SNAPSHOT` command bit writes: the controller's.
pub const SNAPSHOT_ADDRESS: u32 = global::SNAPSHOT;

/// SPI slave onto the register bus. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct SpiBusAdapter {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// SPI clock.
    pub sclk: Signal<In, Bit>,
    /// Chip select, active low.
    pub cs_n: Signal<In, Bit>,
    /// Master out, slave in.
    pub mosi: Signal<In, Bit>,
    /// Master in, slave out.
    pub miso: Signal<Out, Bit>,
    /// Drive MISO.
    pub miso_oe: Signal<Out, Bit>,
    /// Register address of the bus strobe.
    pub bus_address: Signal<Out, Bits<8>>,
    /// Data of the write strobe.
    pub bus_write_data: Signal<Out, Bits<32>>,
    /// Write strobe.
    pub bus_write: Signal<Out, Bit>,
    /// Read strobe.
    pub bus_read: Signal<Out, Bit>,
    /// Read data from the slave.
    pub bus_read_data: Signal<In, Bits<32>>,
    /// A frame ended with a flag.
    pub frame_error: Signal<Out, Bit>,
    // Two-flip-flop synchronizers and the edge detector's last sample.
    sclk_meta: DFF<Bit>,
    sclk_sync: DFF<Bit>,
    sclk_last: DFF<Bit>,
    select_meta: DFF<Bit>,
    select_sync: DFF<Bit>,
    select_last: DFF<Bit>,
    mosi_meta: DFF<Bit>,
    mosi_sync: DFF<Bit>,
    // The frame.
    in_frame: DFF<Bit>,
    since_edge: DFF<Bits<2>>,
    overspeed: DFF<Bit>,
    bit_count: DFF<Bits<3>>,
    position: DFF<Bits<7>>,
    command: DFF<Bits<8>>,
    /// The byte positions of the frame's last CRC and (read frames) last
    /// word byte, registered from the command at byte 1; valid with
    /// `geometry` (set from byte 2 on).
    crc_position: DFF<Bits<7>>,
    end_position: DFF<Bits<7>>,
    geometry: DFF<Bit>,
    // The current byte's role, registered from `position`.
    at_p0: DFF<Bit>,
    at_p1: DFF<Bit>,
    at_p2: DFF<Bit>,
    at_crc: DFF<Bit>,
    capture_lane: DFF<Bit>,
    capture_index: DFF<Bits<4>>,
    out_crc_lane: DFF<Bit>,
    word_lane: DFF<Bit>,
    crc_lane: DFF<Bit>,
    address: DFF<Bits<8>>,
    crc_in: DFF<Bits<8>>,
    /// MISO's CRC-8 in bits 31..24 (the low bits stay 0): it loads into
    /// `out_shift` as it is.
    crc_out: DFF<Bits<32>>,
    in_word: DFF<Bits<32>>,
    out_shift: DFF<Bits<32>>,
    complete: DFF<Bit>,
    crc_error: DFF<Bit>,
    good: DFF<Bit>,
    last_crc_error: DFF<Bit>,
    last_overspeed: DFF<Bit>,
    last_aborted: DFF<Bit>,
    frame_error_reg: DFF<Bit>,
    out_index: DFF<Bits<4>>,
    // The bus engine.
    remaining: DFF<Bits<5>>,
    snapshot_pending: DFF<Bit>,
    writing: DFF<Bit>,
    index: DFF<Bits<4>>,
    op_address: DFF<Bits<8>>,
    bus_address_reg: DFF<Bits<8>>,
    write_stage: DFF<Bit>,
    write_snapshot: DFF<Bit>,
    bus_read_reg: DFF<Bit>,
    read_ack: DFF<Bit>,
    read_index: DFF<Bits<4>>,
    ack_index: DFF<Bits<4>>,
    buffer: HoldingRam<Bits<32>, 4>,
    // Combinational.
    is_write: Signal<Local, Bit>,
    words: Signal<Local, Bits<5>>,
    words4: Signal<Local, Bits<7>>,
    crc_position_of: Signal<Local, Bits<7>>,
    end_position_of: Signal<Local, Bits<7>>,
    sclk_edge: Signal<Local, Bit>,
    rise: Signal<Local, Bit>,
    frame_start: Signal<Local, Bit>,
    frame_end: Signal<Local, Bit>,
    overspeed_any: Signal<Local, Bit>,
    mosi_word: Signal<Local, Bits<32>>,
    in_word_next: Signal<Local, Bits<32>>,
    crc_in_shifted: Signal<Local, Bits<8>>,
    crc_in_next: Signal<Local, Bits<8>>,
    crc_out_shifted: Signal<Local, Bits<32>>,
    crc_out_next: Signal<Local, Bits<32>>,
    crc_ok: Signal<Local, Bit>,
    status_overspeed: Signal<Local, Bits<32>>,
    status_crc: Signal<Local, Bits<32>>,
    last_status_crc: Signal<Local, Bits<32>>,
    last_status_overspeed: Signal<Local, Bits<32>>,
    last_status_aborted: Signal<Local, Bits<32>>,
    kept_overspeed: Signal<Local, Bits<32>>,
    kept_crc: Signal<Local, Bits<32>>,
    byte_done: Signal<Local, Bit>,
    capture: Signal<Local, Bit>,
    busy: Signal<Local, Bit>,
    // Constants.
    snapshot_address: Constant<Bits<8>>,
    count_field: Constant<Bits<7>>,
    poly: Constant<Bits<8>>,
    poly_word: Constant<Bits<32>>,
    count_mask_5: Constant<Bits<5>>,
    one_5: Constant<Bits<5>>,
    two_5: Constant<Bits<5>>,
    marker_word: Constant<Bits<32>>,
    overspeed_word: Constant<Bits<32>>,
    crc_error_word: Constant<Bits<32>>,
    aborted_word: Constant<Bits<32>>,
    zero_32: Constant<Bits<32>>,
    one_32: Constant<Bits<32>>,
    p0: Constant<Bits<7>>,
    p1: Constant<Bits<7>>,
    p2: Constant<Bits<7>>,
    p3: Constant<Bits<7>>,
    p6: Constant<Bits<7>>,
    p7: Constant<Bits<7>>,
    p_last: Constant<Bits<7>>,
    lane_2: Constant<Bits<2>>,
    lane_3: Constant<Bits<2>>,
    one_4: Constant<Bits<4>>,
    seven_3: Constant<Bits<3>>,
    two_2: Constant<Bits<2>>,
    one_2: Constant<Bits<2>>,
    one_3: Constant<Bits<3>>,
    one_8: Constant<Bits<8>>,
    zero_2: Constant<Bits<2>>,
    zero_3: Constant<Bits<3>>,
    zero_4: Constant<Bits<4>>,
    zero_5: Constant<Bits<5>>,
    zero_7: Constant<Bits<7>>,
    zero_8: Constant<Bits<8>>,
}

// The status bits the RTL's constants place at bits 31..24 of a word.
const _: () = assert!(frame::STATUS_MARKER == 0xa0);
const _: () = assert!(frame::STATUS_CRC_ERROR == 0x01);
const _: () = assert!(frame::STATUS_OVERSPEED == 0x02);
const _: () = assert!(frame::STATUS_ABORTED == 0x04);
const _: () = assert!(frame::COMMAND_WRITE == 0x80 && frame::COMMAND_SNAPSHOT == 0x40);
const _: () = assert!(frame::COMMAND_COUNT_MASK == 0x0f && frame::MAX_WORDS == 16);

impl Default for SpiBusAdapter {
    fn default() -> Self {
        Self::with_snapshot_address(SNAPSHOT_ADDRESS as u8)
    }
}

impl SpiBusAdapter {
    /// An adapter whose `SNAPSHOT` command bit writes `address` (the
    /// default is the controller's `SNAPSHOT` register).
    pub fn with_snapshot_address(address: u8) -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            sclk: Default::default(),
            cs_n: Default::default(),
            mosi: Default::default(),
            miso: Default::default(),
            miso_oe: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            bus_read_data: Default::default(),
            frame_error: Default::default(),
            sclk_meta: Default::default(),
            sclk_sync: Default::default(),
            sclk_last: Default::default(),
            select_meta: Default::default(),
            select_sync: Default::default(),
            select_last: Default::default(),
            mosi_meta: Default::default(),
            mosi_sync: Default::default(),
            in_frame: Default::default(),
            since_edge: Default::default(),
            overspeed: Default::default(),
            bit_count: Default::default(),
            position: Default::default(),
            command: Default::default(),
            address: Default::default(),
            crc_in: Default::default(),
            crc_out: Default::default(),
            in_word: Default::default(),
            out_shift: Default::default(),
            complete: Default::default(),
            crc_error: Default::default(),
            good: Default::default(),
            last_crc_error: Default::default(),
            last_overspeed: Default::default(),
            last_aborted: Default::default(),
            frame_error_reg: Default::default(),
            out_index: Default::default(),
            remaining: Default::default(),
            snapshot_pending: Default::default(),
            writing: Default::default(),
            index: Default::default(),
            op_address: Default::default(),
            bus_address_reg: Default::default(),
            write_stage: Default::default(),
            write_snapshot: Default::default(),
            bus_read_reg: Default::default(),
            read_ack: Default::default(),
            read_index: Default::default(),
            ack_index: Default::default(),
            // Collisions: the buffer is written (a captured word, a read's
            // answer) and read (the bus engine, MISO) in different phases
            // of frames at least 5 bytes apart, so no word read in a write's
            // clock is ever used. Power-up: it is read at every clock.
            buffer: HoldingRam::collisions_unobserved().power_up_unobserved(),
            is_write: Default::default(),
            words: Default::default(),
            words4: Default::default(),
            crc_position_of: Default::default(),
            end_position_of: Default::default(),
            crc_position: Default::default(),
            end_position: Default::default(),
            geometry: Default::default(),
            at_p0: Default::default(),
            at_p1: Default::default(),
            at_p2: Default::default(),
            at_crc: Default::default(),
            capture_lane: Default::default(),
            capture_index: Default::default(),
            out_crc_lane: Default::default(),
            word_lane: Default::default(),
            crc_lane: Default::default(),
            sclk_edge: Default::default(),
            rise: Default::default(),
            frame_start: Default::default(),
            frame_end: Default::default(),
            overspeed_any: Default::default(),
            mosi_word: Default::default(),
            in_word_next: Default::default(),
            crc_in_shifted: Default::default(),
            crc_in_next: Default::default(),
            crc_out_shifted: Default::default(),
            crc_out_next: Default::default(),
            crc_ok: Default::default(),
            status_overspeed: Default::default(),
            status_crc: Default::default(),
            last_status_crc: Default::default(),
            last_status_overspeed: Default::default(),
            last_status_aborted: Default::default(),
            kept_overspeed: Default::default(),
            kept_crc: Default::default(),
            byte_done: Default::default(),
            capture: Default::default(),
            busy: Default::default(),
            snapshot_address: konst(address as u64),
            count_field: konst(0x3c),
            poly: konst(0x07),
            poly_word: konst(0x0700_0000),
            count_mask_5: konst(0x0f),
            one_5: konst(1),
            two_5: konst(2),
            marker_word: konst(0xa000_0000),
            overspeed_word: konst(0x0200_0000),
            crc_error_word: konst(0x0100_0000),
            aborted_word: konst(0x0400_0000),
            zero_32: konst(0),
            one_32: konst(1),
            p0: konst(0),
            p1: konst(1),
            p2: konst(2),
            p3: konst(3),
            p6: konst(6),
            p7: konst(7),
            p_last: konst(127),
            lane_2: konst(2),
            lane_3: konst(3),
            one_4: konst(1),
            seven_3: konst(7),
            two_2: konst(2),
            one_2: konst(1),
            one_3: konst(1),
            one_8: konst(1),
            zero_2: konst(0),
            zero_3: konst(0),
            zero_4: konst(0),
            zero_5: konst(0),
            zero_7: konst(0),
            zero_8: konst(0),
        }
    }
}

impl Logic for SpiBusAdapter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            sclk_meta,
            sclk_sync,
            sclk_last,
            select_meta,
            select_sync,
            select_last,
            mosi_meta,
            mosi_sync,
            in_frame,
            since_edge,
            overspeed,
            bit_count,
            position,
            command,
            crc_position,
            end_position,
            geometry,
            at_p0,
            at_p1,
            at_p2,
            at_crc,
            capture_lane,
            capture_index,
            out_crc_lane,
            word_lane,
            crc_lane,
            address,
            crc_in,
            crc_out,
            in_word,
            out_shift,
            complete,
            crc_error,
            good,
            last_crc_error,
            last_overspeed,
            last_aborted,
            frame_error_reg,
            out_index,
            remaining,
            snapshot_pending,
            writing,
            index,
            op_address,
            bus_address_reg,
            write_stage,
            write_snapshot,
            bus_read_reg,
            read_ack,
            read_index,
            ack_index
        );
        clock!(self, clock, buffer);
        self.sclk_meta.d.next = self.sclk.val();
        self.sclk_sync.d.next = self.sclk_meta.q.val();
        self.sclk_last.d.next = self.sclk_sync.q.val();
        self.select_meta.d.next = !self.cs_n.val();
        self.select_sync.d.next = self.select_meta.q.val();
        self.select_last.d.next = self.select_sync.q.val();
        self.mosi_meta.d.next = self.mosi.val();
        self.mosi_sync.d.next = self.mosi_meta.q.val();

        self.miso.next = self.out_shift.q.val().get_bit(31);
        self.miso_oe.next = !self.cs_n.val();
        self.bus_address.next = self.bus_address_reg.q.val();
        self.bus_write.next = self.write_stage.q.val();
        self.bus_read.next = self.bus_read_reg.q.val();
        self.frame_error.next = self.frame_error_reg.q.val();
        self.bus_write_data.next = self.buffer.read_data.val();
        if self.write_snapshot.q.val() {
            self.bus_write_data.next = self.zero_32.val();
        }

        // The frame's geometry, from its command byte (valid from byte 1).
        self.is_write.next = self.command.q.val().get_bit(7);
        self.words.next = self.command.q.val().get_bits::<5>(0) & self.count_mask_5.val();
        self.words4.next = (self.command.q.val().get_bits::<7>(0) << 2) & self.count_field.val();
        self.end_position_of.next = self.words4.val() + self.p7.val();
        self.crc_position_of.next = self.p2.val();
        if self.is_write.val() {
            self.crc_position_of.next = self.words4.val() + self.p7.val();
        }

        self.sclk_edge.next = self.sclk_sync.q.val() ^ self.sclk_last.q.val();
        self.rise.next = self.sclk_sync.q.val()
            & !self.sclk_last.q.val()
            & self.in_frame.q.val()
            & self.select_sync.q.val();
        self.frame_start.next = self.select_sync.q.val() & !self.select_last.q.val();
        self.frame_end.next = self.in_frame.q.val() & !self.select_sync.q.val();
        self.overspeed_any.next = self.overspeed.q.val()
            | (self.in_frame.q.val()
                & self.select_sync.q.val()
                & self.sclk_edge.val()
                & !self.since_edge.q.val().get_bit(1));
        self.overspeed.d.next = self.overspeed_any.val();
        if self.sclk_edge.val() {
            self.since_edge.d.next = self.one_2.val();
        } else if !self.since_edge.q.val().get_bit(1) {
            self.since_edge.d.next = self.since_edge.q.val() + self.one_2.val();
        }
        self.frame_error_reg.d.next = false;

        // The bits at a rise: MOSI into the word and the CRC, MISO's CRC.
        self.mosi_word.next = self.zero_32.val();
        if self.mosi_sync.q.val() {
            self.mosi_word.next = self.one_32.val();
        }
        self.in_word_next.next = (self.in_word.q.val() << 1) | self.mosi_word.val();
        self.crc_in_shifted.next = self.crc_in.q.val() << 1;
        self.crc_in_next.next = self.crc_in_shifted.val();
        if self.crc_in.q.val().get_bit(7) ^ self.mosi_sync.q.val() {
            self.crc_in_next.next = self.crc_in_shifted.val() ^ self.poly.val();
        }
        self.crc_out_shifted.next = self.crc_out.q.val() << 1;
        self.crc_out_next.next = self.crc_out_shifted.val();
        if self.crc_out.q.val().get_bit(31) ^ self.out_shift.q.val().get_bit(31) {
            self.crc_out_next.next = self.crc_out_shifted.val() ^ self.poly_word.val();
        }
        self.crc_ok.next = !self.crc_in_next.val().any();
        self.status_overspeed.next = self.zero_32.val();
        if self.overspeed_any.val() {
            self.status_overspeed.next = self.overspeed_word.val();
        }
        self.status_crc.next = self.crc_error_word.val();
        if self.crc_ok.val() {
            self.status_crc.next = self.zero_32.val();
        }
        // What the current byte's completion does, decided from its
        // position a clock after the position changes (rises are at least
        // two clocks apart, and the frame's start sets the values for
        // byte 0), so no magnitude compare is on the rise's path.
        self.at_p0.d.next = self.position.q.val() == self.p0.val();
        self.at_p1.d.next = self.position.q.val() == self.p1.val();
        self.at_p2.d.next = self.position.q.val() == self.p2.val();
        self.at_crc.d.next =
            (self.position.q.val() == self.crc_position.q.val()) & self.geometry.q.val();
        self.capture_lane.d.next = self.is_write.val()
            & (self.position.q.val() >= self.p6.val())
            & (self.position.q.val() < self.crc_position.q.val())
            & (self.position.q.val().get_bits::<2>(0) == self.lane_2.val());
        self.capture_index.d.next = self.position.q.val().get_bits::<4>(2) - self.one_4.val();
        self.out_crc_lane.d.next = !self.is_write.val()
            & (self.position.q.val() >= self.p3.val())
            & (self.position.q.val() <= self.end_position.q.val());
        self.word_lane.d.next = !self.is_write.val()
            & (self.position.q.val() >= self.p3.val())
            & (self.position.q.val().get_bits::<2>(0) == self.lane_3.val())
            & (self.position.q.val() < self.end_position.q.val());
        self.crc_lane.d.next =
            !self.is_write.val() & (self.position.q.val() == self.end_position.q.val());
        self.byte_done.next = self.rise.val() & (self.bit_count.q.val() == self.seven_3.val());
        self.capture.next = self.byte_done.val() & self.capture_lane.q.val();

        self.kept_overspeed.next = self.zero_32.val();
        if self.overspeed.q.val() {
            self.kept_overspeed.next = self.overspeed_word.val();
        }
        self.kept_crc.next = self.zero_32.val();
        if self.crc_error.q.val() {
            self.kept_crc.next = self.crc_error_word.val();
        }
        if self.rise.val() {
            self.bit_count.d.next = self.bit_count.q.val() + self.one_3.val();
            self.crc_in.d.next = self.crc_in_next.val();
            self.in_word.d.next = self.in_word_next.val();
            if self.out_crc_lane.q.val() {
                self.crc_out.d.next = self.crc_out_next.val();
            }
            self.out_shift.d.next = self.out_shift.q.val() << 1;
            if self.bit_count.q.val() == self.seven_3.val() {
                if self.position.q.val() != self.p_last.val() {
                    self.position.d.next = self.position.q.val() + self.p1.val();
                }
                if self.at_p0.q.val() {
                    self.command.d.next = self.in_word_next.val().get_bits::<8>(0);
                }
                if self.at_p1.q.val() {
                    self.address.d.next = self.in_word_next.val().get_bits::<8>(0);
                    self.crc_position.d.next = self.crc_position_of.val();
                    self.end_position.d.next = self.end_position_of.val();
                    self.geometry.d.next = true;
                }
                if (self.at_crc.q.val() & !self.complete.q.val())
                    | (self.at_p2.q.val() & !self.crc_ok.val())
                {
                    // The verdict: the CRC over every bit up to here is 0
                    // (the header's at byte 2, the frame's at its end). A
                    // frame has one: a write whose header failed gets no
                    // second verdict at its frame CRC, which a corrupted
                    // count would have placed on any byte.
                    self.complete.d.next = true;
                    self.crc_error.d.next = !self.crc_ok.val();
                    self.good.d.next = self.crc_ok.val() & !self.overspeed_any.val();
                    self.out_shift.d.next = self.marker_word.val()
                        | self.status_overspeed.val()
                        | self.status_crc.val();
                    if self.crc_ok.val() & !self.overspeed_any.val() {
                        self.remaining.d.next = self.words.val() + self.one_5.val();
                        self.snapshot_pending.d.next = false;
                        if !self.is_write.val() & self.command.q.val().get_bit(6) {
                            self.remaining.d.next = self.words.val() + self.two_5.val();
                            self.snapshot_pending.d.next = true;
                        }
                        self.writing.d.next = self.is_write.val();
                        self.index.d.next = self.zero_4.val();
                        self.op_address.d.next = self.address.q.val();
                    }
                }
                if self.complete.q.val() & !self.good.q.val() {
                    self.out_shift.d.next =
                        self.marker_word.val() | self.kept_overspeed.val() | self.kept_crc.val();
                }
                if self.good.q.val() & self.word_lane.q.val() {
                    self.out_shift.d.next = self.buffer.read_data.val();
                    self.out_index.d.next = self.out_index.q.val() + self.one_4.val();
                }
                if self.good.q.val() & self.crc_lane.q.val() {
                    self.out_shift.d.next = self.crc_out_next.val();
                }
            }
        }
        self.last_status_crc.next = self.zero_32.val();
        if self.last_crc_error.q.val() {
            self.last_status_crc.next = self.crc_error_word.val();
        }
        self.last_status_overspeed.next = self.zero_32.val();
        if self.last_overspeed.q.val() {
            self.last_status_overspeed.next = self.overspeed_word.val();
        }
        self.last_status_aborted.next = self.zero_32.val();
        if self.last_aborted.q.val() {
            self.last_status_aborted.next = self.aborted_word.val();
        }
        if self.frame_start.val() {
            self.in_frame.d.next = true;
            self.geometry.d.next = false;
            self.at_p0.d.next = true;
            self.at_p1.d.next = false;
            self.at_p2.d.next = false;
            self.at_crc.d.next = false;
            self.capture_lane.d.next = false;
            self.out_crc_lane.d.next = false;
            self.word_lane.d.next = false;
            self.crc_lane.d.next = false;
            self.bit_count.d.next = self.zero_3.val();
            self.position.d.next = self.zero_7.val();
            self.crc_in.d.next = self.zero_8.val();
            self.crc_out.d.next = self.zero_32.val();
            self.overspeed.d.next = false;
            self.complete.d.next = false;
            self.crc_error.d.next = false;
            self.good.d.next = false;
            self.out_index.d.next = self.zero_4.val();
            self.since_edge.d.next = self.two_2.val();
            self.out_shift.d.next = self.marker_word.val()
                | self.last_status_crc.val()
                | self.last_status_overspeed.val()
                | self.last_status_aborted.val();
        }
        if self.frame_end.val() {
            self.in_frame.d.next = false;
            self.last_aborted.d.next = !self.complete.q.val();
            self.last_overspeed.d.next = self.overspeed.q.val();
            self.last_crc_error.d.next = self.crc_error.q.val();
            self.frame_error_reg.d.next =
                !self.complete.q.val() | self.overspeed.q.val() | self.crc_error.q.val();
            self.out_shift.d.next = self.zero_32.val();
        }

        // The bus engine: one strobe a clock once a frame has passed.
        self.busy.next = self.remaining.q.val().any();
        self.write_stage.d.next = false;
        self.bus_read_reg.d.next = false;
        self.buffer.read_enable.next = true;
        self.buffer.read_address.next = self.out_index.q.val();
        if self.busy.val() {
            self.remaining.d.next = self.remaining.q.val() - self.one_5.val();
            self.buffer.read_address.next = self.index.q.val();
            if self.snapshot_pending.q.val() {
                self.write_stage.d.next = true;
                self.write_snapshot.d.next = true;
                self.bus_address_reg.d.next = self.snapshot_address.val();
                self.snapshot_pending.d.next = false;
            } else {
                self.bus_address_reg.d.next = self.op_address.q.val();
                self.op_address.d.next = self.op_address.q.val() + self.one_8.val();
                self.index.d.next = self.index.q.val() + self.one_4.val();
                if self.writing.q.val() {
                    self.write_stage.d.next = true;
                    self.write_snapshot.d.next = false;
                } else {
                    self.bus_read_reg.d.next = true;
                    self.read_index.d.next = self.index.q.val();
                }
            }
        }
        self.read_ack.d.next = self.bus_read_reg.q.val();
        self.ack_index.d.next = self.read_index.q.val();
        self.buffer.write_enable.next =
            (self.capture.val() | self.read_ack.q.val()) & !self.reset.val();
        self.buffer.write_address.next = self.ack_index.q.val();
        self.buffer.write_data.next = self.bus_read_data.val();
        if self.capture.val() {
            self.buffer.write_address.next = self.capture_index.q.val();
            self.buffer.write_data.next = self.in_word_next.val();
        }

        if self.reset.val() {
            self.in_frame.d.next = false;
            self.geometry.d.next = false;
            self.at_p0.d.next = true;
            self.at_p1.d.next = false;
            self.at_p2.d.next = false;
            self.at_crc.d.next = false;
            self.capture_lane.d.next = false;
            self.out_crc_lane.d.next = false;
            self.word_lane.d.next = false;
            self.crc_lane.d.next = false;
            self.crc_position.d.next = self.zero_7.val();
            self.end_position.d.next = self.zero_7.val();
            self.since_edge.d.next = self.zero_2.val();
            self.overspeed.d.next = false;
            self.bit_count.d.next = self.zero_3.val();
            self.position.d.next = self.zero_7.val();
            self.command.d.next = self.zero_8.val();
            self.address.d.next = self.zero_8.val();
            self.crc_in.d.next = self.zero_8.val();
            self.crc_out.d.next = self.zero_32.val();
            self.in_word.d.next = self.zero_32.val();
            self.out_shift.d.next = self.zero_32.val();
            self.complete.d.next = false;
            self.crc_error.d.next = false;
            self.good.d.next = false;
            self.last_crc_error.d.next = false;
            self.last_overspeed.d.next = false;
            self.last_aborted.d.next = false;
            self.frame_error_reg.d.next = false;
            self.out_index.d.next = self.zero_4.val();
            self.remaining.d.next = self.zero_5.val();
            self.snapshot_pending.d.next = false;
            self.writing.d.next = false;
            self.index.d.next = self.zero_4.val();
            self.op_address.d.next = self.zero_8.val();
            self.bus_address_reg.d.next = self.zero_8.val();
            self.write_stage.d.next = false;
            self.write_snapshot.d.next = false;
            self.bus_read_reg.d.next = false;
            self.read_ack.d.next = false;
            self.read_index.d.next = self.zero_4.val();
            self.ack_index.d.next = self.zero_4.val();
        }
    }
}

crate::vector_ports!(impl[] SpiBusAdapter {
    inputs: [reset, sclk, cs_n, mosi, bus_read_data],
    outputs: [miso, miso_oe, bus_address, bus_write_data, bus_write, bus_read, frame_error],
});
