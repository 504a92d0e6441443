//! G-code (RS-274) programs as the controller's input.
//!
//! Work in progress (issue #22): the line lexer is here; the modal
//! interpreter (G0 to G3, planes, units, distance modes, F, G4, M2/M30,
//! refusal of the words that change motion), arcs in the planner and
//! `simulate` on G-code are not built yet.
//!
//! The lexer is our own: the `gcode` crate (0.7.0, and 0.6.1) keeps values
//! as `f32` (`X1234.5678` reads 1234.5677), rejects block delete and
//! checksums, and drops a malformed G number without an error.

pub mod lexer;

pub use lexer::{lex_line, lex_program, Block, LexError, Word};
