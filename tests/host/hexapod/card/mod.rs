//! The parallel card's host side (`src/host/hexapod/card`).

mod bus;
mod program;
mod trajectory;
