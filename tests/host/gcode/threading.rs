//! G33, G33.1, G76 and the tapping cycles G74 and G84: the items they
//! make and their refusals.

use super::support::{error, run};
use motion_hdl::host::toolpath::{Item, SyncedMove};

fn synced(program: &str) -> Vec<SyncedMove> {
    run(program)
        .toolpath
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Synced(m) => Some(*m),
            _ => None,
        })
        .collect()
}

#[test]
fn g33_gears_one_axis_with_its_pitch_speed_and_direction() {
    let moves = synced("G21 G90\nG0 X5 Z2\nS600 M3\nG33 Z-20 K1.5\nM4\nG20 G33 Z-1 K0.0625");
    assert_eq!(moves.len(), 2);
    let first = moves[0];
    assert_eq!(first.axis, 2);
    assert_eq!(first.start, [5.0, 0.0, 2.0]);
    assert_eq!(first.end, [5.0, 0.0, -20.0]);
    assert_eq!(first.pitch, 1.5);
    assert_eq!(
        (first.rpm, first.clockwise, first.rigid_tap),
        (600.0, true, false)
    );
    assert_eq!((first.pass, first.line), (None, 4));
    // Inches: 16 threads per inch is 1.5875 mm a turn; M4 turns counterclockwise.
    let second = moves[1];
    assert!((second.pitch - 1.5875).abs() < 1e-12);
    assert!((second.end[2] + 25.4).abs() < 1e-9);
    assert!(!second.clockwise);
}

#[test]
fn g33_is_modal_with_its_k() {
    let moves = synced("G0 X5 Z2\nS600 M3\nG33 Z-5 K1\nG0 X6 Z2\nX5\nG33 Z-5 K1\nZ-8 K1\nG0 X7");
    assert_eq!(moves.len(), 3);
    assert_eq!(
        (moves[2].start[2], moves[2].end[2], moves[2].line),
        (-5.0, -8.0, 7)
    );
    assert_eq!(
        error("S600 M3\nG33 Z-5 K1\nZ-8"),
        "line 3: G33 needs K, the distance per spindle revolution (LinuxCNC: K word missing in G33)"
    );
}

#[test]
fn g33_1_taps_and_ends_where_it_started() {
    let p = run("G0 X1 Y2 Z3\nS300 M3\nG33.1 Z-10 K1.25\nG0 X4");
    let tap = match p.toolpath.items[1] {
        Item::Synced(m) => m,
        other => panic!("{other:?}"),
    };
    assert!(tap.rigid_tap);
    assert_eq!((tap.start, tap.end), ([1.0, 2.0, 3.0], [1.0, 2.0, -10.0]));
    // The next move starts back at Z3.
    match p.toolpath.items[2] {
        Item::Move(m) => assert_eq!(m.end, [4.0, 2.0, 3.0]),
        other => panic!("{other:?}"),
    }
}

/// The G76 passes by LinuxCNC's formulas, computed here independently:
/// (X of the cut, Z where it starts, Z where it ends).
fn expected_passes(
    drive: [f64; 2],
    end_z: f64,
    ijk: [f64; 3],
    r: f64,
    q_degrees: f64,
    h: u32,
) -> Vec<(f64, f64, f64)> {
    let [i, j, k] = ijk;
    let tan = q_degrees.to_radians().tan();
    let sign = if i > 0.0 { 1.0 } else { -1.0 };
    let mut depths = Vec::new();
    let mut n = 1.0f64;
    loop {
        let d = i.abs() + j * n.powf(1.0 / r);
        if d >= i.abs() + k {
            break;
        }
        depths.push(d);
        n += 1.0;
    }
    depths.extend(std::iter::repeat_n(i.abs() + k, h as usize + 1));
    depths
        .into_iter()
        .map(|d| {
            let zoff = (d - i.abs()) * tan;
            (drive[0] + sign * d, drive[1] - zoff, end_z + k * tan - zoff)
        })
        .collect()
}

#[test]
fn g76_makes_linuxcncs_passes() {
    let program =
        "G18 G21 G90\nG0 X10 Z2\nS400 M3\nG76 P1.5 Z-12 I-0.5 J0.2 K0.92 R1.5 Q29.5 H2\nG0 X20";
    let p = run(program);
    let moves = synced(program);
    let expected = expected_passes([10.0, 2.0], -12.0, [-0.5, 0.2, 0.92], 1.5, 29.5, 2);
    assert_eq!(moves.len(), expected.len());
    for (n, (m, (x, z0, z1))) in moves.iter().zip(&expected).enumerate() {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        assert!(
            close(m.start[0], *x) && close(m.start[2], *z0) && close(m.end[2], *z1),
            "pass {}: {m:?} against X{x} Z{z0}..{z1}",
            n + 1
        );
        assert_eq!(
            (m.axis, m.pass, m.pitch, m.line),
            (2, Some(n as u32 + 1), 1.5, 4)
        );
    }
    // The last passes are at full depth: crest 0.5 plus 0.92 under X10.
    assert!((moves.last().unwrap().start[0] - 8.58).abs() < 1e-9);
    // Each pass: rapid back, rapid in, the cut, rapid out; then a rapid to
    // the block's X and Z, and the program goes on from there.
    let items = &p.toolpath.items;
    let first_cut = items
        .iter()
        .position(|i| matches!(i, Item::Synced(_)))
        .unwrap();
    for (offset, rapid) in [(-2, true), (-1, true), (1, true)] {
        match items[(first_cut as isize + offset) as usize] {
            Item::Move(m) => assert_eq!(m.feed.is_none(), rapid),
            other => panic!("{other:?}"),
        }
    }
    match items[items.len() - 2] {
        Item::Move(m) => assert_eq!((m.end[0], m.end[2], m.feed), (10.0, -12.0, None)),
        other => panic!("{other:?}"),
    }
    assert_eq!(p.final_position, [20.0, 0.0, -12.0]);
}

#[test]
fn g76_inside_thread_cuts_outward() {
    let moves = synced("G0 X10 Z0\nS400 M3\nG76 P1 Z-5 I0.4 J0.3 K0.6");
    assert!(moves.iter().all(|m| m.start[0] > 10.0));
    assert_eq!(moves.len(), 2);
}

#[test]
fn geared_moves_refuse_what_they_cannot_do() {
    for (program, message) in [
        ("G33 Z-5 K1", "line 1: G33 with the spindle stopped: M3 or M4 with S first (LinuxCNC: Spindle not turning in G33)"),
        ("M3\nG33 Z-5 K1", "line 2: G33 with the spindle stopped: S is 0; give S, the speed in rpm"),
        ("S100 M3\nG33 Z-5", "line 2: G33 needs K, the distance per spindle revolution (LinuxCNC: K word missing in G33)"),
        ("S100 M3\nG33 Z-5 K0", "line 2: K0 is not a pitch: the distance per revolution must be above zero"),
        ("S100 M3\nG33 X1 Z-5 K1", "line 2: G33 moves X and Z together: the gearbox drives one axis, so a tapered thread is not supported; thread along one axis"),
        ("S100 M3\nG33 Z-5 K1 I1", "line 2: I1 has no G2 or G3 to use it"),
        ("S-5 M3", "line 1: S-5 is not a spindle speed: it must be 0 or more rpm"),
        ("S100 M3\nG76 P1 I-1 J0.1 K0.5", "line 2: G76 needs Z, where the thread ends"),
        ("S100 M3\nG76 Z-5 I-1 J0.1 K0.5", "line 2: G76 needs P, the pitch (LinuxCNC: P word missing with G76)"),
        ("S100 M3\nG76 Z-5 P1 I0 J0.1 K0.5", "line 2: G76's I is 0: the crest must be off the drive line (LinuxCNC: In G76, I must not be 0)"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0 K0.5", "line 2: G76's J0 is not a depth: it must be above zero (LinuxCNC: In G76, J must be greater than 0)"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.5 K0.5", "line 2: G76's K0.5 must be deeper than J0.5: K is the full depth, J the first cut (LinuxCNC: In G76, K must be greater than J)"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.1 K0.5 R0.5", "line 2: G76's R0.5 is not a depth degression: it must be 1 or more (LinuxCNC silently takes 1)"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.1 K0.5 Q90", "line 2: G76's Q90 is not a compound angle: it must be within ±90 degrees"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.1 K0.5 H1.5", "line 2: G76's H1.5 is not a number of spring passes: a whole number from 0 to 1000"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.1 K0.5 E1 L3", "line 2: G76's E1 asks for a tapered entry or exit: it moves X and Z together, and the gearbox drives one axis; leave out E and L"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.001 K0.5 R3", "line 2: G76 would make about 125000000 passes (K/J to the power R) plus 0 spring passes: more than 1000"),
        ("S100 M3\nG76 Z0 P1 I-1 J0.1 K0.5", "line 2: G76's Z is where the tool stands: the thread has no length"),
        ("S100 M3\nG76 Y1 Z-5 P1 I-1 J0.1 K0.5", "line 2: Y1 with G76: the cycle threads along Z and cuts in X; it takes X and Z only"),
        ("G0 X1 E5", "line 1: E5 drives an extruder (RepRap), an axis this machine does not have"),
        ("S100 M3\nG76 Z-5 P1 I-1 J0.1 K0.5\nX3", "line 3: X3 needs a motion mode (G0, G1, G2 or G3) first"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
}

#[test]
fn g84_feeds_in_dwells_and_feeds_out() {
    let p = run("G17 G21 G90 F120 S200 M3\nG0 Z10\nG84 X1 Y2 R2 Z-8 P0.5");
    let items = &p.toolpath.items;
    let n = items.len();
    match (items[n - 3], items[n - 2], items[n - 1]) {
        (Item::Move(down), Item::Dwell { seconds, .. }, Item::Move(up)) => {
            assert_eq!((down.end, down.feed), ([1.0, 2.0, -8.0], Some(2.0)));
            assert_eq!(seconds, 0.5);
            assert_eq!((up.end, up.feed), ([1.0, 2.0, 2.0], Some(2.0)));
        }
        other => panic!("{other:?}"),
    }
}
