//! Reference model of [`super::SpiBusAdapter`], cycle-exact: the same
//! registers, updated from their values before the edge.

use super::frame::{crc8_bit, COMMAND_COUNT_MASK, COMMAND_SNAPSHOT, COMMAND_WRITE, MAX_WORDS};
use super::frame::{STATUS_MARKER, STATUS_OVERSPEED};

/// Inputs of one clock: the pins and the slave's answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpiInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// SPI clock (mode 0: idle low, data sampled on the rising edge).
    pub sclk: bool,
    /// Chip select, active low.
    pub cs_n: bool,
    /// Master out, slave in.
    pub mosi: bool,
    /// The slave's read data.
    pub bus_read_data: u32,
}

impl Default for SpiInputs {
    /// An idle bus: CS high, SCLK low.
    fn default() -> Self {
        Self {
            reset: false,
            sclk: false,
            cs_n: true,
            mosi: false,
            bus_read_data: 0,
        }
    }
}

impl SpiInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.sclk as u64,
            self.cs_n as u64,
            self.mosi as u64,
            self.bus_read_data as u64,
        ]
    }
}

/// Outputs after one clock edge (`miso_oe` with this clock's pins).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SpiOutputs {
    /// Master in, slave out.
    pub miso: bool,
    /// Drive MISO.
    pub miso_oe: bool,
    /// Register address of the bus strobe.
    pub bus_address: u8,
    /// Data of the write strobe.
    pub bus_write_data: u32,
    /// Write strobe.
    pub bus_write: bool,
    /// Read strobe.
    pub bus_read: bool,
    /// A frame ended with a flag in its status.
    pub frame_error: bool,
}

impl SpiOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            miso: v[0] != 0,
            miso_oe: v[1] != 0,
            bus_address: v[2] as u8,
            bus_write_data: v[3] as u32,
            bus_write: v[4] != 0,
            bus_read: v[5] != 0,
            frame_error: v[6] != 0,
        }
    }
}

/// The model's registers, named as in the RTL.
#[derive(Clone, Copy, Debug, Default)]
struct State {
    sclk_meta: bool,
    sclk_sync: bool,
    sclk_last: bool,
    select_meta: bool,
    select_sync: bool,
    select_last: bool,
    mosi_meta: bool,
    mosi_sync: bool,
    in_frame: bool,
    since_edge: u8,
    overspeed: bool,
    bit_count: u8,
    position: u8,
    command: u8,
    address: u8,
    crc_in: u8,
    crc_out: u8,
    in_word: u32,
    out_shift: u32,
    complete: bool,
    crc_error: bool,
    good: bool,
    last_flags: u8,
    frame_error: bool,
    out_index: u8,
    remaining: u8,
    snapshot_pending: bool,
    writing: bool,
    index: u8,
    op_address: u8,
    bus_address: u8,
    write_stage: bool,
    write_snapshot: bool,
    bus_read: bool,
    read_ack: bool,
    read_index: u8,
    ack_index: u8,
    ram_read_data: u32,
}

/// A status byte in bits 31..24, as the adapter loads it for MISO.
fn status_word(overspeed: bool, crc_error: bool) -> u32 {
    (STATUS_MARKER as u32 | (overspeed as u32 * STATUS_OVERSPEED as u32) | crc_error as u32) << 24
}

/// Cycle-exact model of the SPI adapter.
#[derive(Clone, Debug)]
pub struct SpiBusModel {
    s: State,
    ram: [u32; MAX_WORDS],
    snapshot_address: u8,
}

impl SpiBusModel {
    /// An adapter in its power-up state that writes `snapshot_address` for
    /// a read frame's `SNAPSHOT` bit.
    pub fn new(snapshot_address: u8) -> Self {
        Self {
            s: State::default(),
            ram: [0; MAX_WORDS],
            snapshot_address,
        }
    }

    /// The outputs the registers show, with `cs_n` the pin this clock.
    fn outputs(&self, cs_n: bool) -> SpiOutputs {
        let s = &self.s;
        SpiOutputs {
            miso: s.out_shift >> 31 != 0,
            miso_oe: !cs_n,
            bus_address: s.bus_address,
            bus_write_data: if s.write_snapshot { 0 } else { s.ram_read_data },
            bus_write: s.write_stage,
            bus_read: s.bus_read,
            frame_error: s.frame_error,
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: SpiInputs) -> SpiOutputs {
        let q = self.s;
        let mut d = q;
        // Synchronizers: never reset, like the RTL's.
        d.sclk_meta = i.sclk;
        d.sclk_sync = q.sclk_meta;
        d.sclk_last = q.sclk_sync;
        d.select_meta = !i.cs_n;
        d.select_sync = q.select_meta;
        d.select_last = q.select_sync;
        d.mosi_meta = i.mosi;
        d.mosi_sync = q.mosi_meta;

        let is_write = q.command & COMMAND_WRITE != 0;
        let words4 = (q.command & COMMAND_COUNT_MASK) * 4;
        let crc_position = if is_write { 7 + words4 } else { 2 };
        let end_position = 7 + words4;

        let edge = q.sclk_sync != q.sclk_last;
        let rise = q.sclk_sync && !q.sclk_last && q.in_frame && q.select_sync;
        let start = q.select_sync && !q.select_last;
        let end = q.in_frame && !q.select_sync;
        let overspeed_now = q.in_frame && q.select_sync && edge && q.since_edge < 2;
        let overspeed_any = q.overspeed || overspeed_now;
        d.since_edge = if edge { 1 } else { (q.since_edge + 1).min(2) };
        d.overspeed = overspeed_any;
        d.frame_error = false;

        let mut ram_write = None;
        if rise {
            let mosi = q.mosi_sync;
            let crc_in_next = crc8_bit(q.crc_in, mosi);
            let in_word_next = q.in_word << 1 | mosi as u32;
            let p = q.position;
            d.bit_count = (q.bit_count + 1) % 8;
            d.crc_in = crc_in_next;
            d.in_word = in_word_next;
            let crc_out_next = crc8_bit(q.crc_out, q.out_shift >> 31 != 0);
            if !is_write && p >= 3 && p <= end_position {
                d.crc_out = crc_out_next;
            }
            d.out_shift = q.out_shift << 1;
            if q.bit_count == 7 {
                let byte = in_word_next as u8;
                d.position = (p + 1).min(127);
                if p == 0 {
                    d.command = byte;
                }
                if p == 1 {
                    d.address = byte;
                }
                if is_write && p >= 6 && p < crc_position && p % 4 == 2 {
                    ram_write = Some((((p >> 2) - 1) % MAX_WORDS as u8, in_word_next));
                }
                let crc_ok = crc_in_next == 0;
                if (p == crc_position && !q.complete) || (p == 2 && !crc_ok) {
                    let pass = crc_ok && !overspeed_any;
                    d.complete = true;
                    d.crc_error = !crc_ok;
                    d.good = pass;
                    d.out_shift = status_word(overspeed_any, !crc_ok);
                    if pass {
                        let snapshot = !is_write && q.command & COMMAND_SNAPSHOT != 0;
                        d.remaining = (q.command & COMMAND_COUNT_MASK) + 1 + snapshot as u8;
                        d.snapshot_pending = snapshot;
                        d.writing = is_write;
                        d.index = 0;
                        d.op_address = q.address;
                    }
                }
                if q.complete && !q.good {
                    d.out_shift = status_word(q.overspeed, q.crc_error);
                }
                if q.good && !is_write && p >= 3 && p % 4 == 3 && p < end_position {
                    d.out_shift = q.ram_read_data;
                    d.out_index = (q.out_index + 1) % MAX_WORDS as u8;
                }
                if q.good && !is_write && p == end_position {
                    d.out_shift = (crc_out_next as u32) << 24;
                }
            }
        }
        if start {
            d.in_frame = true;
            d.bit_count = 0;
            d.position = 0;
            d.crc_in = 0;
            d.crc_out = 0;
            d.overspeed = false;
            d.complete = false;
            d.crc_error = false;
            d.good = false;
            d.out_index = 0;
            d.since_edge = 2;
            d.out_shift = ((STATUS_MARKER | q.last_flags) as u32) << 24;
        }
        if end {
            d.in_frame = false;
            let flags = (!q.complete as u8) << 2 | (q.overspeed as u8) << 1 | q.crc_error as u8;
            d.last_flags = flags;
            d.frame_error = flags != 0;
            d.out_shift = 0;
        }

        // The bus engine: one strobe a clock once a frame has passed.
        let busy = q.remaining != 0;
        d.write_stage = false;
        d.bus_read = false;
        let mut read_address = q.out_index;
        if busy {
            d.remaining = q.remaining - 1;
            if q.snapshot_pending {
                d.write_stage = true;
                d.write_snapshot = true;
                d.bus_address = self.snapshot_address;
                d.snapshot_pending = false;
            } else {
                d.bus_address = q.op_address;
                d.op_address = q.op_address.wrapping_add(1);
                d.index = (q.index + 1) % MAX_WORDS as u8;
                if q.writing {
                    d.write_stage = true;
                    d.write_snapshot = false;
                } else {
                    d.bus_read = true;
                    d.read_index = q.index;
                }
            }
            read_address = q.index;
        }
        d.read_ack = q.bus_read;
        d.ack_index = q.read_index;
        // Read-first: the read register takes the word from before this
        // edge's write.
        d.ram_read_data = self.ram[read_address as usize % MAX_WORDS];
        if q.read_ack {
            ram_write = ram_write.or(Some((q.ack_index, i.bus_read_data)));
        }
        if let (Some((at, word)), false) = (ram_write, i.reset) {
            self.ram[at as usize % MAX_WORDS] = word;
        }

        if i.reset {
            d = State {
                sclk_meta: d.sclk_meta,
                sclk_sync: d.sclk_sync,
                sclk_last: d.sclk_last,
                select_meta: d.select_meta,
                select_sync: d.select_sync,
                select_last: d.select_last,
                mosi_meta: d.mosi_meta,
                mosi_sync: d.mosi_sync,
                ram_read_data: d.ram_read_data,
                ..State::default()
            };
        }
        self.s = d;
        self.outputs(i.cs_n)
    }
}

crate::lockstep_model!(SpiBusModel {
    inputs: SpiInputs,
    outputs: SpiOutputs,
    step: |model, inputs| model.step(*inputs),
});
