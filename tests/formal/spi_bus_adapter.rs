//! `formal/spi_bus_adapter.sv`: the proof of "no partial write, no write
//! on a bad CRC", its buffer's RAM premise, a bug the contract alone
//! catches from power-up, and bugs deeper than a bounded check reaches
//! that the proof refuses.

use crate::support::{assert_mutation_caught, assert_proof_fails, assert_proved};

#[test]
fn spi_bus_adapter_writes_only_whole_frames_that_passed_is_proved() {
    assert_proved("spi_bus_adapter");
}

#[test]
fn spi_bus_adapter_buffer_premise_is_proved() {
    assert_proved("spi_bus_adapter_ram");
}

/// A read strobe that no frame asked for.
#[test]
fn spi_bus_adapter_proof_catches_a_strobe_without_a_frame() {
    assert_mutation_caught(
        "spi_bus_adapter",
        "bus_read = bus_read_reg__q;",
        "bus_read = bus_read_reg__q | (sclk_sync__q & mosi_sync__q);",
    );
}

/// The bug this proof found (fixed since): a write frame whose header CRC
/// failed got a second verdict at its frame CRC, so a frame CRC matching
/// the bytes as received (a corrupted count lays it on a data byte) wrote
/// the frame. `a_bad_header_crc_writes_nothing_even_when_the_frame_crc_then_matches`
/// (tests/blocks) shows it in simulation.
#[test]
fn spi_bus_adapter_proof_refuses_a_write_after_a_bad_header() {
    assert_proof_fails(
        "spi_bus_adapter",
        "if ((at_crc__q & ~complete__q) | (at_p2__q & ~crc_ok)) begin",
        "if (at_crc__q | (at_p2__q & ~crc_ok)) begin",
    );
}

/// A bit counted at an SCLK rise after CS rose.
#[test]
fn spi_bus_adapter_proof_refuses_a_bit_after_cs_rose() {
    assert_proof_fails(
        "spi_bus_adapter",
        "rise = sclk_sync__q & ~sclk_last__q & in_frame__q & select_sync__q;",
        "rise = sclk_sync__q & ~sclk_last__q & in_frame__q;",
    );
}

/// A too-fast SCLK no longer flagged.
#[test]
fn spi_bus_adapter_proof_refuses_an_unflagged_too_fast_sclk() {
    assert_proof_fails(
        "spi_bus_adapter",
        "overspeed_any = overspeed__q | (in_frame__q & select_sync__q & sclk_edge & ~since_edge__q[32'h1]);",
        "overspeed_any = overspeed__q;",
    );
}
