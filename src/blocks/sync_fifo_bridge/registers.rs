//! The register maps of [`super::SyncFifoBridge`]: one for the master port
//! and one for every slave port. They are the one source of truth for
//! addresses, fields and reset values: the C headers
//! (`rtl-out/sync_fifo_bridge_master_regs.h`, `..._slave_regs.h`), the
//! Markdown tables, the RTL's address decoders and field constants, the
//! model and the tests all take them from here, by name.

use crate::regmap::{field, register, Access, Field, RegMapError, Register, RegisterMap};

/// `ID` register value: "SFB1".
pub const ID_VALUE: u32 = 0x5346_4231;

/// Address bits of the master port.
pub const MASTER_ADDRESS_BITS: u32 = 8;
/// Address bits of each slave port.
pub const SLAVE_ADDRESS_BITS: u32 = 4;
/// Word address of slave 0's window on the master port; slave k is at
/// `SLAVE_BASE + k * SLAVE_STRIDE`.
pub const SLAVE_BASE: u32 = 0x10;
/// Words per slave window on the master port.
pub const SLAVE_STRIDE: u32 = 0x4;
/// Most slave ports: the per-slave bits of `STATE` are 8 wide.
pub const MAX_SLAVES: usize = 8;
/// Deepest FIFO: every level field is 8 bits wide.
pub const MAX_FIFO_LOG2: u32 = 7;

fn check(slaves: usize, fifo_log2: u32) -> Result<(), RegMapError> {
    if slaves == 0 || slaves > MAX_SLAVES || !(1..=MAX_FIFO_LOG2).contains(&fifo_log2) {
        return Err(RegMapError::NoCopies(format!(
            "sync_fifo_bridge: {slaves} slaves, 2^{fifo_log2} entries (1 to {MAX_SLAVES} slaves, 2^1 to 2^{MAX_FIFO_LOG2} entries)"
        )));
    }
    Ok(())
}

/// The master port's map for `slaves` slave ports and FIFOs of
/// 2^`fifo_log2` entries.
pub fn master_map(slaves: usize, fifo_log2: u32) -> Result<RegisterMap, RegMapError> {
    check(slaves, fifo_log2)?;
    use Access::*;
    let level = fifo_log2 + 1;
    let k = slaves as u32;
    let per_slave = |offset: u32, r: Register| {
        Register {
            address: SLAVE_BASE + offset,
            ..r
        }
        .repeated(k, SLAVE_STRIDE)
    };
    let mut config = register(
        "CONFIG",
        0x01,
        "build configuration",
        vec![
            field("SLAVES", 0, 8, ReadOnly, "number of slave ports K"),
            field(
                "FIFO_DEPTH_LOG2",
                8,
                4,
                ReadOnly,
                "every FIFO holds 2^n words",
            ),
        ],
    );
    config.fields[0].reset = slaves as u64;
    config.fields[1].reset = fifo_log2 as u64;
    let map = RegisterMap {
        name: "SFB",
        address_bits: MASTER_ADDRESS_BITS,
        doc: "sync_fifo_bridge master port: per slave a command FIFO (staged until SYNC) and a status FIFO",
        registers: vec![
            Register::word("ID", 0x00, ReadOnly, ID_VALUE as u64, "identity: 0x53464231, \"SFB1\""),
            config,
            register(
                "CONTROL",
                0x02,
                "release mode",
                vec![field(
                    "TICK_MODE",
                    0,
                    1,
                    ReadWrite,
                    "0: a SYNC write releases at once; 1: a SYNC write arms, the next period_tick pulse releases",
                )],
            ),
            Register::word(
                "SYNC",
                0x03,
                WriteOnly,
                0,
                "any write: release (or, in tick mode, arm the release of) every command written before it, to all slaves at once",
            ),
            register(
                "STATE",
                0x04,
                "live state",
                vec![
                    field("ARMED", 0, 1, ReadOnly, "tick mode: a SYNC waits for the next period_tick"),
                    field("DATA_READY", 8, k, ReadOnly, "bit k: slave k's data_ready (released commands unread)"),
                    field("STATUS_PENDING", 16, k, ReadOnly, "bit k: slave k's status FIFO holds words"),
                ],
            ),
            per_slave(
                0,
                Register::word("CMD", 0, WriteOnly, 0, "push a command for slave n (staged until the next release; refused when full)"),
            ),
            per_slave(
                1,
                Register::word("STATUS", 0, ReadOnly, 0, "read pops slave n's oldest status word (empty: 0, STATUS_UNDERFLOW set)"),
            ),
            per_slave(
                2,
                register(
                    "LEVELS",
                    0,
                    "slave n's FIFO levels",
                    vec![
                        field("CMD_LEVEL", 0, level, ReadOnly, "commands held, staged and released"),
                        field("CMD_RELEASED", 8, level, ReadOnly, "released commands the slave has not read"),
                        field("STATUS_LEVEL", 16, level, ReadOnly, "status words held"),
                    ],
                ),
            ),
            per_slave(
                3,
                register(
                    "FLAGS",
                    0,
                    "slave n's sticky error flags",
                    vec![
                        field("CMD_OVERFLOW", 0, 1, WriteOneToClear, "a CMD write found the command FIFO full and was refused"),
                        field("STATUS_UNDERFLOW", 1, 1, WriteOneToClear, "a STATUS read found the status FIFO empty (returned 0)"),
                        field("SLAVE_CMD_UNDERFLOW", 8, 1, ReadOnly, "the slave's CMD_UNDERFLOW (cleared by the slave)"),
                        field("SLAVE_STATUS_OVERFLOW", 9, 1, ReadOnly, "the slave's STATUS_OVERFLOW (cleared by the slave)"),
                    ],
                ),
            ),
        ],
    };
    map.validate()?;
    Ok(map)
}

/// The map of every slave port, with FIFOs of 2^`fifo_log2` entries.
pub fn slave_map(fifo_log2: u32) -> Result<RegisterMap, RegMapError> {
    check(1, fifo_log2)?;
    use Access::*;
    let level = fifo_log2 + 1;
    let map = RegisterMap {
        name: "SFB_SLAVE",
        address_bits: SLAVE_ADDRESS_BITS,
        doc: "sync_fifo_bridge slave port: commands from the master, status to it",
        registers: vec![
            Register::word(
                "CMD",
                0x0,
                ReadOnly,
                0,
                "read pops the oldest released command (none released: 0, CMD_UNDERFLOW set, nothing popped)",
            ),
            Register::word("STATUS", 0x1, WriteOnly, 0, "push a status word for the master (refused when full)"),
            register(
                "LEVELS",
                0x2,
                "FIFO levels",
                vec![
                    field("CMD_READY", 0, level, ReadOnly, "released commands not yet read (data_ready = CMD_READY != 0)"),
                    field("STATUS_LEVEL", 8, level, ReadOnly, "status words the master has not read"),
                ],
            ),
            register(
                "FLAGS",
                0x3,
                "sticky error flags",
                vec![
                    field("CMD_UNDERFLOW", 0, 1, WriteOneToClear, "a CMD read found no released command"),
                    field("STATUS_OVERFLOW", 1, 1, WriteOneToClear, "a STATUS write found the status FIFO full and was refused"),
                ],
            ),
        ],
    };
    map.validate()?;
    Ok(map)
}

/// One named field of a map: its register and the field, or a panic naming
/// what is missing (the maps are fixed in this file, so a miss is a bug).
pub fn field_of<'a>(
    map: &'a RegisterMap,
    register: &str,
    field: &str,
) -> (&'a Register, &'a Field) {
    let r = map
        .register(register)
        .unwrap_or_else(|e| panic!("{}: {e}", map.name));
    let f = r
        .field(field)
        .unwrap_or_else(|e| panic!("{}: {e}", map.name));
    (r, f)
}
