//! The parallel-machine card end to end (#36): the control DSP, three motor
//! DSPs and six leg plants around the exported `parallel_card`, compiled by
//! Verilator.

use motion_hdl::host::hexapod::card::{run_card, CardRun, CardSettings, Helix, MotorDspError};
use motion_hdl::host::hexapod::Geometry;

fn helix() -> Helix {
    Helix {
        start: Geometry::default().home,
        radius: 20.0,
        turns: 1.0,
        rise: 30.0,
        a_amplitude: 5.0,
        b_amplitude: 5.0,
        seconds: 2.0,
    }
}

fn report(run: &CardRun) {
    for (j, f) in run.following.iter().enumerate() {
        println!(
            "leg {j}: following error max {:.2} rms {:.2} counts; end {} of {:.2}",
            f.max, f.rms, run.final_counts[j], run.final_targets[j]
        );
    }
    println!(
        "{} periods, {} clocks, skew {}, releases {}, saturated {}",
        run.periods, run.clocks, run.skew, run.releases_seen, run.saturated
    );
}

/// A helix with a roll and a pitch ends within one encoder count on every
/// leg, with no underrun and every slave released on the same clock.
#[test]
fn a_helix_with_roll_and_pitch_ends_within_a_count_on_every_leg() {
    let run = run_card(&helix(), &CardSettings::default()).unwrap_or_else(|e| panic!("{e}"));
    report(&run);
    assert_eq!(run.underrun, None);
    assert_eq!(run.motor_error, None);
    assert_eq!(run.skew, 0, "every slave's data_ready rises on one clock");
    assert_eq!(run.releases_seen, run.periods);
    for j in 0..6 {
        assert!(
            (run.final_counts[j] as f64 - run.final_targets[j]).abs() <= 1.0,
            "leg {j}: {} counts for {:.2}",
            run.final_counts[j],
            run.final_targets[j]
        );
    }
}

/// A slave left without its point at a tick stops every joint, and the
/// control DSP reads which slave and which period.
#[test]
fn an_underrun_names_its_slave_and_period_and_stops_every_joint() {
    let settings = CardSettings {
        drop_point: Some((700, 1)),
        settle_periods: 20,
        ..CardSettings::default()
    };
    let run = run_card(&helix(), &settings).unwrap_or_else(|e| panic!("{e}"));
    let underrun = run.underrun.expect("the card flags the underrun");
    assert_eq!((underrun.slave_list(), underrun.period), (vec![1], 700));
    // Slave 1's DSP reads point 701 where 700 was due, and stops.
    assert_eq!(
        run.motor_error,
        Some(MotorDspError::Sequence {
            slave: 1,
            expected: 700,
            got: 701
        })
    );
    // Every DAC is at 0 V from then on: no leg reaches its end.
    assert!((0..6).all(|j| (run.final_counts[j] as f64 - run.final_targets[j]).abs() > 100.0));
}

/// A motion that leaves the workspace is refused before any clock, naming
/// the period and the limit.
#[test]
fn a_pose_outside_the_workspace_is_refused_before_any_motion() {
    let wide = Helix {
        radius: 150.0,
        ..helix()
    };
    let e = run_card(&wide, &CardSettings::default()).expect_err("X reaches -300 mm");
    let text = e.to_string();
    assert!(text.starts_with("period "), "{text}");
    assert!(
        text.contains(": X -") && text.contains("outside the workspace, -200 to 200"),
        "{text}"
    );
}
