//! The readback of the axes' configuration registers from block RAM: the
//! controller's register layer keeps a write-through copy of every axis's
//! AXIS_CONFIG, STEP_LEN, STEP_SPACE, DIR_SETUP, DIR_HOLD and
//! ENC_SAMPLE_RATE in one [`HoldingRam`], and reads them back from it
//! instead of through each axis's read multiplexer. The flip-flops that
//! drive the axes stay in the axes: this is a copy for the bus only.
//!
//! Internal to [`super::MotionController`]; the registers' behavior is the
//! controller's, modelled by [`super::model`].
//!
//! ## Contract (as the controller uses it)
//! * `read_data` is the 16-bit value of the shadowed register that the
//!   read at the last `read` edge addressed (the register's writable bits,
//!   as written), and 0 when that read addressed any other register or
//!   a shadowed register not written since reset. It holds until the next
//!   `read`, and it is 0 from the edge of a `reset` on, as the controller's
//!   own read register is.
//! * Read and write of one register at one edge: the read returns the old
//!   value, as the flip-flops do.
//!
//! ## How
//! * Every shadowed register is below 16 bits wide, so one 256 x 16 block
//!   RAM, addressed by the bus address itself, holds them all.
//! * Reset cannot clear a block RAM, so a valid bit per register (cleared
//!   by reset, set by a write) says whether the RAM's word is the
//!   register's. A read of an invalid or unshadowed register reads word 0
//!   (`ID`, never written) instead: the gate is on the 8-bit address, not
//!   on the 16-bit data. During reset the RAM reads word 0, which clears
//!   its read register.

use rust_hdl::prelude::*;

use super::registers::{axis, fields, AXIS_BASE, AXIS_STRIDE_LOG2};
use crate::blocks::holding_ram::HoldingRam;

/// Width of every shadowed register.
pub const SHADOW_BITS: usize = 16;

// The decode below takes the shadowed registers as the axis window's
// offsets 2..7 (address bit 4 = 0, bit 3 = 0, bits 2..1 not both 0), and
// each register's writable bits as at most SHADOW_BITS.
const _: () = {
    assert!(axis::AXIS_CONFIG == 2);
    assert!(axis::STEP_LEN == 3);
    assert!(axis::STEP_SPACE == 4);
    assert!(axis::DIR_SETUP == 5);
    assert!(axis::DIR_HOLD == 6);
    assert!(axis::ENC_SAMPLE_RATE == 7);
    assert!(fields::STEP_TIMING_WIDTH as usize <= SHADOW_BITS);
    assert!(fields::ENC_SAMPLE_RATE_WIDTH as usize <= SHADOW_BITS);
    assert!(AXIS_STRIDE_LOG2 == 5 && AXIS_BASE >> AXIS_STRIDE_LOG2 == 1);
};

/// The shadow of `K` axes' configuration registers. See the
/// [module documentation](self).
#[derive(LogicBlock)]
pub struct ConfigShadow<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: every register reads 0.
    pub reset: Signal<In, Bit>,
    /// The register bus's word address.
    pub address: Signal<In, Bits<8>>,
    /// Write strobe.
    pub write: Signal<In, Bit>,
    /// Write data: the bus's low 16 bits (no shadowed register is wider).
    pub write_data: Signal<In, Bits<SHADOW_BITS>>,
    /// Read strobe.
    pub read: Signal<In, Bit>,
    /// The shadowed register of the last read, or 0 (see the contract).
    pub read_data: Signal<Out, Bits<SHADOW_BITS>>,

    ram: HoldingRam<Bits<SHADOW_BITS>, 8>,
    /// Per axis, bit o: the register at offset o has been written since
    /// reset (bits 0 and 1 are never set).
    valid: [DFF<Bits<8>>; K],
    /// The address is a shadowed offset of some axis window.
    shadowed: Signal<Local, Bit>,
    /// The address's offset as a one-hot byte.
    offset_bit: Signal<Local, Bits<8>>,
    /// The address is a shadowed register of an axis, and it is valid.
    hit: Signal<Local, Bit>,
    /// A write lands in the RAM.
    write_hit: Signal<Local, Bit>,
    write_mask: Signal<Local, Bits<SHADOW_BITS>>,
    windows: [Constant<Bits<3>>; K],
    one8: Constant<Bits<8>>,
    zero8: Constant<Bits<8>>,
    zero2: Constant<Bits<2>>,
    config_mask: Constant<Bits<SHADOW_BITS>>,
    timing_mask: Constant<Bits<SHADOW_BITS>>,
    sample_rate_mask: Constant<Bits<SHADOW_BITS>>,
    off_config: Constant<Bits<3>>,
    off_sample_rate: Constant<Bits<3>>,
}

impl<const K: usize> ConfigShadow<K> {
    /// The shadow for a controller whose AXIS_CONFIG has the writable bits
    /// `config_mask` (they depend on its build options).
    pub fn new(config_mask: u32) -> Self {
        assert!(
            config_mask as u64 <= crate::blocks::width_mask(SHADOW_BITS as u32),
            "ConfigShadow: AXIS_CONFIG's writable bits must fit {SHADOW_BITS} bits"
        );
        assert!(
            (1..=6).contains(&K),
            "ConfigShadow: 1 to 6 axis windows below address 0x100"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            read: Default::default(),
            read_data: Default::default(),
            ram: Default::default(),
            valid: array_init::array_init(|_| Default::default()),
            shadowed: Default::default(),
            offset_bit: Default::default(),
            hit: Default::default(),
            write_hit: Default::default(),
            write_mask: Default::default(),
            windows: array_init::array_init(|k| {
                Constant::new((((AXIS_BASE >> AXIS_STRIDE_LOG2) + k as u32) as u64).into())
            }),
            one8: Constant::new(1u64.into()),
            zero8: Constant::new(0u64.into()),
            zero2: Constant::new(0u64.into()),
            config_mask: Constant::new((config_mask as u64).into()),
            timing_mask: Constant::new(crate::blocks::width_mask(fields::STEP_TIMING_WIDTH).into()),
            sample_rate_mask: Constant::new(
                crate::blocks::width_mask(fields::ENC_SAMPLE_RATE_WIDTH).into(),
            ),
            off_config: Constant::new((axis::AXIS_CONFIG as u64).into()),
            off_sample_rate: Constant::new((axis::ENC_SAMPLE_RATE as u64).into()),
        }
    }
}

impl<const K: usize> Logic for ConfigShadow<K> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..K {
            self.valid[k].clock.next = self.clock.val();
            self.valid[k].d.next = self.valid[k].q.val();
        }
        self.ram.clock.next = self.clock.val();
        // Offsets 2..7 of an axis window's core half.
        self.shadowed.next = !self.address.val().get_bit(4)
            & !self.address.val().get_bit(3)
            & (self.address.val().get_bits::<2>(1) != self.zero2.val());
        self.offset_bit.next = self.one8.val() << self.address.val().get_bits::<3>(0);
        self.hit.next = false;
        self.write_hit.next = false;
        for k in 0..K {
            if self.shadowed.val() & (self.address.val().get_bits::<3>(5) == self.windows[k].val())
            {
                self.write_hit.next = self.write.val();
                if (self.valid[k].q.val() & self.offset_bit.val()) != self.zero8.val() {
                    self.hit.next = true;
                }
                if self.write.val() {
                    self.valid[k].d.next = self.valid[k].q.val() | self.offset_bit.val();
                }
            }
        }
        self.write_mask.next = self.timing_mask.val();
        if self.address.val().get_bits::<3>(0) == self.off_config.val() {
            self.write_mask.next = self.config_mask.val();
        }
        if self.address.val().get_bits::<3>(0) == self.off_sample_rate.val() {
            self.write_mask.next = self.sample_rate_mask.val();
        }
        self.ram.write_enable.next = self.write_hit.val();
        self.ram.write_address.next = self.address.val();
        self.ram.write_data.next = self.write_data.val() & self.write_mask.val();
        self.ram.read_enable.next = self.read.val() | self.reset.val();
        self.ram.read_address.next = self.zero8.val();
        if self.hit.val() & !self.reset.val() {
            self.ram.read_address.next = self.address.val();
        }
        self.read_data.next = self.ram.read_data.val();
        if self.reset.val() {
            for k in 0..K {
                self.valid[k].d.next = self.zero8.val();
            }
        }
    }
}
