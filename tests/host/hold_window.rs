//! Tests of `motion_hdl::host::hold_window` (`src/host/hold_window.rs`).

use motion_hdl::host::hold_window::*;

/// The square's stop (40 mm/s at 1000 mm/s^2: 40 ms) at 2 MHz and
/// 200 us periods (400 clocks): the smallest divisor that fits, 2,
/// would take RATE 1, a 65.5 ms stop; divisor 16 takes RATE 13, 40.3
/// ms, never shorter than asked.
#[test]
fn the_tick_whose_rate_stops_closest_is_chosen() {
    let (d, ticks) = hold_tick_settings(200e-6, 2e6, 0.04, 1).unwrap();
    assert_eq!((d, ticks), (16, 25));
    let tick_hz = 2e6 / d as f64;
    let rate = rate_for_stop(0.04, tick_hz);
    assert_eq!(rate, 13);
    let stop = stop_time_s(rate, tick_hz);
    assert!((0.04..0.0405).contains(&stop), "{stop}");
    // An axis needing 100 ticks a period keeps the divisor at 4 or
    // less: 2 and 4 both stop in over 40 ms, 4 closer (RATE 3).
    assert_eq!(
        hold_tick_settings(200e-6, 2e6, 0.04, 100).unwrap(),
        (4, 100)
    );
    // No stop to make: the plain settings.
    assert_eq!(hold_tick_settings(1e-3, 1e6, 0.0, 1).unwrap(), (1, 1000));
}
