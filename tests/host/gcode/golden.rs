//! The interpreter against LinuxCNC: each program in `tests/gcode_golden/`
//! runs here and in LinuxCNC 2.9's rs274 (its trace, `NAME.canon`, made by
//! `tests/gcode_golden/regenerate.sh`), and the two toolpaths must agree
//! move for move: kind, end, and an arc's center, direction and turns.

use std::path::PathBuf;

use super::canon::{difference, from_toolpath, parse};
use motion_hdl::host::gcode::interpreter::{interpret_with, Setup};
use motion_hdl::host::tool_table::ToolTable;

/// LinuxCNC's trace has 4 decimals in the program's units: 0.00127 mm in
/// inches.
const TOLERANCE_MM: f64 = 0.002;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/gcode_golden")
}

/// The golden programs' start with `table` (tools.tbl's text) for tools.
fn setup(table: &str) -> Setup {
    Setup {
        tools: Some(ToolTable::parse(table).unwrap()),
        ..Setup::default()
    }
}

fn tools_tbl() -> String {
    std::fs::read_to_string(golden_dir().join("tools.tbl")).unwrap()
}

#[test]
fn golden_programs_move_as_linuxcnc_moves_them() {
    let dir = golden_dir();
    let setup = setup(&tools_tbl());
    let mut programs: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ngc"))
        .collect();
    programs.sort();
    assert!(programs.len() >= 6, "golden programs in {}", dir.display());
    for program in programs {
        let text = std::fs::read_to_string(&program).unwrap();
        let ours =
            interpret_with(&text, &setup).unwrap_or_else(|e| panic!("{}: {e}", program.display()));
        let trace = std::fs::read_to_string(program.with_extension("canon")).unwrap();
        let lcnc = parse(&trace).unwrap();
        assert!(!lcnc.is_empty(), "{}: an empty trace", program.display());
        if let Some(diff) = difference(&lcnc, &from_toolpath(&ours.toolpath.items), TOLERANCE_MM) {
            panic!("{}: {diff}", program.display());
        }
    }
}

/// The comparison can fail: a tool 0.01 mm larger moves every compensated
/// end.
#[test]
fn golden_comparison_sees_a_wrong_radius() {
    let dir = golden_dir();
    let setup = setup(&tools_tbl().replace("D6.0", "D6.02"));
    let program = dir.join("comp_square_outside.ngc");
    let ours = interpret_with(&std::fs::read_to_string(&program).unwrap(), &setup).unwrap();
    let lcnc = parse(&std::fs::read_to_string(program.with_extension("canon")).unwrap()).unwrap();
    let diff = difference(&lcnc, &from_toolpath(&ours.toolpath.items), TOLERANCE_MM);
    assert!(
        diff.is_some_and(|d| d.starts_with("move 1:")),
        "the wrong radius went unseen"
    );
}
