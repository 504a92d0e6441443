//! What the interpreter's tests share: a program run or refused, and
//! the path it takes.

use motion_hdl::host::gcode::interpreter::{interpret_with, Program, Setup};
use motion_hdl::host::toolpath::Item;

/// `program` interpreted; a refusal fails the test, naming the program.
pub(super) fn run(program: &str) -> Program {
    run_with(program, &Setup::default())
}

/// `program` interpreted from `setup`.
pub(super) fn run_with(program: &str, setup: &Setup) -> Program {
    interpret_with(program, setup).unwrap_or_else(|e| panic!("{program:?}: {e}"))
}

/// The refusal of `program`, "line N: message"; acceptance fails the test.
pub(super) fn error(program: &str) -> String {
    error_with(program, &Setup::default())
}

/// The refusal of `program` from `setup`.
pub(super) fn error_with(program: &str, setup: &Setup) -> String {
    match interpret_with(program, setup) {
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
            Item::Synced(m) => Some(m.end[0]),
            Item::Dwell { .. } => None,
        })
        .collect()
}
