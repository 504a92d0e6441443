//! Tests of `motion_hdl::host::gcode::text` (`src/host/gcode/text.rs`).

use std::borrow::Cow;

use motion_hdl::host::gcode::program_text;

#[test]
fn latin1_in_comments_is_read_and_elsewhere_names_its_line() {
    let program = b"G0 X1 (Bohrer \xd8 6 mm)\n; Fr\xe4ser\nG1 X2 F60\n";
    let text = program_text(program).unwrap();
    assert_eq!(
        text,
        "G0 X1 (Bohrer \u{d8} 6 mm)\n; Fr\u{e4}ser\nG1 X2 F60\n"
    );
    // UTF-8 is kept as it is, comments or not.
    let utf8 = "G0 X1 (Bohrer \u{d8})\n".as_bytes();
    assert!(matches!(program_text(utf8).unwrap(), Cow::Borrowed(_)));
    let error = program_text(b"G0 X1\nG1 X\xb12 F60 (\xd8)\n").unwrap_err();
    assert_eq!(
        error.to_string(),
        "line 2: byte 0xB1 outside a comment: the line is not UTF-8 text (Latin-1 is read in comments only)"
    );
    // A `;` inside a parenthesis comment does not open a comment.
    assert!(program_text(b"G0 X1 (a;b) \xb1\n").is_err());
}
