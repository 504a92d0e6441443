//! One axis's register window on the bus: the axis's register layer apart
//! from its core. It decodes the window's writes into the configuration
//! flip-flops and strobes, captures the snapshots, and multiplexes the
//! window's live and captured values onto one read word.
//!
//! Internal to [`super::MotionController`] (one per [`super::axis`]); the
//! registers' behavior is the controller's, modelled by [`super::model`],
//! and their fields are the register map's ([`super::registers`]).
//!
//! ## Contract (as the axis uses it)
//! * The window of axis k is at `AXIS_BASE + k * AXIS_STRIDE`; its lower
//!   half (address bit 4 = 0) is decoded here, the upper half is the axis
//!   I/O's.
//! * A write to AXIS_CONFIG, STEP_LEN, STEP_SPACE, DIR_SETUP, DIR_HOLD or
//!   ENC_SAMPLE_RATE is in its output from the clock after the write edge,
//!   with its writable bits only. Reset clears them.
//! * `command` and `fifo_write` are combinational: high in the clock of a
//!   write to AXIS_COMMAND and FIFO_WRITE.
//! * `snapshot` captures CMD_POSITION and ACT_POSITION together into
//!   CMD_SNAPSHOT and ACT_SNAPSHOT at its edge.
//! * `read_data` is combinational: the window's register at `address`
//!   (FIFO_STATUS, the positions, the snapshots, AXIS_STATUS,
//!   INDEX_POSITION), ORed with the axis I/O's `io_read_data`; 0 outside
//!   the window. The configuration registers read 0 here: the
//!   controller's shadow RAM answers for them.

use rust_hdl::prelude::*;

use super::registers::{axis, fields, AXIS_BASE, AXIS_STRIDE, AXIS_STRIDE_LOG2};

// The decode takes the window from address bits 7..5 and the half from
// bit 4 (address bits, not register fields).
const _: () = assert!(AXIS_STRIDE_LOG2 == 5 && AXIS_STRIDE == 1 << 5);
// FIFO_STATUS.LEVEL is zero-extended from bit 0.
const _: () = assert!(fields::FIFO_LEVEL == 0);

/// AXIS_CONFIG's width: its highest field is ANALOG (checked against the
/// map's writable bits in [`AxisRegisters::new`]).
pub const CONFIG_BITS: usize = fields::AXIS_ANALOG as usize + 1;
/// STEP_LEN, STEP_SPACE, DIR_SETUP and DIR_HOLD's width.
pub const TIMING_BITS: usize = fields::STEP_TIMING_WIDTH as usize;
/// ENC_SAMPLE_RATE's width.
pub const SAMPLE_RATE_BITS: usize = fields::ENC_SAMPLE_RATE_WIDTH as usize;
/// The write data's width here: the widest register written (STEP_LEN).
pub const WRITE_BITS: usize = TIMING_BITS;
const _: () = assert!(CONFIG_BITS <= WRITE_BITS && SAMPLE_RATE_BITS <= WRITE_BITS);

/// The register window of an axis with FIFO levels of `NP1` bits. See the
/// [module documentation](self).
#[derive(LogicBlock)]
pub struct AxisRegisters<const NP1: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: every register 0.
    pub reset: Signal<In, Bit>,
    /// The register bus's word address.
    pub address: Signal<In, Bits<8>>,
    /// Write strobe.
    pub write: Signal<In, Bit>,
    /// Write data: the bus's low [`WRITE_BITS`] (no register written here
    /// is wider).
    pub write_data: Signal<In, Bits<WRITE_BITS>>,
    /// Capture both positions into the snapshots.
    pub snapshot: Signal<In, Bit>,
    /// FIFO_STATUS.LEVEL.
    pub fifo_level: Signal<In, Bits<NP1>>,
    /// FIFO_STATUS.EMPTY.
    pub fifo_empty: Signal<In, Bit>,
    /// FIFO_STATUS.FULL.
    pub fifo_full: Signal<In, Bit>,
    /// FIFO_STATUS.LOW.
    pub fifo_low: Signal<In, Bit>,
    /// AXIS_STATUS.STEP_OVERRUN.
    pub step_overrun: Signal<In, Bit>,
    /// AXIS_STATUS.INTERP_OVERRANGE.
    pub interp_overrange: Signal<In, Bit>,
    /// AXIS_STATUS.INTERP_OVERFLOW.
    pub interp_overflow: Signal<In, Bit>,
    /// AXIS_STATUS.ENCODER_ERROR.
    pub encoder_error: Signal<In, Bit>,
    /// AXIS_STATUS.INDEX_SEEN.
    pub index_seen: Signal<In, Bit>,
    /// AXIS_STATUS.STEP_BUSY.
    pub step_busy: Signal<In, Bit>,
    /// AXIS_STATUS.UNIFORM_RUNNING.
    pub uniform_running: Signal<In, Bit>,
    /// AXIS_STATUS.STEP_MODE_INVALID.
    pub step_mode_invalid: Signal<In, Bit>,
    /// CMD_POSITION.
    pub cmd_position: Signal<In, Bits<32>>,
    /// ACT_POSITION.
    pub act_position: Signal<In, Bits<32>>,
    /// INDEX_POSITION.
    pub index_position: Signal<In, Bits<32>>,
    /// The axis I/O's read word (the window's upper half).
    pub io_read_data: Signal<In, Bits<32>>,
    /// AXIS_CONFIG.
    pub axis_config: Signal<Out, Bits<CONFIG_BITS>>,
    /// STEP_LEN.
    pub step_len: Signal<Out, Bits<TIMING_BITS>>,
    /// STEP_SPACE.
    pub step_space: Signal<Out, Bits<TIMING_BITS>>,
    /// DIR_SETUP.
    pub dir_setup: Signal<Out, Bits<TIMING_BITS>>,
    /// DIR_HOLD.
    pub dir_hold: Signal<Out, Bits<TIMING_BITS>>,
    /// ENC_SAMPLE_RATE.
    pub sample_rate: Signal<Out, Bits<SAMPLE_RATE_BITS>>,
    /// A write to AXIS_COMMAND in this clock.
    pub command: Signal<Out, Bit>,
    /// A write to FIFO_WRITE in this clock.
    pub fifo_write: Signal<Out, Bit>,
    /// The addressed register of this window, 0 outside it.
    pub read_data: Signal<Out, Bits<32>>,

    config_reg: DFF<Bits<CONFIG_BITS>>,
    step_len_reg: DFF<Bits<TIMING_BITS>>,
    step_space_reg: DFF<Bits<TIMING_BITS>>,
    dir_setup_reg: DFF<Bits<TIMING_BITS>>,
    dir_hold_reg: DFF<Bits<TIMING_BITS>>,
    sample_rate_reg: DFF<Bits<SAMPLE_RATE_BITS>>,
    cmd_snapshot: DFF<Bits<32>>,
    act_snapshot: DFF<Bits<32>>,
    /// The address is in this window's lower half, at `offset`.
    selected: Signal<Local, Bit>,
    offset: Signal<Local, Bits<4>>,
    fifo_status: Signal<Local, Bits<32>>,
    axis_status: Signal<Local, Bits<32>>,
    window: Constant<Bits<3>>,
    /// FIFO_STATUS and AXIS_STATUS fields, in place.
    m_fifo_empty: Constant<Bits<32>>,
    m_fifo_full: Constant<Bits<32>>,
    m_fifo_low: Constant<Bits<32>>,
    m_step_overrun: Constant<Bits<32>>,
    m_interp_overrange: Constant<Bits<32>>,
    m_interp_overflow: Constant<Bits<32>>,
    m_encoder_error: Constant<Bits<32>>,
    m_index_seen: Constant<Bits<32>>,
    m_step_busy: Constant<Bits<32>>,
    m_uniform_running: Constant<Bits<32>>,
    m_step_mode_invalid: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    /// `bit_mask[i]` = 1 << i, one per FIFO level bit.
    bit_mask: [Constant<Bits<32>>; NP1],
    /// AXIS_CONFIG's writable bits.
    config_mask: Constant<Bits<CONFIG_BITS>>,
    zero_config: Constant<Bits<CONFIG_BITS>>,
    zero_timing: Constant<Bits<TIMING_BITS>>,
    zero_sample_rate: Constant<Bits<SAMPLE_RATE_BITS>>,
    off_fifo_write: Constant<Bits<4>>,
    off_fifo_status: Constant<Bits<4>>,
    off_config: Constant<Bits<4>>,
    off_step_len: Constant<Bits<4>>,
    off_step_space: Constant<Bits<4>>,
    off_dir_setup: Constant<Bits<4>>,
    off_dir_hold: Constant<Bits<4>>,
    off_sample_rate: Constant<Bits<4>>,
    off_cmd_position: Constant<Bits<4>>,
    off_act_position: Constant<Bits<4>>,
    off_cmd_snapshot: Constant<Bits<4>>,
    off_act_snapshot: Constant<Bits<4>>,
    off_axis_status: Constant<Bits<4>>,
    off_index_position: Constant<Bits<4>>,
    off_command: Constant<Bits<4>>,
}

impl<const NP1: usize> AxisRegisters<NP1> {
    /// The window of axis `index`; `config_mask` is AXIS_CONFIG's
    /// read-write bits in the controller's register map.
    pub fn new(index: usize, config_mask: u32) -> Self {
        assert_eq!(
            config_mask >> CONFIG_BITS,
            0,
            "AXIS_CONFIG has fields above CONFIG_BITS"
        );
        let window = (AXIS_BASE + index as u32 * AXIS_STRIDE) >> AXIS_STRIDE_LOG2;
        let c4 = |v: u32| Constant::new((v as u64).into());
        let bit32 = |n: u32| Constant::new((1u64 << n).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            snapshot: Default::default(),
            fifo_level: Default::default(),
            fifo_empty: Default::default(),
            fifo_full: Default::default(),
            fifo_low: Default::default(),
            step_overrun: Default::default(),
            interp_overrange: Default::default(),
            interp_overflow: Default::default(),
            encoder_error: Default::default(),
            index_seen: Default::default(),
            step_busy: Default::default(),
            uniform_running: Default::default(),
            step_mode_invalid: Default::default(),
            cmd_position: Default::default(),
            act_position: Default::default(),
            index_position: Default::default(),
            io_read_data: Default::default(),
            axis_config: Default::default(),
            step_len: Default::default(),
            step_space: Default::default(),
            dir_setup: Default::default(),
            dir_hold: Default::default(),
            sample_rate: Default::default(),
            command: Default::default(),
            fifo_write: Default::default(),
            read_data: Default::default(),
            config_reg: Default::default(),
            step_len_reg: Default::default(),
            step_space_reg: Default::default(),
            dir_setup_reg: Default::default(),
            dir_hold_reg: Default::default(),
            sample_rate_reg: Default::default(),
            cmd_snapshot: Default::default(),
            act_snapshot: Default::default(),
            selected: Default::default(),
            offset: Default::default(),
            fifo_status: Default::default(),
            axis_status: Default::default(),
            window: Constant::new((window as u64).into()),
            m_fifo_empty: bit32(fields::FIFO_EMPTY),
            m_fifo_full: bit32(fields::FIFO_FULL),
            m_fifo_low: bit32(fields::FIFO_LOW),
            m_step_overrun: bit32(fields::STATUS_STEP_OVERRUN),
            m_interp_overrange: bit32(fields::STATUS_INTERP_OVERRANGE),
            m_interp_overflow: bit32(fields::STATUS_INTERP_OVERFLOW),
            m_encoder_error: bit32(fields::STATUS_ENCODER_ERROR),
            m_index_seen: bit32(fields::STATUS_INDEX_SEEN),
            m_step_busy: bit32(fields::STATUS_STEP_BUSY),
            m_uniform_running: bit32(fields::STATUS_UNIFORM_RUNNING),
            m_step_mode_invalid: bit32(fields::STATUS_STEP_MODE_INVALID),
            zero32: Constant::new(0u64.into()),
            bit_mask: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            config_mask: Constant::new((config_mask as u64).into()),
            zero_config: Constant::new(0u64.into()),
            zero_timing: Constant::new(0u64.into()),
            zero_sample_rate: Constant::new(0u64.into()),
            off_fifo_write: c4(axis::FIFO_WRITE),
            off_fifo_status: c4(axis::FIFO_STATUS),
            off_config: c4(axis::AXIS_CONFIG),
            off_step_len: c4(axis::STEP_LEN),
            off_step_space: c4(axis::STEP_SPACE),
            off_dir_setup: c4(axis::DIR_SETUP),
            off_dir_hold: c4(axis::DIR_HOLD),
            off_sample_rate: c4(axis::ENC_SAMPLE_RATE),
            off_cmd_position: c4(axis::CMD_POSITION),
            off_act_position: c4(axis::ACT_POSITION),
            off_cmd_snapshot: c4(axis::CMD_SNAPSHOT),
            off_act_snapshot: c4(axis::ACT_SNAPSHOT),
            off_axis_status: c4(axis::AXIS_STATUS),
            off_index_position: c4(axis::INDEX_POSITION),
            off_command: c4(axis::AXIS_COMMAND),
        }
    }
}

impl<const NP1: usize> Logic for AxisRegisters<NP1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            config_reg,
            step_len_reg,
            step_space_reg,
            dir_setup_reg,
            dir_hold_reg,
            sample_rate_reg,
            cmd_snapshot,
            act_snapshot
        );
        self.axis_config.next = self.config_reg.q.val();
        self.step_len.next = self.step_len_reg.q.val();
        self.step_space.next = self.step_space_reg.q.val();
        self.dir_setup.next = self.dir_setup_reg.q.val();
        self.dir_hold.next = self.dir_hold_reg.q.val();
        self.sample_rate.next = self.sample_rate_reg.q.val();

        // Window decode: bits 7..5 the window, bit 4 the half (motion core
        // or machine I/O), 3..0 the offset.
        self.selected.next = (self.address.val().get_bits::<3>(5) == self.window.val())
            & !self.address.val().get_bit(4);
        self.offset.next = self.address.val().get_bits::<4>(0);
        self.command.next =
            self.write.val() & self.selected.val() & (self.offset.val() == self.off_command.val());
        self.fifo_write.next = self.write.val()
            & self.selected.val()
            & (self.offset.val() == self.off_fifo_write.val());
        if self.write.val() & self.selected.val() {
            if self.offset.val() == self.off_config.val() {
                self.config_reg.d.next =
                    self.write_data.val().get_bits::<CONFIG_BITS>(0) & self.config_mask.val();
            }
            if self.offset.val() == self.off_step_len.val() {
                self.step_len_reg.d.next = self.write_data.val().get_bits::<TIMING_BITS>(0);
            }
            if self.offset.val() == self.off_step_space.val() {
                self.step_space_reg.d.next = self.write_data.val().get_bits::<TIMING_BITS>(0);
            }
            if self.offset.val() == self.off_dir_setup.val() {
                self.dir_setup_reg.d.next = self.write_data.val().get_bits::<TIMING_BITS>(0);
            }
            if self.offset.val() == self.off_dir_hold.val() {
                self.dir_hold_reg.d.next = self.write_data.val().get_bits::<TIMING_BITS>(0);
            }
            if self.offset.val() == self.off_sample_rate.val() {
                self.sample_rate_reg.d.next = self.write_data.val().get_bits::<SAMPLE_RATE_BITS>(0);
            }
        }
        if self.snapshot.val() {
            self.cmd_snapshot.d.next = self.cmd_position.val();
            self.act_snapshot.d.next = self.act_position.val();
        }

        // FIFO_STATUS and AXIS_STATUS, the level zero-extended bit by bit
        // (rust-hdl's cast prints as a mask that Verilator flags for width).
        self.fifo_status.next = self.zero32.val();
        for i in 0..NP1 {
            if self.fifo_level.val().get_bit(i) {
                self.fifo_status.next = self.fifo_status.val() | self.bit_mask[i].val();
            }
        }
        if self.fifo_empty.val() {
            self.fifo_status.next = self.fifo_status.val() | self.m_fifo_empty.val();
        }
        if self.fifo_full.val() {
            self.fifo_status.next = self.fifo_status.val() | self.m_fifo_full.val();
        }
        if self.fifo_low.val() {
            self.fifo_status.next = self.fifo_status.val() | self.m_fifo_low.val();
        }
        self.axis_status.next = self.zero32.val();
        if self.step_overrun.val() {
            self.axis_status.next = self.axis_status.val() | self.m_step_overrun.val();
        }
        if self.interp_overrange.val() {
            self.axis_status.next = self.axis_status.val() | self.m_interp_overrange.val();
        }
        if self.interp_overflow.val() {
            self.axis_status.next = self.axis_status.val() | self.m_interp_overflow.val();
        }
        if self.encoder_error.val() {
            self.axis_status.next = self.axis_status.val() | self.m_encoder_error.val();
        }
        if self.index_seen.val() {
            self.axis_status.next = self.axis_status.val() | self.m_index_seen.val();
        }
        if self.step_busy.val() {
            self.axis_status.next = self.axis_status.val() | self.m_step_busy.val();
        }
        if self.uniform_running.val() {
            self.axis_status.next = self.axis_status.val() | self.m_uniform_running.val();
        }
        if self.step_mode_invalid.val() {
            self.axis_status.next = self.axis_status.val() | self.m_step_mode_invalid.val();
        }
        // One-hot AND-OR: the offsets are exclusive, which synthesis cannot
        // know of a priority chain; ORing gated sources packs two per LUT4.
        self.read_data.next = self.io_read_data.val();
        if self.selected.val() {
            if self.offset.val() == self.off_fifo_status.val() {
                self.read_data.next = self.read_data.val() | self.fifo_status.val();
            }
            if self.offset.val() == self.off_cmd_position.val() {
                self.read_data.next = self.read_data.val() | self.cmd_position.val();
            }
            if self.offset.val() == self.off_act_position.val() {
                self.read_data.next = self.read_data.val() | self.act_position.val();
            }
            if self.offset.val() == self.off_cmd_snapshot.val() {
                self.read_data.next = self.read_data.val() | self.cmd_snapshot.q.val();
            }
            if self.offset.val() == self.off_act_snapshot.val() {
                self.read_data.next = self.read_data.val() | self.act_snapshot.q.val();
            }
            if self.offset.val() == self.off_axis_status.val() {
                self.read_data.next = self.read_data.val() | self.axis_status.val();
            }
            if self.offset.val() == self.off_index_position.val() {
                self.read_data.next = self.read_data.val() | self.index_position.val();
            }
        }

        if self.reset.val() {
            self.config_reg.d.next = self.zero_config.val();
            self.step_len_reg.d.next = self.zero_timing.val();
            self.step_space_reg.d.next = self.zero_timing.val();
            self.dir_setup_reg.d.next = self.zero_timing.val();
            self.dir_hold_reg.d.next = self.zero_timing.val();
            self.sample_rate_reg.d.next = self.zero_sample_rate.val();
            self.cmd_snapshot.d.next = self.zero32.val();
            self.act_snapshot.d.next = self.zero32.val();
        }
    }
}
