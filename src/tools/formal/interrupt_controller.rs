//! Proofs of `formal/interrupt_controller.sv`.

use super::FormalSpec;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![]
}
