//! `motion-hdl simulate`: a G-code program or a path file through the
//! simulated 3-axis controller (RTL, every step looped back into its axis's encoder, or an
//! axis run as an analog servo: its DAC drives a simulated drive and motor
//! whose encoder closes the host's position loop), with
//! optional machine-input events ([`Trip`]: an E-stop, a limit switch or a
//! drive alarm at a given time) and an optional feed hold ([`HoldWindow`]:
//! requested and released at given times). A run the controller aborts
//! fails with the cause, as the driver reports it ("motion stopped:
//! E-stop ..."). A G-code program with geared moves (G33, G33.1, G76)
//! runs on the spindle build with a simulated spindle instead (see
//! [`spindle_run`](super::spindle_run)).

use std::path::{Path as FsPath, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use super::driver::{DriverError, HoldEvent};
use super::gcode::Prober;
use super::gcode::{
    interpret_probing, interpret_with, program_text, Ignored, Message, Program, Setup, Units,
};
use super::hold_window::{
    hold_tick_settings, min_tick_divisor, rate_for_stop, speeds_at_the_pins, stop_time_s,
    stop_within_limits_s, HoldWindow,
};
use super::laser_log::BurnEnergy;
use super::laser_run::simulate_laser;
use super::machine::axis_index;
use super::planner::to_steps;
use super::servo::{DriveScale, FollowingError, PositionLoop, ServoGains};
use super::simulated_probe::{ProbePlane, ProbeResult, ProbingRun, ProbingSession};
use super::soft_window::{self, SoftWindow};
use super::spindle_run::{has_geared_moves, simulate_geared, SpindleSettings, ThreadReport};
use super::tool_table::ToolTable;
use super::ProbeSurface;
use super::{
    interpolate, plan_toolpath, Driver, DriverConfig, MachineSettings, Path, RtlBus, Toolpath,
};
use crate::blocks::motion_controller::io_model::MachinePins;
use crate::host::spi::{SpiStats, SpiTiming};
use crate::plots::{plot_following_error, plot_path_xy, plot_speed};
use crate::sim::plant::ServoMotor;
use crate::sim::Backend;

/// What a simulated file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputFormat {
    /// A G-code program (`.nc`, `.ngc`, `.gcode`, `.tap`), run on the
    /// [`MachineSettings`] of the options.
    Gcode,
    /// A `.path` file (see [`Path`]), with its own settings.
    Path,
}

impl InputFormat {
    /// The format a file's extension names, if any (case-insensitive).
    pub fn from_extension(file: &FsPath) -> Option<Self> {
        let extension = file.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "nc" | "ngc" | "gcode" | "tap" => Some(Self::Gcode),
            "path" => Some(Self::Path),
            _ => None,
        }
    }

    /// `gcode` or `path`.
    pub fn parse(name: &str) -> Result<Self, String> {
        match name.to_ascii_lowercase().as_str() {
            "gcode" => Ok(Self::Gcode),
            "path" => Ok(Self::Path),
            other => Err(format!("unknown format `{other}` (gcode or path)")),
        }
    }
}

/// Where a G-code program ends, in its own terms and the machine's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProgramEnd {
    /// The work position, in `units`, in `coordinate_system` (with the G92
    /// offset if one applies).
    pub work: [f64; 3],
    /// The program's units at its end.
    pub units: Units,
    /// The coordinate system in force at the end: "G54" to "G59.3".
    pub coordinate_system: &'static str,
    /// The machine position, mm (the toolpath's end).
    pub machine_mm: [f64; 3],
}

/// A file read for simulation: the toolpath, the machine it runs on, and
/// for G-code what the program itself says.
#[derive(Clone, Debug)]
pub struct Job {
    /// The moves, machine units.
    pub toolpath: Toolpath,
    /// The limits and resolution.
    pub machine: MachineSettings,
    /// G-code only: where the program ends.
    pub program_end: Option<ProgramEnd>,
    /// G-code only: the words that do not change motion, each once.
    pub ignored: Vec<Ignored>,
    /// G-code only: how the program ended, as a sentence.
    pub ending: Option<String>,
    /// G-code only: the active comments (MSG, DEBUG, PRINT) as they ran.
    pub messages: Vec<Message>,
    /// The items of `toolpath` its probe moves have run already (see
    /// [`Program::items_run`]); 0 without them.
    pub items_run: usize,
    /// Where the items not yet run start, mm.
    pub pending_start: [f64; 3],
}

impl Job {
    /// Reads `file` as `format` (default: from its extension); a G-code
    /// program runs on `machine` (default: [`MachineSettings::default`])
    /// with `tools` (default: none; see [`Setup::tools`]).
    pub fn read(
        file: &FsPath,
        format: Option<InputFormat>,
        machine: Option<MachineSettings>,
        tools: Option<ToolTable>,
    ) -> Result<Job, String> {
        Self::read_with(file, format, machine, tools, None)
    }

    /// [`Job::read`], a G-code program's probe moves run by `prober` as
    /// they come (without one, a probe move is an error).
    pub fn read_with(
        file: &FsPath,
        format: Option<InputFormat>,
        machine: Option<MachineSettings>,
        tools: Option<ToolTable>,
        prober: Option<Box<dyn Prober>>,
    ) -> Result<Job, String> {
        let format = format.or_else(|| InputFormat::from_extension(file)).ok_or_else(|| {
            format!(
                "{}: unknown file type: G-code ends in .nc, .ngc, .gcode or .tap, a path file in .path (or give --format)",
                file.display()
            )
        })?;
        let bytes =
            std::fs::read(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
        let located = |e: &dyn std::fmt::Display| format!("{}: {e}", file.display());
        let text = match format {
            InputFormat::Gcode => program_text(&bytes).map_err(|e| located(&e))?,
            InputFormat::Path => std::str::from_utf8(&bytes)
                .map(std::borrow::Cow::Borrowed)
                .map_err(|e| format!("cannot read {}: not UTF-8 text: {e}", file.display()))?,
        };
        match format {
            InputFormat::Path => {
                if machine.is_some() {
                    return Err(format!(
                        "{}: machine settings apply to G-code; a path file carries its own",
                        file.display()
                    ));
                }
                if tools.is_some() {
                    return Err(format!(
                        "{}: a tool table applies to G-code only",
                        file.display()
                    ));
                }
                let path = Path::parse(&text).map_err(|e| located(&e))?;
                let toolpath = path.toolpath();
                Ok(Job {
                    pending_start: toolpath.start,
                    items_run: 0,
                    toolpath,
                    machine: path.machine(),
                    program_end: None,
                    ignored: Vec::new(),
                    ending: None,
                    messages: Vec::new(),
                })
            }
            InputFormat::Gcode => {
                let machine = machine.unwrap_or_default();
                machine.validate().map_err(|e| located(&e))?;
                let setup = Setup {
                    start: [0.0; 3],
                    parameters: machine.parameters,
                    tools,
                    laser_s_max: machine.laser(),
                    ..Setup::default()
                };
                let (program, ending) = run_gcode_with(file, &text, &setup, prober)?;
                Ok(Job {
                    items_run: program.items_run,
                    pending_start: program.pending_start,
                    toolpath: program.toolpath,
                    machine,
                    program_end: Some(ProgramEnd {
                        work: program.final_position,
                        units: program.units,
                        coordinate_system: program.coordinate_system,
                        machine_mm: program.final_machine,
                    }),
                    ignored: program.ignored,
                    ending: Some(ending),
                    messages: program.messages,
                })
            }
        }
    }
}

/// Interprets G-code `text` read from `file` with `setup`: the program
/// and how it ended, as a sentence. A program without motion is an error;
/// every error names the file.
pub fn run_gcode(file: &FsPath, text: &str, setup: &Setup) -> Result<(Program, String), String> {
    run_gcode_with(file, text, setup, None)
}

/// [`run_gcode`] with a [`Prober`] for the probe moves.
pub fn run_gcode_with(
    file: &FsPath,
    text: &str,
    setup: &Setup,
    prober: Option<Box<dyn Prober>>,
) -> Result<(Program, String), String> {
    let program = match prober {
        Some(prober) => interpret_probing(text, setup, prober),
        None => interpret_with(text, setup),
    }
    .map_err(|e| format!("{}: {e}", file.display()))?;
    if program.toolpath.items.is_empty() {
        return Err(format!("{}: the program has no motion", file.display()));
    }
    let ending = match (program.end, program.blocks_after_end, program.closing_percent) {
        (Some(line), 0, _) => format!("M2 or M30 on line {line}"),
        (Some(line), n, _) => format!("M2 or M30 on line {line}; {n} blocks after it not run"),
        (None, _, Some(line)) => format!("the closing % on line {line}"),
        (None, _, None) => {
            "end of file without M2, M30 or a closing % (the program ends there; LinuxCNC would refuse the file)"
                .to_string()
        }
    };
    Ok((program, ending))
}

/// A G-code file's text: UTF-8, or Latin-1 in comments ([`program_text`]).
pub fn read_gcode_text(file: &FsPath) -> Result<String, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    program_text(&bytes)
        .map(|t| t.into_owned())
        .map_err(|e| format!("{}: {e}", file.display()))
}

/// Settings of a simulation run.
#[derive(Clone, Debug)]
pub struct SimulationOptions {
    /// The file's format (default: from its extension).
    pub format: Option<InputFormat>,
    /// The machine a G-code program runs on (default:
    /// [`MachineSettings::default`]); a path file carries its own.
    pub machine: Option<MachineSettings>,
    /// A G-code program's tool table (default: none).
    pub tools: Option<ToolTable>,
    /// System clock, Hz (sets the clocks per interpolation period).
    pub clock_hz: f64,
    /// Per axis: the uniform pulse generator instead of the DDA.
    pub uniform: [bool; 3],
    /// Per axis: an analog servo (the `motion_controller_servo` build, the
    /// default [`ServoMotor`], [`ServoGains`] and [`DriveScale`]: the path's
    /// steps are the motor's encoder counts).
    pub servo: [bool; 3],
    /// Step pulse high time, clocks (also the direction setup and hold).
    pub step_len: u32,
    /// Minimum step low time, clocks.
    pub step_space: u32,
    /// Folder for the SVG figures (none: no figures).
    pub out_dir: Option<PathBuf>,
    /// Write every signal of the controller to this VCD file.
    pub vcd: Option<PathBuf>,
    /// Show a progress bar.
    pub progress: bool,
    /// The simulator of the controller.
    pub backend: Backend,
    /// Machine inputs that go active during the run.
    pub trips: Vec<Trip>,
    /// A feed hold the driver requests and releases during the run (the
    /// controller scales the analog axes' codes with it).
    pub hold: Option<HoldWindow>,
    /// A simulated probe against a plane, for a G-code program's probe
    /// moves (G38.2 to G38.5; step axes only, without a hold).
    pub probe_plane: Option<ProbePlane>,
    /// Per axis: a soft-limit window (step axes only; the controller stops
    /// the path inside it at the hold's rate, and the run fails naming
    /// where it stood).
    pub soft_limits: [Option<SoftWindow>; 3],
    /// The simulated spindle, for geared moves (G33, G33.1, G76).
    pub spindle: SpindleSettings,
    /// With an SCLK rate (Hz), the driver reaches the controller through
    /// `spi_bus_adapter` over a simulated SPI link at that rate, at most a
    /// quarter of the clock (`simulate --bus spi`); without, through the
    /// parallel register bus.
    pub spi_sclk_hz: Option<f64>,
}

/// A machine input the simulation drives active (high: tripped, in alarm,
/// stopped) from a given time on, until the end of the run.
#[derive(Clone, Debug, PartialEq)]
pub struct Trip {
    /// When, in seconds of simulated time from power-up (the driver's
    /// configuration takes the first few hundred clocks).
    pub at_s: f64,
    /// The pins it raises (bit k of a per-axis input: axis k).
    pub pins: MachinePins,
}

impl Trip {
    /// Parses `INPUT@MS`: `estop`, or an axis (`x`, `y`, `z`) and one of
    /// `limit-pos`, `limit-neg`, `alarm` (`y-limit-neg@1.5`), active from
    /// that many milliseconds on.
    pub fn parse(text: &str) -> Result<Trip, String> {
        let usage = "estop, or x|y|z-limit-pos, -limit-neg or -alarm, then @ and milliseconds (y-limit-neg@1.5)";
        let (input, ms) = text
            .split_once('@')
            .ok_or_else(|| format!("--trip `{text}`: expected INPUT@MS: {usage}"))?;
        let ms: f64 = ms
            .trim_end_matches("ms")
            .parse()
            .ok()
            .filter(|ms: &f64| ms.is_finite() && *ms >= 0.0)
            .ok_or_else(|| format!("--trip `{text}`: `{ms}` is not a time in milliseconds"))?;
        let input = input.to_ascii_lowercase();
        let mut pins = MachinePins::default();
        if input == "estop" {
            pins.estop = true;
        } else {
            let (axis, what) = input
                .split_once('-')
                .ok_or_else(|| format!("--trip `{text}`: unknown input `{input}`: {usage}"))?;
            let bit = 1
                << axis_index(axis)
                    .ok_or_else(|| format!("--trip `{text}`: unknown axis `{axis}` (x, y or z)"))?;
            match what {
                "limit-pos" => pins.limit_pos = bit,
                "limit-neg" => pins.limit_neg = bit,
                "alarm" => pins.drive_alarm = bit,
                _ => return Err(format!("--trip `{text}`: unknown input `{input}`: {usage}")),
            }
        }
        Ok(Trip {
            at_s: ms * 1e-3,
            pins,
        })
    }
}

/// Each trip's time with the pins from then on (a trip stays active), in
/// time order.
fn trip_schedule(trips: &[Trip]) -> Vec<(f64, MachinePins)> {
    let mut sorted: Vec<&Trip> = trips.iter().collect();
    sorted.sort_by(|a, b| a.at_s.total_cmp(&b.at_s));
    let mut pins = MachinePins::default();
    sorted
        .into_iter()
        .map(|t| {
            pins.limit_pos |= t.pins.limit_pos;
            pins.limit_neg |= t.pins.limit_neg;
            pins.home |= t.pins.home;
            pins.drive_alarm |= t.pins.drive_alarm;
            pins.estop |= t.pins.estop;
            pins.gpio_in |= t.pins.gpio_in;
            (t.at_s, pins)
        })
        .collect()
}

/// What a simulation run found.
#[derive(Clone, Debug)]
pub struct SimulationReport {
    /// The path's end, steps.
    pub target: [i64; 3],
    /// G-code: where the program ends.
    pub program_end: Option<ProgramEnd>,
    /// G-code: the words ignored because they do not change motion.
    pub ignored: Vec<Ignored>,
    /// G-code: how the program ended, as a sentence.
    pub ending: Option<String>,
    /// G-code only: the active comments (MSG, DEBUG, PRINT) as they ran.
    pub messages: Vec<Message>,
    /// Final commanded positions (steps emitted), per axis.
    pub commanded: [i32; 3],
    /// Final actual (encoder) positions.
    pub actual: [i32; 3],
    /// Peak step rate per axis at the pins, steps per second, over 10 ms
    /// windows.
    pub peak_rate: [f64; 3],
    /// Per analog servo axis: its following error, counts.
    pub following: [Option<FollowingError>; 3],
    /// Periods the servo loops held the end before they settled.
    pub settle_periods: usize,
    /// Underruns while periods were still to come.
    pub underruns: usize,
    /// Interpolation periods.
    pub periods: usize,
    /// Clock cycles simulated.
    pub cycles: u64,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Figures written.
    pub figures: Vec<PathBuf>,
    /// With a feed hold: what it did.
    pub hold: Option<HoldReport>,
    /// With `probe_plane`: each probe move (G38.2 to G38.5) as it ran.
    pub probes: Vec<ProbeResult>,
    /// The simulated probe's plane, if any.
    pub probe_plane: Option<ProbePlane>,
    /// The machine's steps per mm.
    pub steps_per_mm: [f64; 3],
    /// The threads of geared moves (G33, G76), each with its lead error
    /// and pass phase spread.
    pub threads: Vec<ThreadReport>,
    /// On a laser machine: each burn's energy per mm at the pins.
    pub burns: Vec<BurnEnergy>,
    /// Over SPI (`spi_sclk_hz`): the link's traffic and time.
    pub spi: Option<SpiReport>,
}

/// What the SPI link carried in a run, and its share of the period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpiReport {
    /// The SCLK the master ran (at or below the rate asked: whole clocks
    /// per phase).
    pub sclk_hz: f64,
    /// Frames, bytes and clocks.
    pub stats: SpiStats,
    /// Seconds of frames per period, on average over the run.
    pub seconds_per_period: f64,
    /// The interpolation period, seconds.
    pub period_s: f64,
}

impl SpiReport {
    /// The report of `bus`'s link over `periods` periods of `period_s`.
    pub fn of(bus: &RtlBus, clock_hz: f64, periods: usize, period_s: f64) -> Option<SpiReport> {
        let (stats, timing) = (bus.spi_stats()?, bus.spi_timing()?);
        Some(SpiReport {
            sclk_hz: timing.sclk_hz(clock_hz),
            stats,
            seconds_per_period: stats.clocks as f64 / clock_hz / periods.max(1) as f64,
            period_s,
        })
    }

    /// The share of the period the frames take.
    pub fn period_share(&self) -> f64 {
        self.seconds_per_period / self.period_s
    }
}

impl std::fmt::Display for SpiReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "SPI bus at SCLK {:.3} MHz: {} frames, {} bytes; {:.1} us of frames per {:.0} us period on average ({:.1} % of the period budget)",
            self.sclk_hz / 1e6,
            self.stats.frames,
            self.stats.bytes,
            self.seconds_per_period * 1e6,
            self.period_s * 1e6,
            100.0 * self.period_share()
        )
    }
}

/// What a simulated feed hold did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoldReport {
    /// `HOLD_CONTROL.RATE` programmed.
    pub rate: u32,
    /// `TICK_DIVISOR` of the run (raised for a slow stop; see
    /// [`HoldWindow`]).
    pub tick_divisor: u32,
    /// A stop from full speed at that rate, seconds.
    pub full_stop_s: f64,
    /// When `HOLD` was written, seconds from power-up; `None` when the run
    /// had ended before.
    pub requested_s: Option<f64>,
    /// When the driver saw the path stand (`STATUS.HELD`); `None` when the
    /// release came first or the path ended before the stop.
    pub stood_s: Option<f64>,
    /// When `RELEASE` was written; `None` when the run had ended before.
    pub released_s: Option<f64>,
    /// The highest path speed at the pins after the release (10 ms
    /// windows), in the plan's units per second.
    pub peak_speed_after: f64,
    /// The plan's highest path speed, in its units per second.
    pub planned_peak_speed: f64,
}

impl HoldReport {
    /// What `hold` did in a run of `cycles` clocks at `clock_hz`, at
    /// `rate` on a tick of `tick_divisor` clocks: `held` holds the clocks
    /// the driver saw `STATUS.HELD`, `speeds` the path speed at the pins
    /// per period of `period_s`; the plan's peak speed beside.
    pub fn measured(
        hold: &HoldWindow,
        (rate, tick_divisor): (u32, u32),
        clock_hz: f64,
        (cycles, held): (u64, &[u64]),
        speeds: &[f64],
        (period_s, planned_peak_speed): (f64, f64),
    ) -> Self {
        let events = hold.events(clock_hz);
        let at = |e: &HoldEvent| (e.clock <= cycles).then_some(e.clock as f64 / clock_hz);
        let after = (hold.resume_at_s / period_s) as usize;
        HoldReport {
            rate,
            tick_divisor,
            full_stop_s: stop_time_s(rate, clock_hz / tick_divisor as f64),
            requested_s: at(&events[0]),
            stood_s: held.first().map(|&c| c as f64 / clock_hz),
            released_s: at(&events[1]),
            peak_speed_after: speeds.iter().skip(after).copied().fold(0.0, f64::max),
            planned_peak_speed,
        }
    }
}

/// Clocks per base tick and base ticks per period for `period_s` at
/// `clock_hz`: the smallest divisor that fits the 16-bit period register
/// and divides the period exactly.
pub fn period_settings(period_s: f64, clock_hz: f64) -> Result<(u32, u32), String> {
    period_settings_from(period_s, clock_hz, 1)
}

/// [`period_settings`] with a tick divisor of at least `min_divisor`.
pub fn period_settings_from(
    period_s: f64,
    clock_hz: f64,
    min_divisor: u64,
) -> Result<(u32, u32), String> {
    let clocks = (period_s * clock_hz).round();
    if !(2.0..=4e9).contains(&clocks) {
        return Err(format!(
            "a period of {period_s} s is {clocks} clocks at {clock_hz} Hz"
        ));
    }
    let clocks = clocks as u64;
    let first = clocks.div_ceil(65_535).max(min_divisor).max(1);
    (first..=clocks)
        .find(|d| clocks.is_multiple_of(*d) && clocks / d <= 65_535)
        .map(|d| (d as u32, (clocks / d) as u32))
        .ok_or_else(|| format!("no tick divisor splits {clocks} clocks into at most 65535 ticks"))
}

/// The most periods a simulation plans (2.8 hours at 1 ms, about 800 MB
/// of per-period counts, positions and speeds): a longer program is
/// refused before they are allocated.
pub const MAX_PERIODS: u64 = 10_000_000;

/// Clocks a run may take before [`slow_run_hint`] suggests a lower clock
/// (about 3 minutes on the compiled backend).
pub const SLOW_RUN_CLOCKS: f64 = 1e8;

/// For a run of more than [`SLOW_RUN_CLOCKS`] at `options.clock_hz`: the
/// lowest clock (to 0.01 MHz, twice what the busiest period's steps need
/// at step_len + step_space clocks a step, or two ticks a step on a
/// uniform axis) that runs the same counts, as a sentence. `None` when the
/// run is short or the clock is already that low.
pub fn slow_run_hint(
    counts: &[[i32; 3]],
    period: f64,
    options: &SimulationOptions,
) -> Option<String> {
    let clocks = counts.len() as f64 * period * options.clock_hz;
    if clocks <= SLOW_RUN_CLOCKS {
        return None;
    }
    let per_step = (options.step_len.max(1) + options.step_space.max(1)) as f64;
    let needed = (0..3)
        .map(|k| {
            let peak = counts
                .iter()
                .map(|c| c[k].unsigned_abs())
                .max()
                .unwrap_or(0) as f64;
            let per_step = if options.uniform[k] {
                per_step.max(2.0)
            } else {
                per_step
            };
            peak * per_step
        })
        .fold(1.0, f64::max);
    let mhz = ((2.0 * needed / period / 1e6) * 100.0).ceil() / 100.0;
    (mhz < options.clock_hz / 1e6).then(|| {
        format!(
            "this run is {:.2e} clocks at {} MHz (about {:.0} minutes at 500,000 clocks/s); \
             its busiest period needs {needed:.0} clocks of {:.0}, \
             so --clock-mhz {mhz} runs the same steps {:.0} times sooner",
            clocks,
            options.clock_hz / 1e6,
            clocks / 5e5 / 60.0,
            period * options.clock_hz,
            options.clock_hz / 1e6 / mhz
        )
    })
}

/// Refuses the combinations of options the simulation does not run.
fn check_options(options: &SimulationOptions) -> Result<(), String> {
    let servo = options.servo.iter().any(|&s| s);
    if let Some(axis) = (0..3).find(|&k| options.servo[k] && options.uniform[k]) {
        return Err(format!(
            "axis {} cannot be both uniform and an analog servo",
            ["x", "y", "z"][axis]
        ));
    }
    if servo && options.probe_plane.is_some() {
        return Err("--probe-plane: the probe moves run as step paths, not through the servo loops of --servo; probe without --servo".into());
    }
    if options.hold.is_some() && options.probe_plane.is_some() {
        return Err(
            "--probe-plane and --hold-at: both program the feed hold; give one of them".into(),
        );
    }
    if let Some(w) = options
        .soft_limits
        .iter()
        .flatten()
        .find(|w| options.servo[w.axis])
    {
        return Err(format!(
            "--soft-limit {}: an analog servo axis (--servo) is never checked; soft limits are for step axes",
            ["x", "y", "z"][w.axis]
        ));
    }
    if options.soft_limits.iter().any(Option::is_some) && options.probe_plane.is_some() {
        return Err("--soft-limit and --probe-plane: the probe moves program the feed hold's rate move by move; give one of them".into());
    }
    if servo && options.uniform.iter().any(|&u| u) {
        return Err("--uniform needs the motion_controller build, --servo the motion_controller_servo build (DDA only): use one of them".into());
    }
    Ok(())
}

/// The driver's settings for `options` at these tick settings.
pub(super) fn driver_config(
    options: &SimulationOptions,
    tick_divisor: u32,
    period_ticks: u32,
    soft_limits: [Option<(i32, i32)>; 3],
) -> DriverConfig {
    DriverConfig {
        tick_divisor,
        period_ticks,
        step_len: options.step_len,
        step_space: options.step_space,
        dir_time: options.step_len.max(1),
        uniform: options.uniform,
        analog: options.servo,
        soft_limits,
    }
}

/// The first option of `options` a DDA-only build without soft limits
/// cannot run (the spindle and laser builds): `--uniform`, `--servo`,
/// `--soft-limit`, `--hold` (unless `hold_runs`) or `--probe-plane`.
pub(super) fn option_beyond_dda_build(
    options: &SimulationOptions,
    hold_runs: bool,
) -> Option<&'static str> {
    [
        ("--uniform", options.uniform.iter().any(|&u| u)),
        ("--servo", options.servo.iter().any(|&s| s)),
        (
            "--soft-limit",
            options.soft_limits.iter().any(Option::is_some),
        ),
        ("--hold", options.hold.is_some() && !hold_runs),
        ("--probe-plane", options.probe_plane.is_some()),
    ]
    .into_iter()
    .find_map(|(name, set)| set.then_some(name))
}

/// What a simulated run records and drives on `bus`: the positions once a
/// period, the peak step rates over 10 ms, and the trips of `options`.
pub(super) fn watch_the_run(
    bus: &mut RtlBus,
    options: &SimulationOptions,
    tick_divisor: u32,
    period_ticks: u32,
) -> Result<(), String> {
    if let Some(sclk_hz) = options.spi_sclk_hz {
        let timing = SpiTiming::at(options.clock_hz, sclk_hz).map_err(|e| e.to_string())?;
        bus.use_spi(options.backend, timing)
            .map_err(|e| e.to_string())?;
    }
    bus.sample_positions(tick_divisor as u64 * period_ticks as u64);
    // 10 ms windows: at a real clock, 10,000 clocks hold only a step or two.
    bus.set_rate_window((options.clock_hz / 100.0).round() as u64);
    for (at_s, pins) in trip_schedule(&options.trips) {
        bus.set_pins_at((at_s * options.clock_hz).round() as u64, pins);
    }
    Ok(())
}

/// The driver of a simulated controller for `options`, at these tick
/// settings, programmed; with `surface`, the probe pin follows it.
fn controller_driver(
    options: &SimulationOptions,
    tick_divisor: u32,
    period_ticks: u32,
    surface: Option<ProbeSurface>,
    soft_limits: [Option<(i32, i32)>; 3],
) -> Result<Driver<RtlBus>, String> {
    let config = driver_config(options, tick_divisor, period_ticks, soft_limits);
    let mut bus = if options.servo.iter().any(|&s| s) {
        let motors = options.servo.map(|s| s.then(ServoMotor::default));
        RtlBus::with_servos(
            options.backend,
            options.vcd.as_deref(),
            motors,
            DriveScale::default(),
            options.clock_hz,
        )
    } else {
        RtlBus::new(options.backend, options.vcd.as_deref())
    }
    .map_err(|e| e.to_string())?;
    watch_the_run(&mut bus, options, tick_divisor, period_ticks)?;
    bus.set_probe_surface(surface);
    Driver::new(bus, config).map_err(|e| e.to_string())
}

/// Interprets a G-code program whose probe moves run on the simulated
/// controller as they come, against `plane` (see [`simulated_probe`]
/// (super::simulated_probe)); the probe moves stop at the rate that
/// stops every axis from its maximum velocity within its maximum
/// acceleration. Returns the job and the run so far.
fn run_probe_moves(
    path_file: &FsPath,
    options: &SimulationOptions,
    plane: ProbePlane,
) -> Result<(Job, ProbingRun), String> {
    let format = options
        .format
        .or_else(|| InputFormat::from_extension(path_file));
    if format == Some(InputFormat::Path) {
        return Err(format!(
            "{}: --probe-plane runs a G-code program's probe moves (G38.2 to G38.5); a path file has none",
            path_file.display()
        ));
    }
    let machine = options.machine.unwrap_or_default();
    let stop_s = stop_within_limits_s(&machine, 0.0, machine.max_velocity);
    let min_divisor = min_tick_divisor(stop_s, options.clock_hz);
    let (tick_divisor, period_ticks) =
        period_settings_from(machine.period, options.clock_hz, min_divisor)?;
    let surface = plane.surface([0.0; 3], machine.steps_per_mm);
    let driver = controller_driver(
        options,
        tick_divisor,
        period_ticks,
        Some(surface),
        [None; 3],
    )?;
    let session = ProbingSession::new(driver, machine, options.clock_hz, [0.0; 3]);
    let job = Job::read_with(
        path_file,
        options.format,
        options.machine,
        options.tools.clone(),
        Some(session.prober()),
    )?;
    Ok((job, session.finish()))
}

/// Runs `path_file` (G-code or a path file) through the RTL controller.
pub fn simulate(
    path_file: &FsPath,
    options: &SimulationOptions,
) -> Result<SimulationReport, String> {
    check_options(options)?;
    let started = Instant::now();
    let (job, probed) = match options.probe_plane {
        None => {
            let job = Job::read(
                path_file,
                options.format,
                options.machine,
                options.tools.clone(),
            )?;
            if job.machine.laser().is_some() {
                return simulate_laser(path_file, options, job);
            }
            if has_geared_moves(&job.toolpath) {
                return simulate_geared(path_file, options, job);
            }
            (job, None)
        }
        Some(plane) => {
            let (job, probed) = run_probe_moves(path_file, options, plane)?;
            (job, Some(probed))
        }
    };
    let machine = job.machine;
    let start = to_steps(job.toolpath.start, machine.steps_per_mm);
    let target = to_steps(job.toolpath.end(), machine.steps_per_mm);
    // What the probe moves have not run yet: the whole program without.
    let rest = Toolpath {
        start: job.pending_start,
        items: job.toolpath.items[job.items_run..].to_vec(),
        ..job.toolpath.clone()
    };
    let segments =
        plan_toolpath(&rest, &machine).map_err(|e| format!("{}: {e}", path_file.display()))?;
    let seconds: f64 = segments.iter().map(|s| s.duration()).sum();
    let periods = seconds / machine.period;
    if periods.is_nan() || periods > MAX_PERIODS as f64 {
        return Err(format!(
            "{}: the program takes {seconds:.0} s, more than {MAX_PERIODS} periods of {} s",
            path_file.display(),
            machine.period
        ));
    }
    let rest_start = to_steps(rest.start, machine.steps_per_mm);
    let interpolation = interpolate(rest_start, &segments, machine.period);
    let planned_peak_speed = interpolation.speeds.iter().copied().fold(0.0, f64::max);
    let peak_axis_speed: [f64; 3] = std::array::from_fn(|k| {
        let steps = interpolation
            .counts
            .iter()
            .map(|c| c[k].unsigned_abs())
            .max();
        steps.unwrap_or(0) as f64 / machine.steps_per_mm[k] / machine.period
    });
    let stop_s = stop_within_limits_s(&machine, planned_peak_speed, peak_axis_speed);
    if options.progress {
        if let Some(hint) = slow_run_hint(&interpolation.counts, machine.period, options) {
            eprintln!("motion-hdl: {hint}");
        }
    }
    let servo = options.servo.iter().any(|&s| s);
    let soft = options.soft_limits.iter().any(Option::is_some);
    let mut windows = [None; 3];
    for (k, window) in options.soft_limits.iter().enumerate() {
        if let Some(w) = window {
            windows[k] = Some(w.steps(machine.steps_per_mm[k], start[k])?);
        }
    }
    let (mut driver, prior) = match probed {
        Some(probed) => (
            probed.driver,
            Some((probed.run, probed.underruns, probed.probes)),
        ),
        None => {
            let machine_rate = match options.hold {
                Some(h) => h.rate.is_none(),
                None => soft,
            };
            let (tick_divisor, period_ticks) = match machine_rate {
                // The machine's stop: the tick whose RATE comes closest.
                true => {
                    let needed = (0..3)
                        .map(|k| {
                            let peak = interpolation.counts.iter().map(|c| c[k].unsigned_abs());
                            let per_step = if options.uniform[k] { 2 } else { 1 };
                            peak.max().unwrap_or(0) as u64 * per_step
                        })
                        .max()
                        .unwrap_or(0);
                    hold_tick_settings(machine.period, options.clock_hz, stop_s, needed)?
                }
                false => period_settings(machine.period, options.clock_hz)?,
            };
            (
                controller_driver(options, tick_divisor, period_ticks, None, windows)?,
                None,
            )
        }
    };
    let (prior, prior_underruns, probes) = prior.unwrap_or_default();
    let period_clocks = driver.period_clocks();
    let tick_divisor = driver.tick_divisor();
    let period_s = period_clocks as f64 / options.clock_hz;
    let tick_hz = options.clock_hz / tick_divisor as f64;
    // The soft limits stop at the hold's rate, or the machine's stop.
    let hold_rate = match options.hold {
        Some(h) => Some(h.rate(stop_s, tick_hz)),
        None if soft => Some(rate_for_stop(stop_s, tick_hz)),
        None => None,
    };
    let hold_events: Vec<HoldEvent> = options
        .hold
        .map_or(Vec::new(), |h| h.events(options.clock_hz).to_vec());
    if let Some(rate) = hold_rate {
        driver.set_hold_rate(rate).map_err(|e| e.to_string())?;
    }
    // The controller starts at 0: the counts move it by (end - start).
    let bar = if options.progress {
        let bar = ProgressBar::new(interpolation.counts.len() as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} periods ({per_sec})",
            )
            .map_err(|e| e.to_string())?,
        );
        Some(bar)
    } else {
        None
    };
    let show = |queued: usize| {
        if let Some(bar) = &bar {
            bar.set_position(queued as u64);
        }
    };
    let mut following = [None; 3];
    let mut errors = Vec::new();
    let mut settle_periods = 0;
    let report = if servo {
        let mut loops: [Option<PositionLoop>; 3] = [None, None, None];
        for k in 0..3 {
            if options.servo[k] {
                loops[k] = Some(
                    PositionLoop::new(ServoGains::default(), DriveScale::default(), period_s)
                        .map_err(|e| e.to_string())?,
                );
            }
        }
        driver
            .run_servo_with_holds(
                &interpolation.counts,
                &mut loops,
                period_s,
                &hold_events,
                show,
            )
            .map(|r| {
                following = r.following;
                errors = r.errors;
                settle_periods = r.settle_periods;
                r.run
            })
    } else {
        driver.run_with_holds(&interpolation.counts, &hold_events, show)
    };
    if let Some(bar) = &bar {
        if report.is_err() {
            bar.abandon();
        }
    }
    // An abort: the driver names the cause ("motion stopped: E-stop ...");
    // a soft limit: where the path stood, in mm.
    let report = report.map_err(|e| match e {
        DriverError::SoftLimit {
            axis,
            negative,
            commanded,
            periods_queued,
            periods,
        } => match &options.soft_limits[axis] {
            Some(window) => {
                let stood_mm = std::array::from_fn(|k| {
                    (commanded[k] as i64 + start[k]) as f64 / machine.steps_per_mm[k]
                });
                soft_window::tripped_line(window, negative, stood_mm, periods_queued, periods)
            }
            None => e.to_string(),
        },
        e => e.to_string(),
    })?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(bar) = bar {
        bar.finish();
    }
    let bus = driver.bus();
    // The probe moves' periods, then the rest's.
    let mut planned_run = prior;
    planned_run
        .positions
        .extend_from_slice(&interpolation.positions);
    planned_run.speeds.extend_from_slice(&interpolation.speeds);
    let offset = |p: [i64; 3]| [p[0] + start[0], p[1] + start[1], p[2] + start[2]];
    // Through a hold: the path speed at the pins, 10 ms windows.
    let pin_speeds = options.hold.map(|_| {
        let window = (0.01 / period_s).round() as usize;
        speeds_at_the_pins(bus.samples(), machine.steps_per_mm, period_s, window)
    });
    let mut figures = Vec::new();
    if let Some(dir) = &options.out_dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let stem = path_file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("path");
        let xy = dir.join(format!("{stem}-path.svg"));
        let unit = if job.program_end.is_some() || machine.steps_per_mm != [1.0; 3] {
            "mm"
        } else {
            "steps"
        };
        // In the program's units (steps for a path file in steps).
        let units = |p: [i64; 3]| -> [f64; 3] {
            std::array::from_fn(|k| p[k] as f64 / machine.steps_per_mm[k])
        };
        let measured: Vec<[f64; 3]> = bus.samples().iter().map(|&p| units(offset(p))).collect();
        let planned: Vec<[f64; 3]> = std::iter::once(start)
            .chain(planned_run.positions.iter().copied())
            .map(units)
            .collect();
        plot_path_xy(&planned, &measured, unit, &xy).map_err(|e| e.to_string())?;
        let speed = dir.join(format!("{stem}-speed.svg"));
        plot_speed(
            &planned_run.speeds,
            pin_speeds
                .as_deref()
                .map(|m| ("at the pins, through the feed hold (10 ms windows)", m)),
            machine.period,
            &format!("{unit}/s"),
            &speed,
        )
        .map_err(|e| e.to_string())?;
        figures = vec![xy, speed];
        if servo {
            let names = ["x", "y", "z"];
            let axes: Vec<(usize, &str)> = (0..3)
                .filter(|&k| options.servo[k])
                .map(|k| (k, names[k]))
                .collect();
            let fe = dir.join(format!("{stem}-following-error.svg"));
            plot_following_error(
                &errors,
                &axes,
                "Following error of the analog servo axes",
                period_s,
                &fe,
            )
            .map_err(|e| e.to_string())?;
            figures.push(fe);
        }
    }
    let hold = options.hold.zip(pin_speeds).map(|(h, speeds)| {
        HoldReport::measured(
            &h,
            (hold_rate.unwrap_or(0), tick_divisor),
            options.clock_hz,
            (report.cycles, &report.held),
            &speeds,
            (period_s, planned_peak_speed),
        )
    });
    let to_path = |p: [i32; 3]| offset(p.map(i64::from));
    let commanded = to_path(report.commanded);
    let actual = to_path(report.actual);
    Ok(SimulationReport {
        target,
        program_end: job.program_end,
        ignored: job.ignored,
        ending: job.ending,
        messages: job.messages,
        commanded: commanded.map(|v| v as i32),
        actual: actual.map(|v| v as i32),
        peak_rate: bus.peak_steps_per_clock().map(|r| r * options.clock_hz),
        following,
        settle_periods,
        underruns: report.underruns + prior_underruns,
        periods: report.periods + planned_run.counts.len(),
        cycles: report.cycles,
        seconds,
        figures,
        hold,
        probes,
        probe_plane: options.probe_plane,
        steps_per_mm: machine.steps_per_mm,
        threads: Vec::new(),
        burns: Vec::new(),
        spi: SpiReport::of(
            bus,
            options.clock_hz,
            report.periods + planned_run.counts.len(),
            period_s,
        ),
    })
}
