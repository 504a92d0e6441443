//! Test benches shared by several test binaries (each binary compiles only
//! what it uses).
#![allow(dead_code)]

pub mod pin_bench;
