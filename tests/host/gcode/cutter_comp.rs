//! Cutter compensation by hand: offsets computed on paper, every refusal,
//! and the held-back moves' order. The golden programs
//! (`golden.rs`) check the geometry against LinuxCNC's own.

use super::support::{error_with, run_with};
use motion_hdl::host::gcode::interpreter::{interpret_with, Program, Setup};
use motion_hdl::host::tool_table::ToolTable;
use motion_hdl::host::toolpath::{Item, MoveKind};

/// T1 is 6 mm across (radius 3), T2 -6 mm (radius 3, other side).
fn setup() -> Setup {
    Setup {
        tools: Some(ToolTable::parse("T1 D6\nT2 D-6\n").unwrap()),
        ..Setup::default()
    }
}

fn run(program: &str) -> Program {
    run_with(program, &setup())
}

fn error(program: &str) -> String {
    error_with(program, &setup())
}

/// A move's x, y and, for an arc, its center and whether it is clockwise.
type PlaneMove = (f64, f64, Option<([f64; 2], bool)>);

/// Each move, rounded to 1e-9.
fn moves(program: &str) -> Vec<PlaneMove> {
    let round = |v: f64| (v * 1e9).round() / 1e9;
    run(program)
        .toolpath
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Move(m) => Some((
                round(m.end[0]),
                round(m.end[1]),
                match m.kind {
                    MoveKind::Arc(a) => Some((a.center.map(round), a.clockwise)),
                    MoveKind::Line => None,
                },
            )),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

/// From (0, -10), up to the origin with compensation on, then along X.
const ENTRY: &str = "G21 F600 G0 X0 Y-10\nT1 M6\nG41\nG1 X0 Y0\n";

#[test]
fn the_entry_ends_square_to_its_line_and_a_convex_corner_is_an_arc() {
    // Heading +Y with the tool on the left: it ends at (-3, 0). Turning
    // right to +X is convex for it: an arc about the corner, clockwise,
    // to (0, 3), then the line 3 above.
    assert_eq!(
        moves(&format!("{ENTRY}X10\nM2")),
        vec![
            (0.0, -10.0, None),
            (-3.0, 0.0, None),
            (0.0, 3.0, Some(([0.0, 0.0], true))),
            (10.0, 3.0, None),
        ]
    );
}

#[test]
fn a_concave_corner_shortens_the_move_into_it() {
    // X10 then Y10 turns left into the tool: the line 3 above the X axis
    // stops 3 short of x = 7, where the tool touches x = 10 - 3 too.
    assert_eq!(
        moves(&format!("{ENTRY}X10\nY10\nM2"))[3..],
        [(7.0, 3.0, None), (7.0, 10.0, None)]
    );
}

#[test]
fn arcs_run_one_radius_inside_or_outside_the_programmed_circle() {
    // Up to (20, 0) with the tool on the left, at (17, 0). G3 about the
    // origin turns left, tangent to the entry: the tool is inside, on the
    // circle of radius 20 - 3, to (0, 17). The line -X is tangent to its
    // end: to (-10, 17). G2 about (-10, 40) turns right, tangent: the tool
    // is outside, on the circle of radius 20 + 3, to (-33, 40).
    let program = "G21 F600 G0 X20 Y-10\nT1 M6 G41\nG1 X20 Y0\n\
                   G3 X0 Y20 I-20 J0\nG1 X-10\nG2 X-30 Y40 I0 J20\nM2";
    assert_eq!(
        moves(program),
        vec![
            (20.0, -10.0, None),
            (17.0, 0.0, None),
            (0.0, 17.0, Some(([0.0, 0.0], false))),
            (-10.0, 17.0, None),
            (-33.0, 40.0, Some(([-10.0, 40.0], true))),
        ]
    );
}

#[test]
fn g42_and_a_negative_diameter_take_the_right() {
    // On the right, X10 turns into the tool: the entry stops at (3, -3).
    let right = vec![(0.0, -10.0, None), (3.0, -3.0, None), (10.0, -3.0, None)];
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nT1 M6 G42\nG1 X0 Y0\nX10\nM2"),
        right
    );
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nG41.1 D-6\nG1 X0 Y0\nX10\nM2"),
        right
    );
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nT2 M6 G41\nG1 X0 Y0\nX10\nM2"),
        right
    );
    // D names the tool: T1 with D1 though T2 is loaded.
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nT2 M6 G42 D1\nG1 X0 Y0\nX10\nM2"),
        right
    );
}

#[test]
fn g40_lets_the_last_move_end_and_the_next_runs_to_its_programmed_end() {
    // The line 3 above ends at (10, 3); the exit runs from there to
    // (20, 0), and X20 alone (Y unwritten) keeps the programmed Y, 0.
    assert_eq!(
        moves(&format!("{ENTRY}X10\nG40\nX20\nM2"))[3..],
        [(10.0, 3.0, None), (20.0, 0.0, None)]
    );
    let p = run(&format!("{ENTRY}X10\nG40\nX20\nM2"));
    assert_eq!(p.final_position, [20.0, 0.0, 0.0]);
}

#[test]
fn a_dwell_waits_behind_the_held_back_move() {
    let p = run(&format!("{ENTRY}G4 P1\nX10\nM2"));
    let kinds: Vec<&str> = p
        .toolpath
        .items
        .iter()
        .map(|i| match i {
            Item::Move(_) => "move",
            Item::Dwell { .. } => "dwell",
            Item::Synced(_) => "synced",
        })
        .collect();
    assert_eq!(kinds, ["move", "move", "dwell", "move", "move"]);
}

#[test]
fn the_held_back_move_runs_at_m2_m0_and_the_files_end() {
    for end in ["M2", "M0", ""] {
        assert_eq!(
            moves(&format!("{ENTRY}X10\n{end}")).last(),
            Some(&(10.0, 3.0, None)),
            "{end:?}"
        );
    }
}

#[test]
fn d0_is_the_loaded_tool_and_m61_reads_the_position_back() {
    // LinuxCNC's D0 is table slot 0, the tool in the spindle: T1.
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nT1 M6 G41 D0\nG1 X0 Y0\nX10\nM2")[1],
        (-3.0, 0.0, None)
    );
    // After G40 the programmed point (10, 0) is apart from the tool's
    // (10, 3); M61 drops it, so X20 keeps the tool's Y.
    assert_eq!(
        moves(&format!("{ENTRY}X10\nG40\nM61 Q1\nX20\nM2")).last(),
        Some(&(20.0, 3.0, None))
    );
}

#[test]
fn a_tool_of_radius_0_compensates_nothing() {
    assert_eq!(
        moves("G21 F600 G0 X0 Y-10\nT0 M6 G41\nG1 X0 Y0\nX10\nM2"),
        vec![(0.0, -10.0, None), (0.0, 0.0, None), (10.0, 0.0, None)]
    );
    // No tool loaded, no table: radius 0, and nothing to report.
    let p = interpret_with("G21 F600 G41 G1 X0 Y5\nM2", &Setup::default()).unwrap();
    assert!(p
        .ignored
        .iter()
        .all(|i| !i.what.starts_with("cutter radius 0")));
}

#[test]
fn the_tool_without_a_table_is_reported_and_compensates_nothing() {
    let p = interpret_with("G21 F600 T3 M6 G41\nG1 X0 Y5\nM2", &Setup::default()).unwrap();
    let report = p
        .ignored
        .iter()
        .find(|i| i.what == "cutter radius 0: no tool table given (--tools)")
        .expect("reported");
    assert_eq!((report.line, report.word.as_str()), (1, "G41 T3"));
}

#[test]
fn corners_the_tool_cannot_reach_are_errors_as_in_linuxcnc() {
    // A slot 2 wide for a tool 6 across (LinuxCNC: the same line).
    assert_eq!(
        error(&format!("{ENTRY}X10\nY10\nX8\nY0\nM2")),
        "line 8: straight feed in concave corner cannot be reached by the tool without gouging \
         (LinuxCNC: Straight feed in concave corner cannot be reached by the tool without gouging)"
    );
    // A rapid into the slot: the held-back move is the feed, X8, and
    // shortening it past its start is LinuxCNC's error for it.
    assert_eq!(
        error(&format!("{ENTRY}X10\nY10\nX8\nG0 Y0\nM2")),
        "line 8: straight feed in concave corner cannot be reached by the tool without gouging \
         (LinuxCNC: Straight feed in concave corner cannot be reached by the tool without gouging)"
    );
    // Straight back on itself is not a corner LinuxCNC refuses.
    run(&format!("{ENTRY}X10\nX0\nM2"));
    assert_eq!(
        error("G21 F600 G0 X0 Y-10\nT1 M6\nG41\nG1 X0 Y-8\nM2"),
        "line 4: G1: the cutter compensation entry move, 2.0000 mm, is not longer than the tool radius, 3.0000 mm \
         (LinuxCNC: Length of cutter compensation entry move is not greater than the tool radius)"
    );
    assert_eq!(
        error(&format!("{ENTRY}G3 X-2 Y2 R2\nM2")),
        "line 5: G3: the arc's radius, 2.0000 mm, is not more than the tool's, 3.0000 mm, and the tool is inside it \
         (LinuxCNC: Tool radius not less than arc radius with comp)"
    );
    assert_eq!(
        error(&format!("{ENTRY}G40\nG2 X10 Y0 R5\nM2")),
        "line 6: G2: the move just after G40 must be straight: it starts where compensation left the tool \
         (LinuxCNC: The move just after exiting cutter compensation mode must be straight, not an arc)"
    );
}

#[test]
fn what_cannot_change_under_compensation_is_refused() {
    let on = "G21 F600 T1 M6 G41\n";
    let refused = |block: &str, lcnc: &str| {
        let e = error(&format!("{on}{block}\nM2"));
        assert!(
            e.starts_with("line 2: ")
                && e.contains(" with cutter radius compensation on (G41 on line 1): turn it off with G40 first")
                && e.ends_with(&format!("(LinuxCNC: {lcnc})")),
            "{block}: {e}"
        );
    };
    refused(
        "T2 M6",
        "Cannot change tools with cutter radius compensation on",
    );
    refused(
        "G43 H1",
        "Cannot change tool offset with cutter radius compensation on",
    );
    refused(
        "G55",
        "Cannot change coordinate systems with cutter radius compensation on",
    );
    refused(
        "G92 X0",
        "Cannot change axis offsets with cutter radius compensation on",
    );
    refused(
        "G92.1",
        "Cannot change axis offsets with cutter radius compensation on",
    );
    refused("G28", "Cannot use g28 or g30 with cutter radius comp");
    refused(
        "G30.1",
        "Cannot set reference point with cutter compensation in effect",
    );
    refused(
        "G10 L2 P0 X1",
        "Cannot change the active coordinate system with cutter radius compensation on",
    );
    refused("G53 G0 X1", "Cannot use g53 with cutter radius comp");
    refused(
        "G81 X1 Y1 R2 Z-1",
        "Cannot use canned cycles with cutter compensation on",
    );
    refused(
        "G98",
        "Cannot change retract mode with cutter radius compensation on",
    );
    refused(
        "G64 P0.1",
        "Cannot change control mode with cutter radius compensation on",
    );
    refused(
        "G18",
        "Cannot change planes with cutter radius compensation on",
    );
    // Another system's origin may change; the same plane may be named.
    run(&format!("{on}G10 L2 P2 X1\nG17\nG40 M2"));
    assert_eq!(
        error(&format!("{on}G42\nM2")),
        "line 2: G42: cutter radius compensation is already on (G41 on line 1) \
         (LinuxCNC: Cannot turn cutter radius comp on when on)"
    );
    assert_eq!(
        error("G19 G41\nM2"),
        "line 1: G41 in G19: cutter radius compensation works in G17 and G18 only \
         (LinuxCNC: Cutter radius compensation allowed only in XY, XZ planes)"
    );
    assert_eq!(
        error("G41 D7\nM2"),
        "line 1: D7: tool 7 is not in the tool table (LinuxCNC: Requested tool 7 not found in the tool table)"
    );
    assert_eq!(
        error("G41 D1.5\nM2"),
        "line 1: D1.5 is not a tool number: a whole number, 0 (no tool) or more \
         (LinuxCNC: G41 requires D word to be a whole number)"
    );
    assert_eq!(
        error("G42.1\nM2"),
        "line 1: G42.1 needs D: the tool's diameter (LinuxCNC: G42.1 with no D word)"
    );
    assert_eq!(
        error("G41.1 D2 L3\nM2"),
        "line 1: L3 with G41.1: lathe tool orientations are not supported"
    );
}
