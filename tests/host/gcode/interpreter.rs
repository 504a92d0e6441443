use super::support::{error, run};
use motion_hdl::host::gcode::interpreter::*;
use motion_hdl::host::toolpath::{Arc, Item, LaserPower, Move, MoveKind, Plane};

fn moves(program: &str) -> Vec<Move> {
    run(program)
        .toolpath
        .items
        .into_iter()
        .map(|item| match item {
            Item::Move(m) => m,
            Item::Dwell { .. } | Item::Synced(_) => panic!("{program:?}: not a move: {item:?}"),
        })
        .collect()
}

fn only_arc(program: &str) -> (Arc, [f64; 3]) {
    match moves(program).as_slice() {
        [Move {
            kind: MoveKind::Arc(arc),
            end,
            ..
        }] => (*arc, *end),
        other => panic!("{program:?}: {other:?}"),
    }
}

fn line(end: [f64; 3], feed: Option<f64>, line: usize) -> Move {
    Move {
        kind: MoveKind::Line,
        end,
        angles: [0.0; 3],
        feed,
        laser: LaserPower::OFF,
        line,
    }
}

fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12
}

#[test]
fn lines_rapids_and_modal_motion_with_file_lines() {
    let program = "G1 X1 Y2 F600\n\nG0 Z5\nX0 (modal G0)\nG1 Y0\n";
    assert_eq!(
        moves(program),
        vec![
            line([1.0, 2.0, 0.0], Some(10.0), 1),
            line([1.0, 2.0, 5.0], None, 3),
            line([0.0, 2.0, 5.0], None, 4),
            line([0.0, 0.0, 5.0], Some(10.0), 5),
        ]
    );
    let p = run(program);
    assert_eq!(p.toolpath.start, [0.0; 3]);
    assert_eq!(
        (p.units, p.final_position, p.end),
        (Units::Millimetre, [0.0, 0.0, 5.0], None)
    );
    assert!(p.ignored.is_empty());
}

#[test]
fn blocks_that_move_nothing_emit_nothing() {
    // A bare motion code sets the mode; a line to where it is adds nothing.
    assert_eq!(
        run("G1 F60\nG0\nG2\nG1 X0 Y0\nG0 Z0").toolpath.items,
        vec![]
    );
    assert_eq!(
        moves("G1 F60\nX1\nG0\nX2"),
        vec![
            line([1.0, 0.0, 0.0], Some(1.0), 2),
            line([2.0, 0.0, 0.0], None, 4)
        ]
    );
}

#[test]
fn the_accepted_no_op_codes_change_nothing() {
    let p = run("G17 G21 G40 G49 G80 G90 G94 G54 G91.1\nG1 X1 F60\nX2");
    assert_eq!(p.toolpath.items.len(), 2);
    assert!(p.ignored.is_empty());
}

/// G80 is in LinuxCNC's motion group: it ends the motion mode, and takes
/// no axis words (both as LinuxCNC 2.9's interpreter refuses them).
#[test]
fn g80_cancels_the_motion_mode() {
    assert_eq!(
        error("G1 X1 F60\nG80\nX2"),
        "line 3: X2 needs a motion mode (G0, G1, G2 or G3) first"
    );
    assert_eq!(
        error("G0 X1\nG80 X2"),
        "line 2: X2 with G80: G80 cancels the motion mode and takes no axis or arc words \
         (LinuxCNC: Cannot use axis values with g80)"
    );
    // Beside another motion code, G80 gives way (LinuxCNC's read_g).
    assert_eq!(moves("G80 G0 X1").len(), 1);
    assert_eq!(moves("G80\nG0 X1").len(), 1);
}

#[test]
fn incremental_moves_sum_exactly() {
    let program = "G91 G1 F60 X0.5 Y0.25\nX0.125 Y-0.5 Z-0.375\nZ0.0625\nG90 X3";
    let ends: Vec<_> = moves(program).iter().map(|m| m.end).collect();
    assert_eq!(
        ends,
        vec![
            [0.5, 0.25, 0.0],
            [0.625, -0.25, -0.375],
            [0.625, -0.25, -0.3125],
            [3.0, -0.25, -0.3125]
        ]
    );
    let from = interpret_from("G91 G0 X0.5 Y-0.25", [1.0, 2.0, 3.0]).unwrap();
    assert_eq!(from.toolpath.start, [1.0, 2.0, 3.0]);
    assert_eq!(from.toolpath.end(), [1.5, 1.75, 3.0]);
    assert_eq!(from.final_position, [1.5, 1.75, 3.0]);
}

#[test]
fn inches_convert_positions_and_feeds() {
    assert_eq!(
        moves("G20\nG1 X1 F10"),
        vec![line([25.4, 0.0, 0.0], Some(25.4 * 10.0 / 60.0), 2)]
    );
    // RS-274/NGC sets F (step 3 of a block) before the units (step 12):
    // F10 beside a G20 is still in mm/min, and a feed keeps its speed when
    // the units change.
    assert_eq!(moves("G20 G1 X1 F10")[0].feed, Some(10.0 / 60.0));
    assert_eq!(moves("G20\nF60\nG21 G1 Y1")[0].feed, Some(25.4));
    let p = run("G1 X25.4 F100\nG20\nG91 X1 Y0.5");
    assert_eq!(p.toolpath.end(), [50.8, 12.7, 0.0]);
    assert_eq!((p.units, p.final_position), (Units::Inch, [2.0, 0.5, 0.0]));
    assert_eq!(run("G20 G1 X1 F1\nG21").final_position, [25.4, 0.0, 0.0]);
    // Repeating the units in force keeps the program's own sums.
    assert_eq!(
        run("G20 G0 X0.1\nG20 G91 X0.2").final_position,
        [0.1 + 0.2, 0.0, 0.0]
    );
    assert_eq!(
        (Units::Inch.name(), Units::Inch.mm_per_unit()),
        ("in", 25.4)
    );
    assert_eq!(
        (Units::Millimetre.name(), Units::Millimetre.mm_per_unit()),
        ("mm", 1.0)
    );
}

#[test]
fn feed_rates() {
    assert_eq!(
        error("G1 X1"),
        "line 1: G1 needs a feed rate: no F word so far"
    );
    assert_eq!(
        error("G3 X10 I5"),
        "line 1: G3 needs a feed rate: no F word so far"
    );
    assert_eq!(
        error("G0 X1\nG1 F0"),
        "line 2: F0 is not a feed rate: it must be above zero"
    );
    assert_eq!(
        error("G1 F-5"),
        "line 1: F-5 is not a feed rate: it must be above zero"
    );
    assert_eq!(moves("G0 X1\nG1 X2 F30")[1].feed, Some(0.5));
}

#[test]
fn arcs_in_each_plane_with_offsets() {
    let (arc, end) = only_arc("G2 X10 Y0 I5 J0 F60");
    assert_eq!(
        arc,
        Arc {
            plane: Plane::Xy,
            center: [5.0, 0.0],
            clockwise: true,
            turns: 0
        }
    );
    assert_eq!(end, [10.0, 0.0, 0.0]);
    // G18 is (Z, X): the center is [Z + K, X + I].
    let (arc, _) = only_arc("G18 G3 X10 Z0 I5 K1 F60");
    assert_eq!(
        arc,
        Arc {
            plane: Plane::Zx,
            center: [1.0, 5.0],
            clockwise: false,
            turns: 0
        }
    );
    // G19 is (Y, Z): [Y + J, Z + K]; offsets count from the arc's start.
    let p = interpret_from("G19 G2 Y11 Z1 J5 K0 F60", [7.0, 1.0, 1.0]).unwrap();
    let arc = Arc {
        plane: Plane::Yz,
        center: [6.0, 1.0],
        clockwise: true,
        turns: 0,
    };
    assert_eq!(
        p.toolpath.items,
        vec![Item::Move(Move {
            kind: MoveKind::Arc(arc),
            end: [7.0, 11.0, 1.0],
            angles: [0.0; 3],
            feed: Some(1.0),
            laser: LaserPower::OFF,
            line: 1
        })]
    );
    // A missing offset counts as zero.
    assert_eq!(only_arc("G3 X5 Y5 J5 F60").0.center, [0.0, 5.0]);
}

#[test]
fn absolute_arc_centers_in_either_unit() {
    let m = moves("G1 X10 F60\nG90.1 G3 X0 Y10 I0 J0");
    assert_eq!(
        m[1].kind,
        MoveKind::Arc(Arc {
            plane: Plane::Xy,
            center: [0.0, 0.0],
            clockwise: false,
            turns: 0
        })
    );
    let m = moves("G20 G0 X1 Y1\nG90.1 G2 X0.5 Y1.5 I0.5 J1 F1");
    match m[1].kind {
        MoveKind::Arc(arc) => assert_eq!(arc.center, [12.7, 25.4]),
        other => panic!("{other:?}"),
    }
    assert_eq!(m[1].end, [0.5 * 25.4, 1.5 * 25.4, 0.0]);
    // Absolute centers need both offsets of the plane (incremental ones
    // count a missing offset as 0).
    assert_eq!(
        error("G0 X1\nG90.1 G2 X3 Y0 I2 F100"),
        "line 2: G2 needs J with G90.1: absolute arc centers need both of the G17 plane's offsets \
         (LinuxCNC: J word missing in absolute center arc)"
    );
    assert_eq!(
        error("G18 G90.1 G3 X3 Z0 I2 F100"),
        "line 1: G3 needs K with G90.1: absolute arc centers need both of the G18 plane's offsets \
         (LinuxCNC: K word missing in absolute center arc)"
    );
}

#[test]
fn radius_arcs_take_the_short_or_long_way() {
    // From (0, 0) to (2, 0) with |R| = 2: the center is (1, ±√3).
    let below = [1.0, -(3.0f64).sqrt()];
    let above = [1.0, (3.0f64).sqrt()];
    for (program, center) in [
        ("G2 X2 R2 F60", below),
        ("G2 X2 R-2 F60", above),
        ("G3 X2 R2 F60", above),
        ("G3 X2 R-2 F60", below),
    ] {
        let (arc, end) = only_arc(program);
        assert!(close(arc.center, center), "{program}: {:?}", arc.center);
        assert_eq!(end, [2.0, 0.0, 0.0]);
    }
    // G18: (Z, X). From Z=0, X=0 to Z=2, X=0: a G2 R2 center is at X = -√3.
    let (arc, _) = only_arc("G18 G2 Z2 R2 F60");
    assert!(close(arc.center, below), "{:?}", arc.center);
    // In inches, R converts too.
    let (arc, _) = only_arc("G20 G2 X2 R2 F60");
    assert!(
        close(arc.center, [25.4, -(3.0f64).sqrt() * 25.4]),
        "{:?}",
        arc.center
    );
}

#[test]
fn radius_arcs_near_a_half_circle() {
    let (arc, _) = only_arc("G2 X10 R4.9999995 F60");
    assert_eq!(arc.center, [5.0, 0.0]);
    assert_eq!(
        error("G2 X10 R4.99 F60"),
        "line 1: R4.99 cannot reach the end: |R| must be at least half the chord, 5.0000 mm"
    );
    assert_eq!(
        error("G20 G2 X1 R-0.4 F60"),
        "line 1: R-0.4 cannot reach the end: |R| must be at least half the chord, 0.5000 in"
    );
    assert_eq!(
        error("G0 X1\nG2 X1 Y0 R5 F60"),
        "line 2: R cannot make a full circle (the end is the start); give the center with I, J or K"
    );
}

#[test]
fn full_circles_turns_and_helices() {
    let (arc, end) = only_arc("G2 X0 Y0 I5 F60 P2");
    assert_eq!(
        arc,
        Arc {
            plane: Plane::Xy,
            center: [5.0, 0.0],
            clockwise: true,
            turns: 1
        }
    );
    assert_eq!(end, [0.0; 3]);
    let (arc, end) = only_arc("G3 X0 Y0 Z-2 I5 P3 F60");
    assert_eq!(
        (arc.turns, arc.clockwise, end),
        (2, false, [0.0, 0.0, -2.0])
    );
    let (arc, end) = only_arc("G17 G2 X10 Y0 Z5 I5 F60");
    assert_eq!((arc.center, end), ([5.0, 0.0], [10.0, 0.0, 5.0]));
    // An end a rounding error away from the start is the start: a full
    // circle, not a sliver.
    let start = 25.4 / 3.0;
    let p = interpret_from("G20 G2 X0.3333333333333333 I1 F1", [start, 0.0, 0.0]).unwrap();
    let Item::Move(m) = p.toolpath.items[0] else {
        panic!()
    };
    assert_eq!(m.end, [start, 0.0, 0.0]);
    assert_eq!(p.final_position, [start / 25.4, 0.0, 0.0]);
}

#[test]
fn arc_errors() {
    assert_eq!(
        error("G2 X10 F60"),
        "line 1: G2 needs a center (I, J or K) or a radius (R)"
    );
    assert_eq!(
        error("G2 X10 I5 R5 F60"),
        "line 1: R5 with I, J or K: give the center or the radius, not both"
    );
    assert_eq!(
        error("G2 X10 I5 K5 F60"),
        "line 1: K5 is not in the G17 plane's offsets (I and J)"
    );
    assert_eq!(
        error("G18 G2 X10 I5 J5 F60"),
        "line 1: J5 is not in the G18 plane's offsets (I and K)"
    );
    assert_eq!(
        error("G19 G2 Y10 I5 F60"),
        "line 1: I5 is not in the G19 plane's offsets (J and K)"
    );
    assert_eq!(
        error("G2 Z5 R5 F60"),
        "line 1: G2 with R needs X or Y (its end in the G17 plane): R cannot make a full circle"
    );
    assert_eq!(
        error("G18 G3 Y1 R5 F60"),
        "line 1: G3 with R needs X or Z (its end in the G18 plane): R cannot make a full circle"
    );
    // I, J, K alone: a full circle (a helix here), as in LinuxCNC.
    assert_eq!(run("G2 Z5 I5 F60").final_machine, [0.0, 0.0, 5.0]);
    assert_eq!(
        error("G2 X20.02 I10 F60"),
        "line 1: the arc's radius is 10.0000 mm at its start and 10.0200 mm at its end"
    );
    assert_eq!(
        error("G20 G3 X2.1 I1 F1"),
        "line 1: the arc's radius is 1.0000 in at its start and 1.1000 in at its end"
    );
    assert_eq!(only_arc("G2 X20.005 I10 F60").1, [20.005, 0.0, 0.0]);
    assert_eq!(
        error("G2 X10 I0 J0 F60"),
        "line 1: the arc's center is its start (zero radius)"
    );
    assert_eq!(
        error("G2 X0.001 I0.001 F60"),
        "line 1: the arc's center is its end (zero radius)"
    );
    assert_eq!(
        error("G2 X0 I5 F60 P1.5"),
        "line 1: P1.5 is not a number of turns: a whole number, 1 or more"
    );
    assert_eq!(
        error("G2 X0 I5 F60 P0"),
        "line 1: P0 is not a number of turns: a whole number, 1 or more"
    );
    assert_eq!(
        error("G1 X1 I5 F60"),
        "line 1: I5 has no G2 or G3 to use it"
    );
    assert_eq!(error("G0 X1 R5"), "line 1: R5 has no G2 or G3 to use it");
    assert_eq!(error("J5"), "line 1: J5 has no G2 or G3 to use it");
}

#[test]
fn dwells() {
    let p = run("G1 X1 F60\nG4 P1.5\nX2\nG4 P0");
    assert_eq!(
        p.toolpath.items[1],
        Item::Dwell {
            seconds: 1.5,
            laser: LaserPower::OFF,
            line: 2
        }
    );
    assert_eq!(
        p.toolpath.items[2],
        Item::Move(line([2.0, 0.0, 0.0], Some(1.0), 3))
    );
    assert_eq!(
        p.toolpath.items[3],
        Item::Dwell {
            seconds: 0.0,
            laser: LaserPower::OFF,
            line: 4
        }
    );
    // A motion code beside G4 only sets the mode.
    assert_eq!(run("G1 G4 P1 F60\nX1").toolpath.items.len(), 2);
    assert_eq!(error("G4"), "line 1: G4 needs a dwell time: P, in seconds");
    assert_eq!(
        error("G4 P-1"),
        "line 1: P-1 is not a dwell time: it must be 0 or more seconds"
    );
    // Axis words beside G4 run the motion after the dwell (LinuxCNC's
    // skeleton.ngc writes `G04 P.001 G0 ...`).
    let p = run("G1 X1 F60\nG4 P1 X2\nG4 P0.5 G0 X3 Y1");
    assert_eq!(
        p.toolpath.items[1..],
        [
            Item::Dwell {
                seconds: 1.0,
                laser: LaserPower::OFF,
                line: 2
            },
            Item::Move(line([2.0, 0.0, 0.0], Some(1.0), 2)),
            Item::Dwell {
                seconds: 0.5,
                laser: LaserPower::OFF,
                line: 3
            },
            Item::Move(line([3.0, 1.0, 0.0], None, 3)),
        ]
    );
    assert_eq!(
        error("G4 P1 X1"),
        "line 1: X1 needs a motion mode (G0, G1, G2 or G3) first"
    );
    assert_eq!(error("G4 P1 P2"), "line 1: P appears twice");
    assert_eq!(
        error("G4 G4 P2"),
        "line 1: G4 and G4 in one block: one non-modal code (G4, G10, G28, G30, G53, G92) per block"
    );
}

#[test]
fn block_delete_and_program_end() {
    assert_eq!(
        moves("/G1 X5 F60\nG0 X1\n/G41"),
        vec![line([1.0, 0.0, 0.0], None, 2)]
    );
    let p = run("G0 X1\nM30\nG41\n/G0 X7\nG0 X5");
    assert_eq!((p.end, p.toolpath.items.len()), (Some(2), 1));
    // Counted for the report; a block-deleted one is not.
    assert_eq!(p.blocks_after_end, 2);
    assert_eq!(run("G0 X1\nM2").blocks_after_end, 0);
    // The motion on the end's own block runs first.
    let p = run("G0 X1\nG0 X2 M2\nG0 X3");
    assert_eq!((p.end, p.toolpath.end()), (Some(2), [2.0, 0.0, 0.0]));
    assert_eq!(run("/M2\nG0 X1").end, None);
    // A closing `%` ends the program when no M2 or M30 came first.
    let p = run("%\nG0 X1\n%\nG0 X5");
    assert_eq!((p.end, p.closing_percent), (None, Some(3)));
    assert_eq!(p.toolpath.end(), [1.0, 0.0, 0.0]);
    // The lexer reads every line first.
    assert_eq!(error("M2\nG1 X1 $"), "line 2: unexpected character `$`");
}

#[test]
fn ignored_words_are_reported_once_at_their_first_line() {
    let p = run("T1 M6\nM3 S12000 M8\nG64 P0.01 Q0.01\nM3 S8000 T2\nM5 M9 M0\nG61\nH1 D2\nM104 S200\nG97 M1 M104\nM2");
    let got: Vec<_> = p
        .ignored
        .iter()
        .map(|i| (i.line, i.word.as_str(), i.what))
        .collect();
    assert_eq!(
        got,
        vec![
            (1, "T1", "tool"),
            (1, "M6", "tool change"),
            (2, "M3", "spindle"),
            (2, "S12000", "spindle speed (G33, G33.1 and G76 use it)"),
            (2, "M8", "coolant"),
            (3, "G64", "path control"),
            (5, "M5", "spindle"),
            (5, "M9", "coolant"),
            (5, "M0", "program pause"),
            (6, "G61", "path control"),
            (7, "D2", "tool offset"),
            (7, "H1", "tool offset"),
            (8, "M104", "unknown M code"),
            (9, "G97", "spindle"),
            (9, "M1", "program pause"),
        ]
    );
    assert_eq!(p.end, Some(10));
    assert!(p.toolpath.items.is_empty());
}

#[test]
fn refused_g_codes_name_what_they_do() {
    for (word, what) in [
        ("G52", "local coordinate offset"),
        ("G93", "inverse-time feed"),
        ("G95", "feed per revolution"),
        ("G5", "spline"),
        ("G5.1", "spline"),
        ("G5.2", "spline"),
        ("G7", "lathe diameter mode"),
        ("G8", "lathe radius mode"),
    ] {
        assert_eq!(
            error(&format!("G0 X1\n{word} X0")),
            format!("line 2: {word} ({what}) changes the motion and is not supported")
        );
    }
    assert_eq!(error("G12 X1"), "line 1: G12 is not a supported G code");
    assert_eq!(error("G81.5"), "line 1: G81.5 is not a supported G code");
    assert_eq!(error("G1.25 X1"), "line 1: G1.25 is not a G code");
    assert_eq!(error("M1.5"), "line 1: M1.5 is not an M code");
}

#[test]
fn words_this_machine_does_not_have() {
    for letter in ['A', 'B', 'C', 'U', 'V', 'W'] {
        assert_eq!(
            error(&format!("G0 {letter}5")),
            format!("line 1: {letter}5 moves an axis this machine does not have (X, Y and Z only)")
        );
    }
    assert_eq!(
        error("G1 X1 E5 F60"),
        "line 1: E5 drives an extruder (RepRap), an axis this machine does not have"
    );
    assert_eq!(
        error("O100 G0 X1"),
        "line 1: O100: subroutines and flow control (O words) are not supported"
    );
    assert_eq!(
        error("G0 X1 L2"),
        "line 1: L2 has no G10 or canned cycle to use it"
    );
    assert_eq!(
        error("G0 X1 Q1"),
        "line 1: Q1 has no G64, M61 or canned cycle to use it"
    );
    assert_eq!(
        error("G1 X1 P2 F60"),
        "line 1: P2 has no G2, G3, G4, G10, G64 or canned cycle to use it"
    );
}

#[test]
fn one_word_per_letter_and_one_code_per_group() {
    assert_eq!(error("G1 X1 X2 F60"), "line 1: X appears twice");
    assert_eq!(
        error("G0 G1 X1"),
        "line 1: G0 and G1 in one block: one motion per block"
    );
    assert_eq!(
        error("G90 G91"),
        "line 1: G90 and G91 in one block: both select the distance mode"
    );
    assert_eq!(
        error("G90.1 G91.1"),
        "line 1: G90.1 and G91.1 in one block: both select the arc center mode"
    );
    assert_eq!(
        error("G17 G18"),
        "line 1: G17 and G18 in one block: both select the plane"
    );
    assert_eq!(
        error("G20 G21"),
        "line 1: G20 and G21 in one block: both select the units"
    );
    assert_eq!(
        error("G61 G64"),
        "line 1: G61 and G64 in one block: both select path control"
    );
    assert_eq!(
        error("M2 M30"),
        "line 1: M2 and M30 in one block: both stop the program"
    );
    assert_eq!(
        error("M3 M5"),
        "line 1: M3 and M5 in one block: both set the spindle"
    );
    // Coolant M7 and M8 may be on together, as in LinuxCNC.
    assert_eq!(run("M7 M8").ignored.len(), 2);
}

#[test]
fn axis_words_need_a_motion_mode() {
    assert_eq!(
        error("G21\nX10"),
        "line 2: X10 needs a motion mode (G0, G1, G2 or G3) first"
    );
    assert_eq!(
        error("F60 Z-1 Y2"),
        "line 1: Z-1 needs a motion mode (G0, G1, G2 or G3) first"
    );
}

#[test]
fn positions_and_values_are_bounded() {
    assert_eq!(
        error("G0 X2000000"),
        "line 1: the X axis would be at 2000000.0000 mm, beyond ±1000000 mm"
    );
    assert_eq!(
        error("G20 G0 Z-40000"),
        "line 1: the Z axis would be at -1016000.0000 mm, beyond ±1000000 mm"
    );
    assert!(run("G0 X1000000").toolpath.items.len() == 1);
    assert!(error("G2 X1 R-1500000 F60").starts_with("line 1: the arc's center would be at "));
    let huge = format!("G0 X1{}", "0".repeat(400));
    assert_eq!(
        error(&huge),
        format!("line 1: X1{} is not a finite number", "0".repeat(400))
    );
}

#[test]
fn lexer_errors_keep_their_line_and_message() {
    let e = interpret("G0 X1\nG1 X").unwrap_err();
    assert_eq!(
        e,
        GcodeError {
            line: 2,
            message: "word `X` has no number".into()
        }
    );
    assert_eq!(e.to_string(), "line 2: word `X` has no number");
}

/// Posts' conventions (#40): a Fanuc/Haas program-number line before any
/// motion, and FreeCAD's grbl post's K0 on G17 arcs.
#[test]
fn a_program_number_before_any_motion_is_reported_and_later_refused() {
    let p = run("%\nO1003 (PART)\nG21 G90\nG0 X1\nM30\n%");
    assert_eq!(p.toolpath.items.len(), 1);
    let got: Vec<_> = p
        .ignored
        .iter()
        .map(|i| (i.line, i.word.as_str(), i.what))
        .collect();
    assert_eq!(got, vec![(2, "O1003", "program number")]);
    assert_eq!(
        error("G0 X1\nO1003\nM30"),
        "line 2: O1003: a program number stands before any motion; subroutines and flow control (O words) are not supported"
    );
    // Not alone on its block, or not a whole number: flow control, refused.
    assert_eq!(
        error("O100 G0 X1"),
        "line 1: O100: subroutines and flow control (O words) are not supported"
    );
    assert_eq!(
        error("O1.5"),
        "line 1: O1.5: subroutines and flow control (O words) are not supported"
    );
}

#[test]
fn a_zero_out_of_plane_arc_offset_is_dropped_and_reported_once() {
    let with_k = only_arc("G17 G2 X10 Y0 I5 J0 K0.000 F60");
    let without = only_arc("G17 G2 X10 Y0 I5 J0 F60");
    assert_eq!(with_k, without);
    let p = run("G17 G2 X10 I5 K0 F60\nG3 X0 I-5 K0.0\nG18 G2 Z10 K5 J0\nM2");
    let got: Vec<_> = p
        .ignored
        .iter()
        .map(|i| (i.line, i.word.as_str()))
        .collect();
    assert_eq!(got, vec![(1, "K0 on G2"), (3, "J0 on G2")]);
    // A non-zero one is still LinuxCNC's error.
    assert_eq!(
        error("G2 X10 I5 K0.001 F60"),
        "line 1: K0.001 is not in the G17 plane's offsets (I and J)"
    );
}
