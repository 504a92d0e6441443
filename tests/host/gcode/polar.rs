//! Polar coordinates against LinuxCNC 2.9's `rs274` on the same programs.

use super::support::error;
use motion_hdl::host::gcode::interpreter::interpret;
use motion_hdl::host::toolpath::Item;

fn ends(program: &str) -> Vec<[f64; 3]> {
    interpret(program)
        .unwrap_or_else(|e| panic!("{program:?}: {e}"))
        .toolpath
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Move(m) => Some(m.end.map(|v| (v * 1e9).round() / 1e9 + 0.0)),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

#[test]
fn polar_ends_absolute_and_incremental() {
    assert_eq!(
        ends("G21 G90 F100\nG0 @10 ^90\n^180\n@5\nG91 G1 @1 ^-90\nM2"),
        [
            [0.0, 10.0, 0.0],
            [-10.0, 0.0, 0.0],
            [-5.0, 0.0, 0.0],
            [0.0, 6.0, 0.0]
        ]
    );
}

#[test]
fn incremental_polar_steps_a_cycle_on_every_repeat() {
    // LinuxCNC's hole-circle.ngc shape: four holes a quarter turn apart.
    assert_eq!(
        ends("G21 G90 F100\nG0 X10 Y0 Z5\nG91 G81 R-3 Z-2 ^90 L4\nG90 G80\nM2"),
        [
            [10.0, 0.0, 5.0],
            [0.0, 10.0, 5.0],
            [0.0, 10.0, 2.0],
            [0.0, 10.0, 0.0],
            [0.0, 10.0, 2.0],
            [-10.0, 0.0, 2.0],
            [-10.0, 0.0, 0.0],
            [-10.0, 0.0, 2.0],
            [0.0, -10.0, 2.0],
            [0.0, -10.0, 0.0],
            [0.0, -10.0, 2.0],
            [10.0, 0.0, 2.0],
            [10.0, 0.0, 0.0],
            [10.0, 0.0, 2.0],
        ]
    );
}

#[test]
fn polar_words_stand_only_where_they_mean_something() {
    for (program, message) in [
        ("G0 X1 @2", "line 1: @2 with X1: give the end in X and Y or in polar coordinates, not both (LinuxCNC: Cannot use X and polar coordinates)"),
        ("G53 G0 @2", "line 1: @2 with G53: machine coordinates are not polar (LinuxCNC: Cannot use polar coordinates with G53)"),
        ("G2 @2 ^90 I1 F100", "line 1: @2: polar coordinates give the end of a G0 or G1, or a canned cycle's hole in the G17 plane"),
        ("G92 ^90", "line 1: ^90: polar coordinates give the end of a G0 or G1, or a canned cycle's hole in the G17 plane"),
        ("G91 G0 ^90", "line 1: incremental polar coordinates at the origin have no angle to add to (LinuxCNC: Incremental motion with polar coordinates is indeterminate when at the origin)"),
        ("G0 @1 @2", "line 1: @ appears twice"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
}
