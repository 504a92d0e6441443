//! Proofs of `formal/command_fifo.sv`, and of `formal/command_fifo_ram.sv`:
//! the RAM premise its induction takes, proved on the RAM itself.

use rust_hdl::prelude::*;

use super::FormalSpec;
use crate::blocks::command_fifo::CommandFifo;
use crate::blocks::holding_ram::HoldingRam;

/// The RAM exactly as `CommandFifo<N, _, 32>` builds it.
fn fifo_ram<const N: usize>() -> Box<dyn Block> {
    Box::new(HoldingRam::<Bits<32>, N>::collisions_unobserved())
}

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "command_fifo_n1",
            block: "command_fifo",
            module: "command_fifo",
            property_file: "command_fifo.sv",
            instance: "N = 1 (2 entries)",
            properties: "level within the depth, empty/full/low from it; a refused write or pop changes nothing and sets its sticky flag; every entry comes out in order with its data (given the RAM premise, proved below); a non-empty FIFO's head never comes from a read that collided with a write",
            bmc_depth: 10,
            induction_depth: 2,
            build: || Box::new(CommandFifo::<1, 2, 32>::default()),
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
            build: || Box::new(CommandFifo::<4, 5, 32>::default()),
        },
        FormalSpec {
            name: "command_fifo_ram_n1",
            block: "command_fifo",
            module: "command_fifo_ram",
            property_file: "command_fifo_ram.sv",
            instance: "HoldingRam, 2 x 32 bits (the N = 1 FIFO's)",
            properties: "the FIFO's RAM premise: an enabled read returns the word last written to its address before the read's edge (read-first), held until the next enabled read",
            bmc_depth: 4,
            induction_depth: 1,
            build: fifo_ram::<1>,
        },
        FormalSpec {
            name: "command_fifo_ram_n4",
            block: "command_fifo",
            module: "command_fifo_ram",
            property_file: "command_fifo_ram.sv",
            instance: "HoldingRam, 16 x 32 bits (the N = 4 FIFO's)",
            properties: "the same, at the motion controller's depth",
            bmc_depth: 4,
            induction_depth: 1,
            build: fifo_ram::<4>,
        },
    ]
}
