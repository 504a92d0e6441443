//! `formal/step_output.sv`: the pins' timing in the three modes and the
//! step count, with one deliberate bug per contract.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn step_output_3_bit_timing_and_step_count_are_proved() {
    assert_proved("step_output_t3_p3");
}

#[test]
fn step_output_exported_16_bit_timing_and_step_count_are_proved() {
    assert_proved("step_output_t16_p16");
}

/// The fall decided one count early: a step pulse one clock short.
#[test]
fn step_output_proof_catches_a_pulse_one_clock_short() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "if (phase_done__q) begin\n                fall = 1'b1;",
        "if (phase_done__q | (phase_count__q == one_t + one_t)) begin\n                fall = 1'b1;",
    );
}

/// A pulse rises as soon as the stage has started, without waiting for
/// the step space.
#[test]
fn step_output_proof_catches_a_rise_inside_the_step_space() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "else if (nonzero__q & phase_done__q & (up_down",
        "else if (nonzero__q & started__q & (up_down",
    );
}

/// A pulse rises without waiting for the direction setup.
#[test]
fn step_output_proof_catches_a_rise_inside_the_dir_setup() {
    assert_mutation_caught("step_output_t3_p3", "& ~setup_wait__q)", "& 1'b1)");
}

/// Direction turns without waiting for the direction hold after a fall.
#[test]
fn step_output_proof_catches_a_turn_inside_the_dir_hold() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "(dir_done__q | timing_setup__q)",
        "(started__q | timing_setup__q)",
    );
}

/// A forward request lost when a forward step leaves at the same edge.
#[test]
fn step_output_proof_catches_a_request_lost_under_an_emitted_step() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "(request & dir) begin\n                    change = zero_p;",
        "(request & dir) begin\n                    change = minus_one_p;",
    );
}

/// Up/down: a backward step counted out but never pulsed on `out_b`.
#[test]
fn step_output_proof_catches_a_lost_up_down_backward_step() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "b_reg__d = ~positive;",
        "b_reg__d = 1'b0;",
    );
}

/// Quadrature: a backward step that leaves B unchanged (no move, or a
/// forward one).
#[test]
fn step_output_proof_catches_a_wrong_quadrature_backward_move() {
    assert_mutation_caught(
        "step_output_t3_p3",
        "b_reg__d = ~a_reg__q;",
        "b_reg__d = a_reg__q;",
    );
}

/// A forward request at the most positive count is not dropped: the count
/// wraps to the most negative and invents backward steps.
#[test]
fn step_output_proof_catches_an_overrun_not_dropped() {
    assert_mutation_caught("step_output_t3_p3", "(dir & at_max__q)", "(dir & 1'b0)");
}

/// `busy` ignores the direction interval, so a mode change may cut a
/// direction hold or setup short.
#[test]
fn step_output_proof_catches_busy_low_during_a_dir_interval() {
    assert_mutation_caught("step_output_t3_p3", " | ~dir_done__q;", ";");
}
