//! Proofs of `formal/quadrature_decoder.sv`.

use super::FormalSpec;
use crate::blocks::quadrature_decoder::QuadratureDecoder;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "quadrature_decoder_w4",
            block: "quadrature_decoder",
            module: "quadrature_decoder",
            property_file: "quadrature_decoder.sv",
            instance: "W = 4, S = 2, TS = 2, filter off",
            properties: "with the filter off, the count exactly as specified, 5 edges after the pins: each legal transition once in its direction, at most one per sample, a double change no count and error set, no count lost to a clear or an index clear; error, dir, index_seen, index_count and timestamp too",
            bmc_depth: 16,
            induction_depth: 5,
            build: || Box::new(QuadratureDecoder::<4, 2, 2>::default()),
        },
        FormalSpec {
            name: "quadrature_decoder_w32",
            block: "quadrature_decoder",
            module: "quadrature_decoder",
            property_file: "quadrature_decoder.sv",
            instance: "W = 32, S = 2, TS = 16 (the exported count and timestamp widths), filter off",
            properties: "the same, on the exported count and timestamp widths",
            bmc_depth: 8,
            induction_depth: 5,
            build: || Box::new(QuadratureDecoder::<32, 2, 16>::default()),
        },
    ]
}
