//! Tests of `motion_hdl::host::gcode::lexer` (`src/host/gcode/lexer.rs`).

use motion_hdl::host::gcode::lexer::*;

fn words(text: &str) -> Vec<(char, f64)> {
    lex_line(1, text)
        .unwrap()
        .unwrap()
        .words
        .iter()
        .map(|w| (w.letter, w.value))
        .collect()
}

#[test]
fn words_with_and_without_spaces_and_in_either_case() {
    assert_eq!(words("G1X1Y2"), vec![('G', 1.0), ('X', 1.0), ('Y', 2.0)]);
    assert_eq!(
        words("g01 x.5 y-0.25 z+1."),
        vec![('G', 1.0), ('X', 0.5), ('Y', -0.25), ('Z', 1.0)]
    );
    assert_eq!(words("G 1 X 1 2.5"), vec![('G', 1.0), ('X', 12.5)]);
    assert_eq!(words("X1234.5678")[0].1, 1234.5678);
}

#[test]
fn codes_are_integers_with_one_decimal() {
    let code = |text: &str| lex_line(1, text).unwrap().unwrap().words[0].code();
    assert_eq!(code("G1"), Some(10));
    assert_eq!(code("G01"), Some(10));
    assert_eq!(code("G90.1"), Some(901));
    assert_eq!(code("G91.1"), Some(911));
    assert_eq!(code("M30"), Some(300));
    assert_eq!(code("G1."), Some(10));
    assert_eq!(code("G1.25"), None);
    assert_eq!(code("G-1"), None);
}

#[test]
fn line_numbers_comments_block_delete_and_checksums() {
    let block = lex_line(7, "/N10 G1 X1 (to the edge) Y2 ; and up")
        .unwrap()
        .unwrap();
    assert_eq!(block.line, 7);
    assert!(block.deleted);
    assert_eq!(block.number, Some(10));
    assert_eq!(block.words.len(), 3);
    assert_eq!(
        block.comments,
        vec!["to the edge".to_string(), " and up".to_string()]
    );
    // N3 T0*57: the RepRap documentation's example.
    let block = lex_line(1, "N3 T0*57").unwrap().unwrap();
    assert_eq!(
        (block.number, block.words[0].name()),
        (Some(3), "T0".to_string())
    );
    assert_eq!(lex_line(1, "%").unwrap(), None);
    assert_eq!(lex_line(1, "   ").unwrap(), None);
    assert_eq!(
        lex_line(1, "(only a comment *)")
            .unwrap()
            .unwrap()
            .words
            .len(),
        0
    );
}

#[test]
fn errors_name_the_line_and_the_text() {
    let message = |text: &str| lex_line(12, text).unwrap_err().to_string();
    assert_eq!(message("G1 X"), "line 12: word `X` has no number");
    assert_eq!(message("G1 X1.2.3"), "line 12: `X1.2.3` is not a number");
    assert_eq!(message("G1 X-"), "line 12: `X-` is not a number");
    assert_eq!(message("G1 X1 $"), "line 12: unexpected character `$`");
    assert_eq!(
        message("G1 (open"),
        "line 12: comment `(` is not closed on its line"
    );
    assert_eq!(
        message("G1 (a (b) c)"),
        "line 12: comment `(a (b)` holds a `(`: comments do not nest"
    );
    assert_eq!(
        message("N3 T0*58"),
        "line 12: checksum *58 does not match the line (its bytes give *57)"
    );
    assert_eq!(
        message("N3 T0*x"),
        "line 12: checksum `*x` is not a number from 0 to 255"
    );
    assert_eq!(
        message("G1 N3"),
        "line 12: line number N3 is not the first word"
    );
    assert_eq!(
        message("N3.5 G1"),
        "line 12: line number N3.5 is not a whole number"
    );
    assert_eq!(
        lex_program("G21\n\nG1 X1 $\n").unwrap_err().to_string(),
        "line 3: unexpected character `$`"
    );
}

/// LinuxCNC's `%` rule, as its 2.9 interpreter runs it: an opening `%`
/// (after blank lines) and the next `%` closes the program, whatever
/// follows; a `%` line after other lines with no opening one is refused.
#[test]
fn percent_lines_open_and_close_the_program() {
    let lexed = lex_program("\n %\nG0 X1\n%\nG0 X5\nnot G-code at all\n").unwrap();
    assert_eq!(lexed.blocks.len(), 1);
    assert_eq!(lexed.closing_percent, Some(4));
    let lexed = lex_program("%\nG0 X1\n").unwrap();
    assert_eq!((lexed.blocks.len(), lexed.closing_percent), (1, None));
    let lexed = lex_program("G0 X1\nM2\n").unwrap();
    assert_eq!((lexed.blocks.len(), lexed.closing_percent), (2, None));
    assert_eq!(
        lex_program("G21\nG0 X1\n%\nG0 X3\n")
            .unwrap_err()
            .to_string(),
        "line 3: `%` closes a program only when its first line is `%` too \
             (LinuxCNC: Bad character '%' used)"
    );
}
