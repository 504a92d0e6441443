//! The register maps of [`super::ParallelCard`]: the master's (the
//! control-level DSP's) and every slave's (a motor-control DSP's). Each is
//! the card's own registers laid beside the maps of the blocks it is made
//! of, cloned at their card addresses: the bridge's master map at 0x000,
//! its slave map at 0x00 of every slave port, the slave's DAC pair's map at
//! 0x20. They are the one source of the addresses and fields for the C
//! headers (`rtl-out/parallel_card_master_regs.h`,
//! `..._slave_regs.h`), the Markdown tables, the RTL's decoders, the model
//! and the tests.

use crate::blocks::dac_interface::registers as dac;
use crate::blocks::sync_fifo_bridge::registers as bridge;
use crate::regmap::{field, register, Access, RegMapError, Register, RegisterMap};

/// `CARD_ID` value: "PCD1".
pub const ID_VALUE: u32 = 0x5043_4431;
/// Address bits of the master port: the bridge's 8 and one to select the
/// card's registers.
pub const MASTER_ADDRESS_BITS: u32 = 9;
/// Address bits of each slave port: the bridge's window, the joints'
/// registers and the DAC pair's window.
pub const SLAVE_ADDRESS_BITS: u32 = 6;
/// Slave ports (motor-control DSPs) of the card.
pub const SLAVES: usize = 3;
/// Joints each slave drives.
pub const JOINTS_PER_SLAVE: usize = 2;
/// Joints of the card.
pub const JOINTS: usize = SLAVES * JOINTS_PER_SLAVE;
/// log2 of every FIFO's depth (64 words).
pub const FIFO_LOG2: u32 = 6;
/// Bits of a DAC code (the AD669's 16).
pub const DAC_BITS: usize = 16;
/// Bits of an encoder count.
pub const COUNT_BITS: usize = 32;

/// Master word address of the card's own registers (`m_address[8]` = 1).
pub const MASTER_CARD_BASE: u32 = 0x100;
/// Slave word address of the joints' registers (`s_address[5:4]` = 01).
pub const SLAVE_JOINT_BASE: u32 = 0x10;
/// Slave word address of the DAC pair's window (`s_address[5]` = 1).
pub const SLAVE_DAC_BASE: u32 = 0x20;

/// Bit positions the RTL slices at literal positions (the maps are built
/// from these).
pub mod fields {
    /// `CARD_CONTROL.ENC_FILTER`.
    pub const ENC_FILTER: u32 = 0;
    /// Width of `ENC_FILTER` (the decoders' `filter`).
    pub const ENC_FILTER_BITS: u32 = 4;
    /// `CARD_FAULT.UNDERRUN` (K bits) and `CARD_STATE.UNDERRUN`.
    pub const UNDERRUN: u32 = 0;
    /// `CARD_FAULT.ESTOP` and `CARD_STATE.ESTOP`.
    pub const ESTOP: u32 = 8;
    /// `CARD_FAULT.STOPPED` and `CARD_STATE.STOPPED`.
    pub const STOPPED: u32 = 9;
    /// `ENCODER.ERROR` (one bit a joint).
    pub const ENC_ERROR: u32 = 0;
    /// `ENCODER.CLEAR` (one bit a joint).
    pub const ENC_CLEAR: u32 = 8;
}

/// Reset value of `CARD_CONTROL.ENC_FILTER`: a change of an encoder pin
/// counts after 3 equal samples (30 ns at 100 MHz), which passes 8 MHz of
/// edges per channel and rejects shorter glitches.
pub const RESET_ENC_FILTER: u64 = 3;

/// The DAC pair's registers as a slave sees them: (card name, the DAC's name).
pub const DAC_REGISTERS: [(&str, &str); 8] = [
    ("DAC_ID", "ID"),
    ("DAC_CONFIG", "CONFIG"),
    ("DAC_CONTROL", "CONTROL"),
    ("DAC_UPDATE", "UPDATE"),
    ("DAC_STATUS", "STATUS"),
    ("DAC_TIMING", "TIMING"),
    ("DAC_CODE", "CODE"),
    ("DAC_APPLIED", "APPLIED"),
];

fn moved(r: &Register, name: &'static str, base: u32) -> Register {
    Register {
        name,
        address: base + r.address,
        ..r.clone()
    }
}

fn stop_fields(
    underrun_width: u32,
    underrun_doc: &'static str,
    w1c: bool,
) -> Vec<crate::regmap::Field> {
    use Access::*;
    vec![
        field(
            "UNDERRUN",
            fields::UNDERRUN,
            underrun_width,
            if w1c { WriteOneToClear } else { ReadOnly },
            underrun_doc,
        ),
        field("ESTOP", fields::ESTOP, 1, ReadOnly, "the estop input, synchronized: high holds every DAC at 0 V"),
        field(
            "STOPPED",
            fields::STOPPED,
            1,
            ReadOnly,
            "every DAC is forced to 0 V and refuses codes: an UNDERRUN flag is set or estop is high",
        ),
    ]
}

/// The master port's map: the bridge's master registers at their own
/// addresses and the card's above 0x100.
pub fn master_map() -> Result<RegisterMap, RegMapError> {
    use Access::*;
    let b = bridge::master_map(SLAVES, FIFO_LOG2)?;
    let mut registers = b.registers.clone();
    let card = MASTER_CARD_BASE;
    registers.extend([
        Register::word("CARD_ID", card, ReadOnly, ID_VALUE as u64, "identity: 0x50434431, \"PCD1\""),
        register(
            "CARD_CONTROL",
            card + 0x1,
            "encoder input filter",
            vec![field(
                "ENC_FILTER",
                fields::ENC_FILTER,
                fields::ENC_FILTER_BITS,
                ReadWrite,
                "every decoder's filter: an encoder pin's change counts after this many equal samples (0 and 1: at once)",
            )
            .with_reset(RESET_ENC_FILTER)],
        ),
        register(
            "CARD_FAULT",
            card + 0x2,
            "the stop of every joint",
            stop_fields(
                SLAVES as u32,
                "bit k: slave k had no released command in the clock after a period_tick (sticky; holds every DAC at 0 V until cleared)",
                true,
            ),
        ),
        Register::word("COUNT", card + 0x8, ReadOnly, 0, "joint n's live encoder count, signed")
            .repeated(JOINTS as u32, 1),
    ]);
    let map = RegisterMap {
        name: "PCARD",
        address_bits: MASTER_ADDRESS_BITS,
        doc: "parallel_card master port: the sync_fifo_bridge's master registers, then the card's at 0x100",
        registers,
    };
    map.validate()?;
    Ok(map)
}

/// Every slave port's map: the bridge's slave registers, the two joints'
/// encoder registers at 0x10 and the DAC pair's registers at 0x20.
pub fn slave_map() -> Result<RegisterMap, RegMapError> {
    use Access::*;
    let b = bridge::slave_map(FIFO_LOG2)?;
    let d = dac::register_map(JOINTS_PER_SLAVE, DAC_BITS)?;
    let joints = SLAVE_JOINT_BASE;
    let j = JOINTS_PER_SLAVE as u32;
    let mut registers = b.registers.clone();
    registers.extend([
        Register::word(
            "COUNT",
            joints,
            ReadOnly,
            0,
            "joint n's encoder count as it stood in the clock of the last period_tick, signed",
        )
        .repeated(j, 1),
        Register::word("LIVE", joints + 0x2, ReadOnly, 0, "joint n's encoder count now, signed")
            .repeated(j, 1),
        register(
            "ENCODER",
            joints + 0x4,
            "the joints' decoders",
            vec![
                field(
                    "ERROR",
                    fields::ENC_ERROR,
                    j,
                    WriteOneToClear,
                    "bit n: joint n's A and B changed on one sample (a count was lost); sticky",
                ),
                field(
                    "CLEAR",
                    fields::ENC_CLEAR,
                    j,
                    WriteOnly,
                    "write 1 to bit n: joint n's count and error to 0",
                ),
            ],
        ),
        register(
            "CARD_STATE",
            joints + 0x5,
            "the card's stop, as this slave sees it",
            stop_fields(1, "this slave had no released command in the clock after a period_tick (the master clears it)", false),
        ),
    ]);
    for (name, dac_name) in DAC_REGISTERS {
        registers.push(moved(d.register(dac_name)?, name, SLAVE_DAC_BASE));
    }
    let map = RegisterMap {
        name: "PCARD_SLAVE",
        address_bits: SLAVE_ADDRESS_BITS,
        doc: "parallel_card slave port: the bridge's slave registers, the two joints' encoders at 0x10, their DACs at 0x20",
        registers,
    };
    map.validate()?;
    Ok(map)
}
