//! `formal/command_fifo.sv`: proofs and mutations.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn command_fifo_2_entries_is_proved() {
    assert_proved("command_fifo_n1");
}

#[test]
fn command_fifo_16_entries_is_proved() {
    assert_proved("command_fifo_n4");
}

/// A full FIFO takes every write (no full check): the level passes the
/// depth.
#[test]
fn command_fifo_proof_catches_a_write_taken_when_full() {
    assert_mutation_caught(
        "command_fifo_n1",
        "write_taken = write & (~is_full | pop_taken);",
        "write_taken = write;",
    );
}

/// A refused write (full FIFO) is still written to the RAM: it overwrites
/// the head entry's slot.
#[test]
fn command_fifo_proof_catches_a_refused_write_reaching_the_ram() {
    assert_mutation_caught(
        "command_fifo_n1",
        "ram__write_enable = write_taken;",
        "ram__write_enable = write;",
    );
}

/// An empty FIFO takes every pop (no empty check): the level wraps.
#[test]
fn command_fifo_proof_catches_a_pop_taken_when_empty() {
    assert_mutation_caught(
        "command_fifo_n1",
        "pop_taken = pop & ~is_empty;",
        "pop_taken = pop;",
    );
}

/// A refused pop (empty FIFO) still moves the read pointer: the next entry
/// written is read from the wrong slot.
#[test]
fn command_fifo_proof_catches_a_refused_pop_moving_the_read_pointer() {
    assert_mutation_caught(
        "command_fifo_n1",
        "if (pop_taken) begin\n            next_read",
        "if (pop) begin\n            next_read",
    );
}

/// A refused write on the clock of `clear_flags` is not flagged: the clear
/// wins over the new overflow.
#[test]
fn command_fifo_proof_catches_an_overflow_lost_to_a_clear() {
    assert_mutation_caught(
        "command_fifo_n1",
        "if (write & ~write_taken) begin",
        "if (write & ~write_taken & ~clear_flags) begin",
    );
}

/// A refused pop that comes with a write is not flagged as an underflow.
#[test]
fn command_fifo_proof_catches_an_underflow_missed_with_a_write() {
    assert_mutation_caught(
        "command_fifo_n1",
        "if (pop & ~pop_taken) begin",
        "if (pop & ~pop_taken & ~write) begin",
    );
}

/// No read-during-write bypass: a write to the slot the head moves to shows
/// the RAM's old word on `head`.
#[test]
fn command_fifo_proof_catches_a_missing_read_during_write_bypass() {
    assert_mutation_caught(
        "command_fifo_n1",
        "bypass__d = write_taken & (write_pointer__q == next_read);",
        "bypass__d = 1'b0;",
    );
}

/// The RAM reads the current head's slot instead of the next one: after a
/// pop, `head` shows the popped entry for a clock.
#[test]
fn command_fifo_proof_catches_a_head_one_pop_late() {
    assert_mutation_caught(
        "command_fifo_n1",
        "ram__read_address = next_read;",
        "ram__read_address = read_pointer__q;",
    );
}

/// The RAM's words are not zero-initialized (a RAM built without its
/// INIT): `head` is not 0 before the first write.
#[test]
fn command_fifo_proof_catches_a_ram_not_zeroed_at_power_up() {
    assert_mutation_caught("command_fifo_n1", "mem[i] = 0;", ";");
}

#[test]
fn command_fifo_ram_premise_is_proved_at_both_depths() {
    assert_proved("command_fifo_ram_n1");
    assert_proved("command_fifo_ram_n4");
}

/// A write-first RAM (the read sees the write on the same edge): the
/// premise, read-first, fails.
#[test]
fn command_fifo_ram_proof_catches_a_write_first_ram() {
    assert_mutation_caught(
        "command_fifo_ram_n1",
        "read_data <= mem[read_address];",
        "read_data <= (write_enable && write_address == read_address) ? write_data : mem[read_address];",
    );
}
