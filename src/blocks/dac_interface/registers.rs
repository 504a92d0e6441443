//! The register map of [`super::DacInterface`]: the one source of its
//! addresses, fields and reset values for the C header
//! (`rtl-out/dac_interface_regs.h`), the Markdown table, the RTL's decoder,
//! the model and the tests.

use crate::regmap::{field, register, Access, Field, RegMapError, Register, RegisterMap};

/// `ID` register value: "DAC1".
pub const ID_VALUE: u32 = 0x4441_4331;
/// Address bits of the register bus.
pub const ADDRESS_BITS: u32 = 5;
/// Most channels: `CODE` and `APPLIED` have eight words each (the
/// motion controller has up to 7 axes).
pub const MAX_CHANNELS: usize = 8;
/// Widest code.
pub const MAX_WIDTH: usize = 16;
/// Word address of `CODE[0]`.
pub const CODE_BASE: u32 = 0x10;
/// Word address of `APPLIED[0]`.
pub const APPLIED_BASE: u32 = 0x18;

/// Reset values of the `TIMING` fields, in clocks: at 100 MHz they meet the
/// AD669 (40 ns CS/L1 and LDAC pulses, 40 ns data setup and 10 ns data hold
/// to the latching edge) with a clock to spare.
pub const RESET_SETUP: u64 = 1;
/// See [`RESET_SETUP`].
pub const RESET_WIDTH: u64 = 5;
/// See [`RESET_SETUP`].
pub const RESET_HOLD: u64 = 2;
/// See [`RESET_SETUP`].
pub const RESET_LDAC_WIDTH: u64 = 5;

/// Bit numbers and widths of the fields the RTL slices at literal
/// positions (the map below is built from these; the RTL reads them
/// through `field_slices!` or at a literal tied to them by a compile-time
/// assertion).
pub mod fields {
    /// `TIMING.SETUP`.
    pub const TIMING_SETUP: u32 = 0;
    /// `TIMING.WIDTH`.
    pub const TIMING_WIDTH: u32 = 8;
    /// `TIMING.HOLD`.
    pub const TIMING_HOLD: u32 = 16;
    /// `TIMING.LDAC_WIDTH`.
    pub const TIMING_LDAC_WIDTH: u32 = 24;
    /// Width of every `TIMING` field.
    pub const TIMING_FIELD_BITS: u32 = 8;
    /// `CODE.VALUE` and `APPLIED.VALUE` (the code width W).
    pub const CODE_VALUE: u32 = 0;
}

/// The map of a `channels`-channel interface with `width`-bit codes.
pub fn register_map(channels: usize, width: usize) -> Result<RegisterMap, RegMapError> {
    if channels == 0 || channels > MAX_CHANNELS || !(2..=MAX_WIDTH).contains(&width) {
        return Err(RegMapError::NoCopies(format!(
            "dac_interface: {channels} channels of {width} bits (1 to {MAX_CHANNELS} channels of 2 to {MAX_WIDTH} bits)"
        )));
    }
    use Access::*;
    let k = channels as u32;
    let w = width as u32;
    let map = RegisterMap {
        name: "DAC",
        address_bits: ADDRESS_BITS,
        doc: "dac_interface: K parallel DACs (AD669 style) with double-buffered latches and one shared LDAC",
        registers: vec![
            Register::word("ID", 0x0, ReadOnly, ID_VALUE as u64, "identifies the block: \"DAC1\""),
            register(
                "CONFIG",
                0x1,
                "build configuration",
                vec![
                    field("CHANNELS", 0, 8, ReadOnly, "number of channels K").with_reset(channels as u64),
                    field("CODE_BITS", 8, 8, ReadOnly, "code width W").with_reset(width as u64),
                ],
            ),
            register(
                "CONTROL",
                0x2,
                "code format",
                vec![field(
                    "OFFSET_BINARY",
                    0,
                    1,
                    ReadWrite,
                    "1: the pins carry offset binary (the MSB inverted); 0: two's complement, as written",
                )],
            ),
            register(
                "UPDATE",
                0x3,
                "starts an update of every channel (deferred if one is running, refused while force_safe is high)",
                vec![field("START", 0, 1, WriteOnly, "write 1: request an update")],
            ),
            register(
                "STATUS",
                0x4,
                "sequencer state and sticky flags",
                vec![
                    field("BUSY", 0, 1, ReadOnly, "an update (or the safe update) is running"),
                    field("SAFE", 1, 1, ReadOnly, "the safe code is applied, or its update is pending or running").with_reset(1),
                    field("FORCE_SAFE", 2, 1, ReadOnly, "the force_safe input is high: codes and updates are refused"),
                    field("PENDING", 3, 1, ReadOnly, "a deferred update waits for the running one"),
                    field("DEFERRED", 8, 1, WriteOneToClear, "an update was requested while one was running"),
                    field("REFUSED", 9, 1, WriteOneToClear, "an update or a CODE write came while force_safe was high"),
                ],
            ),
            register(
                "TIMING",
                0x5,
                "pin timing in clocks, taken at the start of each update; 0 acts as 1",
                vec![
                    field("SETUP", fields::TIMING_SETUP, fields::TIMING_FIELD_BITS, ReadWrite, "CS low and data valid before L1 falls").with_reset(RESET_SETUP),
                    field("WIDTH", fields::TIMING_WIDTH, fields::TIMING_FIELD_BITS, ReadWrite, "L1 low").with_reset(RESET_WIDTH),
                    field("HOLD", fields::TIMING_HOLD, fields::TIMING_FIELD_BITS, ReadWrite, "CS low and data held after L1 rises").with_reset(RESET_HOLD),
                    field("LDAC_WIDTH", fields::TIMING_LDAC_WIDTH, fields::TIMING_FIELD_BITS, ReadWrite, "LDAC high").with_reset(RESET_LDAC_WIDTH),
                ],
            ),
            register(
                "CODE",
                CODE_BASE,
                "channel k's staged code, signed (two's complement); 0 is 0 V",
                vec![field("VALUE", fields::CODE_VALUE, w, ReadWrite, "the code the next update writes")],
            )
            .repeated(k, 1),
            register(
                "APPLIED",
                APPLIED_BASE,
                "channel k's code in the DAC's second rank (the output), signed",
                vec![field("VALUE", fields::CODE_VALUE, w, ReadOnly, "the code of the last LDAC")],
            )
            .repeated(k, 1),
        ],
    };
    map.validate()?;
    Ok(map)
}

/// Register `name`'s field `field` in `map`, which must have it (a
/// lookup of the block's own map by a name fixed in its source).
pub fn field_of<'a>(map: &'a RegisterMap, name: &str, field: &str) -> &'a Field {
    map.field(name, field)
        .unwrap_or_else(|e| panic!("dac_interface map: {e}"))
}
