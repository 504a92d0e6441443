//! Benches shared by several blocks' tests.

pub mod pin_bench;
pub mod timing_diagram;
