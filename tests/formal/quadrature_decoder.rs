//! `formal/quadrature_decoder.sv`: the count with the filter off, 5 edges
//! after the pins; a double change; clears that lose no count.
//!
//! The mutations are checked on the 4-bit instance.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn quadrature_decoder_4_bit_count_is_proved() {
    assert_proved("quadrature_decoder_w4");
}

#[test]
fn quadrature_decoder_32_bit_count_is_proved() {
    assert_proved("quadrature_decoder_w32");
}

/// At most one per sample: a forward transition moves the count by 2.
#[test]
fn quadrature_decoder_proof_catches_a_step_of_two() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "delta__d = one_w;",
        "delta__d = two_w;",
    );
}

/// Each transition in its direction: the direction is taken from the levels
/// alone, not from which channel changed, so B's transitions count
/// backwards.
#[test]
fn quadrature_decoder_proof_catches_b_counting_backwards() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "forward = ~(filter_a__changed ^ (filter_a__filtered != filter_b__filtered));",
        "forward = filter_a__filtered != filter_b__filtered;",
    );
}

/// A double change: counted as a step (either channel changing counts).
#[test]
fn quadrature_decoder_proof_catches_a_double_change_counted() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "up_next = (filter_a__changed ^ filter_b__changed) & forward;",
        "up_next = (filter_a__changed | filter_b__changed) & forward;",
    );
}

/// A double change: `error` not set.
#[test]
fn quadrature_decoder_proof_catches_a_double_change_without_error() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "double__d = filter_a__changed & filter_b__changed;",
        "double__d = 1'b0;",
    );
}

/// A clear on a counting clock: the down step that came with it is lost
/// (not carried to the next edge).
#[test]
fn quadrature_decoder_proof_catches_a_count_lost_to_a_clear() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "carry_down = clear_now & down__q;",
        "carry_down = 1'b0;",
    );
}

/// An index clear on a counting clock: the up step is carried over `clear`
/// only, so an index clear loses it.
#[test]
fn quadrature_decoder_proof_catches_a_count_lost_to_an_index_clear() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "carry_up = clear_now & up__q;",
        "carry_up = clear & up__q;",
    );
}

/// The pin-to-count latency: the count adds the step as it is decoded,
/// bypassing its register, one edge before the documented 5th.
#[test]
fn quadrature_decoder_proof_catches_a_count_one_edge_early() {
    assert_mutation_caught(
        "quadrature_decoder_w4",
        "position__d = position__q + delta__q;",
        "position__d = position__q + delta__d;",
    );
}
