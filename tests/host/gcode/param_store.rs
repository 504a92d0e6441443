//! Parameters, expressions and active comments, with values worked out by
//! hand from LinuxCNC's documented precedence and functions.

use super::support::{error, run, xs};

fn x_of(expression: &str) -> f64 {
    xs(&format!("G0 Y1 X{expression}"))[0]
}

#[test]
fn expressions_follow_linuxcncs_precedence_and_functions() {
    for (expression, x) in [
        ("[1 + 2 * 3]", 7.0),
        ("[2 ** 3 * 2]", 16.0),
        ("[2 * 3 ** 2]", 18.0),
        ("[10 - 4 - 3]", 3.0),
        ("[12 / 3 / 2]", 2.0),
        ("[7 MOD 3]", 1.0),
        ("[-7 MOD 3]", 2.0),
        ("[1 + 2 EQ 3]", 1.0),
        ("[1 EQ 1.0000001]", 1.0),
        ("[2 GT 1 AND 1 GT 2]", 0.0),
        ("[1 LT 2 XOR 2 LT 3]", 0.0),
        ("[0 OR 3]", 1.0),
        ("[SIN[30] * 2]", 1.0),
        ("[ATAN[1]/[1]]", 45.0),
        ("[FIX[-2.5]]", -3.0),
        ("[FUP[2.1]]", 3.0),
        ("[ROUND[2.5]]", 3.0),
        ("[SQRT[16] + ABS[-1]]", 5.0),
        ("[EXP[0] + LN[1]]", 1.0),
        ("-[2]", -2.0),
        ("[acos[0]]", 90.0),
        ("[ 1 +[2]* [ 3 ]]", 7.0),
    ] {
        let got = x_of(expression);
        assert!((got - x).abs() < 1e-9, "X{expression}: {got}, not {x}");
    }
}

#[test]
fn parameters_are_set_after_their_line_and_read_by_number_or_name() {
    // On line 2, X reads #1 before the line sets it.
    assert_eq!(
        xs("#1 = 5\n#1 = 7 G0 X#1\nG0 X#1\n#<depth> = [#1 * 2]\nG0 X#<DEPTH>\n#2 = 1\nG0 X##2\nG0 X#[1 + 1]"),
        [5.0, 7.0, 14.0, 7.0, 1.0]
    );
    // Unset numbered parameters read 0; #5420 is the current X.
    assert_eq!(xs("G0 X3\nG0 Y1 X[#5420 + #99]"), [3.0, 3.0]);
    assert_eq!(xs("G0 X3\nG0 X[#5420 + 1]"), [3.0, 4.0]);
    // A persistent parameter written moves the coordinates at once.
    assert_eq!(xs("#5221 = 10\nG0 X0"), [10.0]);
    // A computed G code and a computed feed.
    let p = run("#3 = 1\nG#3 X[2] F[60 * 10]");
    assert_eq!(p.final_position[0], 2.0);
}

#[test]
fn bad_values_are_named_errors() {
    for (program, message) in [
        ("G0 X[1/0]", "line 1: X[1/0]: division by zero (LinuxCNC: Attempt to divide by zero)"),
        ("G0 X[SQRT[-1]]", "line 1: X[SQRT[-1]]: SQRT[-1]: the argument must be 0 or more (LinuxCNC: Negative argument to sqrt)"),
        ("G0 X[LN[0]]", "line 1: X[LN[0]]: LN[0]: the argument must be above 0 (LinuxCNC: Zero or negative argument to ln)"),
        ("G0 X#<nope>", "line 1: X#<nope>: #<nope> is not set (LinuxCNC: Named parameter #<nope> not defined)"),
        ("G0 X#6000", "line 1: X#6000: #6000 is not a parameter: a whole number from 1 to 5602 (LinuxCNC: Parameter number out of range)"),
        ("#5420 = 1", "line 1: #5420 is read-only here: the current position"),
        ("#5230 = 1", "line 1: #5230 = 1 rotates a coordinate system, which is not supported"),
        ("G0 X[1 + 2", "line 1: `[` is not closed by `]`"),
        ("G0 X[1 ? 2]", "line 1: `?` is not an operator"),
        ("G0 X[FOO[1]]", "line 1: `FOO` is not a function"),
        ("#1", "line 1: a parameter alone on a line is set with `=`: `#1 = 2`"),
        ("N#1 G0 X1", "line 1: line number N#1 is not a whole number"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
}

#[test]
fn active_comments_are_kept_with_parameters_replaced() {
    let p = run("#1 = 2.5\n#<name> = 3\n(MSG, Insert the 6 mm tool)\n(debug, #1 and #<name>, #9)\n(PRINT,x=#1)\n(not a message, #1)\nM2");
    let got: Vec<_> = p
        .messages
        .iter()
        .map(|m| (m.line, m.kind, m.text.as_str()))
        .collect();
    assert_eq!(
        got,
        [
            (3, "MSG", "Insert the 6 mm tool"),
            (4, "DEBUG", "2.500000 and 3.000000, 0.000000"),
            (5, "PRINT", "x=2.500000"),
        ]
    );
}
