//! Tests of `motion_hdl::host::laser_log` (`src/host/laser_log.rs`).

use motion_hdl::host::laser_log::*;

/// One step a clock along X, the laser high every other clock; each
/// period two steps of 0.01 mm each.
fn straight(steps: i64) -> (LaserLog, Vec<(u64, f64)>) {
    let mut log = LaserLog::new();
    for k in 1..=steps {
        log.clock(k % 2 == 0, 1);
    }
    let periods = (1..=steps as u64 / 2).map(|p| (2 * p, 0.02)).collect();
    (log, periods)
}

#[test]
fn windows_take_the_high_clocks_between_their_periods_steps() {
    let (log, periods) = straight(1000);
    let windows = burn_energy(&log, 0, &periods, 1.0);
    // Half the clocks high, one clock per 0.01 mm: 50 per mm.
    assert_eq!(
        windows.len(),
        19,
        "9.8 mm inside the trims, in 0.5 mm windows"
    );
    for w in &windows {
        assert!((w.energy - 50.0).abs() < 1e-6, "{w:?}");
        assert!(w.at_mm > TRIM_MM && w.at_mm < 10.0 - TRIM_MM);
    }
}

#[test]
fn a_burn_shorter_than_its_trims_and_a_window_has_none() {
    let (log, periods) = straight(60);
    assert!(burn_energy(&log, 0, &periods, 1.0).is_empty());
}

#[test]
fn the_deviation_is_against_the_programmed_value() {
    let burn = BurnEnergy {
        line: 1,
        dynamic: true,
        programmed: 2.0,
        length_mm: 1.0,
        feed_steps: 10.0,
        windows: vec![
            EnergyWindow {
                at_mm: 0.0,
                energy: 1.9,
            },
            EnergyWindow {
                at_mm: 1.0,
                energy: 2.05,
            },
        ],
    };
    assert_eq!(burn.range(), Some((1.9, 2.05)));
    assert!((burn.worst_deviation().unwrap() - 0.05).abs() < 1e-12);
}
