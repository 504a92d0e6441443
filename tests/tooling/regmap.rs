//! Register maps: validation errors name the problem, field packing
//! round-trips through bitvec, and the generated C header compiles and
//! agrees with the Rust map.

use motion_hdl::regmap::{c_header, markdown, Access, Field, RegMapError, Register, RegisterMap};

fn field(name: &'static str, lsb: u32, width: u32, access: Access, reset: u64) -> Field {
    Field {
        name,
        lsb,
        width,
        access,
        reset,
        doc: "test field",
    }
}

fn example() -> RegisterMap {
    RegisterMap {
        name: "DEMO",
        address_bits: 8,
        doc: "a demonstration map",
        registers: vec![
            Register::word("ID", 0x00, Access::ReadOnly, 0x4d43_0001, "identity"),
            Register {
                name: "STATUS",
                address: 0x01,
                count: 1,
                stride: 0,
                doc: "status and interrupt flags",
                fields: vec![
                    field("UNDERRUN", 0, 1, Access::WriteOneToClear, 0),
                    field("LEVEL", 8, 8, Access::ReadOnly, 0x10),
                    field("ENABLE", 31, 1, Access::ReadWrite, 1),
                ],
            },
            Register::word("FIFO", 0x10, Access::WriteOnly, 0, "per-axis FIFO push").repeated(3, 4),
            Register::word("POSITION", 0x11, Access::ReadOnly, 0, "per-axis position")
                .repeated(3, 4),
        ],
    }
}

#[test]
fn a_good_map_validates_and_packs() {
    let map = example();
    map.validate().unwrap();
    let status = map.register("STATUS").unwrap();
    assert_eq!(status.reset_value(), 0x8000_1000);
    let word = status.pack(&[("LEVEL", 0xab), ("UNDERRUN", 1)]).unwrap();
    assert_eq!(word, 0x0000_ab01);
    assert_eq!(status.field("LEVEL").unwrap().extract(word).unwrap(), 0xab);
    // Read-modify-write keeps RW fields, never clears pending W1C flags.
    let read = 0x8000_1001;
    assert_eq!(status.modify(read, &[]).unwrap(), 0x8000_0000);
    assert_eq!(
        status.modify(read, &[("UNDERRUN", 1)]).unwrap(),
        0x8000_0001
    );
    assert_eq!(status.modify(read, &[("ENABLE", 0)]).unwrap(), 0);
    assert_eq!(status.w1c_mask(), 1);
    assert_eq!(status.field("ENABLE").unwrap().mask(), 0x8000_0000);
    let fifo = map.register("FIFO").unwrap();
    assert_eq!(fifo.address_of(2).unwrap(), 0x18);
    assert!(matches!(
        fifo.address_of(3),
        Err(RegMapError::NoSuchCopy { .. })
    ));
    assert!(matches!(
        status.pack(&[("LEVEL", 0x100)]),
        Err(RegMapError::ValueTooWide { .. })
    ));
    assert!(matches!(
        status.pack(&[("NOPE", 1)]),
        Err(RegMapError::NoSuchField { .. })
    ));
}

#[test]
fn every_malformed_map_is_refused_with_its_reason() {
    let mut overlap = example();
    overlap.registers[1]
        .fields
        .push(field("CLASH", 12, 8, Access::ReadOnly, 0));
    assert_eq!(
        overlap.validate(),
        Err(RegMapError::FieldOverlap {
            register: "STATUS".into(),
            first: "LEVEL".into(),
            second: "CLASH".into()
        })
    );
    let mut outside = example();
    outside.registers[1]
        .fields
        .push(field("WIDE", 30, 4, Access::ReadOnly, 0));
    assert!(matches!(
        outside.validate(),
        Err(RegMapError::FieldOutOfWord { .. })
    ));
    let mut reset = example();
    reset.registers[1].fields[1].reset = 0x100;
    assert!(matches!(
        reset.validate(),
        Err(RegMapError::ResetTooWide { .. })
    ));
    let mut address = example();
    // POSITION copies 0x11, 0x15, 0x19 meet a register placed at 0x15.
    address
        .registers
        .push(Register::word("EXTRA", 0x15, Access::ReadOnly, 0, "clash"));
    assert_eq!(
        address.validate(),
        Err(RegMapError::AddressOverlap {
            first: "POSITION".into(),
            second: "EXTRA".into(),
            address: 0x15
        })
    );
    let mut range = example();
    range
        .registers
        .push(Register::word("FAR", 0x100, Access::ReadOnly, 0, "too far"));
    assert!(matches!(
        range.validate(),
        Err(RegMapError::AddressOutOfRange { .. })
    ));
    let mut name = example();
    name.registers[0].name = "id";
    assert_eq!(name.validate(), Err(RegMapError::BadName("id".into())));
    let mut twice = example();
    twice
        .registers
        .push(Register::word("ID", 0x40, Access::ReadOnly, 0, "again"));
    assert_eq!(
        twice.validate(),
        Err(RegMapError::DuplicateName("ID".into()))
    );
    // STATUS.LEVEL and a register STATUS_LEVEL would both define
    // DEMO_STATUS_LEVEL_RESET.
    let mut collide = example();
    collide.registers.push(Register::word(
        "STATUS_LEVEL",
        0x40,
        Access::ReadOnly,
        0,
        "clash",
    ));
    assert!(matches!(
        collide.validate(),
        Err(RegMapError::MacroCollision(_))
    ));
    let mut none = example();
    none.registers[2].count = 0;
    assert_eq!(none.validate(), Err(RegMapError::NoCopies("FIFO".into())));
    let mut flat = example();
    flat.registers[2].stride = 0;
    assert_eq!(flat.validate(), Err(RegMapError::ZeroStride("FIFO".into())));
    let mut wo = example();
    wo.registers[2].fields[0].reset = 1;
    assert!(matches!(
        wo.validate(),
        Err(RegMapError::WriteOnlyReset { .. })
    ));
    let mut doc = example();
    doc.registers[0].doc = "ends the comment */ early";
    assert_eq!(doc.validate(), Err(RegMapError::BadDoc("ID".into())));
    let mut bits = example();
    bits.address_bits = 64;
    assert_eq!(bits.validate(), Err(RegMapError::BadAddressBits(64)));
    let mut huge = example();
    huge.registers[2].stride = u32::MAX;
    assert!(matches!(
        huge.validate(),
        Err(RegMapError::AddressOutOfRange { .. })
    ));
    let bad_field = field("BAD", 30, 8, Access::ReadOnly, 0);
    assert!(bad_field.insert(0, 1).is_err() && bad_field.extract(0).is_err());
}

/// The header compiles as C and its constants equal the Rust map's.
#[test]
fn the_c_header_compiles_and_agrees_with_the_map() {
    let map = example();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("demo_regs.h"),
        c_header(&map, "the regmap test"),
    )
    .unwrap();
    let status = map.register("STATUS").unwrap();
    let program = r#"#include <stdio.h>
#include "demo_regs.h"
int main(void) {
    printf("%lu %lu %lu %lu %lu\n", DEMO_STATUS_INDEX, DEMO_STATUS_RESET, DEMO_STATUS_LEVEL_MASK,
           DEMO_FIFO_INDEX(2), DEMO_POSITION_OFFSET(1));
    return 0;
}
"#
    .to_string();
    // Every number is an unsigned long: 32 bits even where int is 16.
    let header = std::fs::read_to_string(dir.path().join("demo_regs.h")).unwrap();
    for line in header.lines().filter(|l| l.starts_with("#define DEMO_")) {
        // (The include guard has no value.)
        if let Some(value) = line.splitn(3, ' ').nth(2) {
            assert!(value.contains("UL"), "no UL suffix: {line}");
        }
    }
    let expected = format!(
        "{} {} {} {} {}\n",
        status.address,
        status.reset_value(),
        status.field("LEVEL").unwrap().mask(),
        map.register("FIFO").unwrap().address_of(2).unwrap(),
        map.register("POSITION").unwrap().address_of(1).unwrap() * 4
    );
    for standard in ["c89", "c99"] {
        let printed = motion_hdl::tools::run_c_program(dir.path(), standard, &program)
            .unwrap_or_else(|e| panic!("{standard}: {e}"));
        assert_eq!(printed, expected, "{standard}");
    }
}

#[test]
fn the_markdown_table_lists_every_register_and_field() {
    let map = example();
    let table = markdown(&map, "the regmap test");
    for text in [
        "| 0x0001 | `STATUS` | `0x80001000` | status and interrupt flags |",
        "| 15:8 | `LEVEL` | RO | `0x10` |",
        "| 0 | `UNDERRUN` | W1C |",
        "0x0010 + n * 0x4 (n < 3)",
    ] {
        assert!(table.contains(text), "table lacks {text:?}:\n{table}");
    }
}

/// The field constants the RTL, the models and the tests use by name
/// (`registers::fields`) against the maps, by register and field name:
/// the maps are built from the constants, and this checks that each
/// constant went into the field it names (and that every width the RTL
/// slices is the map's).
#[test]
fn the_field_constants_agree_with_the_maps() {
    use motion_hdl::blocks::dac_interface::registers as dac;
    use motion_hdl::blocks::motion_controller::registers::{self as mc, fields as f};
    // (register, field, lsb, width; 0 = the map's own width, which depends
    // on the build).
    let controller: &[(&str, &str, u32, u32)] = &[
        ("CONTROL", "RUN", f::CONTROL_RUN, 1),
        ("CONTROL", "FLUSH", f::CONTROL_FLUSH, 1),
        ("STATE", "RUNNING", f::STATE_RUNNING, 1),
        ("STATE", "WATCHDOG_ARMED", f::STATE_WATCHDOG_ARMED, 1),
        ("STATE", "WATCHDOG_EXPIRED", f::STATE_WATCHDOG_EXPIRED, 1),
        ("STATE", "ESTOP_INPUT", f::STATE_ESTOP_INPUT, 1),
        ("STATE", "ESTOP_LATCHED", f::STATE_ESTOP_LATCHED, 1),
        ("STATE", "ABORTED", f::STATE_ABORTED, 1),
        ("STATE", "INPUTS_READY", f::STATE_INPUTS_READY, 1),
        ("CONFIG", "DDA_ONLY", f::CONFIG_DDA_ONLY, 1),
        ("CONFIG", "ANALOG", f::CONFIG_ANALOG, 1),
        ("CONFIG", "PROBE", f::CONFIG_PROBE, 1),
        ("PERIOD_TICKS", "VALUE", f::VALUE, 0),
        ("FIFO_LOW_WATER", "LEVEL", f::FIFO_LEVEL, 0),
        (
            "INPUT_FILTER",
            "LENGTH",
            f::FILTER_LENGTH,
            f::FILTER_LENGTH_WIDTH,
        ),
        (
            "INPUT_FILTER",
            "SAMPLE_RATE",
            f::FILTER_SAMPLE_RATE,
            f::FILTER_SAMPLE_RATE_WIDTH,
        ),
        ("INPUT_POLARITY", "LIMIT_POS", f::POLARITY_LIMIT_POS, 1),
        ("INPUT_POLARITY", "LIMIT_NEG", f::POLARITY_LIMIT_NEG, 1),
        ("INPUT_POLARITY", "HOME", f::POLARITY_HOME, 1),
        ("INPUT_POLARITY", "DRIVE_ALARM", f::POLARITY_DRIVE_ALARM, 1),
        ("INPUT_POLARITY", "GPIO", f::POLARITY_GPIO, f::GPIO_WIDTH),
        (
            "STOP_CAUSE",
            "CAUSE",
            f::STOP_CAUSE_CAUSE,
            f::STOP_CAUSE_WIDTH,
        ),
        (
            "STOP_CAUSE",
            "AXIS",
            f::STOP_CAUSE_AXIS,
            f::STOP_CAUSE_WIDTH,
        ),
        ("GPIO_IN", "LEVEL", f::GPIO_LEVEL, f::GPIO_WIDTH),
        ("GPIO_OUT", "LEVEL", f::GPIO_LEVEL, f::GPIO_WIDTH),
        ("GPIO_SAFE", "MASK", f::GPIO_LEVEL, f::GPIO_WIDTH),
        ("GPIO_IRQ_ENABLE", "RISE", f::GPIO_RISE, f::GPIO_WIDTH),
        ("GPIO_IRQ_ENABLE", "FALL", f::GPIO_FALL, f::GPIO_WIDTH),
        ("GPIO_EDGES", "RISE", f::GPIO_RISE, f::GPIO_WIDTH),
        ("GPIO_EDGES", "FALL", f::GPIO_FALL, f::GPIO_WIDTH),
        ("FIFO_STATUS", "LEVEL", f::FIFO_LEVEL, 0),
        ("FIFO_STATUS", "EMPTY", f::FIFO_EMPTY, 1),
        ("FIFO_STATUS", "FULL", f::FIFO_FULL, 1),
        ("FIFO_STATUS", "LOW", f::FIFO_LOW, 1),
        ("AXIS_CONFIG", "UNIFORM", f::AXIS_UNIFORM, 1),
        ("AXIS_CONFIG", "INTERLEAVED", f::AXIS_INTERLEAVED, 1),
        (
            "AXIS_CONFIG",
            "STEP_MODE",
            f::AXIS_STEP_MODE,
            f::AXIS_STEP_MODE_WIDTH,
        ),
        (
            "AXIS_CONFIG",
            "ENC_FILTER",
            f::AXIS_ENC_FILTER,
            f::AXIS_ENC_FILTER_WIDTH,
        ),
        (
            "AXIS_CONFIG",
            "ENC_COUNTER_MODE",
            f::AXIS_ENC_COUNTER_MODE,
            1,
        ),
        ("AXIS_CONFIG", "INDEX_INVERT", f::AXIS_INDEX_INVERT, 1),
        ("AXIS_CONFIG", "INDEX_CLEAR", f::AXIS_INDEX_CLEAR, 1),
        ("AXIS_CONFIG", "INDEX_LATCH", f::AXIS_INDEX_LATCH, 1),
        ("AXIS_CONFIG", "INDEX_ONCE", f::AXIS_INDEX_ONCE, 1),
        ("AXIS_CONFIG", "ANALOG", f::AXIS_ANALOG, 1),
        ("STEP_LEN", "VALUE", f::VALUE, f::STEP_TIMING_WIDTH),
        ("STEP_SPACE", "VALUE", f::VALUE, f::STEP_TIMING_WIDTH),
        ("DIR_SETUP", "VALUE", f::VALUE, f::STEP_TIMING_WIDTH),
        ("DIR_HOLD", "VALUE", f::VALUE, f::STEP_TIMING_WIDTH),
        (
            "ENC_SAMPLE_RATE",
            "VALUE",
            f::VALUE,
            f::ENC_SAMPLE_RATE_WIDTH,
        ),
        ("AXIS_STATUS", "STEP_OVERRUN", f::STATUS_STEP_OVERRUN, 1),
        (
            "AXIS_STATUS",
            "INTERP_OVERRANGE",
            f::STATUS_INTERP_OVERRANGE,
            1,
        ),
        (
            "AXIS_STATUS",
            "INTERP_OVERFLOW",
            f::STATUS_INTERP_OVERFLOW,
            1,
        ),
        ("AXIS_STATUS", "ENCODER_ERROR", f::STATUS_ENCODER_ERROR, 1),
        ("AXIS_STATUS", "INDEX_SEEN", f::STATUS_INDEX_SEEN, 1),
        ("AXIS_STATUS", "STEP_BUSY", f::STATUS_STEP_BUSY, 1),
        (
            "AXIS_STATUS",
            "UNIFORM_RUNNING",
            f::STATUS_UNIFORM_RUNNING,
            1,
        ),
        (
            "AXIS_STATUS",
            "STEP_MODE_INVALID",
            f::STATUS_STEP_MODE_INVALID,
            1,
        ),
        ("AXIS_COMMAND", "CLEAR_FAULTS", f::CMD_CLEAR_FAULTS, 1),
        ("AXIS_COMMAND", "CLEAR_ENCODER", f::CMD_CLEAR_ENCODER, 1),
        ("AXIS_COMMAND", "REARM_INDEX", f::CMD_REARM_INDEX, 1),
        ("AXIS_COMMAND", "CLEAR_POSITION", f::CMD_CLEAR_POSITION, 1),
        (
            "AXIS_COMMAND",
            "CLEAR_ENCODER_ERROR",
            f::CMD_CLEAR_ENCODER_ERROR,
            1,
        ),
        ("IO_CONFIG", "LIMIT_ENABLE", f::LIMIT_ENABLE, 1),
        ("IO_CONFIG", "ALARM_ENABLE", f::ALARM_ENABLE, 1),
        ("IO_CONFIG", "STOP_ON_HOME", f::STOP_ON_HOME, 1),
        ("IO_CONFIG", "DRIVE_ENABLE", f::DRIVE_ENABLE, 1),
        ("IO_STATUS", "LIMIT_POS", f::IO_LIMIT_POS, 1),
        ("IO_STATUS", "LIMIT_NEG", f::IO_LIMIT_NEG, 1),
        ("IO_STATUS", "HOME", f::IO_HOME, 1),
        ("IO_STATUS", "DRIVE_ALARM", f::IO_DRIVE_ALARM, 1),
        ("IO_STATUS", "LIMIT_POS_TRIPPED", f::IO_LIMIT_POS_TRIPPED, 1),
        ("IO_STATUS", "LIMIT_NEG_TRIPPED", f::IO_LIMIT_NEG_TRIPPED, 1),
        ("IO_STATUS", "ALARM_TRIPPED", f::IO_ALARM_TRIPPED, 1),
        ("IO_STATUS", "HOME_SEEN", f::IO_HOME_SEEN, 1),
        ("IO_STATUS", "DRIVE_ENABLE", f::IO_DRIVE_ENABLE, 1),
        ("IO_COMMAND", "CLEAR_LIMITS", f::CLEAR_LIMITS, 1),
        ("IO_COMMAND", "CLEAR_ALARM", f::CLEAR_ALARM, 1),
        ("IO_COMMAND", "CLEAR_HOME", f::CLEAR_HOME, 1),
        ("PROBE_CONTROL", "ARM", f::PROBE_ARM, 1),
        ("PROBE_CONTROL", "EDGE", f::PROBE_EDGE, 1),
        ("PROBE_CONTROL", "TRIPPED", f::PROBE_TRIPPED, 1),
        ("PROBE_CONTROL", "LEVEL", f::PROBE_LEVEL, 1),
        ("SOFT_LIMIT", "ENABLE", f::SOFT_ENABLE, 3),
        ("SOFT_LIMIT", "BEYOND", f::SOFT_BEYOND, 3),
        ("SOFT_LIMIT", "AXIS", f::SOFT_AXIS, f::SOFT_AXIS_WIDTH),
        ("SOFT_LIMIT", "NEGATIVE", f::SOFT_NEGATIVE, 1),
        ("CONFIG", "SOFT_LIMITS", f::CONFIG_SOFT_LIMITS, 1),
    ];
    let check = |map: &RegisterMap, register: &str, field: &str, lsb: u32, width: u32| {
        let got = map
            .field(register, field)
            .unwrap_or_else(|e| panic!("{}: {e}", map.name));
        assert_eq!(got.lsb, lsb, "{}: {register}.{field} lsb", map.name);
        if width != 0 {
            assert_eq!(got.width, width, "{}: {register}.{field} width", map.name);
        }
    };
    for (uniform, analog) in [(true, false), (false, true), (true, true), (false, false)] {
        let build = mc::BuildOptions {
            uniform,
            analog,
            probe: true,
            soft_limits: true,
            spindle: false,
            laser: false,
        };
        let map = mc::register_map(3, 4, build).unwrap();
        for &(register, field, lsb, width) in controller {
            check(&map, register, field, lsb, width);
        }
        // Without the probe (the soft limits) their registers are absent;
        // the rest is the same.
        let without = mc::register_map(
            3,
            4,
            mc::BuildOptions {
                probe: false,
                ..build
            },
        )
        .unwrap();
        let without_soft = mc::register_map(
            3,
            4,
            mc::BuildOptions {
                soft_limits: false,
                ..build
            },
        )
        .unwrap();
        for &(register, field, lsb, width) in controller {
            match register {
                "PROBE_CONTROL" | "PROBE_CMD_POSITION" | "PROBE_ACT_POSITION" => {
                    assert!(
                        without.register(register).is_err(),
                        "{register} without PROBE"
                    )
                }
                _ => check(&without, register, field, lsb, width),
            }
            match register {
                "SOFT_LIMIT" | "SOFT_MIN" | "SOFT_MAX" => assert!(
                    without_soft.register(register).is_err(),
                    "{register} without SOFT_LIMITS"
                ),
                _ => check(&without_soft, register, field, lsb, width),
            }
        }
        // The interrupt bits: STATUS and IRQ_ENABLE, in event order.
        for register in ["STATUS", "IRQ_ENABLE"] {
            let r = map.register(register).unwrap();
            assert_eq!(r.fields.len(), mc::irq::COUNT);
            for (n, field) in r.fields.iter().enumerate() {
                assert_eq!(
                    (field.lsb, field.width),
                    (n as u32, 1),
                    "{register}.{}",
                    field.name
                );
            }
        }
        assert_eq!(
            map.field("FIFO_STATUS", "LEVEL").unwrap().width,
            map.field("FIFO_LOW_WATER", "LEVEL").unwrap().width
        );
    }
    // The spindle unit's registers: in a SPINDLE build only, at the
    // addresses and bits the RTL and the model take by name.
    let spindle = mc::register_map(3, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_SPINDLE).unwrap();
    let s = mc::spindle::BASE;
    for (register, field, lsb, width, address) in [
        (
            "CONFIG",
            "SPINDLE",
            f::CONFIG_SPINDLE,
            1,
            mc::global::CONFIG,
        ),
        (
            "SPINDLE_CONFIG",
            "FILTER",
            f::SPINDLE_FILTER,
            f::SPINDLE_FILTER_WIDTH,
            s + 3,
        ),
        (
            "SPINDLE_CONFIG",
            "COUNTER_MODE",
            f::SPINDLE_COUNTER_MODE,
            1,
            s + 3,
        ),
        (
            "SPINDLE_CONFIG",
            "INDEX_INVERT",
            f::SPINDLE_INDEX_INVERT,
            1,
            s + 3,
        ),
        (
            "SPINDLE_CONFIG",
            "SPEED_WINDOW",
            f::SPINDLE_SPEED_WINDOW,
            f::SPINDLE_SPEED_WINDOW_WIDTH,
            s + 3,
        ),
        ("GEAR_CONTROL", "ARM", f::GEAR_ARM, 1, s + 4),
        ("GEAR_CONTROL", "STOP", f::GEAR_STOP, 1, s + 4),
        ("GEAR_CONTROL", "HALT", f::GEAR_HALT, 1, s + 4),
        (
            "GEAR_CONTROL",
            "CLEAR_ENCODER_ERROR",
            f::GEAR_CLEAR_ENCODER_ERROR,
            1,
            s + 4,
        ),
        (
            "GEAR_CONTROL",
            "SPINDLE_REVERSE",
            f::GEAR_SPINDLE_REVERSE,
            1,
            s + 4,
        ),
        (
            "GEAR_CONTROL",
            "AXIS_REVERSE",
            f::GEAR_AXIS_REVERSE,
            1,
            s + 4,
        ),
        (
            "GEAR_CONTROL",
            "AXIS",
            f::GEAR_AXIS,
            f::GEAR_AXIS_WIDTH,
            s + 4,
        ),
        (
            "GEAR_STATUS",
            "PHASE",
            f::GEAR_PHASE,
            f::GEAR_PHASE_WIDTH,
            s + 5,
        ),
        ("GEAR_STATUS", "LOCKED", f::GEAR_LOCKED, 1, s + 5),
        ("GEAR_STATUS", "DONE", f::GEAR_DONE, 1, s + 5),
        ("GEAR_STATUS", "INVALID", f::GEAR_INVALID, 1, s + 5),
        ("GEAR_STATUS", "OVERRUN", f::GEAR_OVERRUN, 1, s + 5),
        (
            "GEAR_STATUS",
            "ENCODER_ERROR",
            f::GEAR_ENCODER_ERROR,
            1,
            s + 5,
        ),
        (
            "SPINDLE_POSITION",
            "VALUE",
            f::VALUE,
            24,
            mc::spindle::SPINDLE_POSITION,
        ),
        (
            "SPINDLE_INDEX_POSITION",
            "VALUE",
            f::VALUE,
            24,
            mc::spindle::SPINDLE_INDEX_POSITION,
        ),
        (
            "SPINDLE_SPEED",
            "VALUE",
            f::VALUE,
            24,
            mc::spindle::SPINDLE_SPEED,
        ),
        (
            "GEAR_NUMERATOR",
            "VALUE",
            f::VALUE,
            mc::GEAR_BITS,
            mc::spindle::GEAR_NUMERATOR,
        ),
        (
            "GEAR_DENOMINATOR",
            "VALUE",
            f::VALUE,
            mc::GEAR_BITS,
            mc::spindle::GEAR_DENOMINATOR,
        ),
        (
            "GEAR_RAMP",
            "VALUE",
            f::VALUE,
            mc::GEAR_BITS,
            mc::spindle::GEAR_RAMP,
        ),
        (
            "GEAR_LENGTH",
            "VALUE",
            f::VALUE,
            mc::GEAR_BITS,
            mc::spindle::GEAR_LENGTH,
        ),
        (
            "GEAR_POSITION",
            "VALUE",
            f::VALUE,
            24,
            mc::spindle::GEAR_POSITION,
        ),
    ] {
        check(&spindle, register, field, lsb, width);
        assert_eq!(
            spindle.register(register).unwrap().address,
            address,
            "{register}"
        );
    }
    assert_eq!(
        spindle
            .field("SPINDLE_CONFIG", "SPEED_WINDOW")
            .unwrap()
            .reset,
        f::SPINDLE_SPEED_WINDOW_RESET
    );
    let without_spindle = mc::register_map(3, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA).unwrap();
    assert!(without_spindle.register("GEAR_CONTROL").is_err());
    assert!(mc::register_map(7, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_SPINDLE).is_err());
    assert!(mc::register_map(6, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_SPINDLE).is_ok());

    // The laser unit's registers: in a LASER build only, at the addresses
    // and bits the RTL and the model take by name.
    let laser = mc::register_map(3, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_LASER).unwrap();
    let l = mc::laser::BASE;
    let word = f::LASER_WORD_WIDTH;
    for (register, field, lsb, width, address) in [
        ("CONFIG", "LASER", f::CONFIG_LASER, 1, mc::global::CONFIG),
        ("LASER_CONTROL", "ENABLE", f::LASER_ENABLE, 1, l),
        ("LASER_CONTROL", "DYNAMIC", f::LASER_DYNAMIC, 1, l),
        (
            "LASER_CONTROL",
            "CLEAR_OVERFLOW",
            f::LASER_CLEAR_OVERFLOW,
            1,
            l,
        ),
        (
            "LASER_CONTROL",
            "AXIS_A",
            f::LASER_AXIS_A,
            f::LASER_AXIS_WIDTH,
            l,
        ),
        (
            "LASER_CONTROL",
            "AXIS_B",
            f::LASER_AXIS_B,
            f::LASER_AXIS_WIDTH,
            l,
        ),
        ("LASER_PWM_PERIOD", "VALUE", f::VALUE, word, l + 1),
        ("LASER_FIFO", "POWER", f::LASER_POWER, word, l + 2),
        ("LASER_FIFO", "FEED", f::LASER_FEED, word, l + 2),
        ("LASER_STATUS", "LEVEL", f::LASER_LEVEL, 5, l + 3),
        ("LASER_STATUS", "OVERFLOW", f::LASER_OVERFLOW, 1, l + 3),
        ("LASER_STATUS", "ACTIVE", f::LASER_ACTIVE, 1, l + 3),
        ("LASER_STATUS", "BUSY", f::LASER_BUSY, 1, l + 3),
        ("LASER_OUTPUT", "DUTY", f::LASER_POWER, word, l + 4),
        ("LASER_OUTPUT", "SPEED", f::LASER_SPEED, word, l + 4),
        ("LASER_CONTROL", "SOURCE", f::LASER_SOURCE, 1, l),
        ("LASER_POWER", "POWER", f::LASER_POWER, word, l + 5),
        ("LASER_POWER", "FEED", f::LASER_FEED, word, l + 5),
    ] {
        check(&laser, register, field, lsb, width);
        assert_eq!(
            laser.register(register).unwrap().address,
            address,
            "{register}"
        );
    }
    assert_eq!(
        laser.register("LASER_POWER").unwrap().address,
        mc::laser::LASER_POWER
    );
    assert_eq!(
        mc::laser::BASE + mc::laser::WORDS,
        mc::laser::LASER_POWER + 1,
        "the unit's last word"
    );
    assert!(laser.register("GEAR_CONTROL").is_err());
    assert!(without_spindle.register("LASER_CONTROL").is_err());
    assert!(mc::register_map(7, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_LASER).is_err());
    assert!(mc::register_map(6, 4, mc::BuildOptions::MOTION_CONTROLLER_DDA_LASER).is_ok());

    let map = dac::register_map(3, 16).unwrap();
    for (field, lsb) in [
        ("SETUP", dac::fields::TIMING_SETUP),
        ("WIDTH", dac::fields::TIMING_WIDTH),
        ("HOLD", dac::fields::TIMING_HOLD),
        ("LDAC_WIDTH", dac::fields::TIMING_LDAC_WIDTH),
    ] {
        check(&map, "TIMING", field, lsb, dac::fields::TIMING_FIELD_BITS);
    }
    check(&map, "CODE", "VALUE", dac::fields::CODE_VALUE, 16);
    check(&map, "APPLIED", "VALUE", dac::fields::CODE_VALUE, 16);
}
