//! Proofs of `formal/command_fifo.sv`, and of `formal/command_fifo_ram.sv`:
//! the RAM premise its induction takes, proved on the RAM itself.

use rust_hdl::prelude::*;

use super::FormalSpec;
use crate::blocks::command_fifo::CommandFifo;

/// The RAM exactly as `CommandFifo<N, _>` builds it (2^N zeroed words).
fn fifo_ram<const N: usize>() -> Box<dyn Block> {
    Box::new(RAM::<Bits<32>, N>::from(
        (0..1usize << N).map(|_| Bits::<32>::default()),
    ))
}

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "command_fifo_n1",
            block: "command_fifo",
            module: "command_fifo",
            property_file: "command_fifo.sv",
            instance: "N = 1 (2 entries)",
            properties: "level within the depth, empty/full/low from it; a refused write or pop changes nothing and sets its sticky flag; every entry comes out in order with its data (given the RAM premise, proved below)",
            bmc_depth: 10,
            induction_depth: 2,
            build: || Box::new(CommandFifo::<1, 2>::default()),
        },
        FormalSpec {
            name: "command_fifo_n4",
            block: "command_fifo",
            module: "command_fifo",
            property_file: "command_fifo.sv",
            instance: "N = 4 (16 entries, the motion controller's)",
            properties: "the same, at the motion controller's depth",
            bmc_depth: 4,
            induction_depth: 2,
            build: || Box::new(CommandFifo::<4, 5>::default()),
        },
        FormalSpec {
            name: "command_fifo_ram_n1",
            block: "command_fifo",
            module: "command_fifo_ram",
            property_file: "command_fifo_ram.sv",
            instance: "rust-hdl's RAM, 2 x 32 bits (the N = 1 FIFO's)",
            properties: "the FIFO's RAM premise: a read returns the word last written to its address before the read's edge (read-first)",
            bmc_depth: 4,
            induction_depth: 1,
            build: fifo_ram::<1>,
        },
        FormalSpec {
            name: "command_fifo_ram_n4",
            block: "command_fifo",
            module: "command_fifo_ram",
            property_file: "command_fifo_ram.sv",
            instance: "rust-hdl's RAM, 16 x 32 bits (the N = 4 FIFO's)",
            properties: "the same, at the motion controller's depth",
            bmc_depth: 4,
            induction_depth: 1,
            build: fifo_ram::<4>,
        },
    ]
}
