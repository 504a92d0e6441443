//! The G-code line lexer: one line of a program into a block of words.
//!
//! What a line may hold (RS-274/NGC, with the RepRap checksum):
//! * an optional `/` first: block delete (the block is marked, and skipped
//!   by the interpreter);
//! * words: a letter (either case) and a number, spaces allowed between and
//!   inside them as RS-274 allows between a letter and its number
//!   (`G1X1Y2`, `x.5`, `Y-0.25`, `Z +1.`);
//! * an `N` line number as the first word;
//! * comments: `( ... )` anywhere (not nested), `;` to the end of the line;
//! * a checksum `*NN` at the end: the XOR of every byte before the `*`;
//! * a line holding only `%`: when it is the program's first non-blank
//!   line it opens the program, and the next such line closes it
//!   (LinuxCNC's rule: nothing after the closing `%` is read); a `%` line
//!   with no opening one is an error.
//!
//! Numbers are kept as `f64` and as their text: G and M codes are compared
//! as integers ([`Word::code`]), never as floats. Every error names the
//! 1-based line of the file and the problem, with the text at fault.

use thiserror::Error;

use super::expr::{Cursor, Expr, Param};
use super::flow::OWord;

/// A line of a G-code program that cannot be read.
#[derive(Debug, Error, PartialEq, Eq, Clone)]
#[error("line {line}: {message}")]
pub struct LexError {
    /// The 1-based line of the file.
    pub line: usize,
    /// What is wrong, naming the text at fault.
    pub message: String,
}

/// One word: a letter and its number.
#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    /// The letter, upper case.
    pub letter: char,
    /// The number as written, without spaces (`-0.25`, `90.1`, `+1.`);
    /// for a value computed when the block runs, the value as text.
    pub text: String,
    /// The number's value (NaN until `expr` is evaluated).
    pub value: f64,
    /// A parameter, `[expression]` or signed one, evaluated when the block
    /// runs; `None` for a plain number.
    pub expr: Option<Expr>,
}

impl Word {
    /// A G or M code as an integer, ten times its number: `G1` and `G01` are
    /// 10, `G90.1` is 901. `None` for a negative code or one with more than
    /// one decimal (`G1.25`), which names no code.
    pub fn code(&self) -> Option<u32> {
        let (major, minor) = match self.text.split_once('.') {
            Some((major, "")) => (major, "0"),
            Some((major, minor)) => (major, minor),
            None => (self.text.as_str(), "0"),
        };
        let major = major.strip_prefix('+').unwrap_or(major);
        if major.is_empty() || minor.len() != 1 || !major.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let major: u32 = major.parse().ok()?;
        let minor: u32 = minor.parse().ok()?;
        major.checked_mul(10)?.checked_add(minor)
    }

    /// The word as written in a message: `G90.1`, `X-0.25`.
    pub fn name(&self) -> String {
        format!("{}{}", self.letter, self.text)
    }
}

/// One line of a program, read.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// The 1-based line of the file.
    pub line: usize,
    /// The `N` line number, if the line has one.
    pub number: Option<u32>,
    /// Block delete: the line starts with `/`.
    pub deleted: bool,
    /// The words, in order (the `N` word is not among them).
    pub words: Vec<Word>,
    /// The comments' texts, without their delimiters.
    pub comments: Vec<String>,
    /// `#n = value` and `#<name> = value`, in order: they take effect
    /// after the block (LinuxCNC's rule).
    pub assignments: Vec<(Param, Expr)>,
    /// An O-word statement other than a program number (`o100 sub`,
    /// `o<x> call [1]`): subroutines and flow control.
    pub o_word: Option<OWord>,
}

/// A program read line by line.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Lexed {
    /// The blocks, in order; blank lines and `%` lines have none.
    pub blocks: Vec<Block>,
    /// The line of the `%` that closed the program, when its first
    /// non-blank line was `%`: the lines after it are not read.
    pub closing_percent: Option<usize>,
}

/// Reads the lines of `program` up to its closing `%`, if it has one (see
/// the [module doc](self)); lines with nothing but spaces are skipped.
pub fn lex_program(program: &str) -> Result<Lexed, LexError> {
    let mut lexed = Lexed::default();
    let mut opened = false;
    let mut first = true;
    for (index, text) in program.lines().enumerate() {
        let line = index + 1;
        let trimmed = text.trim();
        if trimmed == "%" {
            if first {
                opened = true;
            } else if opened {
                lexed.closing_percent = Some(line);
                break;
            } else {
                return Err(LexError {
                    line,
                    message: "`%` closes a program only when its first line is `%` too \
                        (LinuxCNC: Bad character '%' used)"
                        .into(),
                });
            }
        }
        first &= trimmed.is_empty();
        if let Some(block) = lex_line(line, text)? {
            lexed.blocks.push(block);
        }
    }
    Ok(lexed)
}

/// Reads one line (`line` is its 1-based number in the file). `None` for a
/// blank or `%` line.
pub fn lex_line(line: usize, text: &str) -> Result<Option<Block>, LexError> {
    let error = |message: String| LexError { line, message };
    let trimmed = text.trim();
    if trimmed.is_empty() || trimmed == "%" {
        return Ok(None);
    }
    let body = checked_body(trimmed).map_err(error)?;
    let mut block = Block {
        line,
        ..Block::default()
    };
    let bytes = body.as_bytes();
    let mut at = 0;
    skip_spaces(bytes, &mut at);
    if bytes.get(at) == Some(&b'/') {
        block.deleted = true;
        at += 1;
    }
    loop {
        skip_spaces(bytes, &mut at);
        let Some(&byte) = bytes.get(at) else { break };
        match byte {
            b'(' => {
                let close = body[at..]
                    .find(')')
                    .ok_or_else(|| error("comment `(` is not closed on its line".into()))?;
                let comment = &body[at + 1..at + close];
                if comment.contains('(') {
                    return Err(error(format!(
                        "comment `({comment})` holds a `(`: comments do not nest"
                    )));
                }
                block.comments.push(comment.to_string());
                at += close + 1;
            }
            b';' => {
                block.comments.push(body[at + 1..].to_string());
                break;
            }
            b'#' => {
                let mut cursor = Cursor { bytes, at: at + 1 };
                let param = cursor.param().map_err(error)?;
                if cursor.peek() != Some(b'=') {
                    return Err(error(
                        "a parameter alone on a line is set with `=`: `#1 = 2`".into(),
                    ));
                }
                cursor.at += 1;
                let value = cursor.value().map_err(error)?;
                block.assignments.push((param, value));
                at = cursor.at;
            }
            // `@` and `^`: LinuxCNC's polar distance and angle words.
            letter if letter.is_ascii_alphabetic() || letter == b'@' || letter == b'^' => {
                let letter = letter.to_ascii_uppercase() as char;
                at += 1;
                if letter == 'O' {
                    if let Some(statement) = o_statement(body, at) {
                        block.o_word = Some(super::flow::parse(&statement[1..]).map_err(error)?);
                        break;
                    }
                }
                let mut cursor = Cursor { bytes, at };
                let computed = match cursor.peek() {
                    Some(b'[' | b'#') => true,
                    Some(b'-' | b'+') => {
                        let sign = cursor.at;
                        cursor.at += 1;
                        let next = cursor.peek();
                        cursor.at = sign;
                        matches!(next, Some(b'[' | b'#'))
                    }
                    _ => false,
                };
                let word = if computed {
                    let start = cursor.at;
                    let expr = cursor.value().map_err(error)?;
                    let text: String = body[start..cursor.at].split_whitespace().collect();
                    at = cursor.at;
                    Word {
                        letter,
                        text,
                        value: f64::NAN,
                        expr: Some(expr),
                    }
                } else {
                    let number = read_number(bytes, &mut at);
                    parse_word(letter, &number).map_err(error)?
                };
                if letter == 'N' && word.expr.is_some() {
                    return Err(error(format!(
                        "line number N{} is not a whole number",
                        word.text
                    )));
                }
                if letter == 'N' {
                    if !block.words.is_empty() || block.number.is_some() {
                        return Err(error(format!(
                            "line number {} is not the first word",
                            word.name()
                        )));
                    }
                    block.number = Some(word.text.parse().map_err(|_| {
                        error(format!("line number {} is not a whole number", word.name()))
                    })?);
                } else {
                    block.words.push(word);
                }
            }
            other => {
                let shown = body[at..].chars().next().unwrap_or(other as char);
                return Err(error(format!("unexpected character `{shown}`")));
            }
        }
    }
    Ok(Some(block))
}

/// The line without its checksum, after checking it: `*NN` is the XOR of
/// every byte before the `*`. A `*` inside a comment is not a checksum.
fn checked_body(line: &str) -> Result<&str, String> {
    let Some(star) = checksum_star(line) else {
        return Ok(line);
    };
    let (body, tail) = (&line[..star], line[star + 1..].trim());
    let given: u8 = tail
        .parse()
        .map_err(|_| format!("checksum `*{tail}` is not a number from 0 to 255"))?;
    let computed = body.bytes().fold(0u8, |x, b| x ^ b);
    if given != computed {
        return Err(format!(
            "checksum *{given} does not match the line (its bytes give *{computed})"
        ));
    }
    Ok(body)
}

/// Where the checksum's `*` is: the first `*` outside a comment and
/// outside `[ ]` (where `*` and `**` are operators).
fn checksum_star(line: &str) -> Option<usize> {
    let mut in_comment = false;
    let mut depth = 0usize;
    for (i, c) in line.char_indices() {
        match c {
            '(' => in_comment = true,
            ')' => in_comment = false,
            '[' if !in_comment => depth += 1,
            ']' if !in_comment => depth = depth.saturating_sub(1),
            ';' if !in_comment => return None,
            '*' if !in_comment && depth == 0 => return Some(i),
            _ => {}
        }
    }
    None
}

fn skip_spaces(bytes: &[u8], at: &mut usize) {
    while bytes.get(*at).is_some_and(|b| b.is_ascii_whitespace()) {
        *at += 1;
    }
}

/// The text after a letter: a sign, digits and points, spaces allowed
/// between them and removed.
fn read_number(bytes: &[u8], at: &mut usize) -> String {
    let mut number = String::new();
    loop {
        skip_spaces(bytes, at);
        match bytes.get(*at) {
            Some(&b) if (b == b'+' || b == b'-') && number.is_empty() => number.push(b as char),
            Some(&b) if b.is_ascii_digit() || b == b'.' => number.push(b as char),
            _ => return number,
        }
        *at += 1;
    }
}

fn parse_word(letter: char, number: &str) -> Result<Word, String> {
    if number.is_empty() {
        return Err(format!("word `{letter}` has no number"));
    }
    let digits = number.trim_start_matches(['+', '-']);
    let points = digits.matches('.').count();
    if points > 1 || !digits.bytes().any(|b| b.is_ascii_digit()) {
        return Err(format!("`{letter}{number}` is not a number"));
    }
    let value: f64 = number
        .parse()
        .map_err(|_| format!("`{letter}{number}` is not a number"))?;
    Ok(Word {
        letter,
        text: number.to_string(),
        value,
        expr: None,
    })
}

/// The O-word statement starting after the `O` at `at`, if the line holds
/// one: `<name>` or a number followed by a keyword (`sub`, `call`, `if`...).
/// A bare `O1003` is a program number, not a statement.
fn o_statement(body: &str, at: usize) -> Option<String> {
    let rest = body[at..].trim_start();
    let after_name = if rest.starts_with('<') {
        &rest[rest.find('>').map_or(rest.len(), |i| i + 1)..]
    } else {
        rest.trim_start_matches(|c: char| c.is_ascii_digit() || c == '.' || c.is_whitespace())
    };
    let named = rest.starts_with('<');
    let word: String = after_name
        .trim_start()
        .chars()
        .take_while(char::is_ascii_alphabetic)
        .map(|c| c.to_ascii_lowercase())
        .collect();
    // A keyword (`sub`, `if`...) or any word of two letters or more, which
    // the O-word parser refuses by name; one letter and a number is a
    // G-code word after an O number.
    let keyword = word.len() >= 2;
    (named || keyword).then(|| {
        let end = body[at..].find([';', '(']).map_or(body.len(), |i| at + i);
        format!("O{}", body[at..end].trim())
    })
}
