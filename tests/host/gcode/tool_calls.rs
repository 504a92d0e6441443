//! Tools and the tool length offset against hand-computed machine
//! positions: the sequence of the first test is LinuxCNC 2.9's `rs274`
//! run (in inches there: T1 0.5 in, T3 1.0 in), in mm here.

use motion_hdl::host::gcode::interpreter::{interpret_with, Program, Setup};
use motion_hdl::host::toolpath::Item;
use motion_hdl::host::ToolTable;

fn table() -> ToolTable {
    ToolTable::parse("T1 P1 Z12.5 D6 ;6 mm end mill\nT3 P3 Z25 D3\n").unwrap()
}

fn outcome(program: &str, tools: Option<ToolTable>) -> Result<Program, String> {
    let setup = Setup {
        tools,
        ..Setup::default()
    };
    interpret_with(program, &setup).map_err(|e| e.to_string())
}

fn run(program: &str) -> Program {
    outcome(program, Some(table())).unwrap_or_else(|e| panic!("{program:?}: {e}"))
}

fn error(program: &str) -> String {
    outcome(program, Some(table())).unwrap_err()
}

/// Every move's (line, machine Z).
fn z_ends(program: &Program) -> Vec<(usize, f64)> {
    program
        .toolpath
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Move(m) => Some((m.line, m.end[2])),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

#[test]
fn g43_g43_1_g43_2_and_g49_shift_the_work_coordinates() {
    let p =
        run("T1 M6\nG43\nG0 Z0\nG43 H3\nG0 Z0\nG49\nG0 Z0\nG43.1 Z5\nG0 Z0\nG43.2 H1\nG0 Z0\nM2");
    assert_eq!(
        z_ends(&p),
        [(3, 12.5), (5, 25.0), (7, 0.0), (9, 5.0), (11, 17.5)]
    );
    // T, M6 and G43 in one block: the tool is loaded before G43 takes it.
    assert_eq!(z_ends(&run("T3 M6 G43 G0 Z0")), [(1, 25.0)]);
    assert_eq!(z_ends(&run("M61 Q3\nG43\nG0 Z1")), [(3, 26.0)]);
    // T alone loads nothing: G43 takes the empty spindle's 0.
    assert_eq!(z_ends(&run("T3\nG43\nG0 Z1")), [(3, 1.0)]);
    // G43 moves nothing: the work position reads the offset.
    let p = run("T1 M6 G43");
    assert!(p.toolpath.items.is_empty());
    assert_eq!(p.final_position, [0.0, 0.0, -12.5]);
    // Fusion 360's `G43 Z0.6 H1` in inches: the offset, then the modal G0.
    let p = run("G20 G0 X1\nT1 M6\nG43 Z0.6 H1");
    assert_eq!(z_ends(&p)[1], (3, 0.6 * 25.4 + 12.5));
}

#[test]
fn g92_g10_l20_count_the_tool_offset_and_g53_does_not() {
    let p = run("T1 M6 G43\nG0 Z0\nG92 Z10\nG0 Z0\nG10 L20 P1 Z1\nG0 Z0\nG53 G0 Z0");
    // G92 Z10 at machine 12.5: offset 12.5 - 12.5 - 10 = -10, so Z0 is
    // machine 2.5; L20 Z1 there: origin 2.5 + 10 - 12.5 - 1 = -1.
    assert_eq!(z_ends(&p), [(2, 12.5), (4, 2.5), (6, 1.5), (7, 0.0)]);
    assert_eq!(p.parameters.get(5223), Some(-1.0));
}

#[test]
fn tool_words_are_checked_by_name() {
    for (program, message) in [
        ("T7 M6", "line 1: T7: tool 7 is not in the tool table (LinuxCNC: Requested tool 7 not found in the tool table)"),
        ("G43 H7", "line 1: H7: tool 7 is not in the tool table (LinuxCNC: Requested tool 7 not found in the tool table)"),
        ("M61 Q9", "line 1: Q9: tool 9 is not in the tool table (LinuxCNC: Requested tool 9 not found in the tool table)"),
        ("M6", "line 1: M6 needs a tool selected first with T (LinuxCNC: Need tool prepared -Txx- for toolchange)"),
        ("T1.5", "line 1: T1.5 is not a tool number: a whole number, 0 (no tool) or more"),
        ("M61", "line 1: M61 needs Q: the tool now in the spindle"),
        ("G43.2", "line 1: G43.2 needs H (a tool) or axis words (the offset to add)"),
        ("G43.1 Z1 G0 X1", "line 1: G43.1 and G0 in one block: both use the axis words (LinuxCNC: Cannot use two g codes that both use axis values)"),
        ("G43 G49", "line 1: G43 and G49 in one block: both set the tool length offset"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
    // T0 and H0 are no tool: always accepted, no offset.
    assert_eq!(z_ends(&run("T0 M6 G43\nG43 H0\nG0 Z1")), [(3, 1.0)]);
}

#[test]
fn without_a_table_every_tool_is_accepted_with_no_offset_and_reported() {
    let p = outcome("T1 M6\nG43 H1\nG0 Z0\nG0 Z1 H2", None).unwrap();
    assert!(z_ends(&p) == [(4, 1.0)]);
    let got: Vec<_> = p
        .ignored
        .iter()
        .map(|i| (i.line, i.word.as_str(), i.what))
        .collect();
    assert_eq!(
        got,
        [
            (1, "T1", "tool"),
            (1, "M6", "tool change"),
            (
                2,
                "G43 H1",
                "tool length offset 0: no tool table given (--tools)"
            ),
            (4, "H2", "tool offset"),
        ]
    );
}
