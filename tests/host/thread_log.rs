//! Tests of `motion_hdl::host::thread_log` (`src/host/thread_log.rs`).

use motion_hdl::host::thread_log::*;

#[test]
fn samples_each_count_after_the_step_latency_and_finds_the_index() {
    let mut log = GearLog::new(2);
    for clock in 0..1000u64 {
        let count = (clock / 100) as i64;
        // The axis steps 40 clocks after each count (as the gearbox would).
        let position = (clock.saturating_sub(40) / 100) as i64;
        log.clock(clock, count, count % 4 == 0, position);
    }
    assert_eq!(log.samples.len(), 9);
    assert!(log.samples.iter().all(|s| s.position == s.count));
    assert_eq!(log.samples[0].clock, 100);
    assert_eq!(log.index_before(450), Some(4));
    // Counts 0 (high from the first clock), 4 and 8.
    assert_eq!(log.indexes.len(), 3);
}

#[test]
fn lead_error_is_half_the_spread_and_phase_spread_the_passes_difference() {
    let samples: Vec<CountSample> = (0..100)
        .map(|c| CountSample {
            clock: c as u64,
            count: c,
            // 0.25 step per count, floored: a sawtooth of one step.
            position: c / 4,
        })
        .collect();
    let a = PassErrors::measure(&samples, (0, 99), 0.0, 1.0, 0.25, 0);
    assert_eq!(
        ThreadFigures::of(std::slice::from_ref(&a))
            .unwrap()
            .lead_error,
        0.375
    );
    // The same pass a step later: phase spread 1, lead error 0.875.
    let b = PassErrors::measure(&samples, (0, 99), -1.0, 1.0, 0.25, 0);
    let f = ThreadFigures::of(&[a, b]).unwrap();
    assert_eq!(
        (f.phase_spread, f.lead_error, f.passes, f.counts),
        (1.0, 0.875, 2, 200)
    );
}
