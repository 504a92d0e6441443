//! # `WordAssembler`: a narrow register bus to a wide one, with coherent reads and atomic writes
//!
//! A master with an `N`-bit data bus reaches `W`-bit registers as
//! `W / N` consecutive narrow addresses (parts), lowest part first at the
//! lowest address: narrow address = wide address × (W/N) + part. Torn
//! accesses are where narrow buses go wrong: a 32-bit position read as two
//! halves can combine the low half of one value with the high half of the
//! next. This block makes both directions whole:
//!
//! * **Reads never tear.** Reading part 0 reads the wide register once
//!   (one `bus_read`) and latches the whole word; reading parts 1 and up of
//!   the same register returns the latched word's parts and reads nothing.
//! * **Writes are atomic.** Writes of the lower parts go into a holding
//!   register; writing the highest part commits the whole word as one
//!   `bus_write`. No part of a register changes before the whole word does.
//!
//! Both sides are this project's synchronous register bus. The wide
//! strobes are combinational from the narrow ones (same clock), and the
//! narrow read data is valid in the clock after `narrow_read`, as the wide
//! slave's is: the block adds no clock of latency. It sits between a
//! [`crate::blocks::bus_synchronizer::BusSynchronizer`] (the pins) and the
//! register slave; [`crate::blocks::narrow_bus_adapter`] composes the two.
//!
//! ## Ports
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing, in clocks
//! | event | latency |
//! |---|---|
//! | `narrow_read` of part 0 to `bus_read` | 0 (same clock) |
//! | `narrow_read` to `narrow_read_data` valid | 1 (as the wide slave) |
//! | highest-part `narrow_write` to `bus_write` | 0 (same clock) |
//! | lower-part `narrow_write` | no wide strobe; held |
//! | offending strobe to `order_error` | 1 |
//!
//! ## Required order, and what breaking it does
//! Firmware reads a register part 0 first, then any higher parts; it
//! writes all lower parts (in any order), then the highest part, with no
//! other register's part written in between. Reads and writes do not
//! disturb each other (the read latch and the write holding register are
//! separate), so an interrupt handler that only reads cannot break a
//! write sequence of the code it interrupted.
//!
//! | broken rule | outcome | flagged |
//! |---|---|---|
//! | part k > 0 read without part 0 of the same register being the last part-0 read | the register is read fresh (one `bus_read`, latched) and its part k returned | `order_error` |
//! | highest part written without every lower part of the same register since the last commit | nothing is written (a torn word never reaches the register); the holding register empties | `order_error` |
//! | a lower part written while another register's parts are held | the held parts are dropped and the new write starts a new word | `order_error` |
//! | a lower part written twice | the later data is kept | no |
//! | part k > 0 read again | the same latched part | no |
//!
//! A latched word is a snapshot: reading the higher parts long after part 0
//! returns the value of the moment part 0 was read, even if the register
//! has changed since. That is the point.
//!
//! ## Parameters
//! `W / N` (the parts per word) must be a power of two from 2 to 8, and
//! `NA` must be `A + log2(W / N)`; `new` checks both.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

/// Meaning of every port.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: read latch and write holding register empty (0), no error"),
    port("narrow_address", "NA", "narrow word address: wide address * (W/N) + part"),
    port("narrow_write_data", "N", "data of `narrow_write`"),
    port("narrow_write", "1", "one-clock narrow write strobe"),
    port("narrow_read", "1", "one-clock narrow read strobe"),
    port("narrow_read_data", "N", "the read part, valid in the clock after `narrow_read`"),
    port("bus_address", "A", "wide address (`narrow_address` without its part bits), combinational"),
    port("bus_write_data", "W", "the assembled word of `bus_write`, combinational"),
    port("bus_write", "1", "one-clock wide write strobe: the highest part completed a word"),
    port("bus_read", "1", "one-clock wide read strobe: part 0 was read (or an out-of-order part)"),
    port("bus_read_data", "W", "the slave's read data, valid in the clock after `bus_read`"),
    port("order_error", "1", "one-clock pulse: the master broke the access order (torn write dropped, out-of-order read)"),
];

/// Narrow-to-wide register bus bridge. See the [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct WordAssembler<const A: usize, const NA: usize, const N: usize, const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Narrow word address.
    pub narrow_address: Signal<In, Bits<NA>>,
    /// Data of the narrow write.
    pub narrow_write_data: Signal<In, Bits<N>>,
    /// Narrow write strobe.
    pub narrow_write: Signal<In, Bit>,
    /// Narrow read strobe.
    pub narrow_read: Signal<In, Bit>,
    /// The part read, the clock after `narrow_read`.
    pub narrow_read_data: Signal<Out, Bits<N>>,
    /// Wide address.
    pub bus_address: Signal<Out, Bits<A>>,
    /// Assembled word.
    pub bus_write_data: Signal<Out, Bits<W>>,
    /// Wide write strobe.
    pub bus_write: Signal<Out, Bit>,
    /// Wide read strobe.
    pub bus_read: Signal<Out, Bit>,
    /// The slave's read data.
    pub bus_read_data: Signal<In, Bits<W>>,
    /// Access-order violation.
    pub order_error: Signal<Out, Bit>,
    // Read side: the word latched by the last wide read, and where from.
    latch: DFF<Bits<W>>,
    latch_address: DFF<Bits<A>>,
    latch_valid: DFF<Bit>,
    /// The read answered this clock comes from the slave, not the latch.
    answer_from_bus: DFF<Bit>,
    /// Bit offset of the part being answered.
    answer_offset: DFF<Bits<NA>>,
    // Write side: the lower parts written so far, and for which register.
    holding: DFF<Bits<W>>,
    held_parts: DFF<Bits<8>>,
    holding_address: DFF<Bits<A>>,
    error_reg: DFF<Bit>,
    part: Signal<Local, Bits<NA>>,
    offset: Signal<Local, Bits<NA>>,
    part_bit: Signal<Local, Bits<8>>,
    data_wide: Signal<Local, Bits<W>>,
    address_shifted: Signal<Local, Bits<NA>>,
    answer_word: Signal<Local, Bits<W>>,
    merged: Signal<Local, Bits<W>>,
    latch_hit: Signal<Local, Bit>,
    holding_hit: Signal<Local, Bit>,
    /// log2(W / N): the part bits of a narrow address.
    part_bits: Constant<Bits<NA>>,
    /// W / N - 1: the highest part, and the mask of the part bits.
    top_part: Constant<Bits<NA>>,
    /// log2(N): part to bit offset.
    part_to_offset: Constant<Bits<NA>>,
    /// One bit per lower part: every lower part held.
    lower_parts: Constant<Bits<8>>,
    part_ones: Constant<Bits<W>>,
    one: Constant<Bits<8>>,
    zero_parts: Constant<Bits<8>>,
    zero_na: Constant<Bits<NA>>,
    zero_w: Constant<Bits<W>>,
    zero_a: Constant<Bits<A>>,
}

impl<const A: usize, const NA: usize, const N: usize, const W: usize> WordAssembler<A, NA, N, W> {
    /// The block; panics if `W / N` is not a power of two from 2 to 8 or
    /// `NA != A + log2(W / N)` (a build-time parameter error).
    pub fn new() -> Self {
        let parts = W / N;
        assert!(
            N * parts == W && parts.is_power_of_two() && (2..=8).contains(&parts),
            "WordAssembler: W / N must be a power of two from 2 to 8 (W = {W}, N = {N})"
        );
        let part_bits = parts.trailing_zeros() as usize;
        assert!(
            NA == A + part_bits,
            "WordAssembler: NA must be A + log2(W / N) = {} (NA = {NA})",
            A + part_bits
        );
        assert!(
            NA < 64 && (W - N) < (1 << NA),
            "WordAssembler: NA = {NA} bits cannot hold the part offset {}",
            W - N
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            narrow_address: Default::default(),
            narrow_write_data: Default::default(),
            narrow_write: Default::default(),
            narrow_read: Default::default(),
            narrow_read_data: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            bus_read_data: Default::default(),
            order_error: Default::default(),
            latch: Default::default(),
            latch_address: Default::default(),
            latch_valid: Default::default(),
            answer_from_bus: Default::default(),
            answer_offset: Default::default(),
            holding: Default::default(),
            held_parts: Default::default(),
            holding_address: Default::default(),
            error_reg: Default::default(),
            part: Default::default(),
            offset: Default::default(),
            part_bit: Default::default(),
            data_wide: Default::default(),
            address_shifted: Default::default(),
            answer_word: Default::default(),
            merged: Default::default(),
            latch_hit: Default::default(),
            holding_hit: Default::default(),
            part_bits: Constant::new((part_bits as u64).into()),
            top_part: Constant::new(((parts - 1) as u64).into()),
            part_to_offset: Constant::new((N.trailing_zeros() as u64).into()),
            lower_parts: Constant::new((((1u64 << parts) >> 1) - 1).into()),
            part_ones: Constant::new(crate::blocks::width_mask(N as u32).into()),
            one: Constant::new(1u64.into()),
            zero_parts: Constant::new(0u64.into()),
            zero_na: Constant::new(0u64.into()),
            zero_w: Constant::new(0u64.into()),
            zero_a: Constant::new(0u64.into()),
        }
    }
}

impl<const A: usize, const NA: usize, const N: usize, const W: usize> Default
    for WordAssembler<A, NA, N, W>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<const A: usize, const NA: usize, const N: usize, const W: usize> Logic
    for WordAssembler<A, NA, N, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            latch,
            latch_address,
            latch_valid,
            answer_from_bus,
            answer_offset,
            holding,
            held_parts,
            holding_address,
            error_reg
        );
        self.part.next = self.narrow_address.val() & self.top_part.val();
        self.offset.next = self.part.val() << self.part_to_offset.val();
        self.part_bit.next = self.one.val() << self.part.val();
        self.address_shifted.next = self.narrow_address.val() >> self.part_bits.val();
        self.bus_address.next = self.address_shifted.val().get_bits::<A>(0);
        // rust-hdl's only zero-extension; its mask is waived in the lint file.
        self.data_wide.next = bit_cast::<W, N>(self.narrow_write_data.val());
        self.merged.next = (self.holding.q.val() & !(self.part_ones.val() << self.offset.val()))
            | (self.data_wide.val() << self.offset.val());
        self.bus_write_data.next = self.merged.val();
        self.latch_hit.next =
            self.latch_valid.q.val() & (self.latch_address.q.val() == self.bus_address.val());
        self.holding_hit.next = self.holding_address.q.val() == self.bus_address.val();
        self.order_error.next = self.error_reg.q.val();

        // The answer of the read one clock ago: the slave's word if it was
        // read then (and it is latched now), else the latched word.
        // (A shift, not an indexed part-select: the index would have to be
        // exactly log2(W) bits wide to lint clean.)
        self.answer_word.next = self.latch.q.val() >> self.answer_offset.q.val();
        if self.answer_from_bus.q.val() {
            self.answer_word.next = self.bus_read_data.val() >> self.answer_offset.q.val();
            self.latch.d.next = self.bus_read_data.val();
        }
        self.narrow_read_data.next = self.answer_word.val().get_bits::<N>(0);

        self.bus_read.next = false;
        self.bus_write.next = false;
        self.error_reg.d.next = false;
        self.answer_from_bus.d.next = false;
        if self.narrow_read.val() {
            self.answer_offset.d.next = self.offset.val();
            // Part 0 always reads (and latches) the register; a higher part
            // reads it only if the latch holds another register.
            if (self.part.val() == self.zero_na.val()) | !self.latch_hit.val() {
                self.bus_read.next = true;
                self.answer_from_bus.d.next = true;
                self.latch_address.d.next = self.bus_address.val();
                self.latch_valid.d.next = true;
                self.error_reg.d.next = self.part.val() != self.zero_na.val();
            }
        }
        if self.narrow_write.val() {
            if self.part.val() == self.top_part.val() {
                // Commit only a whole word of one register.
                if self.holding_hit.val() & (self.held_parts.q.val() == self.lower_parts.val()) {
                    self.bus_write.next = true;
                } else {
                    self.error_reg.d.next = true;
                }
                self.held_parts.d.next = self.zero_parts.val();
            } else {
                self.holding.d.next = self.merged.val();
                self.holding_address.d.next = self.bus_address.val();
                if self.holding_hit.val() {
                    self.held_parts.d.next = self.held_parts.q.val() | self.part_bit.val();
                } else {
                    self.held_parts.d.next = self.part_bit.val();
                    // Parts of another register were abandoned.
                    self.error_reg.d.next = self.held_parts.q.val() != self.zero_parts.val();
                }
            }
        }

        if self.reset.val() {
            self.latch.d.next = self.zero_w.val();
            self.latch_address.d.next = self.zero_a.val();
            self.latch_valid.d.next = false;
            self.answer_from_bus.d.next = false;
            self.answer_offset.d.next = self.zero_na.val();
            self.holding.d.next = self.zero_w.val();
            self.held_parts.d.next = self.zero_parts.val();
            self.holding_address.d.next = self.zero_a.val();
            self.error_reg.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const A: usize, const NA: usize, const N: usize, const W: usize] WordAssembler<A, NA, N, W> {
    inputs: [reset, narrow_address, narrow_write_data, narrow_write, narrow_read, bus_read_data],
    outputs: [narrow_read_data, bus_address, bus_write_data, bus_write, bus_read, order_error],
});
