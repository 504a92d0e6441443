//! Proofs of `formal/step_output.sv`.

use super::FormalSpec;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![]
}
