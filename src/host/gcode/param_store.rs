//! A program's parameters while it runs: numbered #1 to #5602 and named
//! `#<name>` (local) and `#<_name>` (global; without subroutines both live
//! in the program's one scope), evaluated into each block's words before
//! it runs, and set after it (LinuxCNC: "parameter setting takes effect
//! after the line is read").
//!
//! Numbers with a meaning here: #5161 to #5390 are the persistent
//! parameters ([`PersistentParameters`](super::PersistentParameters): a
//! write is checked as the settings file's is, and an offset written takes
//! effect at once); #5400 (the loaded tool) and #5420 to #5422 (the
//! current X, Y, Z in the program's units and coordinates) read the state
//! and cannot be written. Every other number reads 0 until set.

use std::borrow::Cow;
use std::collections::HashMap;

use super::expr::{Expr, Param, Parameters};
use super::interpreter::State;
use super::lexer::{Block, Word};
use super::parameters::{FIRST, LAST};

/// The highest parameter number (LinuxCNC's RS274NGC_MAX_PARAMETERS - 1).
pub const MAX_NUMBERED: u32 = 5602;
const LOADED_TOOL: u32 = 5400;
const POSITION: u32 = 5420;

/// The numbered and named parameters that are not persistent.
#[derive(Clone, Debug, Default)]
pub(super) struct ParamStore {
    numbered: HashMap<u32, f64>,
    named: HashMap<String, f64>,
}

/// What a call hides from its caller: #1 to #30 and the local names.
pub(super) struct Saved {
    numbered: [Option<f64>; 30],
    locals: HashMap<String, f64>,
}

impl ParamStore {
    /// Sets numbered parameter `n` (one the program may set itself, such
    /// as the probe's #5061 to #5070).
    pub(super) fn set_numbered(&mut self, n: u32, value: f64) {
        self.numbered.insert(n, value);
    }

    /// A call's entry: #1 to #30 are the arguments (0 past them) and no
    /// local name is set; the caller's are kept for [`leave`](Self::leave).
    pub(super) fn enter(&mut self, arguments: &[f64]) -> Saved {
        let numbered = std::array::from_fn(|k| self.numbered.remove(&(k as u32 + 1)));
        for k in 0..30 {
            let value = arguments.get(k).copied().unwrap_or(0.0);
            self.numbered.insert(k as u32 + 1, value);
        }
        let locals = self
            .named
            .iter()
            .filter(|(name, _)| !name.starts_with('_'))
            .map(|(name, v)| (name.clone(), *v))
            .collect();
        self.named.retain(|name, _| name.starts_with('_'));
        Saved { numbered, locals }
    }

    /// A call's return: the caller's #1 to #30 and locals back; a returned
    /// value in `#<_value>`, and `#<_value_returned>` 1 or 0 (LinuxCNC's).
    pub(super) fn leave(&mut self, saved: Saved, value: Option<f64>) {
        for (k, kept) in saved.numbered.into_iter().enumerate() {
            match kept {
                Some(v) => self.numbered.insert(k as u32 + 1, v),
                None => self.numbered.remove(&(k as u32 + 1)),
            };
        }
        self.named.retain(|name, _| name.starts_with('_'));
        self.named.extend(saved.locals);
        if let Some(v) = value {
            self.named.insert("_value".into(), v);
        }
        self.named.insert(
            "_value_returned".into(),
            f64::from(u8::from(value.is_some())),
        );
    }
}

/// A parameter number from a value: a whole number from 1 to 5602.
fn number(n: f64) -> Result<u32, String> {
    let rounded = n.round();
    if (n - rounded).abs() > 1e-6 || !(1.0..=f64::from(MAX_NUMBERED)).contains(&rounded) {
        return Err(format!(
            "#{n} is not a parameter: a whole number from 1 to {MAX_NUMBERED} (LinuxCNC: Parameter number out of range)"
        ));
    }
    Ok(rounded as u32)
}

impl Parameters for State {
    fn numbered(&self, n: f64) -> Result<f64, String> {
        let n = number(n)?;
        Ok(match n {
            FIRST..=LAST => self.parameters.get(n).unwrap_or(0.0),
            LOADED_TOOL => f64::from(self.loaded),
            POSITION..=5422 => self.position[(n - POSITION) as usize],
            _ => self.params.numbered.get(&n).copied().unwrap_or(0.0),
        })
    }

    fn named(&self, name: &str) -> Option<f64> {
        self.params.named.get(name).copied()
    }
}

/// A value as a word's text: whole numbers without a point, others with
/// up to 6 decimals (so that `G[90+0.1]` reads as G90.1).
fn as_text(v: f64) -> String {
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

impl State {
    /// `block` with every computed word evaluated; a block without one is
    /// not copied.
    pub(super) fn evaluate<'b>(&self, block: &'b Block) -> Result<Cow<'b, Block>, String> {
        if block.words.iter().all(|w| w.expr.is_none()) {
            return Ok(Cow::Borrowed(block));
        }
        let mut evaluated = block.clone();
        for word in &mut evaluated.words {
            if let Some(expr) = word.expr.take() {
                let value = expr
                    .evaluate(self)
                    .map_err(|e| format!("{}{}: {e}", word.letter, word.text))?;
                *word = Word {
                    letter: word.letter,
                    text: as_text(value),
                    value,
                    expr: None,
                };
            }
        }
        Ok(Cow::Owned(evaluated))
    }

    /// The block's assignments, every value read before any is set.
    pub(super) fn assign(&mut self, assignments: &[(Param, Expr)]) -> Result<(), String> {
        let mut values = Vec::with_capacity(assignments.len());
        for (param, expr) in assignments {
            let target = match param {
                Param::Numbered(n) => Ok(number(n.evaluate(self)?)?),
                Param::Named(name) => Err(name.clone()),
            };
            values.push((target, expr.evaluate(self)?));
        }
        for (target, value) in values {
            match target {
                Ok(n @ FIRST..=LAST) => {
                    self.parameters.set(n, value)?;
                    self.sync_work_position();
                }
                Ok(n @ (LOADED_TOOL | POSITION..=5422)) => {
                    return Err(format!(
                        "#{n} is read-only here: {}",
                        if n == LOADED_TOOL {
                            "the loaded tool"
                        } else {
                            "the current position"
                        }
                    ))
                }
                Ok(n) => {
                    self.params.numbered.insert(n, value);
                }
                Err(name) => {
                    self.params.named.insert(name, value);
                }
            }
        }
        Ok(())
    }
}
