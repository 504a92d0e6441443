//! The host side: planner and coarse interpolator against closed-form
//! cases and random paths, the path file parser's errors, the driver
//! running paths end to end through the RTL controller, and aborts (E-stop,
//! limit switch, drive alarm) reported by their cause.

use motion_hdl::blocks::motion_controller::io_model::MachinePins;
use motion_hdl::blocks::motion_controller::registers::{register_map, StopCause};
use motion_hdl::host::driver::ProbeEdge;
use motion_hdl::host::planner::junction_speed;
use motion_hdl::host::{
    interpolate, plan, ControllerBus, Driver, DriverConfig, DriverError, ModelBus, Path, PathError,
    RecordingBus, RtlBus,
};
use motion_hdl::sim::Backend;
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
    let segments = plan(&path).unwrap();
    let interpolation = interpolate(path.start, &segments, path.period);
    // The exported Verilog, compiled (25 s on rust-hdl, whose RTL the
    // driver meets in `an_e_stop_in_the_middle_of_a_move...`).
    let bus = RtlBus::new(Backend::from_env_or(Backend::Verilator).unwrap(), None).unwrap();
    let mut driver = Driver::new(bus, config).unwrap();
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
    assert_eq!(
        travelled, expected,
        "every step of every period left the pins"
    );
    assert!(
        expected > 2500 && report.periods > 100,
        "{expected} steps, {} periods",
        report.periods
    );
    println!("{report:?}");
}

const PERIOD: f64 = 1e-3;

fn single(end: [i64; 3], feed: f64, accel: f64) -> Path {
    Path::new([0, 0, 0], &[end], feed, accel, 0.0, PERIOD).unwrap()
}

#[test]
fn a_long_straight_move_accelerates_cruises_and_decelerates() {
    // 10,000 steps at 1,000 steps/s with 2,000 steps/s^2: 0.5 s and 250
    // steps to reach the feed, the same to stop, 9,500 steps of cruise.
    let segments = plan(&single([10_000, 0, 0], 1000.0, 2000.0)).unwrap();
    let s = segments[0];
    assert_eq!((s.v_entry, s.v_cruise, s.v_exit), (0.0, 1000.0, 0.0));
    assert!((s.duration() - (0.5 + 9.5 + 0.5)).abs() < 1e-9);
    let (d, v) = s.state_at(0.25);
    assert!((d - 62.5).abs() < 1e-9 && (v - 500.0).abs() < 1e-9);
    let (d, v) = s.state_at(10.25);
    assert!((d - (10_000.0 - 62.5)).abs() < 1e-6 && (v - 500.0).abs() < 1e-9);
    let i = interpolate([0, 0, 0], &segments, PERIOD);
    assert_eq!(i.counts.len(), 10_500);
    assert_eq!(*i.positions.last().unwrap(), [10_000, 0, 0]);
}

#[test]
fn a_very_short_move_is_a_triangle() {
    // 100 steps at 2,000 steps/s^2 never reaches a 1,000 steps/s feed:
    // peak sqrt(a L) = 447.2 steps/s at the middle.
    let s = plan(&single([0, 100, 0], 1000.0, 2000.0)).unwrap()[0];
    assert!((s.v_cruise - (2000.0f64 * 100.0).sqrt()).abs() < 1e-9);
    assert!((s.duration() - 2.0 * (100.0f64 / 2000.0).sqrt()).abs() < 1e-9);
}

#[test]
fn a_right_angle_corner_is_taken_at_the_contour_error_speed() {
    let path = Path::new(
        [0, 0, 0],
        &[[5000, 0, 0], [5000, 5000, 0]],
        1000.0,
        2000.0,
        1.0,
        PERIOD,
    )
    .unwrap();
    let segments = plan(&path).unwrap();
    // sin(90/2) = 0.7071: v = sqrt(a e s / (1 - s)) = sqrt(2000 * 2.414).
    let expected = (2000.0 * 1.0 * 0.5f64.sqrt() / (1.0 - 0.5f64.sqrt())).sqrt();
    assert!(
        (segments[0].v_exit - expected).abs() < 1e-6,
        "{}",
        segments[0].v_exit
    );
    assert_eq!(segments[0].v_exit, segments[1].v_entry);
    assert!(
        (junction_speed([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2000.0, 1.0, 1e9) - expected).abs()
            < 1e-9
    );
}

#[test]
fn a_reversal_stops_and_a_straight_continuation_does_not() {
    let reversal = Path::new(
        [0, 0, 0],
        &[[3000, 0, 0], [0, 0, 0]],
        1000.0,
        2000.0,
        5.0,
        PERIOD,
    )
    .unwrap();
    assert_eq!(plan(&reversal).unwrap()[0].v_exit, 0.0);
    let straight = Path::new(
        [0, 0, 0],
        &[[3000, 0, 0], [6000, 0, 0]],
        1000.0,
        2000.0,
        5.0,
        PERIOD,
    )
    .unwrap();
    assert_eq!(plan(&straight).unwrap()[0].v_exit, 1000.0);
    let i = interpolate([0, 0, 0], &plan(&reversal).unwrap(), PERIOD);
    assert_eq!(*i.positions.last().unwrap(), [0, 0, 0]);
    assert_eq!(i.positions.iter().map(|p| p[0]).max(), Some(3000));
}

/// Random paths: the end is exact, the speed never exceeds the feed, the
/// speed changes by at most accel * T per period, every period's position
/// is within one step of the planned continuous position (no drift), and
/// no segment is entered faster than it can be left.
#[test]
fn random_paths_end_exactly_within_their_limits_without_drift() {
    let mut rng = StdRng::seed_from_u64(0x9a7);
    for case in 0..200 {
        let n = rng.gen_range(1..12);
        let ends: Vec<[i64; 3]> = (0..n)
            .map(|_| {
                [
                    rng.gen_range(-3000..3000),
                    rng.gen_range(-3000..3000),
                    rng.gen_range(-300..300),
                ]
            })
            .collect();
        let feed = rng.gen_range(100.0..5000.0);
        let accel = rng.gen_range(500.0..50_000.0);
        let path = Path::new(
            [rng.gen_range(-50..50), 0, 0],
            &ends,
            feed,
            accel,
            rng.gen_range(0.0..5.0),
            PERIOD,
        )
        .unwrap();
        let segments = plan(&path).unwrap();
        for s in &segments {
            assert!(
                s.v_cruise <= feed * (1.0 + 1e-12),
                "case {case}: cruise above feed"
            );
            assert!(
                s.v_entry.powi(2) <= s.v_exit.powi(2) + 2.0 * accel * s.length + 1e-6,
                "case {case}: cannot stop in time"
            );
            assert!(
                s.v_exit.powi(2) <= s.v_entry.powi(2) + 2.0 * accel * s.length + 1e-6,
                "case {case}: exit unreachable"
            );
        }
        let i = interpolate(path.start, &segments, PERIOD);
        assert_eq!(*i.positions.last().unwrap(), path.end(), "case {case}");
        let mut sum = path.start;
        for c in &i.counts {
            for k in 0..3 {
                sum[k] += c[k] as i64;
            }
        }
        assert_eq!(
            sum,
            path.end(),
            "case {case}: the counts add up to the move"
        );
        let mut previous = 0.0;
        for v in &i.speeds {
            assert!(*v <= feed * (1.0 + 1e-9));
            assert!(
                (v - previous).abs() <= accel * PERIOD * (1.0 + 1e-9) + 1e-9,
                "case {case}: acceleration"
            );
            previous = *v;
        }
        // No drift: each period's position is the floor of the planned one.
        let mut t = 0.0;
        let mut at = 0;
        let mut start_time = 0.0;
        for (k, p) in i.positions.iter().enumerate().take(i.positions.len() - 1) {
            t = (k + 1) as f64 * PERIOD;
            while at < segments.len() && t >= start_time + segments[at].duration() {
                start_time += segments[at].duration();
                at += 1;
            }
            if at == segments.len() {
                break;
            }
            let s = &segments[at];
            let (d, _) = s.state_at(t - start_time);
            for axis in 0..3 {
                let exact =
                    s.start[axis] as f64 + (s.end[axis] - s.start[axis]) as f64 * d / s.length;
                assert!(
                    (p[axis] as f64 - exact).abs() < 1.0 + 1e-6,
                    "case {case} period {k}: drift"
                );
            }
        }
        let _ = t;
    }
}

#[test]
fn path_files_parse_and_bad_ones_name_the_line_and_problem() {
    let text = "# demo\nunits mm\nsteps_per_mm 100 100 400\nfeed 10\naccel 100\ncontour_error 0.01\nperiod_us 500\nline 1 0 0\nline 1 2 0.5\n";
    let path = Path::parse(text).unwrap();
    assert_eq!(path.end(), [100, 200, 200]);
    // Planned in mm: Z's 400 steps/mm do not make it a faster axis.
    assert_eq!((path.feed, path.accel, path.period), (10.0, 100.0, 5e-4));
    assert_eq!(path.steps_per_unit, [100.0, 100.0, 400.0]);
    for (bad, expected) in [
        (
            "feed 10\naccel 1\nline 1 2\n",
            "line 3: `line` takes 3 number(s), found 2",
        ),
        ("feed x\n", "line 1: `x` is not a number"),
        (
            "feed 10\naccel 1\nline 1 2 3\nfeed 5\n",
            "line 4: `feed` must come before the first `line`",
        ),
        ("spin 3\n", "line 1: unknown statement `spin`"),
        (
            "units mm\nfeed 1\naccel 1\nline 1 1 1\n",
            "units mm needs steps_per_mm",
        ),
        ("feed 10\naccel 1\n", "the path has no `line`"),
        ("accel 1\nline 1 1 1\n", "missing `feed`"),
        (
            "feed -3\naccel 1\nline 1 1 1\n",
            "feed must be a positive number, not -3",
        ),
        ("units inch\n", "line 1: unknown unit `inch` (mm or steps)"),
    ] {
        let error: PathError = Path::parse(bad).unwrap_err();
        assert_eq!(error.to_string(), expected, "{bad:?}");
    }
}

/// The driver refuses work the hardware cannot do, naming the problem,
/// and the recording bus logs the register writes by name.
#[test]
fn the_driver_names_bad_settings_and_the_recorder_logs_writes() {
    let bad = DriverConfig {
        period_ticks: 70_000,
        ..Default::default()
    };
    let error = Driver::new(ModelBus::new(), bad).err().unwrap();
    assert_eq!(
        error.to_string(),
        "invalid configuration: period_ticks 70000 is outside 1..=65535"
    );
    let map = motion_hdl::blocks::motion_controller::registers::register_map(
        3,
        4,
        motion_hdl::blocks::motion_controller::registers::BuildOptions::MOTION_CONTROLLER,
    )
    .unwrap();
    let mut driver = Driver::new(
        RecordingBus::new(ModelBus::new(), &map),
        DriverConfig::default(),
    )
    .unwrap();
    let error = driver.run(&[[0, 101, 0]], |_| {}).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("axis 1: 101 steps exceed the limit of 50"),
        "{error}"
    );
    // A path that would leave the position counters' range
    // (CONFIG.POSITION_BITS) is refused before anything is queued.
    let far = vec![[50, 0, 0]; 167_773];
    let error = driver.run(&far, |_| {}).unwrap_err();
    assert!(
        matches!(error, DriverError::PositionOutOfRange { .. }),
        "{error}"
    );
    assert_eq!(
        error.to_string(),
        "period 167772, axis 0: the commanded position would reach 8388650 steps, beyond the controller's range of +-8388607 (CONFIG.POSITION_BITS = 24)"
    );
    assert!(!driver.bus().log.contains("FIFO_WRITE"), "nothing queued");
    let report = driver.run(&[[3, -2, 1], [0, 0, 0]], |_| {}).unwrap();
    assert_eq!(report.commanded, [3, -2, 1]);
    assert_eq!(report.underruns, 0);
    let log = &driver.bus().log;
    assert!(log.contains("PERIOD_TICKS <- 0x000000c8"), "{log}");
    assert!(log.contains("FIFO_WRITE[1] <- 0xfffffffe"), "{log}");
    assert!(log.contains("CONTROL <- 0x00000001"), "{log}");
    // Every drive enabled, limits and alarms kept enabled.
    assert!(log.contains("IO_CONFIG[2] <- 0x0000000b"), "{log}");
}

/// Writes `fields` of register `name` (index `index`) through the map.
fn write_fields(bus: &mut impl ControllerBus, name: &str, index: u32, fields: &[(&str, u64)]) {
    let map = register_map(
        3,
        4,
        motion_hdl::blocks::motion_controller::registers::BuildOptions::MOTION_CONTROLLER,
    )
    .unwrap();
    let register = map.register(name).unwrap();
    bus.write(
        register.address_of(index).unwrap(),
        register.pack(fields).unwrap(),
    );
}

/// An E-stop in the middle of a move through the RTL: the run fails naming
/// the E-stop, every step counted left the pins, and the controller refuses
/// the next run, saying why, until the E-stop is released and its latch
/// cleared; then it runs again from where it stopped.
#[test]
fn an_e_stop_in_the_middle_of_a_move_is_reported_by_its_cause() {
    let counts = vec![[20, -10, 5]; 30];
    let mut bus = RtlBus::new(Backend::from_env_or(Backend::RustHdl).unwrap(), None).unwrap();
    // Configuration and the first FIFO fill take about 150 clocks; the
    // 30 periods 6000 more.
    let estop = MachinePins {
        estop: true,
        ..Default::default()
    };
    bus.set_pins_at(2500, estop);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    let error = driver.run(&counts, |_| {}).unwrap_err();
    let message = error.to_string();
    assert!(message.starts_with("motion stopped: E-stop"), "{message}");
    let DriverError::Stopped {
        cause,
        axis,
        commanded,
        ..
    } = error
    else {
        panic!("not a stop: {message}")
    };
    assert_eq!((cause, axis), (StopCause::Estop, None));
    let pins = driver.bus().encoders().map(|e| e.net as i32);
    assert_eq!(
        commanded, pins,
        "the commanded position is the steps at the pins"
    );
    assert!(
        commanded[0] > 0 && commanded[0] < 20 * 30,
        "stopped part way: {commanded:?}"
    );

    // Held: the input is still active.
    let error = driver.run(&[[1, 0, 0]], |_| {}).unwrap_err().to_string();
    assert!(
        error.starts_with("RUN refused: the E-stop input is active"),
        "{error}"
    );
    // Released, but latched until STATUS.ESTOP is cleared.
    driver.bus_mut().set_pins(MachinePins::default());
    driver.bus_mut().wait(20);
    let error = driver.run(&[[1, 0, 0]], |_| {}).unwrap_err().to_string();
    assert!(error.contains("E-stop latched"), "{error}");
    assert!(!error.contains("input is active"), "{error}");
    write_fields(driver.bus_mut(), "STATUS", 0, &[("ESTOP", 1)]);
    write_fields(driver.bus_mut(), "CONTROL", 0, &[("FLUSH", 1)]);
    let report = driver.run(&[[3, 2, 1], [0, 0, 0]], |_| {}).unwrap();
    assert_eq!(
        report.commanded,
        [commanded[0] + 3, commanded[1] + 2, commanded[2] + 1]
    );
    assert_eq!(report.actual, report.commanded);
}

/// A limit switch and a drive alarm (on the model, fast): each stops the
/// move, and the error names the cause and the axis. After the limit, a
/// run toward it is refused until CLEAR_LIMITS; then a move away from the
/// still-active switch runs to its end.
#[test]
fn a_limit_switch_or_a_drive_alarm_is_reported_with_its_axis() {
    // Axis 1 moves toward its negative limit.
    let toward = vec![[0, -10, 0]; 30];
    let mut bus = ModelBus::new();
    let limit = MachinePins {
        limit_neg: 1 << 1,
        ..Default::default()
    };
    bus.set_pins_at(2500, limit);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    let error = driver.run(&toward, |_| {}).unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with("motion stopped: limit switch on axis 1"),
        "{message}"
    );
    assert!(message.contains("negative limit"), "{message}");
    let DriverError::Stopped {
        cause,
        axis,
        commanded,
        ..
    } = error
    else {
        panic!("not a stop: {message}")
    };
    assert_eq!((cause, axis), (StopCause::Limit, Some(1)));
    assert!(commanded[1] < 0 && commanded[1] > -300, "{commanded:?}");

    let error = driver.run(&[[0, 5, 0]], |_| {}).unwrap_err().to_string();
    assert!(
        error.starts_with("RUN refused: axis 1: negative limit"),
        "{error}"
    );
    // Back off: clear the trip, flush, move away (the switch still active).
    write_fields(driver.bus_mut(), "IO_COMMAND", 1, &[("CLEAR_LIMITS", 1)]);
    write_fields(driver.bus_mut(), "CONTROL", 0, &[("FLUSH", 1)]);
    let report = driver
        .run(&[[0, 5, 0], [0, 5, 0], [0, 0, 0]], |_| {})
        .unwrap();
    assert_eq!(report.commanded, [0, commanded[1] + 10, 0]);

    // A drive alarm on axis 2 stops every axis.
    let mut bus = ModelBus::new();
    let alarm = MachinePins {
        drive_alarm: 1 << 2,
        ..Default::default()
    };
    bus.set_pins_at(2500, alarm);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    let error = driver.run(&vec![[10, 10, 0]; 30], |_| {}).unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with("motion stopped: drive alarm on axis 2"),
        "{message}"
    );
    let DriverError::Stopped {
        cause,
        axis,
        commanded,
        ..
    } = error
    else {
        panic!("not a stop: {message}")
    };
    assert_eq!((cause, axis), (StopCause::DriveAlarm, Some(2)));
    assert!(commanded[0] > 0 && commanded[0] < 300, "{commanded:?}");
}

/// The CLI on an abort: `simulate --trip estop@2` stops with the cause and
/// a non-zero exit status; a bad `--trip` is named.
#[test]
fn simulate_reports_an_abort_by_its_cause_and_fails() {
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let dir = tempfile::tempdir().unwrap();
    let run = |trip: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
            .arg("simulate")
            .arg(&square)
            .args(["--backend", "rust-hdl", "--trip", trip, "--out-dir"])
            .arg(dir.path())
            .output()
            .unwrap()
    };
    let out = run("estop@2");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(
        stderr.contains("motion-hdl: motion stopped: E-stop"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let out = run("w-limit-pos@2");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("--trip `w-limit-pos@2`: unknown axis `w`"),
        "{stderr}"
    );
}

/// The CLI: a malformed path file stops with the file, line and problem,
/// and a non-zero exit status; no panic.
#[test]
fn simulate_rejects_a_malformed_path_file_with_a_clear_message() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.path");
    std::fs::write(&file, "feed 10\naccel 1\nline 1 two 3\n").unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
        .arg("simulate")
        .arg(&file)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("bad.path: line 3: `two` is not a number"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// The CLI without Verilator on PATH: `--backend verilator` stops with the
/// install line and a non-zero exit status (no silent fall-back), and an
/// unknown backend is named.
#[test]
fn simulate_names_the_install_line_when_verilator_is_missing() {
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
            .arg("simulate")
            .arg(&square)
            .args(args)
            .env("PATH", "/nonexistent")
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?} succeeded");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let stderr = run(&["--backend", "verilator"]);
    assert!(
        stderr.contains("needs `verilator`") && stderr.contains("apt-get install -y verilator g++"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let stderr = run(&["--backend", "icarus"]);
    assert!(
        stderr.contains("unknown simulation backend `icarus`"),
        "{stderr}"
    );
}

/// Each subcommand's help is its own: `simulate` once took over the doc
/// comment of `plot-pulses`, which was left with none.
#[test]
fn every_subcommand_has_its_own_help_line() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    let line = |command: &str| {
        help.lines()
            .find(|l| l.trim_start().starts_with(&format!("{command} ")))
            .unwrap_or_else(|| panic!("no `{command}` in:\n{help}"))
            .to_string()
    };
    assert!(line("simulate").contains("Run a path file"), "{help}");
    assert!(
        !line("simulate").contains("uniform pulse generator's figures"),
        "{help}"
    );
    assert!(
        line("plot-pulses").contains("uniform pulse generator's figures"),
        "{help}"
    );
}

/// The long run: a 2000-segment circle approximation through the exported
/// controller compiled by Verilator, at the board example's 48 MHz. Not in
/// the default suite: `cargo test --release --test host -- --ignored`.
#[test]
#[ignore]
fn a_2000_segment_circle_through_the_rtl_ends_exactly() {
    let config = DriverConfig::default();
    let period = config.period_ticks as f64 * config.tick_divisor as f64 / 48e6;
    let path = Path::new([0, 0, 0], &polygon(2000, 3000.0), 1e7, 2e10, 2.0, period).unwrap();
    let interpolation = interpolate(path.start, &plan(&path).unwrap(), path.period);
    let bus = RtlBus::new(Backend::from_env_or(Backend::Verilator).unwrap(), None).unwrap();
    let mut driver = Driver::new(bus, config).unwrap();
    let started = std::time::Instant::now();
    let report = driver.run(&interpolation.counts, |_| {}).unwrap();
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "{report:?}: {} clocks in {seconds:.1} s, {:.0} cycles/s",
        report.cycles,
        report.cycles as f64 / seconds
    );
    assert_eq!(
        (report.commanded, report.actual, report.underruns),
        ([0; 3], [0; 3], 0)
    );
}

/// The probe through the driver and the RTL: armed for contact before a
/// move and touched part way (the pin rises at clock 2500), it latches
/// every axis's positions of one clock a few clocks later: the steps at the
/// pins then, and the encoder count a few clocks behind them (the
/// loopback's and the decoder's lag). The move runs on to its end. The
/// still-touching probe latches nothing more; armed for release, lifting
/// it latches anew.
#[test]
fn the_driver_arms_the_probe_and_reads_the_positions_of_its_trip() {
    let counts = vec![[20, -10, 5]; 30];
    let mut bus = RtlBus::new(Backend::from_env_or(Backend::Verilator).unwrap(), None).unwrap();
    bus.sample_positions(1);
    let touching = MachinePins {
        probe: true,
        ..Default::default()
    };
    bus.set_pins_at(2500, touching);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    assert!(driver.has_probe());
    driver.arm_probe(ProbeEdge::Contact).unwrap();
    assert_eq!(driver.probe_trip().unwrap(), None, "armed, not tripped");
    let report = driver.run(&counts, |_| {}).unwrap();
    assert_eq!(
        report.commanded,
        [600, -300, 150],
        "the move ran to its end"
    );
    let trip = driver.probe_trip().unwrap().expect("the probe tripped");
    let samples = driver.bus().samples();
    let at = |window: std::ops::Range<usize>, position: [i32; 3]| {
        window
            .clone()
            .find(|&c| samples[c] == position.map(i64::from))
    };
    let pins_at = at(2500..2540, trip.commanded).unwrap_or_else(|| {
        panic!("{trip:?}: no clock shortly after the touch had these steps at the pins")
    });
    assert!(
        at(pins_at.saturating_sub(20)..pins_at + 1, trip.actual).is_some(),
        "{trip:?}: the encoder count is not the pins' of a few clocks before"
    );
    assert!(
        trip.commanded[0] > 0 && trip.commanded[0] < 600,
        "part way: {trip:?}"
    );

    driver.run(&[[4, 0, 0], [0, 0, 0]], |_| {}).unwrap();
    assert_eq!(
        driver.probe_trip().unwrap(),
        Some(trip),
        "one trip per arming"
    );
    driver.arm_probe(ProbeEdge::Release).unwrap();
    let lift = driver.bus().cycles() + 200;
    driver.bus_mut().set_pins_at(lift, MachinePins::default());
    driver.run(&[[6, 0, 0]; 4], |_| {}).unwrap();
    let second = driver.probe_trip().unwrap().expect("lifting it tripped");
    assert!(second.commanded[0] > trip.commanded[0], "{second:?}");
}

/// `motion-hdl simulate FILE --clock-mhz MHZ --out-dir OUT ARGS...`: its
/// success, stdout and stderr.
pub(crate) fn run_simulate(
    file: &std::path::Path,
    clock_mhz: &str,
    out_dir: &std::path::Path,
    args: &[&str],
) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
        .arg("simulate")
        .arg(file)
        .args(["--clock-mhz", clock_mhz, "--out-dir"])
        .arg(out_dir)
        .args(args)
        .output()
        .unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.success(), text(&out.stdout), text(&out.stderr))
}
