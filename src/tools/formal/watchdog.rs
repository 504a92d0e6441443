//! Proofs of `formal/watchdog.sv`.

use super::FormalSpec;
use crate::blocks::watchdog::Watchdog;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "watchdog_w4",
            block: "watchdog",
            module: "watchdog",
            property_file: "watchdog.sv",
            instance: "W = 4",
            properties: "expired set exactly at the timeout-th tick after the last kick (none with timeout 0, none while kicked in time), sticky until clear; armed as specified",
            bmc_depth: 20,
            induction_depth: 1,
            build: || Box::new(Watchdog::<4>::default()),
        },
        FormalSpec {
            name: "watchdog_w32",
            block: "watchdog",
            module: "watchdog",
            property_file: "watchdog.sv",
            instance: "W = 32 (the motion controller's)",
            properties: "the same, on the motion controller's width",
            bmc_depth: 6,
            induction_depth: 1,
            build: || Box::new(Watchdog::<32>::default()),
        },
    ]
}
