//! Canned cycles against LinuxCNC 2.9's `rs274` (run on these programs:
//! its canonical moves are the expected lists here, in mm, G54 at the
//! machine's origin so that work = machine), and its errors.

use super::support::error;
use motion_hdl::host::gcode::interpreter::{interpret, Program};
use motion_hdl::host::toolpath::Item;

/// `R`apid, `F`eed or `D`well, with the end (or the seconds in [0]).
fn trace(program: &Program) -> Vec<(char, [f64; 3])> {
    program
        .toolpath
        .items
        .iter()
        .map(|item| match item {
            Item::Move(m) => (if m.feed.is_none() { 'R' } else { 'F' }, m.end),
            Item::Dwell { seconds, .. } => ('D', [*seconds, 0.0, 0.0]),
            Item::Synced(m) => ('S', m.end),
        })
        .collect()
}

/// rs274's list, without its zero-length moves (which add no move here),
/// rounded as it prints them (4 decimals).
fn check(program: &str, expected: &[(char, [f64; 3])]) {
    let p = interpret(program).unwrap_or_else(|e| panic!("{program:?}: {e}"));
    let got: Vec<(char, [f64; 3])> = trace(&p)
        .into_iter()
        .map(|(k, e)| (k, e.map(|v| (v * 1e4).round() / 1e4)))
        .collect();
    assert_eq!(got, expected, "{program:?}");
}

const R: char = 'R';
const F: char = 'F';
const D: char = 'D';

#[test]
fn g83_pecks_back_to_r_with_the_clearance_and_g99_is_the_default() {
    check(
        "G21 G17 G90 F100\nG0 X0 Y0 Z10\nG83 X1 Y2 R2 Q3 Z-7\nX5\nG99 X6 Z-2\nG80\nM2",
        &[
            (R, [0.0, 0.0, 10.0]),
            (R, [1.0, 2.0, 10.0]),
            (R, [1.0, 2.0, 2.0]),
            (F, [1.0, 2.0, -1.0]),
            (R, [1.0, 2.0, 2.0]),
            (R, [1.0, 2.0, -0.746]),
            (F, [1.0, 2.0, -4.0]),
            (R, [1.0, 2.0, 2.0]),
            (R, [1.0, 2.0, -3.746]),
            (F, [1.0, 2.0, -7.0]),
            (R, [1.0, 2.0, 2.0]),
            (R, [5.0, 2.0, 2.0]),
            (F, [5.0, 2.0, -1.0]),
            (R, [5.0, 2.0, 2.0]),
            (R, [5.0, 2.0, -0.746]),
            (F, [5.0, 2.0, -4.0]),
            (R, [5.0, 2.0, 2.0]),
            (R, [5.0, 2.0, -3.746]),
            (F, [5.0, 2.0, -7.0]),
            (R, [5.0, 2.0, 2.0]),
            (R, [6.0, 2.0, 2.0]),
            (F, [6.0, 2.0, -1.0]),
            (R, [6.0, 2.0, 2.0]),
            (R, [6.0, 2.0, -0.746]),
            (F, [6.0, 2.0, -2.0]),
            (R, [6.0, 2.0, 2.0]),
        ],
    );
}

#[test]
fn g91_repeats_step_and_count_r_from_the_initial_level() {
    check(
        "G21 G90 F100\nG0 Z10\nG91 G81 X5 R-8 Z-5 L3\nG90 G80\nM2",
        &[
            (R, [0.0, 0.0, 10.0]),
            (R, [5.0, 0.0, 10.0]),
            (R, [5.0, 0.0, 2.0]),
            (F, [5.0, 0.0, -3.0]),
            (R, [5.0, 0.0, 2.0]),
            (R, [10.0, 0.0, 2.0]),
            (F, [10.0, 0.0, -3.0]),
            (R, [10.0, 0.0, 2.0]),
            (R, [15.0, 0.0, 2.0]),
            (F, [15.0, 0.0, -3.0]),
            (R, [15.0, 0.0, 2.0]),
        ],
    );
}

#[test]
fn g98_returns_to_the_initial_level_and_a_series_ends_at_g80() {
    check(
        "G21 G90 F100 G98\nG0 Z10\nG81 X1 R2 Z-7\nX2\nG80 G0 Z0\nG81 X3 R2 Z-1\nM2",
        &[
            (R, [0.0, 0.0, 10.0]),
            (R, [1.0, 0.0, 10.0]),
            (R, [1.0, 0.0, 2.0]),
            (F, [1.0, 0.0, -7.0]),
            (R, [1.0, 0.0, 10.0]),
            (R, [2.0, 0.0, 10.0]),
            (R, [2.0, 0.0, 2.0]),
            (F, [2.0, 0.0, -7.0]),
            (R, [2.0, 0.0, 10.0]),
            (R, [2.0, 0.0, 0.0]),
            // Below R: up to R first, which is then the clear level.
            (R, [2.0, 0.0, 2.0]),
            (R, [3.0, 0.0, 2.0]),
            (F, [3.0, 0.0, -1.0]),
            (R, [3.0, 0.0, 2.0]),
        ],
    );
}

#[test]
fn sticky_words_and_a_change_of_cycle_within_a_series() {
    check(
        "G21 G90 F100\nG0 Z10\nG81 X1 R2 Z-7\nG81 X2\nY1\nG83 Q1 R1 Z-2 X3\nM2",
        &[
            (R, [0.0, 0.0, 10.0]),
            (R, [1.0, 0.0, 10.0]),
            (R, [1.0, 0.0, 2.0]),
            (F, [1.0, 0.0, -7.0]),
            (R, [1.0, 0.0, 2.0]),
            (R, [2.0, 0.0, 2.0]),
            (F, [2.0, 0.0, -7.0]),
            (R, [2.0, 0.0, 2.0]),
            (R, [2.0, 1.0, 2.0]),
            (F, [2.0, 1.0, -7.0]),
            (R, [2.0, 1.0, 2.0]),
            (R, [3.0, 1.0, 2.0]),
            (R, [3.0, 1.0, 1.0]),
            (F, [3.0, 1.0, 0.0]),
            (R, [3.0, 1.0, 1.0]),
            (R, [3.0, 1.0, 0.254]),
            (F, [3.0, 1.0, -1.0]),
            (R, [3.0, 1.0, 1.0]),
            (R, [3.0, 1.0, -0.746]),
            (F, [3.0, 1.0, -2.0]),
            (R, [3.0, 1.0, 1.0]),
        ],
    );
}

#[test]
fn g73_g82_g85_to_g89() {
    check(
        "G21 G90 F100\nG0 Z1\nG73 X1 R2 Q2 Z-5\nG82 X2 R2 Z-1 P0.5\nM2",
        &[
            (R, [0.0, 0.0, 1.0]),
            (R, [0.0, 0.0, 2.0]),
            (R, [1.0, 0.0, 2.0]),
            (F, [1.0, 0.0, 0.0]),
            (R, [1.0, 0.0, 0.254]),
            (F, [1.0, 0.0, -2.0]),
            (R, [1.0, 0.0, -1.746]),
            (F, [1.0, 0.0, -4.0]),
            (R, [1.0, 0.0, -3.746]),
            (F, [1.0, 0.0, -5.0]),
            (R, [1.0, 0.0, 2.0]),
            (R, [2.0, 0.0, 2.0]),
            (F, [2.0, 0.0, -1.0]),
            (D, [0.5, 0.0, 0.0]),
            (R, [2.0, 0.0, 2.0]),
        ],
    );
    check(
        "G21 G90 F100\nG0 Z1\nG85 X3 R2 Z-2\nG89 X4 R3 Z-1 P1\nM3\nG86 X5 R2 Z-1 P0\n\
         G87 X6 R2 Z-4 I1 J0 K-2\nG88 X7 R2 Z-1 P0.2\nG0 X0\nM2",
        &[
            (R, [0.0, 0.0, 1.0]),
            (R, [0.0, 0.0, 2.0]),
            (R, [3.0, 0.0, 2.0]),
            (F, [3.0, 0.0, -2.0]),
            (F, [3.0, 0.0, 2.0]),
            // The series' initial level stays 1: G89 rises to its R first.
            (R, [3.0, 0.0, 3.0]),
            (R, [4.0, 0.0, 3.0]),
            (F, [4.0, 0.0, -1.0]),
            (D, [1.0, 0.0, 0.0]),
            (F, [4.0, 0.0, 3.0]),
            (R, [4.0, 0.0, 2.0]),
            (R, [5.0, 0.0, 2.0]),
            (F, [5.0, 0.0, -1.0]),
            (D, [0.0, 0.0, 0.0]),
            (R, [5.0, 0.0, 2.0]),
            (R, [6.0, 0.0, 2.0]),
            (R, [7.0, 0.0, 2.0]),
            (R, [7.0, 0.0, -4.0]),
            (R, [6.0, 0.0, -4.0]),
            (F, [6.0, 0.0, -2.0]),
            (F, [6.0, 0.0, -4.0]),
            (R, [7.0, 0.0, -4.0]),
            (R, [7.0, 0.0, 2.0]),
            (R, [6.0, 0.0, 2.0]),
            (R, [7.0, 0.0, 2.0]),
            (F, [7.0, 0.0, -1.0]),
            (D, [0.2, 0.0, 0.0]),
            // LinuxCNC stops here for a retract by hand; simulate rapids out.
            (R, [7.0, 0.0, 2.0]),
            (R, [0.0, 0.0, 2.0]),
        ],
    );
}

#[test]
fn g18_and_g19_drill_along_y_and_x() {
    check(
        "G21 G90 F100 G18\nG0 Y10\nG81 X1 Z2 R2 Y-3\nG19 G81 Y1 Z2 R3 X-3\nM2",
        &[
            (R, [0.0, 10.0, 0.0]),
            (R, [1.0, 10.0, 2.0]),
            (R, [1.0, 2.0, 2.0]),
            (F, [1.0, -3.0, 2.0]),
            (R, [1.0, 2.0, 2.0]),
            (R, [3.0, 1.0, 2.0]),
            (F, [-3.0, 1.0, 2.0]),
            (R, [3.0, 1.0, 2.0]),
        ],
    );
}

#[test]
fn cycle_errors_name_the_word_as_linuxcnc_does() {
    for (program, message) in [
        ("F100\nG0 Z10\nG83 X1 R2 Q0 Z-7", "line 3: Q0 is not a peck depth: it must be above zero (LinuxCNC: Negative or zero q value used)"),
        ("F100\nG83 X1 R2 Z-7", "line 2: G83 needs Q (LinuxCNC: Q word missing with g83)"),
        ("F100\nG82 X1 R2 Z-7", "line 2: G82 needs P (LinuxCNC: Dwell time p word missing with g82)"),
        ("F100\nG81 X1 Z-7", "line 2: G81 needs R, the retract level (LinuxCNC: R clearance plane unspecified in cycle)"),
        ("F100\nG81 X1 R2", "line 2: G81 needs Z, the bottom of the hole (LinuxCNC: Z value unspecified in G17 plane canned cycle)"),
        ("F100\nG81 X1 R-2 Z0", "line 2: R-2 is below the bottom Z0 (LinuxCNC: R less than z in cycle in G17 plane)"),
        ("F100\nG81 X1 R2 Z0 L0", "line 2: L0 is not a number of repeats: a whole number from 1 (LinuxCNC: Cannot do zero repeats of cycle)"),
        ("G81 X1 R2 Z0", "line 1: G81 needs a feed rate: no F word so far"),
        ("F100\nG86 X1 R2 Z0 P1", "line 2: G86 needs the spindle turning: M3 or M4 first (LinuxCNC: Spindle not turning in g86)"),
        ("F100 M3\nG87 X1 R2 Z0 I1 J1", "line 2: G87 needs K (LinuxCNC: K word missing with g87)"),
        ("F100\nG81 X1 R2 Z0 I1", "line 2: I1 has no G2, G3 or G87 to use it"),
        ("F100\nG84 X1 R2 Z0", "line 2: G84 needs the spindle turning: M3 first (LinuxCNC: Spindle not turning in g84)"),
        ("F100 M4\nG84 X1 R2 Z0", "line 2: G84 taps right-hand: the spindle must turn clockwise (M3), not M4 (LinuxCNC: Spindle turning counterclockwise in G84)"),
        ("F100 M3\nG74 X1 R2 Z0", "line 2: G74 taps left-hand: the spindle must turn counterclockwise (M4), not M3 (LinuxCNC: Spindle turning clockwise in G74)"),
        ("G0 X1 L2", "line 1: L2 has no G10 or canned cycle to use it"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
    // M5 stops the spindle: G86 needs it again.
    assert!(error("F100 M3\nM5\nG86 X1 R2 Z0 P1").contains("G86 needs the spindle turning"));
}
