//! `formal/watchdog.sv`: expiry exactly `timeout` ticks after the last
//! kick, never while kicked in time; `armed` as specified.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn watchdog_4_bit_expiry_is_proved() {
    assert_proved("watchdog_w4");
}

#[test]
fn watchdog_32_bit_expiry_is_proved() {
    assert_proved("watchdog_w32");
}

/// The countdown flags its last tick one tick early: the watchdog expires
/// one tick before the timeout (for T >= 3).
#[test]
fn watchdog_proof_catches_an_expiry_one_tick_early() {
    assert_mutation_caught("watchdog_w4", "left__q == two", "left__q == two + one");
}

/// The expiry takes priority over a kick on its edge: a host kicking
/// exactly in time trips the watchdog.
#[test]
fn watchdog_proof_catches_an_expiry_beating_a_kick_in_time() {
    assert_mutation_caught(
        "watchdog_w4",
        "if (kick) begin",
        "if (kick & ~(tick & armed_reg__q & last__q)) begin",
    );
}

/// A kick with `timeout` = 0 arms the watchdog instead of disarming it.
#[test]
fn watchdog_proof_catches_timeout_0_arming() {
    assert_mutation_caught(
        "watchdog_w4",
        "armed_reg__d = timeout != zero;",
        "armed_reg__d = 1'b1;",
    );
}

/// The counter counts clocks, not ticks: the watchdog expires early when
/// `tick` is slower than the clock.
#[test]
fn watchdog_proof_catches_counting_clocks_instead_of_ticks() {
    assert_mutation_caught(
        "watchdog_w4",
        "else if (tick & armed_reg__q) begin",
        "else if (armed_reg__q) begin",
    );
}
