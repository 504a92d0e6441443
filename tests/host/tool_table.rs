//! Tests of `motion_hdl::host::tool_table` (`src/host/tool_table.rs`).

use motion_hdl::host::tool_table::*;

#[test]
fn linuxcnc_tables_read_in_mm() {
    // The shape of LinuxCNC's configs/sim/axis/sim_mm.tbl.
    let table = ToolTable::parse(
        "T1 P1 D0.635 Z+0.511 ;1/8 end mill\n\n; a whole-line remark\nt2 p2 d6.35 z0.1 x-1 q0 i0 j0 a0\nT99999 P99999 Z0.100 ;big tool number\n",
    )
        .unwrap();
    assert_eq!(table.tools.len(), 3);
    let t1 = table.get(1).unwrap();
    assert_eq!(
        (t1.pocket, t1.offset, t1.diameter, t1.remark.as_str()),
        (Some(1), [0.0, 0.0, 0.511], 0.635, "1/8 end mill")
    );
    assert_eq!(table.get(2).unwrap().offset, [-1.0, 0.0, 0.1]);
    assert!(table.get(99999).is_some());
    assert_eq!(table.get(3), None);
}

#[test]
fn errors_name_the_line_and_the_word() {
    let error = |text: &str| ToolTable::parse(text).unwrap_err().to_string();
    assert_eq!(error("P1 Z1"), "line 1: a tool needs its number, T");
    assert_eq!(
        error("T1\nT0 Z1"),
        "line 2: T0 is not a tool number: a whole number from 1 (T0 is no tool)"
    );
    assert_eq!(error("T1 Z1\nT1 Z2"), "line 2: T1 is already in the table");
    assert_eq!(error("T1 Zx"), "line 1: `Zx` is not a number after Z");
    assert_eq!(error("T1 Z1 Z2"), "line 1: Z appears twice");
    assert_eq!(
        ToolTable::parse("T1 D-2").unwrap().get(1).unwrap().diameter,
        -2.0
    );
    assert_eq!(
        error("T1 A5"),
        "line 1: A5 offsets an axis this machine does not have (X, Y and Z only)"
    );
    assert_eq!(
        error("T1 P1.5"),
        "line 1: P1.5 is not a pocket: a whole number from 0"
    );
    assert_eq!(error("T1 R2"), "line 1: R2: R is not a tool table word");
    assert_eq!(
        error("T1 5"),
        "line 1: `5` is not a word: a letter and a number"
    );
}
