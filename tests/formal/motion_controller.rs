//! `formal/motion_controller_*.sv`: the motion controller's limit and
//! E-stop rules, proved on its sub-blocks (the limit gate, the axis, the
//! machine I/O), and a deliberate bug each proof must catch.

use motion_hdl::blocks::motion_controller::latency;
use motion_hdl::tools::formal::formal_dir;

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn motion_controller_limit_gate_is_proved() {
    assert_proved("motion_controller_axis_io");
}

#[test]
fn motion_controller_axis_step_path_is_proved() {
    assert_proved("motion_controller_axis");
}

#[test]
fn motion_controller_axis_stage_premise_is_proved() {
    assert_proved("motion_controller_stage");
}

#[test]
fn motion_controller_estop_conditioning_and_latch_are_proved() {
    assert_proved("motion_controller_machine_io");
}

/// LIMIT_ENABLE read without undoing its storage XOR: its reset value (1)
/// is lost, so limits are ignored from power-up and after every reset.
#[test]
fn motion_controller_proof_catches_limits_disabled_at_reset() {
    assert_mutation_caught(
        "motion_controller_axis_io",
        "io_config = io_config_x__q ^ config_reset;",
        "io_config = io_config_x__q;",
    );
}

/// The cut forgets the request register: a forward step already requested
/// when the positive limit closes still reaches the stage.
#[test]
fn motion_controller_proof_catches_a_cut_that_misses_the_request() {
    assert_mutation_caught(
        "motion_controller_axis_io",
        "pending_forward | (request & request_forward) | (pulse & pulse_forward)",
        "pending_forward | (pulse & pulse_forward)",
    );
}

/// The abort no longer gates the request register: a step offered in the
/// abort's clock enters the output stage after it.
#[test]
fn motion_controller_proof_catches_a_request_after_an_abort() {
    assert_mutation_caught(
        "motion_controller_axis",
        "request__d = candidate & ~abort & ~candidate_blocked;",
        "request__d = candidate & ~candidate_blocked;",
    );
}

/// The limit gates the step one clock late: not at the request register but
/// only in the stage, so a step toward a limit blocked when it was offered
/// enters the stage.
#[test]
fn motion_controller_proof_catches_a_limit_gate_one_clock_late() {
    assert_mutation_caught(
        "motion_controller_axis",
        "request__d = candidate & ~abort & ~candidate_blocked;",
        "request__d = candidate & ~abort;",
    );
}

/// The abort no longer flushes the output stage: steps pending at the abort
/// still leave.
#[test]
fn motion_controller_proof_catches_an_abort_that_does_not_flush() {
    assert_mutation_caught(
        "motion_controller_axis",
        "stage__flush = abort | io__cut;",
        "stage__flush = io__cut;",
    );
}

/// A flush on a clock with a new request keeps the pending count (the
/// request wins): steps pending at an abort or a limit cut still leave.
#[test]
fn motion_controller_proof_catches_a_stage_flush_lost_to_a_request() {
    assert_mutation_caught(
        "motion_controller_stage",
        "if (flush) begin",
        "if (flush & ~step) begin",
    );
}

/// The E-stop latch set by the conditioned level's rise, not the level: a
/// STATUS.ESTOP clear while the E-stop is still active releases it.
#[test]
fn motion_controller_proof_catches_an_estop_latch_released_while_active() {
    assert_mutation_caught(
        "motion_controller_machine_io",
        "if (estop_in__active != zero1) begin",
        "if (estop_in__rise != zero1) begin",
    );
}

/// The E-stop filtered one sample longer than INPUT_FILTER.LENGTH says:
/// one clock over the stated latency.
#[test]
fn motion_controller_proof_catches_an_estop_filter_one_sample_long() {
    assert_mutation_caught(
        "motion_controller_machine_io",
        "estop_in__length = filter[(32'h0)+:(4)];",
        "estop_in__length = filter[(32'h0)+:(4)] + 4'h1;",
    );
}

/// The numbers the property files and the datasheet's composition use are
/// the datasheet's own `latency` constants.
#[test]
fn motion_controller_proofs_use_the_stated_latencies() {
    let text = std::fs::read_to_string(formal_dir().join("motion_controller_machine_io.sv"))
        .expect("formal/motion_controller_machine_io.sv");
    let switch: u64 = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("localparam F_SWITCH = "))
        .and_then(|v| v.trim_end_matches(';').trim().parse().ok())
        .expect("localparam F_SWITCH = N; in formal/motion_controller_machine_io.sv");
    assert_eq!(
        switch,
        latency::switch(4, 0),
        "F_SWITCH is latency::switch at the reset INPUT_FILTER"
    );
    // E-stop, from the filtered level set at s: the latch at s + 1 (this
    // proof), the controller's abort_hold register at s + 2, the last step
    // at s + 3 (the axis proof: none after the edge that follows an abort
    // clock).
    assert_eq!(latency::ABORT_ALL_AXES, 1 + 1 + 1);
    // A limit level set at s blocks from clock s + 1 on: the step decided in
    // that clock still leaves (the stage decides from its registers), none
    // after it.
    assert_eq!(latency::LIMIT_OWN_AXIS, 1);
}

#[test]
fn motion_controller_hold_ramp_gate_and_ramp_are_proved() {
    assert_proved("motion_controller_hold_ramp");
}

/// The gate passes a tick in a clock without one: a hold would create
/// steps.
#[test]
fn hold_ramp_proof_catches_a_gate_that_creates_a_tick() {
    assert_mutation_caught(
        "motion_controller_hold_ramp",
        "tick_out = tick & (((fraction__q) & 17'h1ffff) >= deficit__q);",
        "tick_out = tick | (((fraction__q) & 17'h1ffff) >= deficit__q);",
    );
}

/// The fraction of a gated tick is dropped instead of carried: a hold
/// would lose steps' time (the path would end late, not where it should).
#[test]
fn hold_ramp_proof_catches_a_lost_fraction() {
    assert_mutation_caught(
        "motion_controller_hold_ramp",
        "fraction__d = fraction__q - deficit__q[(32'h0)+:(16)];",
        "fraction__d = (fraction__q >= deficit__q) ? 16'h0 : fraction__q;",
    );
}

/// The factor falls by twice RATE per tick: a ramp steeper than the
/// programmed deceleration.
#[test]
fn hold_ramp_proof_catches_a_ramp_too_steep() {
    assert_mutation_caught(
        "motion_controller_hold_ramp",
        "deficit__d = sum;",
        "deficit__d = (sum + rate17 > unity) ? unity : sum + rate17;",
    );
}
