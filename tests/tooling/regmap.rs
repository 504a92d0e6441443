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
