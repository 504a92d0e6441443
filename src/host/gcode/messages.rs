//! Active comments, as LinuxCNC reads them: `(MSG, text)` shows the text;
//! `(DEBUG, text)` and `(PRINT, text)` show it with each `#n` and
//! `#<name>` replaced by the parameter's value (six decimals, as
//! LinuxCNC's `%lf`). The keyword may be in either case. In `simulate`
//! they are collected in [`Program::messages`](super::Program::messages),
//! in the order the program gives them.

use super::expr::{Cursor, Parameters};
use super::interpreter::State;
use super::lexer::Block;

/// One active comment, as the program ran it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// The 1-based line of the file.
    pub line: usize,
    /// "MSG", "DEBUG" or "PRINT".
    pub kind: &'static str,
    /// The text, parameters replaced.
    pub text: String,
}

impl State {
    /// Collects the block's active comments.
    pub(super) fn messages(&mut self, block: &Block) {
        for comment in &block.comments {
            let Some((keyword, text)) = comment.split_once(',') else {
                continue;
            };
            let kind = match keyword.trim().to_ascii_uppercase().as_str() {
                "MSG" => "MSG",
                "DEBUG" => "DEBUG",
                "PRINT" => "PRINT",
                _ => continue,
            };
            let text = if kind == "MSG" {
                text.trim_start().to_string()
            } else {
                self.substitute(text.trim_start())
            };
            self.messages.push(Message {
                line: block.line,
                kind,
                text,
            });
        }
    }

    /// `text` with its parameters replaced by their values; a reference
    /// that cannot be read is left as written.
    fn substitute(&self, text: &str) -> String {
        let bytes = text.as_bytes();
        let mut out = String::new();
        let mut at = 0;
        while at < bytes.len() {
            if bytes[at] == b'#' {
                let mut cursor = Cursor { bytes, at: at + 1 };
                let value = cursor.param().ok().and_then(|p| match p {
                    super::expr::Param::Numbered(n) => {
                        n.evaluate(self).ok().and_then(|n| self.numbered(n).ok())
                    }
                    super::expr::Param::Named(name) => self.named(&name),
                });
                if let Some(v) = value {
                    out.push_str(&format!("{v:.6}"));
                    // The cursor skips spaces after a number: keep them.
                    while cursor.at > at + 1 && bytes[cursor.at - 1].is_ascii_whitespace() {
                        cursor.at -= 1;
                    }
                    at = cursor.at;
                    continue;
                }
            }
            let ch = text[at..].chars().next().unwrap_or(' ');
            out.push(ch);
            at += ch.len_utf8();
        }
        out
    }
}
