//! What the interpreter's unit tests share: a program run or refused, and
//! the path it takes.

use super::interpreter::{interpret, Program};
use crate::host::toolpath::Item;

/// `program` interpreted; a refusal fails the test, naming the program.
pub(super) fn run(program: &str) -> Program {
    interpret(program).unwrap_or_else(|e| panic!("{program:?}: {e}"))
}

/// The refusal of `program`, "line N: message"; acceptance fails the test.
pub(super) fn error(program: &str) -> String {
    match interpret(program) {
        Ok(p) => panic!("{program:?} was accepted: {p:?}"),
        Err(e) => e.to_string(),
    }
}

/// The X of every move of `program`: `G0 X...` lines mark the path taken.
pub(super) fn xs(program: &str) -> Vec<f64> {
    run(program)
        .toolpath
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Move(m) => Some(m.end[0]),
            Item::Dwell { .. } => None,
        })
        .collect()
}
