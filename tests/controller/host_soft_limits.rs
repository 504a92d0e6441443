//! The soft limits from the host: the driver programs the windows, waits
//! for the stop's reach to be measured, and turns a trip into
//! `DriverError::SoftLimit` with the machine stopped inside the window,
//! ready to run the next path; and its refusals.

use motion_hdl::host::{Driver, DriverConfig, DriverError, RtlBus};
use motion_hdl::sim::Backend;

fn config(window: (i32, i32)) -> DriverConfig {
    DriverConfig {
        soft_limits: [Some(window), None, None],
        ..DriverConfig::default()
    }
}

/// X runs toward a window that ends at 300 steps: the run fails naming X
/// and the direction, X stands inside the window, and a path back runs.
#[test]
fn a_path_past_a_window_stops_inside_it_and_the_next_path_runs() {
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    let bus = RtlBus::new(backend, None).unwrap();
    let mut driver = Driver::new(bus, config((-1000, 300))).unwrap();
    driver.set_hold_rate(8192).unwrap();
    let mut counts: Vec<[i32; 3]> = vec![[20, -10, 5]; 40];
    counts.push([0; 3]);
    let stopped = match driver.run(&counts, |_| {}) {
        Err(DriverError::SoftLimit {
            axis,
            negative,
            commanded,
            ..
        }) => {
            assert_eq!((axis, negative), (0, false));
            commanded
        }
        other => panic!("{other:?}"),
    };
    assert!(
        (200..=300).contains(&stopped[0]),
        "X stopped at {}",
        stopped[0]
    );
    // Back in: no trip, and the run ends exactly.
    let back: Vec<[i32; 3]> = vec![[-10, 0, 0], [-10, 0, 0], [0, 0, 0]];
    let report = driver.run(&back, |_| {}).unwrap();
    assert_eq!(report.commanded[0], stopped[0] - 20);
}

#[test]
fn an_empty_window_is_refused_naming_the_axis() {
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    let bus = RtlBus::new(backend, None).unwrap();
    let empty = Driver::new(bus, config((10, -10))).err().unwrap();
    assert!(
        empty
            .to_string()
            .contains("axis 0's soft-limit window 10..-10 is empty"),
        "{empty}"
    );
}
