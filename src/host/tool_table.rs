//! A tool table in LinuxCNC's `.tbl` format, read for G-code's T, M6,
//! M61, G43 and cutter compensation (G41, G42): `simulate --tools FILE`.
//!
//! ## Format
//! One tool a line: words of a letter and a number, separated by spaces,
//! either case; `;` starts the remark (the rest of the line); blank lines
//! and lines starting with `;` are skipped.
//!
//! ```text
//! T1  P1 Z12.5  D6.0   ;6 mm end mill
//! T4  P4 Z25.4  D3.175 ;1/8 in drill
//! ```
//!
//! | Word | Meaning |
//! |---|---|
//! | T | tool number, a whole number from 1 (required, once per table) |
//! | P | pocket, a whole number from 0 (kept, not used: no tool changer is simulated) |
//! | X, Y, Z | tool offsets, mm (LinuxCNC's machine units: this machine's are mm); G43 applies all three, a mill's is usually Z only |
//! | D | diameter, mm; negative for a tool smaller than the one a compensated path was drawn for (cutter compensation then takes the other side, as in LinuxCNC) |
//! | A, B, C, U, V, W | offsets along axes this machine does not have: 0 only |
//! | I, J, Q | lathe front angle, back angle, orientation: accepted, not used |
//!
//! Every error names the line and the word. Unlike LinuxCNC, which skips
//! a line it cannot read, a bad line stops the whole table: a tool read
//! wrong would move the tool somewhere else.

use std::collections::BTreeMap;

use thiserror::Error;

/// A tool table line that cannot be read.
#[derive(Debug, Error, PartialEq, Eq, Clone)]
#[error("line {line}: {message}")]
pub struct ToolTableError {
    /// The 1-based line of the file.
    pub line: usize,
    /// What is wrong, naming the word at fault.
    pub message: String,
}

/// One tool.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tool {
    /// The pocket (P), if given.
    pub pocket: Option<u32>,
    /// X, Y, Z offsets, mm.
    pub offset: [f64; 3],
    /// Diameter, mm.
    pub diameter: f64,
    /// The remark after `;`, trimmed.
    pub remark: String,
}

/// The tools by number.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ToolTable {
    /// Tool number to tool.
    pub tools: BTreeMap<u32, Tool>,
}

impl ToolTable {
    /// Reads a table (see the [module documentation](self)).
    pub fn parse(text: &str) -> Result<Self, ToolTableError> {
        let mut table = ToolTable::default();
        for (index, raw) in text.lines().enumerate() {
            let line = index + 1;
            let error = |message: String| ToolTableError { line, message };
            let (body, remark) = raw.split_once(';').unwrap_or((raw, ""));
            if body.trim().is_empty() {
                continue;
            }
            let mut number = None;
            let mut tool = Tool {
                remark: remark.trim().to_string(),
                ..Tool::default()
            };
            let mut seen = String::new();
            for word in body.split_whitespace() {
                let mut chars = word.chars();
                let letter = chars.next().map(|c| c.to_ascii_uppercase());
                let letter = letter.filter(char::is_ascii_alphabetic).ok_or_else(|| {
                    error(format!("`{word}` is not a word: a letter and a number"))
                })?;
                if seen.contains(letter) {
                    return Err(error(format!("{letter} appears twice")));
                }
                seen.push(letter);
                let text = chars.as_str();
                let value: f64 = text
                    .parse()
                    .ok()
                    .filter(|v: &f64| v.is_finite())
                    .ok_or_else(|| error(format!("`{word}` is not a number after {letter}")))?;
                let whole = |least: f64| {
                    (value.fract() == 0.0 && value >= least && value <= f64::from(u32::MAX))
                        .then_some(value as u32)
                };
                match letter {
                    'T' => {
                        number = Some(whole(1.0).ok_or_else(|| {
                            error(format!(
                            "{word} is not a tool number: a whole number from 1 (T0 is no tool)"
                        ))
                        })?)
                    }
                    'P' => {
                        tool.pocket = Some(whole(0.0).ok_or_else(|| {
                            error(format!("{word} is not a pocket: a whole number from 0"))
                        })?)
                    }
                    'X' | 'Y' | 'Z' => tool.offset[(letter as u8 - b'X') as usize] = value,
                    'D' => tool.diameter = value,
                    'A' | 'B' | 'C' | 'U' | 'V' | 'W' if value == 0.0 => {}
                    'A' | 'B' | 'C' | 'U' | 'V' | 'W' => {
                        return Err(error(format!(
                            "{word} offsets an axis this machine does not have (X, Y and Z only)"
                        )))
                    }
                    'I' | 'J' | 'Q' => {}
                    _ => return Err(error(format!("{word}: {letter} is not a tool table word"))),
                }
            }
            let number = number.ok_or_else(|| error("a tool needs its number, T".into()))?;
            if table.tools.insert(number, tool).is_some() {
                return Err(error(format!("T{number} is already in the table")));
            }
        }
        Ok(table)
    }

    /// Tool `number`, if the table has it.
    pub fn get(&self, number: u32) -> Option<&Tool> {
        self.tools.get(&number)
    }
}
