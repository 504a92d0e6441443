//! O-words with LinuxCNC's semantics: `sub`/`endsub`/`call`/`return` with
//! arguments #1 to #30 and `#<_value>`, `if`/`elseif`/`else`/`endif`,
//! `while`/`endwhile`, `do`/`while`, `repeat`/`endrepeat`,
//! `break`/`continue`. Statements pair by their label (`o100`, `o<name>`),
//! as in LinuxCNC; a program is checked whole before it runs, so a
//! structure left open is an error naming its line.
//!
//! Limits (LinuxCNC's): 10 call levels, 30 arguments. A loop has no bound
//! in LinuxCNC; here the program's loops together may jump back at most
//! [`MAX_ITERATIONS`] times, then the loop is an error, never a hang.

use std::collections::HashMap;

use super::expr::{Cursor, Expr};
use super::lexer::Block;

/// Backward jumps a program may make in all its loops.
pub const MAX_ITERATIONS: u64 = 10_000_000;
/// Nested calls (LinuxCNC's MAX_NESTED_CALLS... its "Too many subroutine
/// levels").
pub const MAX_CALL_DEPTH: usize = 10;
/// Arguments of a call (#1 to #30).
pub const MAX_ARGUMENTS: usize = 30;

/// An O-word statement, parsed.
#[derive(Clone, Debug, PartialEq)]
pub struct OWord {
    /// `100` or `<name>` (lower case), as a key.
    pub label: String,
    /// What it does.
    pub kind: OKind,
}

/// The O-word keywords.
#[derive(Clone, Debug, PartialEq)]
#[allow(missing_docs)]
pub enum OKind {
    Sub,
    EndSub(Option<Expr>),
    Call(Vec<Expr>),
    Return(Option<Expr>),
    If(Expr),
    ElseIf(Expr),
    Else,
    EndIf,
    Do,
    While(Expr),
    EndWhile,
    Repeat(Expr),
    EndRepeat,
    Break,
    Continue,
}

impl OKind {
    /// The word that names it: "sub", "elseif", "endrepeat"...
    pub fn keyword(&self) -> &'static str {
        match self {
            OKind::Sub => "sub",
            OKind::EndSub(_) => "endsub",
            OKind::Call(_) => "call",
            OKind::Return(_) => "return",
            OKind::If(_) => "if",
            OKind::ElseIf(_) => "elseif",
            OKind::Else => "else",
            OKind::EndIf => "endif",
            OKind::Do => "do",
            OKind::While(_) => "while",
            OKind::EndWhile => "endwhile",
            OKind::Repeat(_) => "repeat",
            OKind::EndRepeat => "endrepeat",
            OKind::Break => "break",
            OKind::Continue => "continue",
        }
    }
}

/// Parses `O100 sub`, `O<x> call [1] [2]`, `O1 if [#1 GT 2]`... (the text
/// after the `O` is `rest`).
pub(super) fn parse(rest: &str) -> Result<OWord, String> {
    let rest = rest.trim_start();
    let (label, after) = if let Some(named) = rest.strip_prefix('<') {
        let end = named.find('>').ok_or("O<name> has no closing `>`")?;
        let name: String = named[..end]
            .chars()
            .filter(|c| !c.is_whitespace())
            .map(|c| c.to_ascii_lowercase())
            .collect();
        (format!("<{name}>"), &named[end + 1..])
    } else {
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c.is_whitespace()))
            .unwrap_or(rest.len());
        let number: String = rest[..end].split_whitespace().collect();
        if number.is_empty() {
            return Err("an O word needs a number or a <name>".into());
        }
        let number: u32 = number
            .parse()
            .map_err(|_| format!("O{number} is not an O number"))?;
        (number.to_string(), &rest[end..])
    };
    let after = after.trim_start();
    let keyword_end = after
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(after.len());
    let keyword = after[..keyword_end].to_ascii_lowercase();
    let mut cursor = Cursor {
        bytes: &after.as_bytes()[keyword_end..],
        at: 0,
    };
    let mut values = Vec::new();
    while cursor.peek().is_some() {
        if cursor.peek() != Some(b'[') {
            return Err(format!(
                "O{label} {keyword}: its values are written in `[ ]`"
            ));
        }
        values.push(cursor.value()?);
    }
    let one = |values: &mut Vec<Expr>| -> Result<Expr, String> {
        match values.len() {
            1 => Ok(values.remove(0)),
            _ => Err(format!("O{label} {keyword} needs one value in `[ ]`")),
        }
    };
    let at_most_one = |values: &mut Vec<Expr>| -> Result<Option<Expr>, String> {
        match values.len() {
            0 => Ok(None),
            1 => Ok(Some(values.remove(0))),
            _ => Err(format!("O{label} {keyword} takes at most one value")),
        }
    };
    let none = |values: &Vec<Expr>| -> Result<(), String> {
        if values.is_empty() {
            Ok(())
        } else {
            Err(format!("O{label} {keyword} takes no value"))
        }
    };
    let kind = match keyword.as_str() {
        "sub" => none(&values).map(|_| OKind::Sub)?,
        "endsub" => OKind::EndSub(at_most_one(&mut values)?),
        "call" if values.len() <= MAX_ARGUMENTS => OKind::Call(values),
        "call" => {
            return Err(format!(
                "O{label} call has {} arguments: at most {MAX_ARGUMENTS}",
                values.len()
            ))
        }
        "return" => OKind::Return(at_most_one(&mut values)?),
        "if" => OKind::If(one(&mut values)?),
        "elseif" => OKind::ElseIf(one(&mut values)?),
        "else" => none(&values).map(|_| OKind::Else)?,
        "endif" => none(&values).map(|_| OKind::EndIf)?,
        "do" => none(&values).map(|_| OKind::Do)?,
        "while" => OKind::While(one(&mut values)?),
        "endwhile" => none(&values).map(|_| OKind::EndWhile)?,
        "repeat" => OKind::Repeat(one(&mut values)?),
        "endrepeat" => none(&values).map(|_| OKind::EndRepeat)?,
        "break" => none(&values).map(|_| OKind::Break)?,
        "continue" => none(&values).map(|_| OKind::Continue)?,
        other => return Err(format!("O{label} {other}: not an O-word keyword")),
    };
    Ok(OWord { label, kind })
}

/// Where each statement jumps, found before the program runs (indices
/// into the blocks).
#[derive(Debug, Default)]
pub(super) struct Structure {
    /// Sub label → (index of `sub`, index of `endsub`).
    pub(super) subs: HashMap<String, (usize, usize)>,
    /// For `if`, `elseif`, `else`: the next branch (elseif, else or endif);
    /// for `sub`: its `endsub`; for a loop's head (`while`, `repeat`) and
    /// a `do`'s closing `while`: the loop's end; for `endwhile`,
    /// `endrepeat` and a `do`'s `while`: the loop's head; for `break` and
    /// `continue`: the loop's end; for every branch: its `endif`.
    pub(super) target: HashMap<usize, usize>,
    /// The `endif` of every `if`, `elseif` and `else`.
    pub(super) endif: HashMap<usize, usize>,
    /// For `break` and `continue`: the loop's head and end.
    pub(super) loop_of: HashMap<usize, (usize, usize)>,
    /// Indices of `while` statements that close a `do`.
    pub(super) do_while: std::collections::HashSet<usize>,
}

/// Pairs the statements of `blocks` by label; every error names its line.
pub(super) fn structure(blocks: &[Block]) -> Result<Structure, (usize, String)> {
    let mut s = Structure::default();
    // Open structures: (label, the opening index, the keyword, the last
    // branch index for an if).
    let mut open: Vec<(String, usize, &'static str, usize)> = Vec::new();
    let mut loops_inner: Vec<(usize, Vec<usize>)> = Vec::new();
    for (i, block) in blocks.iter().enumerate() {
        let Some(o) = &block.o_word else { continue };
        let line = block.line;
        let label = &o.label;
        let find = |open: &Vec<(String, usize, &'static str, usize)>, kinds: &[&str]| {
            open.iter()
                .rposition(|(l, _, k, _)| l == label && kinds.contains(k))
        };
        let closes =
            |open: &mut Vec<(String, usize, &'static str, usize)>, kinds: &[&str], what: &str| {
                let top = open
                    .last()
                    .is_some_and(|(l, _, k, _)| l == label && kinds.contains(k));
                match open.pop() {
                    Some(entry) if top => Ok(entry),
                    other => {
                        open.extend(other);
                        Err((
                            line,
                            format!(
                                "O{label} {what} closes no open O{label} {}",
                                kinds.join(" or ")
                            ),
                        ))
                    }
                }
            };
        match &o.kind {
            OKind::Sub => {
                if !open.is_empty() {
                    return Err((
                        line,
                        format!("O{label} sub inside another O-word structure"),
                    ));
                }
                open.push((label.clone(), i, "sub", i));
            }
            OKind::EndSub(_) => {
                let (_, start, _, _) = closes(&mut open, &["sub"], "endsub")?;
                if s.subs.insert(label.clone(), (start, i)).is_some() {
                    return Err((line, format!("O{label} sub is defined twice")));
                }
                s.target.insert(start, i);
            }
            OKind::If(_) => open.push((label.clone(), i, "if", i)),
            OKind::ElseIf(_) | OKind::Else => {
                let at = find(&open, &["if"])
                    .filter(|&at| at + 1 == open.len())
                    .ok_or_else(|| {
                        (
                            line,
                            format!("O{label} {} has no open O{label} if", o.kind.keyword()),
                        )
                    })?;
                let last = open[at].3;
                s.target.insert(last, i);
                open[at].3 = i;
            }
            OKind::EndIf => {
                let (_, start, _, last) = closes(&mut open, &["if"], "endif")?;
                s.target.insert(last, i);
                // Every branch of this if ends here.
                let mut branch = start;
                loop {
                    s.endif.insert(branch, i);
                    match s.target.get(&branch) {
                        Some(&next) if next != i => branch = next,
                        _ => break,
                    }
                }
            }
            OKind::Do => {
                open.push((label.clone(), i, "do", i));
                loops_inner.push((i, Vec::new()));
            }
            OKind::While(_) if find(&open, &["do"]).is_some_and(|at| at + 1 == open.len()) => {
                let (_, start, _, _) = closes(&mut open, &["do"], "while")?;
                s.do_while.insert(i);
                s.target.insert(i, start);
                close_loop(&mut s, &mut loops_inner, start, i, i);
            }
            OKind::While(_) => {
                open.push((label.clone(), i, "while", i));
                loops_inner.push((i, Vec::new()));
            }
            OKind::EndWhile => {
                let (_, start, _, _) = closes(&mut open, &["while"], "endwhile")?;
                s.target.insert(start, i);
                s.target.insert(i, start);
                close_loop(&mut s, &mut loops_inner, start, start, i);
            }
            OKind::Repeat(_) => {
                open.push((label.clone(), i, "repeat", i));
                loops_inner.push((i, Vec::new()));
            }
            OKind::EndRepeat => {
                let (_, start, _, _) = closes(&mut open, &["repeat"], "endrepeat")?;
                s.target.insert(start, i);
                s.target.insert(i, start);
                close_loop(&mut s, &mut loops_inner, start, start, i);
            }
            OKind::Break | OKind::Continue => {
                let at = find(&open, &["while", "do", "repeat"]).ok_or_else(|| {
                    (
                        line,
                        format!("O{label} {} is in no O{label} loop", o.kind.keyword()),
                    )
                })?;
                let head = open[at].1;
                if let Some((_, inner)) = loops_inner.iter_mut().find(|(h, _)| *h == head) {
                    inner.push(i);
                }
            }
            OKind::Call(_) | OKind::Return(_) => {}
        }
    }
    if let Some((label, start, kind, _)) = open.pop() {
        let line = blocks[start].line;
        return Err((line, format!("O{label} {kind} is never closed")));
    }
    Ok(s)
}

/// Records a loop's head (where `continue` goes), end and its breaks.
fn close_loop(
    s: &mut Structure,
    loops_inner: &mut Vec<(usize, Vec<usize>)>,
    opening: usize,
    head: usize,
    end: usize,
) {
    if let Some(at) = loops_inner.iter().rposition(|(h, _)| *h == opening) {
        let (_, inner) = loops_inner.remove(at);
        for statement in inner {
            s.loop_of.insert(statement, (head, end));
        }
    }
}
