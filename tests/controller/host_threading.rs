//! Geared moves through `simulate`: G76, G33 and G33.1 on the spindle
//! build with the simulated spindle (±10 % ripple, a 5 % dip under load),
//! measured at the pins against pitch x spindle angle; the refusals, by
//! line.

use motion_hdl::host::simulation::{simulate, SimulationOptions, Trip};
use motion_hdl::host::spindle_run::ThreadReport;
use motion_hdl::host::MachineSettings;

/// `gcode.rs`'s options at 1 MHz with a 1000-count spindle encoder: at
/// S600 the spindle counts every 91 clocks or more, three times slower
/// than the gearbox's limit.
fn options(out_dir: &std::path::Path) -> SimulationOptions {
    SimulationOptions {
        clock_hz: 1e6,
        machine: Some(MachineSettings {
            spindle_counts_per_rev: 1000,
            ..MachineSettings::default()
        }),
        ..crate::gcode::options(out_dir)
    }
}

fn run(
    name: &str,
    program: &str,
    options: &SimulationOptions,
) -> Result<Vec<ThreadReport>, String> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(name);
    std::fs::write(&file, program).unwrap();
    let r = simulate(&file, options)?;
    assert_eq!(r.commanded.map(i64::from), r.target, "{name}: commanded");
    assert_eq!(r.actual.map(i64::from), r.target, "{name}: actual");
    assert_eq!(r.underruns, 0);
    Ok(r.threads)
}

/// The targets: lead error within one step at every locked
/// spindle count of every pass, and every pass in the same phase within
/// one step.
fn assert_on_target(t: &ThreadReport, passes: usize) {
    let f = t.figures.expect("a pass locked");
    assert_eq!(
        (t.passes, t.unlocked, f.passes),
        (passes, 0, passes),
        "{t:?}"
    );
    assert!(f.lead_error <= 1.0, "lead error {f:?}");
    assert!(f.phase_spread <= 1.0, "phase spread {f:?}");
    assert!(f.counts > 1000 * passes, "{f:?}");
}

#[test]
fn a_g76_thread_lands_every_pass_in_the_same_groove() {
    let dir = tempfile::tempdir().unwrap();
    let options = options(dir.path());
    // Straight infeed: every pass starts at the same Z, so the phases agree
    // to within the floor of the fraction (a pass's mean error).
    let threads = run(
        "straight.ngc",
        "G18 G21 G90\nG0 X6 Z1\nS600 M3\nG76 P1 Z-3 I-0.5 J0.3 K0.6 H1\nG0 X10\nM2\n",
        &options,
    )
    .unwrap();
    assert_eq!(threads.len(), 1);
    assert_on_target(&threads[0], 3);
    assert!(
        threads[0].figures.unwrap().phase_spread < 0.05,
        "{threads:?}"
    );
    // Compound infeed (Q29.5): each pass starts back along Z by a length
    // that is not a whole number of steps.
    let threads = run(
        "compound.ngc",
        "G18 G21 G90\nG0 X6 Z1\nS600 M3\nG76 P1 Z-3 I-0.5 J0.3 K0.6 R1.5 Q29.5\nG0 X10\nM2\n",
        &options,
    )
    .unwrap();
    assert_on_target(&threads[0], 3);
}

#[test]
fn g33_passes_both_ways_and_with_m4_are_one_thread_each() {
    let dir = tempfile::tempdir().unwrap();
    let options = options(dir.path());
    // Two passes of a thread cut toward +Z with the spindle in reverse.
    let program =
        "G18 G21 G90\nG0 X5 Z-3\nS500 M4\nG33 Z0 K0.8\nG0 X6\nZ-3\nX4.9\nG33 Z0 K0.8\nG0 X6\nM2\n";
    let threads = run("m4.ngc", program, &options).unwrap();
    assert_eq!(threads.len(), 1, "{threads:?}");
    assert!(threads[0].gear.run.spindle_reverse && !threads[0].gear.run.axis_reverse);
    assert_on_target(&threads[0], 2);
}

#[test]
fn a_rigid_tap_follows_the_spindle_in_and_out_and_ends_where_it_started() {
    let dir = tempfile::tempdir().unwrap();
    let options = options(dir.path());
    let threads = run(
        "tap.ngc",
        "G17 G21 G90\nG0 X2 Y3 Z1\nS300 M3\nG33.1 Z-2 K0.7\nG0 Z5\nM2\n",
        &options,
    )
    .unwrap();
    assert_eq!((threads.len(), threads[0].passes), (1, 1));
    // 3 mm at 400 steps/mm: the tap reached the depth, and went on while
    // the spindle reversed (at 5 rev/s and a 50 ms time constant, about a
    // quarter turn).
    let deepest = threads[0].deepest.expect("a tap");
    assert!((1200..1200 + 200).contains(&deepest), "{threads:?}");
}

#[test]
fn an_estop_mid_thread_halts_the_gearbox_and_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut options = options(dir.path());
    options.trips = vec![Trip::parse("estop@600").unwrap()];
    let error = run(
        "estop.ngc",
        "G18 G21 G90\nG0 X6 Z1\nS600 M3\nG33 Z-8 K1\nM2\n",
        &options,
    )
    .unwrap_err();
    assert!(
        error.contains("line 4: spindle sync: the gearbox stopped after")
            && error.contains("the E-stop input is active"),
        "{error}"
    );
}

#[test]
fn geared_moves_that_cannot_run_are_refused_by_line() {
    let dir = tempfile::tempdir().unwrap();
    let base = options(dir.path());
    let no_encoder = SimulationOptions {
        machine: Some(MachineSettings {
            spindle_counts_per_rev: 0,
            ..MachineSettings::default()
        }),
        ..base.clone()
    };
    let slow_clock = SimulationOptions {
        clock_hz: 2e5,
        ..base.clone()
    };
    for (program, options, message) in [
        ("S600 M3\nG33 Z-3 K1\nM2\n", &no_encoder, "line 2: G33 needs a spindle encoder, and the machine has none (spindle_encoder 0 in its settings)"),
        ("S600 M3\nG33 Z-3 K3\nM2\n", &base, "line 2: G33's pitch of 3 mm is 1200.0 steps per revolution on Z, more than the spindle encoder's 1000 counts: the gearbox makes at most one step per count"),
        ("S1500 M3\nG33 Z-3 K1\nM2\n", &base, "line 2: G33's pitch of 1 mm at S1500 moves Z at up to 27.5 mm/s (with the spindle's +10 % ripple), above its max_velocity of 20 mm/s"),
        ("S600 M3\nG33 Z-3 K1\nM2\n", &slow_clock, "line 2: at S600 the spindle encoder counts up to 11000 counts/s (with the +10 % ripple); the gearbox takes one count per 31 clocks, 6452 counts/s at 0.2 MHz: lower S, or raise the clock"),
        ("G33 Z-3 K1\nM2\n", &base, "line 1: G33 with the spindle stopped: M3 or M4 with S first (LinuxCNC: Spindle not turning in G33)"),
        ("S600 M3\nG76 P1 Z-3 I-0.5 J0.6 K0.6\nM2\n", &base, "line 2: G76's K0.6 must be deeper than J0.6: K is the full depth, J the first cut (LinuxCNC: In G76, K must be greater than J)"),
    ] {
        let error = run("bad.ngc", program, options).unwrap_err();
        assert!(error.ends_with(message), "{program:?}: {error}");
    }
    let uniform = SimulationOptions {
        uniform: [true, false, false],
        ..base.clone()
    };
    let error = run("uniform.ngc", "S600 M3\nG33 Z-3 K1\nM2\n", &uniform).unwrap_err();
    assert!(
        error.contains("--uniform cannot run with geared moves"),
        "{error}"
    );
}

/// The CLI prints the lead error and the pass phase spread on lines of
/// their own, and refuses a geared move it cannot run with the line and a
/// non-zero exit status.
#[test]
fn the_cli_prints_lead_error_and_phase_spread_on_their_own_lines() {
    let dir = tempfile::tempdir().unwrap();
    let machine = dir.path().join("lathe.machine");
    std::fs::write(&machine, "spindle_encoder 1000\n").unwrap();
    let program = dir.path().join("thread.ngc");
    std::fs::write(
        &program,
        "G18 G21 G90\nG0 X6 Z1\nS600 M3\nG76 P1 Z-2 I-0.5 J0.4 K0.6\nG0 X10\nM2\n",
    )
    .unwrap();
    let simulate = |machine: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_motion-hdl"))
            .arg("simulate")
            .arg(&program)
            .arg("--machine")
            .arg(machine)
            .args(["--clock-mhz", "1", "--backend", "verilator", "--out-dir"])
            .arg(dir.path())
            .output()
            .unwrap()
    };
    let out = simulate(&machine);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let figure = |prefix: &str| -> f64 {
        let line = stdout
            .lines()
            .find(|l| l.starts_with(prefix))
            .unwrap_or_else(|| panic!("no `{prefix}` line in {stdout}"));
        let value = line[prefix.len()..].strip_suffix(" steps").expect(line);
        value.parse().expect(line)
    };
    assert!(figure("lead error: max ") <= 1.0, "{stdout}");
    assert!(figure("pass phase spread: ") <= 1.0, "{stdout}");
    let none = dir.path().join("mill.machine");
    std::fs::write(&none, "spindle_encoder 0\n").unwrap();
    let out = simulate(&none);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr
            .contains("thread.ngc: line 4: G76 needs a spindle encoder, and the machine has none"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}
