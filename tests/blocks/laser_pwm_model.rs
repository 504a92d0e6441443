//! Tests of `motion_hdl::blocks::laser_pwm::model` (`src/blocks/laser_pwm/model.rs`).

use motion_hdl::blocks::laser_pwm::model::*;

#[test]
fn the_dynamic_duty_is_power_times_speed_over_feed() {
    assert_eq!(isqrt(0), 0);
    assert_eq!(isqrt(24), 4);
    assert_eq!(isqrt(25), 5);
    assert_eq!(isqrt((1u64 << 31) - 1), 46340);
    assert_eq!(vector_steps(3, -4), 5);
    // At the feed: the power. Half the feed: half. Above it: the power.
    assert_eq!(dynamic_duty(30, 40, 1000, 800, FACTOR_ONE), 1000);
    assert_eq!(dynamic_duty(15, 20, 1000, 800, FACTOR_ONE), 500);
    assert_eq!(dynamic_duty(60, 80, 1000, 800, FACTOR_ONE), 1000);
    // The hold's factor scales the speed; standing still or no feed: off.
    assert_eq!(dynamic_duty(30, 40, 1000, 800, FACTOR_ONE / 4), 250);
    assert_eq!(dynamic_duty(0, 0, 1000, 800, FACTOR_ONE), 0);
    assert_eq!(dynamic_duty(30, 40, 1000, 0, FACTOR_ONE), 0);
    // The extremes of the widths (C = 16, R = 16, F = 24).
    assert_eq!(dynamic_duty(-32768, -32768, 65535, 1, 131071), 65535);
    // The feed's 1/16 step: sqrt(2) steps a period at a feed of 24/16.
    assert_eq!(dynamic_duty(1, 1, 1000, 24, FACTOR_ONE), 917);
}

#[test]
fn a_pulse_never_restarts_in_its_pwm_period_and_kill_is_at_once() {
    let mut m = LaserPwmModel::new(16, 16, 24);
    let mut i = LaserInputs {
        pwm_period: 10,
        power: 3,
        enable: true,
        ..Default::default()
    };
    let highs: Vec<bool> = (0..30).map(|_| m.step(&i).pwm).collect();
    // The duty takes effect at once: edges 1 and 2 (counter 1, 2), then
    // 3 of every 10 clocks from the wrap at edge 10.
    let expected: Vec<bool> = (1..=30).map(|e| e % 10 < 3).collect();
    assert_eq!(highs, expected);
    // A larger duty while a pulse is under way lengthens it (edges 30
    // to 35); once it has ended (edge 36), a larger one waits for the
    // next wrap (edge 40).
    i.power = 6;
    let under_way: Vec<bool> = (31..=36).map(|_| m.step(&i).pwm).collect();
    i.power = 8;
    let ended: Vec<bool> = (37..=41).map(|_| m.step(&i).pwm).collect();
    assert_eq!(under_way, [true, true, true, true, true, false]);
    assert_eq!(ended, [false, false, false, true, true]);
    i.kill = true;
    assert!(!m.step(&i).pwm);
    assert_eq!(m.outputs(&i).duty, 0);
}
