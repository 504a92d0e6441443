//! Proofs of `formal/freq_divider.sv`.

use super::FormalSpec;
use crate::blocks::freq_divider::FreqDivider;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "freq_divider_w4",
            block: "freq_divider",
            module: "freq_divider",
            property_file: "freq_divider.sv",
            instance: "W = 4",
            properties: "strobe exactly as specified: first enabled edge with D != 0, then every latched D enabled edges; none with enable low or in reset",
            bmc_depth: 20,
            induction_depth: 2,
            build: || Box::new(FreqDivider::<4>::default()),
        },
        FormalSpec {
            name: "freq_divider_w32",
            block: "freq_divider",
            module: "freq_divider",
            property_file: "freq_divider.sv",
            instance: "W = 32 (exported)",
            properties: "the same, on the exported width",
            bmc_depth: 6,
            induction_depth: 2,
            build: || Box::new(FreqDivider::<32>::default()),
        },
    ]
}
