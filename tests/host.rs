//! The host side: planner and coarse interpolator against closed-form
//! cases and random paths, the path file parser's errors, and the driver
//! running paths end to end through the RTL controller.

use motion_hdl::host::{
    interpolate, plan, ControllerBus, Driver, DriverConfig, ModelBus, Path, PathError, RecordingBus, RtlBus,
};
use motion_hdl::host::planner::junction_speed;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A closed polygon of `sides` segments around (0, 0), radius `r` steps,
/// with a Z wobble, starting and ending at the origin.
fn polygon(sides: usize, r: f64) -> Vec<[i64; 3]> {
    let mut ends: Vec<[i64; 3]> = (1..sides)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / sides as f64;
            [
                (r * a.cos() - r).round() as i64,
                (r * a.sin()).round() as i64,
                ((i % 3) as i64 - 1) * 7,
            ]
        })
        .collect();
    ends.push([0, 0, 0]);
    ends
}

#[test]
fn a_closed_50_segment_polygon_through_the_rtl_ends_exactly_at_its_start() {
    // One tick per clock at a nominal 50 MHz, 200-tick (4 us) periods; the
    // feed (10^7 steps/s, 40 steps per period) stays below the output
    // stage's limit of 50 steps per period (2 + 2 clocks per step).
    let config = DriverConfig::default();
    let period = config.period_ticks as f64 * config.tick_divisor as f64 / 50e6;
    let path = Path::new([0, 0, 0], &polygon(50, 400.0), 1e7, 2e10, 2.0, period).unwrap();
    let segments = plan(&path);
    let interpolation = interpolate(path.start, &segments, path.period);
    let mut driver = Driver::new(RtlBus::new().unwrap(), config).unwrap();
    let report = driver.run(&interpolation.counts, |_| {}).unwrap();
    assert_eq!(report.underruns, 0, "{report:?}");
    assert_eq!(report.commanded, [0, 0, 0], "{report:?}");
    assert_eq!(report.actual, [0, 0, 0], "{report:?}");
    let travelled: u64 = driver.bus().encoders().iter().map(|e| e.total).sum();
    let expected: u64 = interpolation
        .counts
        .iter()
        .map(|c| c.iter().map(|n| n.unsigned_abs() as u64).sum::<u64>())
        .sum();
    assert_eq!(travelled, expected, "every step of every period left the pins");
    assert!(expected > 2500 && report.periods > 100, "{expected} steps, {} periods", report.periods);
    println!("{report:?}");
}
