//! A program file's bytes as text. CAM posts on Windows write comments in
//! Latin-1 (`(Bohrer Ø6)` as the byte 0xD8), so a line that is not UTF-8
//! is read as Latin-1 when every byte above 0x7F lies in a comment, where
//! it cannot change the motion. A byte above 0x7F outside a comment is an
//! error naming its line. Lines that are UTF-8 are kept as they are.

use std::borrow::Cow;

use super::lexer::LexError;

/// The program's text, or the first line with a non-UTF-8 byte outside a
/// comment.
pub fn program_text(bytes: &[u8]) -> Result<Cow<'_, str>, LexError> {
    if let Ok(text) = std::str::from_utf8(bytes) {
        return Ok(Cow::Borrowed(text));
    }
    let mut text = String::with_capacity(bytes.len() + bytes.len() / 8);
    for (index, line) in bytes.split_inclusive(|&b| b == b'\n').enumerate() {
        match std::str::from_utf8(line) {
            Ok(utf8) => text.push_str(utf8),
            Err(_) => {
                if let Some(byte) = byte_outside_comments(line) {
                    return Err(LexError {
                        line: index + 1,
                        message: format!(
                            "byte 0x{byte:02X} outside a comment: the line is not UTF-8 text (Latin-1 is read in comments only)"
                        ),
                    });
                }
                text.extend(line.iter().map(|&b| b as char));
            }
        }
    }
    Ok(Cow::Owned(text))
}

/// The first byte above 0x7F outside `( )` and `;` comments, if any.
fn byte_outside_comments(line: &[u8]) -> Option<u8> {
    let mut in_comment = false;
    for &byte in line {
        match byte {
            b'(' => in_comment = true,
            b')' => in_comment = false,
            b';' if !in_comment => return None,
            b if b > 0x7f && !in_comment => return Some(b),
            _ => {}
        }
    }
    None
}
