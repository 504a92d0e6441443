//! `simulate PROGRAM --kinematics hexapod` (#36 step 4): a G-code program
//! in X Y Z A B C planned, checked, and run on the parallel-machine card
//! with the load-scheduled and the fixed PID.

use std::path::{Path, PathBuf};
use std::process::Command;

use motion_hdl::host::hexapod::card::CardSettings;
use motion_hdl::host::hexapod::simulate::{simulate_hexapod, HexapodOptions};
use motion_hdl::host::hexapod::{inverse, Geometry};

const EXAMPLE: &str = "examples/hexapod-tilted-arcs.ngc";

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(EXAMPLE)
}

fn program(dir: &Path, text: &str) -> PathBuf {
    let file = dir.join("job.ngc");
    std::fs::write(&file, text).unwrap();
    file
}

/// The shipped example, both schedules: every leg ends within a count, the
/// final pose by the forward kinematics of the counts is within a count's
/// worth of the program's end, every slave is released on one clock, and
/// the report and figures are there.
#[test]
fn the_example_program_runs_on_the_card_with_both_schedules() {
    let out = tempfile::tempdir().unwrap();
    let options = HexapodOptions {
        out_dir: Some(out.path().to_path_buf()),
        ..HexapodOptions::default()
    };
    let report = simulate_hexapod(&example(), &options).unwrap();
    let lines = report.summary();
    for line in &lines {
        println!("{line}");
    }
    let g = Geometry::default();
    let end = inverse(&g, &report.end_pose);
    let home = inverse(&g, &g.home);
    for run in [&report.scheduled, &report.fixed] {
        assert!(run.ends_within_a_count(), "{:?}", run.run.final_counts);
        assert_eq!(run.run.skew, 0);
        assert_eq!(run.run.releases_seen, run.run.periods);
        assert!(run.run.underrun.is_none() && run.run.motor_error.is_none());
        // A count is 2.5 µm of leg: the pose within a few of them.
        let e = run.pose_error;
        assert!(e[..3].iter().all(|v| v.abs() < 0.01), "{e:?}");
        assert!(e[3..].iter().all(|v| v.abs() < 0.002), "{e:?}");
        assert!(run.max_following() < 2.0, "{}", run.max_following());
        for j in 0..6 {
            let target = (end[j] - home[j]) * 400.0;
            assert!((run.run.final_targets[j] - target).abs() < 1e-6);
        }
    }
    // Measured: 1.07 counts scheduled, 1.39 fixed (2 ms drives).
    assert!(report.scheduled.max_following() <= report.fixed.max_following());
    // The example ends tilted off home: the legs moved.
    assert!(report
        .scheduled
        .run
        .final_counts
        .iter()
        .any(|&c| c.abs() > 1000));
    assert_eq!(
        lines.iter().filter(|l| l.starts_with("pose error")).count(),
        2
    );
    assert_eq!(
        lines
            .iter()
            .filter(|l| l.contains("following error"))
            .count(),
        7
    );
    assert!(lines.iter().any(|l| l.starts_with("skew       0 clocks")));
    // README quotes this run's report: every line but the run times.
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let command = format!("$ motion-hdl simulate {EXAMPLE} --kinematics hexapod\n");
    let quoted = readme
        .split_once(&command)
        .expect("README quotes the example's run")
        .1
        .split("```")
        .next()
        .unwrap();
    let timed = without_run_times(&lines);
    for line in quoted.lines().filter(|l| !l.starts_with("wrote")) {
        assert!(
            timed.iter().any(|l| l == line),
            "README: {line:?} is not in {timed:#?}"
        );
    }
    assert_eq!(
        quoted.lines().filter(|l| !l.starts_with("wrote")).count(),
        lines.len()
    );
    assert_eq!(report.figures.len(), 3);
    for figure in &report.figures {
        let svg = std::fs::read_to_string(figure).unwrap();
        assert!(
            svg.contains("<svg") && svg.len() > 10_000,
            "{}",
            figure.display()
        );
    }
}

/// Each bad input is an error naming the line or the setting before any
/// motion, through the command line.
#[test]
fn bad_input_is_named_before_any_motion() {
    let dir = tempfile::tempdir().unwrap();
    let cli = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
            .args(args)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?} succeeded");
        String::from_utf8(out.stderr).unwrap()
    };
    let run = |text: &str| {
        let file = program(dir.path(), text);
        cli(&[
            "simulate",
            file.to_str().unwrap(),
            "--kinematics",
            "hexapod",
        ])
    };
    assert!(run("G0 X10\nG1 X250 F600\nM2")
        .contains("job.ngc: line 2: X 250 is outside the workspace, -200 to 200"),);
    let stroke = run("G0 X-150 Z700");
    assert!(
        stroke.contains("job.ngc: line 1: leg 1 would be 996.")
            && stroke.contains("beyond its stroke of 600 to 950 mm"),
        "{stroke}"
    );
    assert!(run("G0 A25").contains("job.ngc: line 1: A 25 is outside the workspace, -20 to 20"));
    assert!(run("G0 U1").contains(
        "line 1: U1 moves an axis this machine does not have (X, Y, Z, A, B and C only)"
    ));
    assert!(run("G92 A1")
        .contains("line 1: A1 with G92: the rotary axes move with G0, G1, G2 and G3 only"));
    // Near-singular: a condition limit just above home's.
    let geometry = dir.path().join("tight.hex");
    std::fs::write(&geometry, "condition_limit 7.9\n").unwrap();
    let job = program(dir.path(), "G0 X1\nG0 A15 B15\n");
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--kinematics",
        "hexapod",
        "--geometry",
        geometry.to_str().unwrap(),
    ]);
    assert!(e.contains("line 2: the pose is singular or nearly"), "{e}");
    // A geometry that is not a platform names the setting.
    std::fs::write(&geometry, "stroke 900 800\n").unwrap();
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--kinematics",
        "hexapod",
        "--geometry",
        geometry.to_str().unwrap(),
    ]);
    assert!(
        e.contains("tight.hex") && e.contains("stroke 900 800"),
        "{e}"
    );
    // A program too long, a path file, an unknown format, a drive lag out
    // of range.
    assert!(run("G0 X1\nG4 P20000").contains("job.ngc: line 2: the program would run 2.000e4 s"));
    let path = dir.path().join("square.path");
    std::fs::write(&path, "line 1 0 0\n").unwrap();
    let e = cli(&[
        "simulate",
        path.to_str().unwrap(),
        "--kinematics",
        "hexapod",
    ]);
    assert!(e.contains("runs G-code programs, not path files"), "{e}");
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--kinematics",
        "hexapod",
        "--format",
        "foo",
    ]);
    assert!(e.contains("unknown format `foo`"), "{e}");
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--kinematics",
        "hexapod",
        "--drive-lag-ms",
        "0.000001",
    ]);
    assert!(
        e.contains("--drive-lag-ms must be from 0.1 to 1000, not 0.000001"),
        "{e}"
    );
    // Options of the 3-axis controller, and a geometry without hexapod.
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--kinematics",
        "hexapod",
        "--servo",
        "x",
    ]);
    assert!(
        e.contains("--servo applies to the 3-axis controller"),
        "{e}"
    );
    let e = cli(&[
        "simulate",
        job.to_str().unwrap(),
        "--geometry",
        geometry.to_str().unwrap(),
    ]);
    assert!(
        e.contains("--geometry and --drive-lag-ms describe a hexapod"),
        "{e}"
    );
}

/// A point the control DSP leaves out: the run stops and `simulate` names
/// the slave and the period.
#[test]
fn an_underrun_names_its_slave_and_period() {
    let dir = tempfile::tempdir().unwrap();
    let file = program(dir.path(), "G1 X5 Y5 A1 F1200\nM2\n");
    let options = HexapodOptions {
        card: CardSettings {
            drop_point: Some((150, 2)),
            settle_periods: 50,
            ..CardSettings::default()
        },
        ..HexapodOptions::default()
    };
    let e = simulate_hexapod(&file, &options).unwrap_err();
    assert!(
        e.ends_with(
            "scheduled PID: slave 2 had no point at period 150: the card stopped every joint"
        ),
        "{e}"
    );
}

/// The report's lines with each run's seconds written as "…".
fn without_run_times(lines: &[String]) -> Vec<String> {
    lines
        .iter()
        .map(|l| match (l.find(" in "), l.find(" s, ")) {
            (Some(a), Some(b)) if l.starts_with("card") && a < b => {
                format!("{} in …{}", &l[..a], &l[b..])
            }
            _ => l.clone(),
        })
        .collect()
}
