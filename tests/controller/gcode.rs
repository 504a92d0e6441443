//! G-code programs through the host and the controller: the examples
//! planned to their exact end, one of them run end to end through the RTL
//! controller on the compiled backend, incremental moves summing exactly,
//! random programs of lines and arcs, and the errors `simulate` gives for
//! a file it cannot run.

use std::path::PathBuf;

use motion_hdl::host::gcode::{interpret, Units};
use motion_hdl::host::planner::to_steps;
use motion_hdl::host::simulation::{simulate, slow_run_hint, InputFormat, Job, SimulationOptions};
use motion_hdl::host::{interpolate, plan_toolpath, Item, MachineSettings, Move, MoveKind};
use motion_hdl::sim::Backend;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn example(name: &str) -> PathBuf {
    motion_hdl::tools::repo_root().join("examples").join(name)
}

/// Plans a program on the default machine: the last period's position in
/// steps, the number of periods, and the program's end in steps.
fn plan_program(text: &str) -> ([i64; 3], usize, [i64; 3]) {
    let program = interpret(text).unwrap_or_else(|e| panic!("{e}"));
    let machine = MachineSettings::default();
    let segments = plan_toolpath(&program.toolpath, &machine).unwrap_or_else(|e| panic!("{e}"));
    let start = to_steps(program.toolpath.start, machine.steps_per_mm);
    let i = interpolate(start, &segments, machine.period);
    let end = to_steps(program.toolpath.end(), machine.steps_per_mm);
    (*i.positions.last().unwrap(), i.counts.len(), end)
}

#[test]
fn the_example_programs_plan_to_their_exact_ends() {
    for (name, end_mm) in [
        ("pocket.ngc", [0.0, 0.0, 5.0]),
        ("engraving.nc", [0.0, 0.0, 2.0]),
    ] {
        let text = std::fs::read_to_string(example(name)).unwrap();
        let program = interpret(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(program.final_position, end_mm, "{name}");
        assert_eq!(program.units, Units::Millimetre);
        let (last, periods, end) = plan_program(&text);
        assert_eq!(
            last, end,
            "{name}: the last period ends at the program's end"
        );
        println!("{name}: {periods} periods of 1 ms, ends at {end:?} steps");
    }
}

#[test]
fn incremental_moves_sum_exactly() {
    // 64 incremental moves of dyadic lengths: the sum is exact in f64,
    // and so is its step count.
    let mut program = String::from("G21 G91 F600\n");
    for _ in 0..64 {
        program.push_str("G1 X0.125 Y-0.375 Z0.0625\n");
    }
    program.push_str("G3 X0 Y0 I1.5 J0\nM30\n");
    let parsed = interpret(&program).unwrap();
    assert_eq!(parsed.final_position, [8.0, -24.0, 4.0]);
    let (last, _, end) = plan_program(&program);
    assert_eq!((last, end), ([800, -2400, 1600], [800, -2400, 1600]));
}

/// Random programs of the kind CAM writes (absolute lines, arcs by I/J or
/// R, either way, sometimes helical, feeds in mm/min, an occasional
/// incremental stretch and dwell) end exactly at their final position.
#[test]
fn random_programs_of_lines_and_arcs_end_exactly() {
    let mut rng = StdRng::seed_from_u64(0x6c0de);
    for case in 0..60 {
        let mut text = String::from("G17 G21 G90\n");
        let mut at = [0.0f64, 0.0, 0.0];
        for _ in 0..rng.gen_range(1..15) {
            let feed = rng.gen_range(60..3000);
            match rng.gen_range(0..6) {
                0 | 1 => {
                    at = [
                        rng.gen_range(-30.0..30.0),
                        rng.gen_range(-30.0..30.0),
                        rng.gen_range(-3.0..3.0),
                    ];
                    text.push_str(&format!(
                        "G1 X{:.4} Y{:.4} Z{:.4} F{feed}\n",
                        at[0], at[1], at[2]
                    ));
                    // What the interpreter reads back.
                    at = at.map(|v| format!("{v:.4}").parse().unwrap());
                }
                2 | 3 => {
                    let r: f64 = rng.gen_range(0.5..12.0);
                    let a0: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
                    let (i, j) = (
                        (-r * a0.cos() * 1e4).round() / 1e4,
                        (-r * a0.sin() * 1e4).round() / 1e4,
                    );
                    let (cx, cy) = (at[0] + i, at[1] + j);
                    let r = i.hypot(j);
                    let a1 = (at[1] - cy).atan2(at[0] - cx) + rng.gen_range(-3.0..3.0);
                    let end = [cx + r * a1.cos(), cy + r * a1.sin()];
                    let g = if rng.gen_bool(0.5) { 2 } else { 3 };
                    let z = if rng.gen_bool(0.3) {
                        format!(" Z{:.4}", at[2] - 0.5)
                    } else {
                        String::new()
                    };
                    text.push_str(&format!(
                        "G{g} X{:.4} Y{:.4}{z} I{i:.4} J{j:.4} F{feed}\n",
                        end[0], end[1]
                    ));
                    at[0] = format!("{:.4}", end[0]).parse().unwrap();
                    at[1] = format!("{:.4}", end[1]).parse().unwrap();
                    if !z.is_empty() {
                        at[2] = format!("{:.4}", at[2] - 0.5).parse().unwrap();
                    }
                }
                4 => {
                    let (dx, dy) = (
                        rng.gen_range(-8i32..8) as f64 * 0.25,
                        rng.gen_range(-8i32..8) as f64 * 0.25,
                    );
                    text.push_str(&format!("G91 G1 X{dx} Y{dy} F{feed}\nG90\n"));
                    at[0] += dx;
                    at[1] += dy;
                }
                _ => text.push_str("G4 P0.005\n"),
            }
        }
        text.push_str("M2\n");
        let program = interpret(&text).unwrap_or_else(|e| panic!("case {case}: {e}\n{text}"));
        for k in 0..3 {
            assert!(
                (program.final_position[k] - at[k]).abs() < 1e-9,
                "case {case}: {:?} vs {at:?}",
                program.final_position
            );
        }
        let (last, _, end) = plan_program(&text);
        assert_eq!(last, end, "case {case}:\n{text}");
        assert_eq!(
            end,
            to_steps(
                program.final_position,
                MachineSettings::default().steps_per_mm
            )
        );
    }
}

#[test]
fn an_r_arc_a_little_short_of_the_half_chord_is_a_half_circle() {
    // CAM writes R to 4 decimals: 4.9999 for a half circle of 10 mm is
    // within LinuxCNC's 0.005 mm and runs as the half circle.
    let program = interpret("G1 X10 F600\nG2 X0 R4.9999\n").unwrap();
    let Item::Move(Move {
        kind: MoveKind::Arc(arc),
        ..
    }) = program.toolpath.items[1]
    else {
        panic!("an arc")
    };
    assert_eq!(arc.center, [5.0, 0.0]);
    assert_eq!(
        interpret("G1 X10 F600\nG2 X0 R4.99\n")
            .unwrap_err()
            .to_string(),
        "line 2: R4.99 cannot reach the end: |R| must be at least half the chord, 5.0000 mm"
    );
}

#[test]
fn a_file_simulate_cannot_run_is_refused_with_its_reason() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let file = dir.path().join(name);
        std::fs::write(&file, text).unwrap();
        file
    };
    let message =
        |file: &PathBuf, format: Option<InputFormat>, machine: Option<MachineSettings>| {
            Job::read(file, format, machine, None)
                .unwrap_err()
                .replace(&format!("{}", dir.path().display()), "DIR")
        };
    let program = write("part.txt", "G1 X1 F100\n");
    assert_eq!(
        message(&program, None, None),
        "DIR/part.txt: unknown file type: G-code ends in .nc, .ngc, .gcode or .tap, a path file in .path (or give --format)"
    );
    assert!(
        Job::read(&program, Some(InputFormat::Gcode), None, None).is_ok(),
        "--format gcode reads any name"
    );
    let bad = write("bad.ngc", "G21\nG1 X1 F100\nG52 X1\n");
    assert_eq!(
        message(&bad, None, None),
        "DIR/bad.ngc: line 3: G52 (local coordinate offset) changes the motion and is not supported"
    );
    // Latin-1 bytes from a Windows post: read in a comment, refused by
    // line elsewhere.
    let latin1 = dir.path().join("latin1.nc");
    std::fs::write(&latin1, b"(Fr\xe4ser \xd8 6)\nG1 X1 F100 ; Ende \xb1\nM2\n").unwrap();
    let job = Job::read(&latin1, None, None, None).unwrap();
    assert_eq!(job.ending.as_deref(), Some("M2 or M30 on line 3"));
    let open_ended = write("open.ngc", "G1 X1 F100\n");
    assert_eq!(
        Job::read(&open_ended, None, None, None)
            .unwrap()
            .ending
            .as_deref(),
        Some("end of file without M2, M30 or a closing % (the program ends there; LinuxCNC would refuse the file)")
    );
    let percent = write("percent.ngc", "%\nG1 X1 F100\n%\nnot read\n");
    assert_eq!(
        Job::read(&percent, None, None, None)
            .unwrap()
            .ending
            .as_deref(),
        Some("the closing % on line 3")
    );
    let trailing = write("trailing.ngc", "G1 X1 F100\nM30\nG0 X0\nG0 Y0\n");
    assert_eq!(
        Job::read(&trailing, None, None, None)
            .unwrap()
            .ending
            .as_deref(),
        Some("M2 or M30 on line 2; 2 blocks after it not run")
    );
    let stray = dir.path().join("stray.nc");
    std::fs::write(&stray, b"G1 X1 F100\nG1 X\xb12\n").unwrap();
    assert_eq!(
        message(&stray, None, None),
        "DIR/stray.nc: line 2: byte 0xB1 outside a comment: the line is not UTF-8 text (Latin-1 is read in comments only)"
    );
    let empty = write("empty.tap", "G21 G90\nM3 S1000\nM2\n");
    assert_eq!(
        message(&empty, None, None),
        "DIR/empty.tap: the program has no motion"
    );
    let path = write("square.path", "feed 10\naccel 100\nline 10 0 0\n");
    assert_eq!(
        message(&path, None, Some(MachineSettings::default())),
        "DIR/square.path: machine settings apply to G-code; a path file carries its own"
    );
    assert_eq!(
        InputFormat::parse("nc").unwrap_err(),
        "unknown format `nc` (gcode or path)"
    );
    // Refused before any step count is allocated or the RTL is built.
    let endless = write("endless.ngc", "G21 F100\nG1 X1\nG4 P1000000000\nM2\n");
    let refused = simulate(&endless, &options(dir.path()))
        .unwrap_err()
        .replace(&format!("{}", dir.path().display()), "DIR");
    assert_eq!(
        refused,
        "DIR/endless.ngc: the program takes 1000000001 s, more than 10000000 periods of 0.001 s"
    );
}

#[test]
fn machine_settings_files_read_over_the_defaults_and_name_bad_lines() {
    let settings =
        MachineSettings::parse("# a router\nsteps_per_mm 80 80 400\nperiod_us 500\n").unwrap();
    assert_eq!(settings.steps_per_mm, [80.0, 80.0, 400.0]);
    assert_eq!(settings.period, 5e-4);
    assert_eq!(
        settings.max_velocity,
        MachineSettings::default().max_velocity
    );
    let message = |text: &str| MachineSettings::parse(text).unwrap_err().to_string();
    assert_eq!(
        message("steps_per_mm 80 80\n"),
        "line 1: `steps_per_mm` takes 3 number(s), found 2"
    );
    assert_eq!(
        message("\nmax_accel 100 -1 100"),
        "line 2: max_accel for Y must be a positive number, not -1"
    );
    assert_eq!(
        message("feed 100"),
        "line 1: unknown setting `feed` (steps_per_mm, max_velocity, max_accel, contour_error, period_us, parameter, spindle_encoder, laser_s_max, laser_pwm_us)"
    );
    assert_eq!(message("contour_error x"), "line 1: `x` is not a number");
    assert_eq!(
        message("steps_per_mm 1e12 100 400"),
        "line 1: steps_per_mm for X is 1000000000000, beyond 1000000 (a nanometre a step)"
    );
    // LinuxCNC's persistent parameters, by number, in mm.
    let settings = MachineSettings::parse(
        "parameter 5221 100
parameter 5220 2
",
    )
    .unwrap();
    assert_eq!(settings.parameters.get(5221), Some(100.0));
    assert_eq!(settings.parameters.get(5220), Some(2.0));
    assert_eq!(
        message("parameter 5221.5 1"),
        "line 1: parameter `5221.5` is not a parameter number"
    );
    assert_eq!(
        message("\nparameter 5230 45"),
        "line 2: #5230 = 45 rotates a coordinate system, which is not supported"
    );
}

/// The options the tests simulate with: the compiled backend, step axes,
/// 50 clocks per 1 ms period (the fastest axis, Z at 20 mm/s, is 8 steps a
/// period, 32 clocks at 2 + 2 clocks a step).
pub(crate) fn options(out_dir: &std::path::Path) -> SimulationOptions {
    SimulationOptions {
        format: None,
        machine: None,
        tools: None,
        clock_hz: 5e4,
        uniform: [false; 3],
        servo: [false; 3],
        step_len: 2,
        step_space: 2,
        out_dir: Some(out_dir.to_path_buf()),
        vcd: None,
        progress: false,
        backend: Backend::from_env_or(Backend::Verilator).unwrap(),
        trips: Vec::new(),
        hold: None,
        probe_plane: None,
        soft_limits: [None; 3],
        spindle: Default::default(),
        spi_sclk_hz: None,
    }
}

/// The pocket (helical entries, arcs by I/J and by R, rapids, two depths)
/// through the RTL controller, compiled: every axis ends where the program
/// ends, in steps, commanded and actual, with no underrun.
#[test]
fn the_pocket_program_runs_through_the_rtl_controller_to_its_exact_end() {
    let dir = tempfile::tempdir().unwrap();
    let options = options(dir.path());
    let r = simulate(&example("pocket.ngc"), &options).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "pocket: {} periods, {} clocks in {:.1} s ({:.0} cycles/s), target {:?}, commanded {:?}, actual {:?}",
        r.periods,
        r.cycles,
        r.seconds,
        r.cycles as f64 / r.seconds,
        r.target,
        r.commanded,
        r.actual
    );
    let end = r.program_end.unwrap();
    assert_eq!((end.work, end.units), ([0.0, 0.0, 5.0], Units::Millimetre));
    assert_eq!(
        (end.coordinate_system, end.machine_mm),
        ("G54", [0.0, 0.0, 5.0])
    );
    assert_eq!(r.target, [0, 0, 2000]);
    assert_eq!(r.commanded.map(i64::from), r.target);
    assert_eq!(r.actual.map(i64::from), r.target);
    assert_eq!(r.underruns, 0);
    let words: Vec<&str> = r.ignored.iter().map(|i| i.word.as_str()).collect();
    assert_eq!(words, ["M6", "T1", "M3", "S12000", "M8", "M9", "M5"]);
    assert_eq!(r.figures.len(), 2);
}

/// The engraving (600 chords of about 0.3 mm, G64 reported and ignored)
/// through the RTL controller: it ends exactly where the program ends.
#[test]
fn the_engraving_program_runs_through_the_rtl_controller_to_its_exact_end() {
    let dir = tempfile::tempdir().unwrap();
    let r =
        simulate(&example("engraving.nc"), &options(dir.path())).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "engraving: {} periods, {} clocks in {:.1} s, actual {:?}",
        r.periods, r.cycles, r.seconds, r.actual
    );
    let end = r.program_end.unwrap();
    assert_eq!((end.work, end.units), ([0.0, 0.0, 2.0], Units::Millimetre));
    assert_eq!(r.target, [0, 0, 800]);
    assert_eq!(r.commanded.map(i64::from), r.target);
    assert_eq!(r.actual.map(i64::from), r.target);
    assert_eq!(r.underruns, 0);
    let words: Vec<&str> = r.ignored.iter().map(|i| i.word.as_str()).collect();
    assert_eq!(words, ["G64", "M3", "S20000", "M5", "M9"]);
}

#[test]
fn a_long_run_at_a_high_clock_is_told_the_clock_that_would_do() {
    // 40,000 periods of 1 ms at 48 MHz with at most 8 steps a period: 1.9e9
    // clocks; 8 steps of 4 clocks need 32 of the period's 48,000, so twice
    // that, 64 clocks a millisecond, is 0.07 MHz rounded up.
    let mut counts = vec![[5, -5, 0]; 40_000];
    counts[7] = [0, 0, 8];
    let mut options = options(std::path::Path::new("."));
    options.clock_hz = 48e6;
    assert_eq!(
        slow_run_hint(&counts, 1e-3, &options).unwrap(),
        "this run is 1.92e9 clocks at 48 MHz (about 64 minutes at 500,000 clocks/s); its busiest period needs \
         32 clocks of 48000, so --clock-mhz 0.07 runs the same steps 686 times sooner"
    );
    options.clock_hz = 2e6;
    assert_eq!(
        slow_run_hint(&counts, 1e-3, &options),
        None,
        "8e7 clocks: short enough"
    );
}
