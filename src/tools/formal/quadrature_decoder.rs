//! Proofs of `formal/quadrature_decoder.sv`.

use super::FormalSpec;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![]
}
