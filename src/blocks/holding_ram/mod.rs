//! # `HoldingRam`: block RAM whose read port holds its word between reads
//!
//! One clock, one synchronous write port and one synchronous read port
//! with a read enable: the read register loads `mem[read_address]` only at
//! an edge with `read_enable` high and holds it otherwise. rust-hdl's `RAM`
//! reads at every edge; the iCE40 block RAM has a read-clock enable
//! (SB_RAM40_4K's RCLKE), and this block is that RAM, so a register
//! readback can keep its answer without a holding register after the RAM.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing and bad input
//! * Read latency 1: an enabled read at edge t shows its word after edge t.
//! * Read during write of the same word at the same edge: the read returns
//!   the old word (read-first), in the rust-hdl simulation and in the
//!   Verilog. On iCE40 the hardware's collision result is undefined, so
//!   yosys adds a small bypass that makes it read-first (a delayed write
//!   and a compare: flip-flops and LUTs in the user's synthesis report).
//! * [`HoldingRam::collisions_unobserved`] builds a RAM whose user never
//!   looks at the word read in such a collision (a FIFO that bypasses it,
//!   say). Its Verilog carries yosys's `no_rw_check` attribute, so yosys
//!   adds no bypass, and the collision's word is then undefined on the
//!   hardware (the simulations still read the old word). The user states
//!   why the word is never observed, and proves it where it can.
//! * [`HoldingRam::power_up_unobserved`] drops the read register's
//!   power-up 0 from the Verilog, for a user that never looks at
//!   `read_data` before its first enabled read (it gates the word with a
//!   valid bit of its own, say). An iCE40 block RAM's output register has
//!   no initial value, so yosys otherwise gates the output with a
//!   flip-flop and a LUT a bit. Before the first read the word is then
//!   undefined on the hardware (0 in the simulations).
//! * Every word is 0 at power-up (block-RAM initialization in the Verilog;
//!   the simulation starts empty, which reads as 0). Nothing resets the
//!   words or the read register: a user who needs a 0 after reset reads an
//!   address that is never written, with `read_enable` during reset.
//!
//! ## Model
//! The model is the memory itself, a map from address to word, and a held
//! read word: [`HoldingRamModel`].

use std::collections::BTreeMap;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port: the one source of the datasheet's port table.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock of both ports"),
    port("read_enable", "1", "load the read register at this edge"),
    port("read_address", "N", "word read at an edge with `read_enable`"),
    port(
        "read_data",
        "D",
        "registered: the word at `read_address` from the edge of the last enabled read, held until the next one; 0 before the first",
    ),
    port("write_enable", "1", "write `write_data` at `write_address` at this edge"),
    port("write_address", "N", "word written"),
    port("write_data", "D", "data written"),
];

/// Block RAM of 2^N words of type D with a read enable. See the
/// [module documentation](self).
#[derive(LogicBlock, Default)]
pub struct HoldingRam<D: Synth, const N: usize> {
    /// Rising-edge clock of both ports.
    pub clock: Signal<In, Clock>,
    /// Load the read register at this edge.
    pub read_enable: Signal<In, Bit>,
    /// Word read.
    pub read_address: Signal<In, Bits<N>>,
    /// The last enabled read's word, held.
    pub read_data: Signal<Out, D>,
    /// Write at this edge.
    pub write_enable: Signal<In, Bit>,
    /// Word written.
    pub write_address: Signal<In, Bits<N>>,
    /// Data written.
    pub write_data: Signal<In, D>,
    _memory: BTreeMap<Bits<N>, D>,
    /// The Verilog has no read-during-write guarantee (`no_rw_check`).
    _collisions_unobserved: bool,
    /// The Verilog gives the read register no power-up value.
    _power_up_unobserved: bool,
}

impl<D: Synth, const N: usize> HoldingRam<D, N> {
    /// A RAM whose read-during-write word is never looked at: no
    /// read-first logic on the hardware. See the
    /// [module documentation](self).
    pub fn collisions_unobserved() -> Self {
        Self {
            _collisions_unobserved: true,
            ..Default::default()
        }
    }

    /// This RAM, its read register without a power-up value: its user
    /// never looks at `read_data` before the first enabled read. See the
    /// [module documentation](self).
    pub fn power_up_unobserved(self) -> Self {
        Self {
            _power_up_unobserved: true,
            ..self
        }
    }
}

impl<D: Synth, const N: usize> Logic for HoldingRam<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            // Read first: the read sees the word as it was before this
            // edge's write.
            if self.read_enable.val() {
                self.read_data.next = *self
                    ._memory
                    .get(&self.read_address.val())
                    .unwrap_or(&D::default());
            }
            if self.write_enable.val() {
                self._memory
                    .insert(self.write_address.val(), self.write_data.val());
            }
        }
    }

    fn connect(&mut self) {
        self.read_data.connect();
    }

    fn hdl(&self) -> Verilog {
        // Without a bypass: the user never reads a colliding word.
        let attribute = if self._collisions_unobserved {
            "(* no_rw_check *) "
        } else {
            ""
        };
        Verilog::Custom(format!(
            "\
{attribute}reg [{msb}:0] mem [0:{last}];
integer i;

{power_up_comment}
initial begin
   for (i = 0; i <= {last}; i = i + 1) mem[i] = 0;
{power_up}end

always @(posedge clock) begin
   if (read_enable) begin
      read_data <= mem[read_address];
   end
end

always @(posedge clock) begin
   if (write_enable) begin
      mem[write_address] <= write_data;
   end
end
",
            power_up_comment = if self._power_up_unobserved {
                "// Block RAM powers up 0, and so do the words here (the read register\n\
                 // has no power-up value: its user gates it)."
            } else {
                "// Block RAM powers up 0, and so do the words and the read register here."
            },
            power_up = if self._power_up_unobserved {
                ""
            } else {
                "   read_data = 0;\n"
            },
            msb = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}

crate::vector_ports!(impl[const N: usize] HoldingRam<Bits<16>, N> {
    inputs: [read_enable, read_address, write_enable, write_address, write_data],
    outputs: [read_data],
});

/// Reference model of [`HoldingRam`] with 16-bit words: the words and the
/// held read word.
#[derive(Clone, Debug, Default)]
pub struct HoldingRamModel {
    words: BTreeMap<u64, u64>,
    read_data: u64,
}

impl HoldingRamModel {
    /// One clock edge; returns `read_data` after it.
    pub fn step(&mut self, read_enable: bool, read_address: u64, write: Option<(u64, u64)>) -> u64 {
        if read_enable {
            self.read_data = self.words.get(&read_address).copied().unwrap_or(0);
        }
        if let Some((address, data)) = write {
            self.words.insert(address, data);
        }
        self.read_data
    }
}
