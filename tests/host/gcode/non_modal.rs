//! Coordinate systems, G92, G53, G28 and G30 against hand-computed machine
//! positions. The sequences of the first two tests were also run through
//! LinuxCNC 2.9's `rs274` (which prints work coordinates and the offsets
//! it sets): the machine positions here are its work positions plus its
//! offsets.

use super::support::{error, run};
use motion_hdl::host::gcode::interpreter::{interpret_with, Program, Setup};
use motion_hdl::host::gcode::parameters::PersistentParameters;
use motion_hdl::host::toolpath::{Item, MoveKind};

fn run_with(program: &str, parameters: &PersistentParameters) -> Program {
    let setup = Setup {
        parameters: *parameters,
        ..Setup::default()
    };
    interpret_with(program, &setup).unwrap_or_else(|e| panic!("{program:?}: {e}"))
}

/// Every move's (line, machine end) and whether it is a rapid.
fn ends(program: &Program) -> Vec<(usize, [f64; 3], bool)> {
    program
        .toolpath
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Move(m) => Some((m.line, m.end, m.feed.is_none())),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

fn parameters(values: &[(u32, f64)]) -> PersistentParameters {
    let mut p = PersistentParameters::default();
    for &(n, v) in values {
        p.set(n, v).unwrap();
    }
    p
}

#[test]
fn g10_l2_and_l20_set_origins_and_g55_selects_one() {
    let p = run(
        "G21\nG10 L2 P1 X10 Y20\nG0 X1 Y1\nG91 G10 L2 P2 X5\nG90 G55 X1\n\
         G10 L20 P0 X0\nG0 X0 Y0\nG92 X1\nG10 L20 P0 X2\nG0 X0\nM2",
    );
    assert_eq!(
        ends(&p),
        vec![
            (3, [11.0, 21.0, 0.0], true),
            // G91 does not apply to G10 L2: G55's X origin is 5.
            (5, [6.0, 21.0, 0.0], true),
            // L20 made X read 0 here: the origin is 6.
            (7, [6.0, 0.0, 0.0], true),
            // G92 X1: offset -1; L20 X2: origin 6 + 1 - 2 = 5; X0 is 5 - 1.
            (10, [4.0, 0.0, 0.0], true),
        ]
    );
    assert_eq!(p.coordinate_system, "G55");
    assert_eq!(
        (p.final_position, p.final_machine),
        ([0.0; 3], [4.0, 0.0, 0.0])
    );
    let kept = [5221, 5222, 5241, 5210, 5211, 5220].map(|n| p.parameters.get(n).unwrap());
    assert_eq!(kept, [10.0, 20.0, 5.0, 1.0, -1.0, 2.0]);
}

#[test]
fn g92_offsets_keep_unnamed_axes_and_g92_1_to_g92_3_clear_suspend_restore() {
    let p =
        run("G21\nG1 F100 X1\nG92 X5\nX6\nG92 Y0\nG0 X7 Y7\nG92 Z3\nG0 X8\nG92.1\nX0 Y0 Z0\nM2");
    assert_eq!(
        ends(&p),
        vec![
            (2, [1.0, 0.0, 0.0], false),
            (4, [2.0, 0.0, 0.0], false),
            // G92 Y0 keeps X's offset, -4 (LinuxCNC's source).
            (6, [3.0, 7.0, 0.0], true),
            // G92 Z3 offsets Z only: the machine's Z stays at 0 (work Z 3).
            (8, [4.0, 7.0, 0.0], true),
            (10, [0.0, 0.0, 0.0], true),
        ]
    );
    let p = run("G0 X10\nG92 X0\nG92.2\nG0 X1\nG92.3\nG0 X1\nG92.1\nG92.3\nG0 X2");
    let x: Vec<f64> = ends(&p).iter().map(|e| e.1[0]).collect();
    assert_eq!(x, [10.0, 1.0, 11.0, 2.0]);
    assert_eq!(
        error("G92"),
        "line 1: G92 needs an axis word (LinuxCNC: All axes missing with g92)"
    );
    assert_eq!(
        error("G92.1 X1"),
        "line 1: X1 with G92.1: it takes no axis words"
    );
}

#[test]
fn g53_moves_in_machine_coordinates_for_its_block_only() {
    let p = run("G10 L2 P1 X100 Z-50\nG0 Z10\nG53 G0 Z0\nG0 X1\nG1 X2 F60\nG53 X0\nM2");
    assert_eq!(
        ends(&p),
        vec![
            (2, [0.0, 0.0, -40.0], true),
            (3, [0.0, 0.0, 0.0], true),
            (4, [101.0, 0.0, 0.0], true),
            (5, [102.0, 0.0, 0.0], false),
            // The modal G1 runs the G53 move.
            (6, [0.0, 0.0, 0.0], false),
        ]
    );
    assert_eq!(p.final_position, [-100.0, 0.0, 50.0]);
    for (program, message) in [
        (
            "G53",
            "G53 needs a G0 or G1 move with axis words (LinuxCNC: Must use g0 or g1 with g53)",
        ),
        (
            "G2 X2 I1 F60\nG53 X2",
            "G53 needs a G0 or G1 move with axis words (LinuxCNC: Must use g0 or g1 with g53)",
        ),
        (
            "G91 G53 G0 X0",
            "G53 with G91: machine coordinates are absolute (LinuxCNC: Cannot use g53 incremental)",
        ),
        (
            "G4 P1 G53 G0 X0",
            "G4 and G53 in one block: one non-modal code (G4, G10, G28, G30, G53, G92) per block",
        ),
    ] {
        assert!(
            error(program).ends_with(message),
            "{program:?}: {}",
            error(program)
        );
    }
}

#[test]
fn g28_and_g30_go_through_the_named_point_to_the_stored_one() {
    let stored = parameters(&[(5161, 1.0), (5162, 2.0), (5163, 3.0), (5181, -1.0)]);
    let p = run_with(
        "G0 X5 Y5 Z5\nG28 X4\nG91 G28 Z0\nG90 G28\nG1 X7 F60\nG30 Y9\nX8",
        &stored,
    );
    assert_eq!(
        ends(&p),
        vec![
            (1, [5.0, 5.0, 5.0], true),
            (2, [4.0, 5.0, 5.0], true),
            (2, [1.0, 5.0, 5.0], true),
            // G91 Z0: no point on the way.
            (3, [1.0, 5.0, 3.0], true),
            (4, [1.0, 2.0, 3.0], true),
            (5, [7.0, 2.0, 3.0], false),
            (6, [7.0, 9.0, 3.0], true),
            (6, [7.0, 0.0, 3.0], true),
            // G30 kept the motion mode, G1.
            (7, [8.0, 0.0, 3.0], false),
        ]
    );
    // G28.1 and G30.1 store the machine position; an inch program reads
    // the stored millimetres.
    let p = run("G10 L2 P1 X50\nG0 X7 Y1\nG28.1\nG0 X0 Y0\nG28 X0\nG20 G0 Y1");
    assert_eq!(p.parameters.get(5161), Some(57.0));
    assert_eq!(ends(&p)[2], (5, [57.0, 0.0, 0.0], true));
    assert_eq!(ends(&p)[3], (6, [57.0, 25.4, 0.0], true));
    let fusion = parameters(&[(5163, 76.2)]);
    let p = run_with("G20\nG28 G91 Z0.\nG90", &fusion);
    assert_eq!(ends(&p), vec![(2, [0.0, 0.0, 76.2], true)]);
    // 76.2 mm read in inches: 3 to within a rounding.
    assert!((p.final_position[2] - 3.0).abs() < 1e-12);
    assert_eq!(
        error("G28 G1 X2 F10"),
        "line 1: G28 and G1 in one block: both use the axis words \
         (LinuxCNC: Cannot use two g codes that both use axis values)"
    );
}

#[test]
fn the_settings_select_the_starting_system_and_arcs_follow_the_offsets() {
    let g55 = parameters(&[(5220, 2.0), (5241, 100.0)]);
    let p = run_with("G0 X0\nG2 X10 Y0 I5 J0 F60\nG90.1 G3 X0 Y0 I5 J0", &g55);
    let centers: Vec<[f64; 2]> = p
        .toolpath
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Move(m) => match m.kind {
                MoveKind::Arc(arc) => Some(arc.center),
                MoveKind::Line => None,
            },
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect();
    assert_eq!(centers, [[105.0, 0.0], [105.0, 0.0]]);
    assert_eq!(ends(&p)[0].1, [100.0, 0.0, 0.0]);
    assert_eq!(p.coordinate_system, "G55");
    // Inches: G10 L2 takes the program's units.
    assert_eq!(
        ends(&run("G20\nG10 L2 P1 X1\nG0 X0"))[0].1,
        [25.4, 0.0, 0.0]
    );
    let p = run("G0 X1\nG59.3\nG10 L20 P9 X0\nG0 Y1");
    assert_eq!(
        (p.coordinate_system, p.final_position),
        ("G59.3", [0.0, 1.0, 0.0])
    );
}

#[test]
fn g10_words_are_checked_by_name() {
    for (program, message) in [
        ("G10 L2 X1", "line 1: G10 needs P: the coordinate system, 0 (the active one) or 1 (G54) to 9 (G59.3)"),
        ("G10 P1 X1", "line 1: G10 with no L: L2 and L20 set a coordinate system; L1, L10 and L11 set the tool table, which is not supported"),
        ("G10 L1 P1 Z1", "line 1: G10 with L1: L2 and L20 set a coordinate system; L1, L10 and L11 set the tool table, which is not supported"),
        ("G10 L2 P10 X1", "line 1: P10 is not a coordinate system: 0 (the active one) or 1 (G54) to 9 (G59.3)"),
        ("G10 L2 P1 R30", "line 1: R30 on G10 rotates the coordinate system, which is not supported"),
        ("G10 L2 P1 I1", "line 1: I1 has no G2 or G3 to use it"),
        ("G0 X1 L2", "line 1: L2 has no G10 or canned cycle to use it"),
        ("G0 X1 P2", "line 1: P2 has no G2, G3, G4, G10, G64 or canned cycle to use it"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
    // R0 rotates nothing; G10 moves nothing.
    assert!(run("G10 L2 P1 X5 R0").toolpath.items.is_empty());
}
