//! Proofs of `formal/step_output.sv`.

use super::FormalSpec;
use crate::blocks::step_output::StepOutput;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "step_output_t3_p3",
            block: "step_output",
            module: "step_output",
            property_file: "step_output.sv",
            instance: "T = 3, P = 3",
            properties: "step/dir: pulse exactly step_len, space, dir setup and hold; up/down: length, space, never both high; quadrature: one Gray move per step, each state held step_len; all modes: no step lost or invented (pin steps against accepted requests), drops and overrun, emitted, busy",
            bmc_depth: 8,
            induction_depth: 1,
            build: || Box::new(StepOutput::<3, 3>::default()),
        },
        FormalSpec {
            name: "step_output_t16_p16",
            block: "step_output",
            module: "step_output",
            property_file: "step_output.sv",
            instance: "T = 16, P = 16 (exported)",
            properties: "the same, on the exported widths",
            bmc_depth: 4,
            induction_depth: 1,
            build: || Box::new(StepOutput::<16, 16>::default()),
        },
    ]
}
