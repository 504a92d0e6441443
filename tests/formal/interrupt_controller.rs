//! `formal/interrupt_controller.sv`: proofs and mutations.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn interrupt_controller_3_bits_is_proved() {
    assert_proved("interrupt_controller_n3");
}

#[test]
fn interrupt_controller_12_bits_is_proved() {
    assert_proved("interrupt_controller_n12");
}

/// The clear applied after the events: an event on the clock of its bit's
/// W1C is lost.
#[test]
fn interrupt_controller_proof_catches_an_event_lost_to_a_clear() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "status_reg__d = (status_reg__q & ~clear_bits) | events;",
        "status_reg__d = (status_reg__q | events) & ~clear_bits;",
    );
}

/// A clear ignores `clear_bits`: every status bit is cleared.
#[test]
fn interrupt_controller_proof_catches_a_clear_of_unselected_bits() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "(status_reg__q & ~clear_bits)",
        "(status_reg__q & zero)",
    );
}

/// Write 1 to toggle instead of write 1 to clear: a W1C of a clear bit sets it.
#[test]
fn interrupt_controller_proof_catches_a_clear_that_sets_bits() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "(status_reg__q & ~clear_bits)",
        "(status_reg__q ^ clear_bits)",
    );
}

/// `irq` ignores the enable mask.
#[test]
fn interrupt_controller_proof_catches_an_unmasked_irq() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "irq_reg__d = (status_reg__q & enable) != zero;",
        "irq_reg__d = status_reg__q != zero;",
    );
}

/// `irq` from the status after the edge: one clock early.
#[test]
fn interrupt_controller_proof_catches_an_irq_one_clock_early() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "irq_reg__d = (status_reg__q & enable) != zero;",
        "irq_reg__d = (status_reg__d & enable) != zero;",
    );
}

/// Reset clears the status but leaves `irq` as computed.
#[test]
fn interrupt_controller_proof_catches_an_irq_kept_through_reset() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "irq_reg__d = 1'b0;",
        "irq_reg__d = irq_reg__d;",
    );
}

/// The write strobe is ignored: a W1C clears nothing.
#[test]
fn interrupt_controller_proof_catches_a_w1c_that_clears_nothing() {
    assert_mutation_caught(
        "interrupt_controller_n3",
        "if (clear) begin",
        "if (1'b0) begin",
    );
}
