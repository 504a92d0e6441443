//! The feed hold from the host: the driver's hold and release at given
//! clocks of a run, on the RTL and on the model, and `simulate --hold-at
//! --resume-at` with its errors.

use motion_hdl::host::driver::{HoldAction, HoldEvent};
use motion_hdl::host::{ControllerBus, Driver, DriverConfig, DriverError, ModelBus, RtlBus};
use motion_hdl::sim::Backend;

/// A move of 40 periods with every axis busy, the last period empty.
fn counts() -> Vec<[i32; 3]> {
    let mut counts: Vec<[i32; 3]> = (0..40)
        .map(|p| [20 + p % 7, -10 - p % 3, 5 + p % 2])
        .collect();
    counts.push([0, 0, 0]);
    counts
}

fn end(counts: &[[i32; 3]]) -> [i32; 3] {
    counts
        .iter()
        .fold([0; 3], |a, c| [a[0] + c[0], a[1] + c[1], a[2] + c[2]])
}

fn events(hold: u64, release: u64) -> [HoldEvent; 2] {
    [
        HoldEvent {
            clock: hold,
            action: HoldAction::Hold,
        },
        HoldEvent {
            clock: release,
            action: HoldAction::Release,
        },
    ]
}

/// Through the RTL (the exported Verilog): a hold at 2500 clocks ramps the
/// path to a stop; no step leaves the pins from the driver's sight of
/// `STATUS.HELD` to the release; the run then ends exactly where the same
/// run without the hold ends, later by at least the time held.
#[test]
fn a_hold_and_release_through_the_driver_end_where_the_unheld_run_ends() {
    let counts = counts();
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    let unheld = {
        let bus = RtlBus::new(backend, None).unwrap();
        let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
        driver.run(&counts, |_| {}).unwrap()
    };
    assert_eq!(unheld.commanded, end(&counts));
    assert!(unheld.held.is_empty(), "{unheld:?}");

    let mut bus = RtlBus::new(backend, None).unwrap();
    bus.sample_positions(1);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    // 8 base ticks from full speed to a stop: a ramp well inside a period.
    driver.set_hold_rate(8192).unwrap();
    let (hold, release) = (2500, 4500);
    let report = driver
        .run_with_holds(&counts, &events(hold, release), |_| {})
        .unwrap();
    assert_eq!(report.commanded, unheld.commanded, "{report:?}");
    assert_eq!(report.actual, unheld.actual, "{report:?}");
    assert_eq!(report.underruns, 0, "{report:?}");
    let &[stood] = report.held.as_slice() else {
        panic!("one stop: {report:?}")
    };
    assert!(
        stood > hold && stood < hold + 100,
        "stood at {stood}, held at {hold}"
    );
    let samples = driver.bus().samples();
    let at_stop = samples[stood as usize];
    assert!(
        (stood as usize..release as usize).all(|c| samples[c] == at_stop),
        "a step left the pins while held"
    );
    assert!(
        at_stop[0] > 0 && at_stop[0] < unheld.commanded[0] as i64,
        "held part way: {at_stop:?}"
    );
    assert!(
        report.cycles >= unheld.cycles + (release - stood),
        "held {} clocks, ran {} against {}",
        release - stood,
        report.cycles,
        unheld.cycles
    );
    let state = driver.hold_state().unwrap();
    assert!(
        !state.requested && !state.holding && !state.held,
        "{state:?}"
    );
}

/// On the model: a hold with nothing to release it fails the run with
/// [`DriverError::Held`], naming the position and the periods queued; a
/// release and a run of the periods not yet queued end the path. A hold from the `feed_hold` input
/// names the input. Bad events and rates are refused.
#[test]
fn a_hold_with_no_release_fails_the_run_and_names_the_position() {
    let counts = counts();
    let mut driver = Driver::new(ModelBus::new(), DriverConfig::default()).unwrap();
    let hold = [HoldEvent {
        clock: 2500,
        action: HoldAction::Hold,
    }];
    let error = driver.run_with_holds(&counts, &hold, |_| {}).unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with("motion held (HOLD_CONTROL.REQUESTED) with no release to come"),
        "{message}"
    );
    let DriverError::Held {
        input,
        commanded,
        periods_queued,
        ..
    } = error
    else {
        panic!("not a hold: {message}")
    };
    assert!(!input);
    assert!(
        commanded[0] > 0 && commanded[0] < end(&counts)[0],
        "{commanded:?}"
    );
    assert!(driver.hold_state().unwrap().held);
    assert!(periods_queued < counts.len(), "{periods_queued}");
    driver.release().unwrap();
    let rest = driver.run(&counts[periods_queued..], |_| {}).unwrap();
    assert_eq!(rest.commanded, end(&counts), "{rest:?}");

    // The input holds: the error says so.
    let mut bus = ModelBus::new();
    let pressed = motion_hdl::blocks::motion_controller::io_model::MachinePins {
        feed_hold: true,
        ..Default::default()
    };
    bus.set_pins_at(2500, pressed);
    let mut driver = Driver::new(bus, DriverConfig::default()).unwrap();
    let message = driver.run(&counts, |_| {}).unwrap_err().to_string();
    assert!(message.contains("the feed_hold input active"), "{message}");

    let mut driver = Driver::new(ModelBus::new(), DriverConfig::default()).unwrap();
    let message = driver.set_hold_rate(65536).unwrap_err().to_string();
    assert!(
        message.contains("hold rate 65536 does not fit"),
        "{message}"
    );
    let backwards = [events(10, 20)[1], events(10, 20)[0]];
    let message = driver
        .run_with_holds(&counts, &backwards, |_| {})
        .unwrap_err()
        .to_string();
    assert!(message.contains("not in clock order"), "{message}");
    assert!(driver.bus().cycles() < 2000, "refused before running");
}

/// `simulate --hold-at --resume-at` on the square (2 MHz, the exported
/// Verilog): the run ends at the target as unheld, prints the hold's line
/// with the stop before the release, and the speed plot shows the path
/// standing. Bad hold options are named, with a non-zero exit.
#[test]
fn simulate_holds_and_resumes_the_square_and_names_bad_hold_options() {
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| crate::host::run_simulate(&square, "2", dir.path(), args);
    let (ok, stdout, stderr) = run(&["--hold-at", "0.2s", "--resume-at", "350ms"]);
    assert!(ok, "{stdout}{stderr}");
    assert!(stdout.contains("commanded  [0, 0, 0]"), "{stdout}");
    let hold_line = stdout
        .lines()
        .find(|l| l.starts_with("feed hold  RATE"))
        .unwrap_or_else(|| panic!("no hold line: {stdout}"));
    let time_after = |word: &str| -> f64 {
        let rest = &hold_line[hold_line.find(word).unwrap() + word.len()..];
        rest.trim().split(' ').next().unwrap().parse().unwrap()
    };
    let (requested, standing, released) = (
        time_after("requested"),
        time_after("standing"),
        time_after("released"),
    );
    assert_eq!((requested, released), (0.2, 0.35), "{hold_line}");
    assert!(standing > requested && standing < released, "{hold_line}");
    assert!(std::fs::read_to_string(dir.path().join("square-speed.svg"))
        .unwrap()
        .contains("through the feed hold"));

    for (args, message) in [
        (&["--hold-at", "0.2"][..], "--hold-at needs --resume-at"),
        (&["--resume-at", "0.2"][..], "--resume-at needs --hold-at"),
        (
            &["--hold-at", "0.3", "--resume-at", "0.2"][..],
            "--resume-at 0.2 s is not after --hold-at 0.3 s",
        ),
        (
            &["--hold-at", "soon", "--resume-at", "0.2"][..],
            "--hold-at `soon`: not a time",
        ),
        (
            &[
                "--hold-at",
                "0.1",
                "--resume-at",
                "0.2",
                "--hold-rate",
                "70000",
            ][..],
            "--hold-rate 70000 does not fit HOLD_CONTROL.RATE",
        ),
    ] {
        let (ok, stdout, stderr) = run(args);
        assert!(!ok, "{args:?}: {stdout}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}
