//! Proofs of `formal/external_bus_adapter.sv` (the 32-bit adapter) and
//! `formal/narrow_bus_adapter.sv` (the 16- and 8-bit adapters).

use super::FormalSpec;
use crate::blocks::external_bus_adapter::ExternalBusAdapter;
use crate::blocks::narrow_bus_adapter::{
    ExternalBusAdapter16, ExternalBusAdapter8, NarrowBusAdapter,
};

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "external_bus_adapter_a2",
            block: "external_bus_adapter",
            module: "external_bus_adapter",
            property_file: "external_bus_adapter.sv",
            instance: "A = 2, data 32",
            properties: "one bus_write per write access, one bus_read per read access, at their latencies, with the sampled address and data (runts: none; both strobes together: the read put off a clock when the write takes it); data_out; data_oe; reset",
            bmc_depth: 12,
            induction_depth: 6,
            build: || Box::new(ExternalBusAdapter::<2>::default()),
        },
        FormalSpec {
            name: "external_bus_adapter_a8",
            block: "external_bus_adapter",
            module: "external_bus_adapter",
            property_file: "external_bus_adapter.sv",
            instance: "A = 8, data 32 (exported)",
            properties: "the same, on the exported instance",
            bmc_depth: 6,
            induction_depth: 6,
            build: || Box::new(ExternalBusAdapter::<8>::default()),
        },
        FormalSpec {
            name: "narrow_bus_adapter_2_of_4",
            block: "narrow_bus_adapter",
            module: "narrow_bus_adapter",
            property_file: "narrow_bus_adapter.sv",
            instance: "A = 1, NA = 2, N = 2, W = 4 (2 parts, as external_bus_adapter_16)",
            properties: "per narrow access at the pins: one bus_write per completed word with the whole word, none for a torn one; one bus_read per part-0 (or out-of-order) read, parts from the latched word; order_error; data_out; ready",
            bmc_depth: 12,
            induction_depth: 4,
            build: || Box::new(NarrowBusAdapter::<1, 2, 2, 4>::default()),
        },
        FormalSpec {
            name: "external_bus_adapter_16",
            block: "narrow_bus_adapter",
            module: "external_bus_adapter_16",
            property_file: "narrow_bus_adapter.sv",
            instance: "A = 8, NA = 9, N = 16, W = 32 (exported)",
            properties: "the same, on the exported 16-bit adapter (2 parts)",
            bmc_depth: 6,
            induction_depth: 4,
            build: || Box::new(ExternalBusAdapter16::default()),
        },
        FormalSpec {
            name: "external_bus_adapter_8",
            block: "narrow_bus_adapter",
            module: "external_bus_adapter_8",
            property_file: "narrow_bus_adapter.sv",
            instance: "A = 8, NA = 10, N = 8, W = 32 (exported)",
            properties: "the same, on the exported 8-bit adapter (4 parts)",
            bmc_depth: 6,
            induction_depth: 4,
            build: || Box::new(ExternalBusAdapter8::default()),
        },
    ]
}
