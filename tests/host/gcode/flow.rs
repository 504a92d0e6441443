//! O-words: each structure's path worked out by hand (the X of each move
//! records where the program went), and the errors.

use super::support::{error, xs};

#[test]
fn subroutines_take_arguments_return_values_and_keep_the_callers_parameters() {
    let program = "\
o<hole> sub
  G0 X[#1 * 10] Y#<_n>
  #<local> = 99
  #<_n> = [#<_n> + 1]
  o<hole> return [#1 + #2]
o<hole> endsub
#1 = 7
#<local> = 5
#<_n> = 1
o<hole> call [1] [2]
G0 X#<_value> Y0
o<hole> call [3]
G0 X[#1 + #<local>] Y#<_n>
M2";
    // Calls at X10 (Y1) and X30 (Y2); the first returns 3; after them #1
    // and #<local> are the caller's, #<_n> the global count.
    assert_eq!(xs(program), [10.0, 3.0, 30.0, 12.0]);
    // A sub ending without a value leaves #<_value_returned> 0.
    assert_eq!(
        xs("o1 sub\no1 endsub\no1 call\nG0 X[#<_value_returned> + 1]"),
        [1.0]
    );
}

#[test]
fn if_elseif_else_take_the_first_true_branch() {
    let program = |n: i32| {
        format!(
            "#1 = {n}\no10 if [#1 EQ 1]\nG0 X1\no10 elseif [#1 EQ 2]\nG0 X2\no10 elseif [#1 GT 2]\nG0 X3\no10 else\nG0 X4\no10 endif\nG0 X9"
        )
    };
    for (n, x) in [(1, 1.0), (2, 2.0), (5, 3.0), (0, 4.0)] {
        assert_eq!(xs(&program(n)), [x, 9.0], "#1 = {n}");
    }
    assert_eq!(xs("o1 if [0]\nG0 X1\no1 endif\nG0 X2"), [2.0]);
}

#[test]
fn loops_while_do_repeat_break_and_continue() {
    assert_eq!(
        xs("#1 = 1\no1 while [#1 LE 3]\nG0 X#1\n#1 = [#1 + 1]\no1 endwhile\nG0 X0"),
        [1.0, 2.0, 3.0, 0.0]
    );
    // do runs its body once before the test.
    assert_eq!(
        xs("#1 = 5\no2 do\nG0 X#1\n#1 = [#1 + 1]\no2 while [#1 LT 3]"),
        [5.0]
    );
    assert_eq!(
        xs("#1 = 0\no3 repeat [3]\n#1 = [#1 + 1]\nG0 X#1\no3 endrepeat"),
        [1.0, 2.0, 3.0]
    );
    assert_eq!(xs("o3 repeat [0]\nG0 X1\no3 endrepeat\nG0 X2"), [2.0]);
    // break leaves the loop; continue skips to the next test.
    assert_eq!(
        xs("#1 = 0\no4 while [1]\n#1 = [#1 + 1]\no5 if [#1 EQ 2]\no4 continue\no5 endif\no6 if [#1 GT 3]\no4 break\no6 endif\nG0 X#1\no4 endwhile\nG0 X0"),
        [1.0, 3.0, 0.0]
    );
    // A repeat entered again starts counting again.
    assert_eq!(
        xs("#2 = 0\no7 repeat [2]\no8 repeat [2]\n#2 = [#2 + 1]\nG0 X#2\no8 endrepeat\no7 endrepeat"),
        [1.0, 2.0, 3.0, 4.0]
    );
}

#[test]
fn recursion_runs_to_ten_levels() {
    // LinuxCNC's factorial.ngc shape: a sub that calls itself.
    let program = "o<f> sub\no1 if [#1 LE 1]\no<f> return [1]\no1 endif\no<f> call [#1 - 1]\no<f> return [#1 * #<_value>]\no<f> endsub\no<f> call [5]\nG0 X#<_value>";
    assert_eq!(xs(program), [120.0]);
    assert_eq!(
        error("o<f> sub\no<f> call [#1 + 1]\no<f> endsub\no<f> call [1]"),
        "line 2: O<f> call: more than 10 calls deep (LinuxCNC: Too many subroutine levels) (in O<f> called on line 2)"
    );
}

#[test]
fn o_word_errors_name_their_line() {
    for (program, message) in [
        ("o1 if [1]\nG0 X1", "line 1: O1 if is never closed"),
        ("o1 endif", "line 1: O1 endif closes no open O1 if"),
        ("o1 while [1]\no2 endwhile", "line 2: O2 endwhile closes no open O2 while"),
        ("o1 else", "line 1: O1 else has no open O1 if"),
        ("o1 break", "line 1: O1 break is in no O1 loop"),
        ("o1 sub\no1 endsub\no1 sub\no1 endsub", "line 4: O1 sub is defined twice"),
        ("o1 sub\no2 sub\no2 endsub\no1 endsub", "line 2: O2 sub inside another O-word structure"),
        ("o9 call", "line 1: O9 call: this file has no O9 sub (LinuxCNC would look for a file 9.ngc; subroutine files are not read)"),
        ("o1 return", "line 1: O1 return outside a subroutine"),
        ("o1 if 1\no1 endif", "line 1: O1 if: its values are written in `[ ]`"),
        ("o1 if\no1 endif", "line 1: O1 if needs one value in `[ ]`"),
        ("o1 frobnicate", "line 1: O1 frobnicate: not an O-word keyword"),
        ("o1 sub\nG0 X[1/0]\no1 endsub\no1 call", "line 2: X[1/0]: division by zero (LinuxCNC: Attempt to divide by zero) (in O1 called on line 4)"),
    ] {
        assert_eq!(error(program), message, "{program:?}");
    }
}

#[test]
fn a_loop_that_never_ends_is_an_error_not_a_hang() {
    assert_eq!(
        error("o1 while [1]\no1 endwhile"),
        "line 2: O1: the program's loops jumped back 10000000 times: a loop that does not end (this interpreter's bound; LinuxCNC has none)"
    );
}
