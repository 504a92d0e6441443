//! G38.2 to G38.5 run on the simulated controller (`simulate
//! --probe-plane`): the trip is the first step position in contact at any
//! feed, the machine stops along the move past it, and the program goes
//! on from where it stopped; bad probe options and moves are named.

use motion_hdl::host::simulated_probe::ProbePlane;
use motion_hdl::host::simulation::{simulate, SimulationOptions};

/// `gcode.rs`'s options (50 kHz, step axes, the compiled backend) with
/// the probe against `plane`.
fn options(out_dir: &std::path::Path, plane: &str) -> SimulationOptions {
    SimulationOptions {
        probe_plane: Some(ProbePlane::parse(plane).unwrap()),
        soft_limits: [None; 3],
        ..crate::gcode::options(out_dir)
    }
}

/// Probes toward planes off the step grid on Z (down) and X (up), at
/// feeds from 0.5 mm/s to each axis's maximum velocity: every trip is the
/// first whole step in contact (so within one step of the plane), every
/// stop lies past the trip along the move, and the run ends at the
/// program's end as the driver streamed it.
#[test]
fn every_trip_is_the_first_step_in_contact_at_any_feed() {
    let dir = tempfile::tempdir().unwrap();
    let feeds = [30.0, 120.0, 480.0, 1200.0, 3000.0];
    for (plane, axis, steps_per_mm, toward) in [
        ("z=-1.234", 2, 400.0, "Z-3"),
        ("z=-0.4987", 2, 400.0, "Z-3"),
        ("x=3.3333", 0, 100.0, "X6"),
    ] {
        let mut program = String::from("G21 G90\n");
        for f in feeds {
            // Z's limit is 20 mm/s (F1200): the planner holds the feed to it.
            program += &format!("G0 X0 Z0\nG38.2 {toward} F{f}\n");
        }
        program += "G0 X0 Z0\nM2\n";
        let file = dir.path().join("feeds.ngc");
        std::fs::write(&file, &program).unwrap();
        let report =
            simulate(&file, &options(dir.path(), plane)).unwrap_or_else(|e| panic!("{plane}: {e}"));
        assert_eq!(report.probes.len(), feeds.len(), "{plane}");
        let height = ProbePlane::parse(plane).unwrap().height_mm;
        let first_in_contact = match axis {
            2 => (height * steps_per_mm).floor() / steps_per_mm,
            _ => (height * steps_per_mm).ceil() / steps_per_mm,
        };
        for (p, f) in report.probes.iter().zip(feeds) {
            let trip = p.trip_mm.unwrap_or_else(|| panic!("{plane} F{f}: no trip"));
            assert!(
                (trip[axis] - first_in_contact).abs() < 1e-9,
                "{plane} F{f}: tripped at {trip:?}, the first step in contact is {first_in_contact}"
            );
            assert!((trip[axis] - height).abs() < 1.0 / steps_per_mm);
            let past = (p.stop_mm[axis] - trip[axis]) * (first_in_contact - height).signum();
            assert!(past >= 0.0, "{plane} F{f}: stopped at {:?}", p.stop_mm);
            // The trip's hold stops the slower moves well short of the
            // programmed point (the fastest may reach it while slowing).
            let end: f64 = toward[1..].parse().unwrap();
            if f <= 480.0 {
                assert!(
                    (p.stop_mm[axis] - end).abs() > 0.5,
                    "{plane} F{f}: ran on to {:?}",
                    p.stop_mm
                );
            }
        }
        assert_eq!(report.commanded.map(i64::from), report.target, "{plane}");
        assert_eq!(report.underruns, 0);
    }
}

/// The CLI on the example: the touch-off's trip and stop, G38.3 going on
/// without contact, the run ending at the program's end; and each bad
/// probe option or move named, with a non-zero exit.
#[test]
fn simulate_probe_plane_runs_the_example_and_names_bad_probing() {
    let root = motion_hdl::tools::repo_root();
    let example = root.join("examples/probe-touch-off.ngc");
    let dir = tempfile::tempdir().unwrap();
    let run = |file: &std::path::Path, args: &[&str]| {
        crate::host::run_simulate(file, "0.05", dir.path(), args)
    };
    let (ok, stdout, stderr) = run(&example, &["--probe-plane", "z=-1.234"]);
    assert!(ok, "{stdout}{stderr}");
    assert!(
        stdout.contains("probe      line 6 G38.2: tripped at X 5.0000 Y 5.0000 Z -1.2350 mm, 0.0010 mm (0.40 steps) past the plane z=-1.234; stopped at X 5.0000 Y 5.0000 Z -1.2"),
        "{stdout}"
    );
    assert!(
        stdout.contains("probe      line 16 G38.3: no trip"),
        "{stdout}"
    );
    assert!(
        stdout.contains("(PRINT): top of the stock at Z-1.235000, trip 1.000000"),
        "{stdout}"
    );
    let line = |name: &str| stdout.lines().find(|l| l.starts_with(name)).unwrap()[11..].to_string();
    assert_eq!(line("target"), line("commanded"), "{stdout}");

    let program = |name: &str, text: &str| {
        let file = dir.path().join(name);
        std::fs::write(&file, text).unwrap();
        file
    };
    let miss = program("miss.ngc", "G38.2 Z-1 F60\nM2\n");
    let touching = program("touching.ngc", "G0 Z-3\nG38.2 Z-4 F60\nM2\n");
    let square = root.join("examples/square.path");
    for (file, args, message) in [
        (
            &example,
            &["--probe-plane", "w=1"][..],
            "--probe-plane `w=1`: unknown axis `w`",
        ),
        (
            &example,
            &["--probe-plane", "z=low"][..],
            "--probe-plane `z=low`: `low` is not a position in mm",
        ),
        (
            &example,
            &["--probe-plane", "z"][..],
            "--probe-plane `z`: expected AXIS=HEIGHT",
        ),
        (
            &example,
            &[][..],
            "line 6: G38.2: probing needs a probe, and this run has none",
        ),
        (
            &miss,
            &["--probe-plane", "z=-2"][..],
            "line 1: G38.2: the move reached the probe point without the probe making contact",
        ),
        (
            &touching,
            &["--probe-plane", "z=-2"][..],
            "line 2: G38.2: the probe already touches where the move starts",
        ),
        (
            &square,
            &["--probe-plane", "z=-2"][..],
            "--probe-plane runs a G-code program's probe moves",
        ),
        (
            &example,
            &["--probe-plane", "z=-2", "--servo", "x"][..],
            "probe without --servo",
        ),
        (
            &example,
            &[
                "--probe-plane",
                "z=-2",
                "--hold-at",
                "1",
                "--resume-at",
                "2",
            ][..],
            "both program the feed hold",
        ),
    ] {
        let (ok, stdout, stderr) = run(file, args);
        assert!(!ok, "{args:?}: {stdout}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}
