//! `formal/freq_divider.sv`: the strobe's whole contract.

use crate::support::{assert_mutation_caught, assert_proved};

#[test]
fn freq_divider_4_bit_strobes_are_proved() {
    assert_proved("freq_divider_w4");
}

#[test]
fn freq_divider_exported_32_bit_strobes_are_proved() {
    assert_proved("freq_divider_w32");
}

/// The interval's end compared one count late: every interval one clock long.
#[test]
fn freq_divider_proof_catches_an_interval_one_clock_long() {
    assert_mutation_caught(
        "freq_divider_w4",
        "count__q != latched_divisor__q",
        "count__q != latched_divisor__q + 1",
    );
}
