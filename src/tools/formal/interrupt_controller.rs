//! Proofs of `formal/interrupt_controller.sv`.

use super::FormalSpec;
use crate::blocks::interrupt_controller::InterruptController;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "interrupt_controller_n3",
            block: "interrupt_controller",
            module: "interrupt_controller",
            property_file: "interrupt_controller.sv",
            instance: "N = 3",
            properties: "status set by its event (never lost to a clear on the same clock), cleared only by a W1C of its bit; irq = OR(status & enable), one clock later; reset",
            bmc_depth: 8,
            induction_depth: 1,
            build: || Box::new(InterruptController::<3>::default()),
        },
        FormalSpec {
            name: "interrupt_controller_n12",
            block: "interrupt_controller",
            module: "interrupt_controller",
            property_file: "interrupt_controller.sv",
            instance: "N = 12 (the motion controller's)",
            properties: "the same, at the motion controller's width",
            bmc_depth: 4,
            induction_depth: 1,
            build: || Box::new(InterruptController::<12>::default()),
        },
    ]
}
