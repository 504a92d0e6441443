//! Proofs of `formal/watchdog.sv`.

use super::FormalSpec;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![]
}
