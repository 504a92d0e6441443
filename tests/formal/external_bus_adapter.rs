//! `formal/external_bus_adapter.sv` (the 32-bit adapter) and
//! `formal/narrow_bus_adapter.sv` (the 16- and 8-bit adapters): the proofs,
//! and for each contract a bug its proof must catch.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn external_bus_adapter_2_bit_address_strobes_are_proved() {
    assert_proved("external_bus_adapter_a2");
}

#[test]
fn external_bus_adapter_exported_strobes_are_proved() {
    assert_proved("external_bus_adapter_a8");
}

#[test]
fn narrow_bus_adapter_2_parts_of_2_bits_are_proved() {
    assert_proved("narrow_bus_adapter_2_of_4");
}

#[test]
fn external_bus_adapter_16_is_proved() {
    assert_proved("external_bus_adapter_16");
}

#[test]
fn external_bus_adapter_8_is_proved() {
    assert_proved("external_bus_adapter_8");
}

/// A write strobe on both edges of the access: the synchronizer also
/// detects the strobe's start (two active samples after an inactive one)
/// as a write.
#[test]
fn external_bus_adapter_proof_catches_a_write_on_both_edges() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "write_ends = write_older__q & write_prev__q & ~write_sync__q;",
        "write_ends = (write_older__q & write_prev__q & ~write_sync__q) | (~write_prev__q & write_sync__q & write_meta__q);",
    );
}

/// A read lost at the minimum spacing: the "served" flag waits for two
/// inactive samples, so a read one inactive sample after the previous one
/// is never issued.
#[test]
fn external_bus_adapter_proof_catches_a_read_lost_at_minimum_spacing() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "if (~read_sync__q) begin",
        "if (~read_sync__q & ~read_prev__q) begin",
    );
}

/// The bug this proof found under the bad input of both strobes active
/// (fixed since): the "served" flag is not cleared on the clock a put-off
/// read is issued, so after a read that overlapped a write's end and was
/// put off a clock, a read starting one inactive sample later is never
/// issued.
#[test]
fn external_bus_adapter_proof_catches_a_read_lost_after_a_put_off_read() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "if (~read_sync__q) begin",
        "if (~read_sync__q & ~read_wanted) begin",
    );
}

/// A put-off read (both strobes active, the write took its clock) issued
/// with the address of the clock it is issued in instead of the one it
/// was qualified with.
#[test]
fn external_bus_adapter_proof_catches_a_put_off_read_with_a_late_address() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "bus_address_reg__d = address_prev__q;",
        "bus_address_reg__d = address_sync__q;",
    );
}

/// A wrong write address: the sample of the last active clock (which a
/// master with zero hold time may corrupt) instead of the one before it.
#[test]
fn external_bus_adapter_proof_catches_a_write_address_sampled_too_late() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "bus_address_reg__d = address_older__q;",
        "bus_address_reg__d = address_prev__q;",
    );
}

/// data_out loaded a clock early, with the slave's data of the clock of
/// bus_read itself (not yet valid).
#[test]
fn external_bus_adapter_proof_catches_read_data_taken_a_clock_early() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "if (read_answer__q) begin",
        "if (bus_read_reg__q) begin",
    );
}

/// The data pins driven during a write with rd_n also low (the master
/// drives them then): data_oe without its `we_n` term.
#[test]
fn external_bus_adapter_proof_catches_pins_driven_against_a_write() {
    assert_mutation_caught(
        "external_bus_adapter_a2",
        "data_oe = ~cs_n & ~rd_n & we_n;",
        "data_oe = ~cs_n & ~rd_n;",
    );
}

/// A torn write: the highest part commits the word without checking that
/// every lower part was written.
#[test]
fn narrow_bus_adapter_proof_catches_a_torn_write() {
    assert_mutation_caught(
        "narrow_bus_adapter_2_of_4",
        "if (holding_hit & (held_parts__q == lower_parts)) begin",
        "if (holding_hit) begin",
    );
}

/// A tearing read: every part reads the register again instead of the
/// latched word.
#[test]
fn narrow_bus_adapter_proof_catches_a_read_of_every_part() {
    assert_mutation_caught(
        "narrow_bus_adapter_2_of_4",
        "if ((part == zero_na) | ~latch_hit) begin",
        "if (1'b1) begin",
    );
}

/// A higher part answered from the slave's current data instead of the
/// word latched with part 0.
#[test]
fn narrow_bus_adapter_proof_catches_a_part_not_from_the_latched_word() {
    assert_mutation_caught(
        "narrow_bus_adapter_2_of_4",
        "answer_word = latch__q >> answer_offset__q;",
        "answer_word = bus_read_data >> answer_offset__q;",
    );
}

/// No order_error when a lower part of another register drops the held
/// parts.
#[test]
fn narrow_bus_adapter_proof_catches_a_silent_abandoned_word() {
    assert_mutation_caught(
        "narrow_bus_adapter_2_of_4",
        "error_reg__d = held_parts__q != zero_parts;",
        "error_reg__d = 1'b0;",
    );
}

/// ready of a read rising a clock before the answer is on data_out.
#[test]
fn narrow_bus_adapter_proof_catches_ready_before_the_read_data() {
    assert_mutation_caught(
        "narrow_bus_adapter_2_of_4",
        "read_done__d = (read_done__q | read_answer__q) & read_sync__q;",
        "read_done__d = (read_done__q | bus_read_reg__q) & read_sync__q;",
    );
}
