//! Proofs of `formal/spi_bus_adapter.sv` (the SPI adapter's frames against
//! its bus strobes), and of the frame buffer's RAM premise with
//! `formal/command_fifo_ram.sv` (the same RAM contract as the FIFO's).

use rust_hdl::prelude::*;

use super::FormalSpec;
use crate::blocks::holding_ram::HoldingRam;
use crate::blocks::spi_bus_adapter::SpiBusAdapter;

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "spi_bus_adapter",
            block: "spi_bus_adapter",
            module: "spi_bus_adapter",
            property_file: "spi_bus_adapter.sv",
            instance: "the exported adapter (16-word buffer, SNAPSHOT = 0x0b)",
            properties: "no partial write, no write on a bad CRC: every bus strobe belongs to a frame that passed (its CRC byte ended with CS low, the CRCs 0, SCLK never too fast), after it its SNAPSHOT write and all its N words at consecutive addresses, one a clock, and nothing else; each written word is the frame's, all 32 bits (given the RAM premise, proved below), never from a collided buffer read",
            bmc_depth: 8,
            induction_depth: 6,
            build: || Box::new(SpiBusAdapter::default()),
        },
        FormalSpec {
            name: "spi_bus_adapter_ram",
            block: "spi_bus_adapter",
            module: "spi_bus_adapter_ram",
            property_file: "command_fifo_ram.sv",
            instance: "HoldingRam, 16 x 32 bits, no power-up read word (the adapter's frame buffer)",
            properties: "the adapter's RAM premise: an enabled read returns the word last written to its address before the read's edge",
            bmc_depth: 4,
            induction_depth: 1,
            build: || {
                Box::new(
                    HoldingRam::<Bits<32>, 4>::collisions_unobserved().power_up_unobserved(),
                )
            },
        },
    ]
}
