//! The parallel-machine card end to end (#36): the control DSP, three motor
//! DSPs and six leg plants around the exported `parallel_card`, compiled by
//! Verilator.

use motion_hdl::host::hexapod::card::{
    run_card, CardRun, CardSettings, CartesianMotion, GainSchedule, Helix, MotorDspError,
};
use motion_hdl::host::hexapod::{leg_inertia, Geometry, PlatformInertia};
use motion_hdl::host::ServoGains;

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

/// A wider, higher helix, 4 s: its legs' loads range from 0.8 to 1.4
/// times their load at home.
fn wide_helix() -> Helix {
    Helix {
        radius: 60.0,
        rise: 120.0,
        a_amplitude: 12.0,
        b_amplitude: 9.0,
        seconds: 4.0,
        ..helix()
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

/// The load-scheduled PID against fixed gains on a wide helix, with a
/// heavy platform's sluggish drives (8 ms at home): each leg's load, and
/// so its drive's lag, ranges from 0.8 to 1.4 times its value at home along
/// the path. The scheduled loop's largest following error is at or below
/// the best of five fixed gains (kp 20 to 320 /s, ki = kp² / 7.5, the
/// default's ratio), each with the lag at home in its feed-forward.
#[test]
fn the_scheduled_pid_follows_at_least_as_well_as_the_best_fixed_gain() {
    let run_with = |schedule, kp: f64| {
        let mut settings = CardSettings::default();
        settings.plant.time_constant_s = 0.008;
        settings.motor.time_constant_s = 0.008;
        settings.motor.schedule = schedule;
        settings.motor.gains = ServoGains {
            kp,
            ki: kp * kp / 7.5,
            ..ServoGains::default()
        };
        settings.settle_periods = 50;
        let run = run_card(&wide_helix(), &settings).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((run.underrun, run.skew, run.saturated), (None, 0, 0));
        let max = run.following.iter().map(|f| f.max).fold(0.0, f64::max);
        let rms = run.following.iter().map(|f| f.rms).fold(0.0, f64::max);
        println!(
            "{schedule:?} kp {kp}: following error max {max:.2}, worst leg's RMS {rms:.2} counts"
        );
        max
    };
    let scheduled = run_with(GainSchedule::Load, 40.0);
    let best = [20.0, 40.0, 80.0, 160.0, 320.0]
        .into_iter()
        .map(|kp| run_with(GainSchedule::Fixed, kp))
        .fold(f64::INFINITY, f64::min);
    assert!(
        scheduled <= best,
        "scheduled {scheduled:.2} counts, best fixed {best:.2}"
    );
}

/// The wide helix's loads span what the scheduling test says.
#[test]
fn the_wide_helix_loads_each_leg_from_0_8_to_1_4_times_home() {
    let g = Geometry::default();
    let body = PlatformInertia::default();
    let home = leg_inertia(&g, &g.home, &body).unwrap();
    let (mut lo, mut hi) = (f64::MAX, 0.0f64);
    let h = wide_helix();
    for i in 0..=400 {
        let m = leg_inertia(&g, &h.at(i as f64 * 0.01).pose, &body).unwrap();
        for j in 0..6 {
            lo = lo.min(m[j] / home[j]);
            hi = hi.max(m[j] / home[j]);
        }
    }
    assert!(
        (0.75..0.85).contains(&lo) && (1.35..1.45).contains(&hi),
        "{lo:.3} to {hi:.3}"
    );
}
