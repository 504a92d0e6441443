//! A, B and C on a machine that has them (the hexapod), and refused on one
//! that does not.

use super::support::{error, error_with, run_with};
use motion_hdl::host::gcode::interpreter::Setup;
use motion_hdl::host::toolpath::{Item, Move, MoveKind};

fn hexapod() -> Setup {
    Setup {
        start: [0.0, 0.0, 508.0],
        start_angles: [1.0, 0.0, 0.0],
        rotary_axes: true,
        ..Setup::default()
    }
}

fn moves(program: &str) -> Vec<Move> {
    run_with(program, &hexapod())
        .toolpath
        .items
        .into_iter()
        .filter_map(|i| match i {
            Item::Move(m) => Some(m),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

#[test]
fn rotary_words_move_with_g0_to_g3_absolute_or_incremental() {
    let m = moves("G0 X10 A5\nG1 F600 B-2\nG91 G1 A1 C3\nG90 G2 X20 I5 A0 F600");
    assert_eq!(m.len(), 4);
    assert_eq!(
        (m[0].end, m[0].angles),
        ([10.0, 0.0, 508.0], [5.0, 0.0, 0.0])
    );
    assert_eq!(m[0].feed, None);
    // B alone: F600 is 600 degrees a minute, 10 degrees/s.
    assert_eq!(
        (m[1].end, m[1].angles),
        ([10.0, 0.0, 508.0], [5.0, -2.0, 0.0])
    );
    assert_eq!(m[1].feed, Some(10.0));
    assert_eq!(m[2].angles, [6.0, -2.0, 3.0]);
    assert!(matches!(m[3].kind, MoveKind::Arc(_)));
    assert_eq!(m[3].angles, [0.0, -2.0, 3.0]);
    let p = run_with("G0 A-3 X1", &hexapod());
    assert_eq!(p.final_angles, [-3.0, 0.0, 0.0]);
    assert_eq!(p.toolpath.start_angles, [1.0, 0.0, 0.0]);
    assert_eq!(p.toolpath.end_angles(), [-3.0, 0.0, 0.0]);
}

#[test]
fn inches_scale_lengths_and_feeds_but_not_degrees() {
    let m = moves("G20\nG1 F60 X1 A10\nG1 A20");
    assert_eq!(m[0].end[0], 25.4);
    assert_eq!(m[0].angles[0], 10.0);
    // X moves: F is inches a minute along X Y Z.
    assert!((m[0].feed.unwrap() - 25.4).abs() < 1e-12);
    // A alone: degrees a minute, whatever the units.
    assert_eq!(m[1].feed, Some(1.0));
}

#[test]
fn a_move_to_the_same_pose_adds_nothing() {
    assert_eq!(moves("G0 X1 A1\nG0 X1 A1\nG1 F100 A1").len(), 1);
    // The angle alone moves.
    assert_eq!(moves("G0 X1\nG0 A2").len(), 2);
}

#[test]
fn rotary_words_elsewhere_are_refused_naming_the_word() {
    let cases = [
        (
            "G92 A5",
            "line 1: A5 with G92: the rotary axes move with G0, G1, G2 and G3 only; their offsets and stored positions are not supported",
        ),
        (
            "G28 B1",
            "line 1: B1 with G28: the rotary axes move with G0, G1, G2 and G3 only; their offsets and stored positions are not supported",
        ),
        (
            "G10 L20 P1 C2",
            "line 1: C2 with G10: the rotary axes move with G0, G1, G2 and G3 only; their offsets and stored positions are not supported",
        ),
        (
            "G81 X1 Z500 R510 F100 A3",
            "line 1: A3 with G81: the rotary axes move with G0, G1, G2 and G3 only, not in canned cycles",
        ),
        (
            "G41.1 D2 G1 X10 F100 A1",
            "line 1: A1: the rotary axes cannot move while cutter radius compensation is on (G40 first)",
        ),
        (
            "G41.1 D2 G1 X10 F100\nG1 Y10 A1",
            "line 2: A1: the rotary axes cannot move while cutter radius compensation is on (G40 first)",
        ),
        (
            "G1 F100 U1",
            "line 1: U1 moves an axis this machine does not have (X, Y, Z, A, B and C only)",
        ),
        ("A5", "line 1: A5 needs a motion mode (G0, G1, G2 or G3) first"),
    ];
    for (program, message) in cases {
        assert_eq!(error_with(program, &hexapod()), message, "{program}");
    }
}

#[test]
fn a_three_axis_machine_refuses_them_as_before() {
    for letter in ['A', 'B', 'C'] {
        assert_eq!(
            error(&format!("G0 X1 {letter}5")),
            format!("line 1: {letter}5 moves an axis this machine does not have (X, Y and Z only)")
        );
    }
}

#[test]
fn g40_beside_the_angles_turns_compensation_off_first() {
    let m = moves("G40 G1 X1 A1 F600");
    assert_eq!(m[0].angles, [1.0, 0.0, 0.0]);
    let m = moves("G41.1 D2 G1 X10 F100\nG1 Y10\nG40 G1 X0 A5");
    assert_eq!(m.last().unwrap().angles, [5.0, 0.0, 0.0]);
}

/// X Y Z travel left by a sum of increments (5.6e-17 mm) is no travel: the
/// move is of the angles alone, its F degrees a minute.
#[test]
fn float_dust_in_x_y_z_does_not_change_the_feed_rule() {
    let m = moves("G91 G1 X0.1 F100\nG1 X0.2\nG90 G1 X0.3 A15");
    let last = m.last().unwrap();
    // The dust is there: 0.1 + 0.2 is not 0.3.
    assert!(last.end[0] != m[1].end[0] && (last.end[0] - m[1].end[0]).abs() < 1e-15);
    assert_eq!(last.feed, Some(100.0 / 60.0));
}

#[test]
fn angles_out_of_range_are_refused() {
    assert_eq!(
        error_with("G0 A10000000", &hexapod()),
        "line 1: the A axis would be at 10000000.0000 degrees, beyond ±1000000 degrees"
    );
}

/// On a 3-axis machine the rotary word is named before a later bad word,
/// as when the reader refused it.
#[test]
fn a_three_axis_machine_names_the_rotary_word_first() {
    assert_eq!(
        error("G0 A5 E1"),
        "line 1: A5 moves an axis this machine does not have (X, Y and Z only)"
    );
}
