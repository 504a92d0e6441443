//! Tests of `motion_hdl::host::servo` (`src/host/servo.rs`).

use motion_hdl::host::servo::*;
use motion_hdl::sim::plant::ServoMotor;

/// Loop and motor at a 1 ms period on a commanded trajectory (position
/// and velocity per period); returns the motor and the error figures.
fn run(
    gains: ServoGains,
    trajectory: &[(f64, f64)],
    settle: usize,
) -> (ServoMotor, FollowingError, u64) {
    let period = 0.001;
    let mut servo = PositionLoop::new(gains, DriveScale::default(), period).unwrap();
    let mut motor = ServoMotor::default();
    let scale = DriveScale::default();
    let mut figures = FollowingError::default();
    let mut saturated = 0;
    let last = *trajectory.last().unwrap();
    for &(position, velocity) in trajectory
        .iter()
        .chain(std::iter::repeat_n(&(last.0, 0.0), settle))
    {
        let out = servo.step(position, velocity, motor.counts());
        figures.add(out.following_error);
        saturated += out.saturated as u64;
        motor.advance(scale.volts(out.code), period);
    }
    (motor, figures, saturated)
}

/// A move of 20 000 counts at 40 000 counts/s with 400 000 counts/s²
/// ramps, sampled every ms.
fn trapezoid() -> Vec<(f64, f64)> {
    let (distance, v, a): (f64, f64, f64) = (20_000.0, 40_000.0, 400_000.0);
    let ramp = v / a;
    let cruise = (distance - v * ramp) / v;
    let total = 2.0 * ramp + cruise;
    (1..=(total * 1000.0).ceil() as usize)
        .map(|i| {
            let t = (i as f64 / 1000.0).min(total);
            if t < ramp {
                (0.5 * a * t * t, a * t)
            } else if t < ramp + cruise {
                (0.5 * v * ramp + v * (t - ramp), v)
            } else {
                let d = total - t;
                (distance - 0.5 * a * d * d, a * d)
            }
        })
        .collect()
}

#[test]
fn a_trapezoid_move_ends_within_a_count_of_its_target() {
    let (motor, figures, saturated) = run(ServoGains::default(), &trapezoid(), 300);
    assert!(
        (motor.counts() - 20_000).abs() <= 1,
        "ended at {}",
        motor.counts()
    );
    assert!(
        motor.velocity().abs() < 50.0,
        "still moving at {} counts/s",
        motor.velocity()
    );
    assert_eq!(saturated, 0, "the move is within the DAC's range");
    println!(
        "following error: peak {:.1}, RMS {:.2} counts",
        figures.max, figures.rms
    );
    assert!(
        figures.max < 200.0,
        "following error peaks at {:.1} counts",
        figures.max
    );
}

#[test]
fn feed_forward_cuts_the_following_error_of_a_move() {
    let with = run(ServoGains::default(), &trapezoid(), 0).1;
    let without = run(
        ServoGains {
            kff: 0.0,
            ..ServoGains::default()
        },
        &trapezoid(),
        0,
    )
    .1;
    println!(
        "peak following error: {:.1} counts with feed-forward, {:.1} without",
        with.max, without.max
    );
    assert!(
        with.max * 3.0 < without.max,
        "peak with {:.1}, without {:.1} counts",
        with.max,
        without.max
    );
}

#[test]
fn a_large_error_clamps_the_code_and_does_not_wind_up() {
    let scale = DriveScale::default();
    let mut servo = PositionLoop::new(ServoGains::default(), scale, 0.001).unwrap();
    for _ in 0..100 {
        let out = servo.step(1.0e9, 0.0, 0);
        assert_eq!((out.code, out.saturated), (32_767, true));
    }
    // Back at the target: no stored integral pushes on.
    let out = servo.step(0.0, 0.0, 0);
    assert_eq!(out.code, 0, "the integral held while clamped");
    assert_eq!(scale.code(-20.0), (-32_768, true));
    assert_eq!(scale.register_value(-1), 0xffff);
    assert!((scale.volts(16_384) - 5.0).abs() < 1e-12);
}

#[test]
fn bad_settings_are_errors_naming_the_setting() {
    let scale = DriveScale::default();
    let bad = |gains: ServoGains, scale: DriveScale, period: f64| {
        PositionLoop::new(gains, scale, period)
            .unwrap_err()
            .to_string()
    };
    let g = ServoGains::default();
    assert_eq!(
        bad(ServoGains { kp: -1.0, ..g }, scale, 0.001),
        "servo setting `kp` = -1: 0 or more (1/s)"
    );
    assert_eq!(
        bad(ServoGains { ki: f64::NAN, ..g }, scale, 0.001),
        "servo setting `ki` = NaN: 0 or more (1/s²)"
    );
    assert_eq!(
        bad(g, scale, 0.0),
        "servo setting `period_s` = 0: above 0 (s)"
    );
    assert_eq!(
        bad(
            g,
            DriveScale {
                code_bits: 40,
                ..scale
            },
            0.001
        ),
        "servo setting `code_bits` = 40: 2 to 32"
    );
    assert_eq!(
        bad(g, DriveScale { counts_per_s_per_volt: 0.0, ..scale }, 0.001),
        "servo setting `counts_per_s_per_volt` = 0: not 0 (counts/s per V; negative for a reversed drive)"
    );
}
