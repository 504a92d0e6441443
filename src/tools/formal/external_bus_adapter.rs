//! Proofs of `formal/external_bus_adapter.sv`.

use super::FormalSpec;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![]
}
