//! Tests of `motion_hdl::sim::plant::spindle_motor` (`src/sim/plant/spindle_motor.rs`).

use motion_hdl::sim::plant::*;

#[test]
fn reaches_its_speed_counts_up_on_m3_and_marks_each_turn() {
    let mut s = SpindleMotor::new(400);
    s.ripple = 0.0;
    s.command(600.0);
    let dt = 1e-5;
    for _ in 0..100_000 {
        s.advance(dt);
    }
    // After 1 s (20 time constants) at speed: 10 rev/s.
    assert!((s.speed_rpm() - 600.0).abs() < 1e-3);
    let (start, mut indexes) = (s.count(), 0);
    let mut was = s.pins().2;
    for _ in 0..100_000 {
        s.advance(dt);
        let index = s.pins().2;
        indexes += (index && !was) as u32;
        was = index;
    }
    assert!(((s.count() - start) as f64 - 4000.0).abs() <= 1.0);
    assert_eq!(indexes, 10);
    s.command(-600.0);
    for _ in 0..100_000 {
        s.advance(dt);
    }
    assert!(s.speed_rpm() < -599.0);
}

#[test]
fn ripples_and_dips_under_load() {
    let mut s = SpindleMotor::new(4096);
    s.command(1000.0);
    let (mut low, mut high) = (f64::MAX, f64::MIN);
    for n in 0..200_000 {
        s.advance(1e-5);
        if n > 100_000 {
            low = low.min(s.speed_rpm());
            high = high.max(s.speed_rpm());
        }
    }
    assert!(low < 905.0 && low > 895.0 && high > 1095.0 && high < 1105.0);
    s.ripple = 0.0;
    s.set_load(true);
    for _ in 0..100_000 {
        s.advance(1e-5);
    }
    assert!((s.speed_rpm() - 950.0).abs() < 0.1);
}
