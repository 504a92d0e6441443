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

/// `simulate --soft-limit` on the square (2 MHz, the exported Verilog):
/// a window that ends inside the path stops X inside it and fails the run
/// naming where it stood; a window around the path runs it to its end.
/// Bad windows are named, with a non-zero exit.
#[test]
fn simulate_stops_the_square_inside_a_soft_limit_and_names_bad_windows() {
    let square = motion_hdl::tools::repo_root().join("examples/square.path");
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| crate::host::run_simulate(&square, "2", dir.path(), args);

    let (ok, stdout, stderr) = run(&["--soft-limit", "x=-1:4"]);
    assert!(!ok, "{stdout}");
    let line = stderr
        .lines()
        .find(|l| l.contains("soft limit: X would pass its maximum 4.0000 mm"))
        .unwrap_or_else(|| panic!("no soft-limit line: {stderr}"));
    let after = |word: &str| -> f64 {
        let rest = &line[line.find(word).unwrap() + word.len()..];
        rest.trim().split(' ').next().unwrap().parse().unwrap()
    };
    let (held, inside) = (after("held it at"), after("mm,"));
    assert!(held > 3.0 && held <= 4.0, "{line}");
    assert!((4.0 - held - inside).abs() < 1e-9, "{line}");

    let (ok, stdout, stderr) = run(&["--soft-limit", "x=-2:8", "--soft-limit", "z=-1:2"]);
    assert!(ok, "{stdout}{stderr}");
    assert!(stdout.contains("commanded  [0, 0, 0]"), "{stdout}");

    for (args, message) in [
        (&["--soft-limit", "w=0:1"][..], "unknown axis `w`"),
        (&["--soft-limit", "x=2:1"][..], "the window is empty"),
        (
            &["--soft-limit", "x=0:5", "--soft-limit", "x=0:6"][..],
            "--soft-limit x given twice",
        ),
        (
            &["--soft-limit", "y=0.001:0.002"][..],
            "holds no step at 80 steps/mm",
        ),
        (
            &["--soft-limit", "x=-1:6", "--servo", "x"][..],
            "--soft-limit x: an analog servo axis (--servo) is never checked",
        ),
        (
            &["--soft-limit", "x=-1:6", "--probe-plane", "z=-1"][..],
            "--soft-limit and --probe-plane",
        ),
    ] {
        let (ok, stdout, stderr) = run(args);
        assert!(!ok, "{args:?}: {stdout}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
    let hexapod = std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
        .arg("simulate")
        .arg(&square)
        .args(["--soft-limit", "x=0:5", "--kinematics", "hexapod"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&hexapod.stderr);
    assert!(!hexapod.status.success());
    assert!(
        stderr.contains("--soft-limit applies to the 3-axis controller"),
        "{stderr}"
    );
}
