//! `simulate` for a program with geared moves (G33, G33.1, G76): the
//! spindle build (`motion_controller_dda_spindle`) with a simulated
//! spindle ([`SpindleMotor`]) on its encoder pins.
//!
//! The toolpath runs in order: the moves between two geared moves are
//! planned and streamed as one run, which ends with the axes at rest;
//! then the driver commands the spindle, waits until `SPINDLE_SPEED`
//! reads the speed (within the ripple and 5 %), and runs the geared move
//! on the gearbox ([`Driver::gear_run`]). The cutting load dips the
//! spindle while the gearbox is engaged. Each geared move is recorded at
//! the pins ([`GearLog`]) and measured against pitch x spindle angle
//! ([`ThreadFigures`]); the passes of one thread (a G76, or G33 moves with
//! the same start along their axis and the same pitch) are measured
//! together.
//!
//! **The gearbox's settings for a move** ([`gear_settings`]): the ratio
//! n/d = pitch x steps per mm / counts per revolution (exact for a ratio
//! whose denominator fits 24 bits, else the nearest such fraction); the
//! ramp, the largest rate change per count that keeps the axis within its
//! `max_accel` at the fastest spindle (the programmed S with the ripple
//! on top), at most d - n so that the gearbox can catch up and lock; the
//! length, the move's steps.
//!
//! **G33.1** (rigid tap): the gearbox is armed for the depth and ten
//! revolutions more (LinuxCNC's allowance). At the depth the spindle is
//! commanded in reverse; the axis follows it through the stop and back
//! out. At the start the spindle is commanded forward again, and where it
//! stands still (the axis with it) the driver halts the gearbox. A rapid
//! then places the axis at the start exactly.
//!
//! Refused before the run, by line: a machine without a spindle encoder;
//! a pitch needing more than one step per spindle count; a pitch that
//! at S (with the ripple) moves the axis beyond its `max_velocity`; a
//! spindle that counts faster than the gearbox takes counts (one per 31
//! clocks); a move longer than `GEAR_LENGTH` holds.

use std::path::Path as FsPath;
use std::time::Instant;

use super::driver::{GearAction, GearReport, GearRun, GEAR_POLL_CLOCKS};
use super::interpolator::interpolate;
use super::planner::{plan_toolpath, to_steps};
use super::simulation::{
    driver_config, option_beyond_dda_build, period_settings, watch_the_run, Job, SimulationOptions,
    SimulationReport, SpiReport,
};
use super::thread_log::{GearLog, PassErrors, ThreadFigures};
use super::toolpath::{Item, LaserPower, Move, MoveKind, SyncedMove, Toolpath};
use super::{ControllerBus, Driver, MachineSettings, RtlBus};
use crate::blocks::electronic_gearbox::model::ENGINE_CLOCKS;
use crate::sim::plant::SpindleMotor;

/// The widest ratio, ramp and length words of the export (W = L = 24).
pub const GEAR_WORD_MAX: u64 = (1 << 24) - 1;

/// The fewest clocks between two spindle counts the gearbox takes.
pub const CLOCKS_PER_COUNT: u64 = ENGINE_CLOCKS as u64 + 1;

/// The lag a ramp-in may leave is bounded by the lag register: ramp x
/// 2^(E - W - 1) >= n (E = 40, W = 24).
const RAMP_SHIFT: u32 = 15;

/// The simulated spindle's behaviour (see [`SpindleMotor`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpindleSettings {
    /// Speed ripple, a fraction (0.1: ±10 %).
    pub ripple: f64,
    /// Speed dip under the cutting load, a fraction.
    pub load_dip: f64,
}

impl Default for SpindleSettings {
    /// ±10 % ripple, a 5 % dip.
    fn default() -> Self {
        Self {
            ripple: 0.1,
            load_dip: 0.05,
        }
    }
}

/// A geared move as the gearbox will run it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GearSettings {
    /// The registers.
    pub run: GearRun,
    /// Steps per spindle revolution.
    pub steps_per_rev: f64,
    /// The fastest count rate expected, counts per second.
    pub count_rate: f64,
}

/// One thread's figures: its passes measured together.
#[derive(Clone, Debug, PartialEq)]
pub struct ThreadReport {
    /// The line of its first pass.
    pub line: usize,
    /// The geared axis.
    pub axis: usize,
    /// Passes run.
    pub passes: usize,
    /// Passes that never locked (shorter than their ramp-in and
    /// catch-up): not measured.
    pub unlocked: usize,
    /// The gearbox's settings of the first pass.
    pub gear: GearSettings,
    /// Lead error and phase spread; `None` when no pass locked.
    pub figures: Option<ThreadFigures>,
    /// A rigid tap: the deepest `GEAR_POSITION` it reached, steps (past
    /// the depth by what the spindle turned while it reversed).
    pub deepest: Option<i64>,
}

/// Best rational approximation of `x` (0 < x <= 1) with a denominator of
/// at most `max_denominator`: (n, d).
pub fn ratio(x: f64, max_denominator: u64) -> (u64, u64) {
    // Continued fraction convergents, then the best semiconvergent.
    let (mut p0, mut q0, mut p1, mut q1) = (0u64, 1u64, 1u64, 0u64);
    let mut rest = x;
    loop {
        let a = rest.floor();
        let a_int = a as u64;
        let (p2, q2) = (a_int * p1 + p0, a_int * q1 + q0);
        if q2 > max_denominator {
            let k = (max_denominator - q0) / q1;
            let (ps, qs) = (k * p1 + p0, k * q1 + q0);
            let better = |p: u64, q: u64| (p as f64 / q as f64 - x).abs();
            return if qs > 0 && better(ps, qs) < better(p1, q1) {
                (ps, qs)
            } else {
                (p1, q1)
            };
        }
        (p0, q0, p1, q1) = (p1, q1, p2, q2);
        let frac = rest - a;
        if frac < 1e-12 || (p1 as f64 / q1 as f64 - x).abs() < 1e-15 {
            return (p1, q1);
        }
        rest = 1.0 / frac;
    }
}

/// The gearbox's settings for `m` on `machine` at `clock_hz`, with the
/// spindle's `ripple`; an error (without the line) when the move cannot
/// run geared.
pub fn gear_settings(
    m: &SyncedMove,
    machine: &MachineSettings,
    clock_hz: f64,
    ripple: f64,
) -> Result<GearSettings, String> {
    let name = match (m.rigid_tap, m.pass) {
        (true, _) => "G33.1",
        (false, Some(_)) => "G76",
        (false, None) => "G33",
    };
    let letter = ['X', 'Y', 'Z'][m.axis];
    let cpr = machine.spindle_counts_per_rev;
    if cpr == 0 {
        return Err(format!(
            "{name} needs a spindle encoder, and the machine has none (spindle_encoder 0 in its settings)"
        ));
    }
    let spm = machine.steps_per_mm[m.axis];
    let steps_per_rev = m.pitch * spm;
    let per_count = steps_per_rev / cpr as f64;
    if per_count > 1.0 {
        return Err(format!(
            "{name}'s pitch of {} mm is {steps_per_rev:.1} steps per revolution on {letter}, more than the spindle encoder's {cpr} counts: the gearbox makes at most one step per count",
            m.pitch
        ));
    }
    let fastest_rpm = m.rpm * (1.0 + ripple);
    let speed = m.pitch * fastest_rpm / 60.0;
    if speed > machine.max_velocity[m.axis] {
        return Err(format!(
            "{name}'s pitch of {} mm at S{} moves {letter} at up to {speed:.1} mm/s (with the spindle's +{:.0} % ripple), above its max_velocity of {} mm/s",
            m.pitch,
            m.rpm,
            ripple * 100.0,
            machine.max_velocity[m.axis]
        ));
    }
    let count_rate = fastest_rpm / 60.0 * cpr as f64;
    if count_rate * CLOCKS_PER_COUNT as f64 > clock_hz {
        return Err(format!(
            "at S{} the spindle encoder counts up to {:.0} counts/s (with the +{:.0} % ripple); the gearbox takes one count per {CLOCKS_PER_COUNT} clocks, {:.0} counts/s at {} MHz: lower S, or raise the clock",
            m.rpm,
            count_rate,
            ripple * 100.0,
            clock_hz / CLOCKS_PER_COUNT as f64,
            clock_hz / 1e6
        ));
    }
    // The ratio in the largest terms that fit: the ramp's unit is 1/d
    // step per count per count, so a large d lets the ramp follow the
    // axis's acceleration finely.
    let (n, d) = ratio(per_count, GEAR_WORD_MAX);
    let scale = GEAR_WORD_MAX / d;
    let (n, d) = (n * scale, d * scale);
    let from = to_steps(m.start, machine.steps_per_mm)[m.axis];
    let to = to_steps(m.end, machine.steps_per_mm)[m.axis];
    let mut length = (to - from).unsigned_abs();
    if m.rigid_tap {
        // LinuxCNC's allowance: ten turns for the spindle to stop.
        length += (10.0 * steps_per_rev).ceil() as u64;
    }
    if length > GEAR_WORD_MAX {
        return Err(format!(
            "{name} moves {letter} {length} steps, more than GEAR_LENGTH holds ({GEAR_WORD_MAX})"
        ));
    }
    // The axis's acceleration bound at the fastest count rate: ramp / d
    // x f^2 <= a steps/s^2.
    let accel = machine.max_accel[m.axis] * spm;
    let by_accel = (accel * d as f64 / (count_rate * count_rate)).floor();
    let least = n.div_ceil(1 << RAMP_SHIFT).max(1);
    let room = d - n;
    if room < least {
        return Err(format!(
            "{name}'s pitch of {} mm is {n}/{d} steps per count on {letter}: too close to one step per count for the gearbox to catch up its ramp-in; use an encoder with more counts",
            m.pitch
        ));
    }
    let ramp = (by_accel.min(room as f64) as u64).max(least);
    Ok(GearSettings {
        run: GearRun {
            axis: m.axis,
            numerator: n as u32,
            denominator: d as u32,
            ramp: ramp as u32,
            length: length as u32,
            spindle_reverse: !m.clockwise,
            axis_reverse: to < from,
        },
        steps_per_rev,
        count_rate,
    })
}

/// Every geared move of `items` checked against the machine and the
/// clock, before anything runs: their settings in order, or the first
/// error, by line.
fn check_geared(
    items: &[Item],
    machine: &MachineSettings,
    options: &SimulationOptions,
) -> Result<Vec<GearSettings>, String> {
    items
        .iter()
        .filter_map(|item| match item {
            Item::Synced(m) => Some(
                gear_settings(m, machine, options.clock_hz, options.spindle.ripple)
                    .map_err(|e| format!("line {}: {e}", m.line)),
            ),
            _ => None,
        })
        .collect()
}

/// Whether a toolpath has geared moves (then [`simulate_geared`] runs it).
pub fn has_geared_moves(toolpath: &Toolpath) -> bool {
    toolpath.items.iter().any(|i| matches!(i, Item::Synced(_)))
}

/// What groups passes into one thread.
#[derive(Clone, Copy, Debug, PartialEq)]
enum ThreadKey {
    /// A G76's passes: its line.
    Cycle(usize),
    /// G33 moves with this axis, start along it and pitch.
    Moves(usize, f64, f64),
}

fn thread_key(m: &SyncedMove) -> ThreadKey {
    match m.pass {
        Some(_) => ThreadKey::Cycle(m.line),
        None => ThreadKey::Moves(m.axis, m.start[m.axis], m.pitch),
    }
}

/// A pass's errors from its record, or `None` if it never locked.
fn pass_errors(
    log: &GearLog,
    report: &GearReport,
    m: &SyncedMove,
    gear: &GearSettings,
    machine: &MachineSettings,
) -> Option<PassErrors> {
    let locked = report.locked_at?;
    let engaged = log.index_before(report.engaged_at)?;
    // Counts taken before the ramp-out started, with a poll's and an
    // engine's margin for when the poll saw it.
    let end = report.stopping_at.unwrap_or(report.ended_at);
    let to = end.checked_sub(2 * GEAR_POLL_CLOCKS + ENGINE_CLOCKS as u64 + 8)?;
    // The directions the gearbox was armed with: a forward count of the
    // spindle moves the axis down under one of them, up under both.
    let dir = match gear.run.axis_reverse != gear.run.spindle_reverse {
        true => -1.0,
        false => 1.0,
    };
    let per_count = gear.steps_per_rev / machine.spindle_counts_per_rev as f64;
    let errors = PassErrors::measure(
        &log.samples,
        (locked, to),
        m.start[m.axis] * machine.steps_per_mm[m.axis],
        dir,
        per_count,
        engaged,
    );
    (!errors.errors.is_empty()).then_some(errors)
}

/// Waits until `SPINDLE_SPEED` reads the commanded speed within the
/// ripple and 5 % for two windows in a row; at most `timeout_s`.
fn wait_at_speed(
    driver: &mut Driver<RtlBus>,
    rpm: f64,
    cpr: u32,
    ripple: f64,
    clock_hz: f64,
    timeout_s: f64,
) -> Result<(), String> {
    let window = driver.speed_window_clocks().map_err(|e| e.to_string())?;
    let expected = rpm / 60.0 * cpr as f64 * window as f64 / clock_hz;
    let tolerance = expected.abs() * (ripple + 0.05);
    let start = driver.bus().cycles();
    let mut good = 0;
    while good < 2 {
        if (driver.bus().cycles() - start) as f64 > timeout_s * clock_hz {
            let read = driver.spindle_speed().map_err(|e| e.to_string())?;
            return Err(format!(
                "the spindle did not reach S{} within {timeout_s} s: SPINDLE_SPEED reads {read} counts per {window} clocks, {expected:.0} expected",
                rpm.abs()
            ));
        }
        driver.bus_mut().wait(window);
        let read = driver.spindle_speed().map_err(|e| e.to_string())? as f64;
        good = if (read - expected).abs() <= tolerance {
            good + 1
        } else {
            0
        };
    }
    Ok(())
}

/// The speed window closest to 10 ms at `clock_hz`, as SPINDLE_CONFIG's
/// SPEED_WINDOW (2^n clocks, n from 8 to 31).
pub fn speed_window_log2(clock_hz: f64) -> u32 {
    ((clock_hz * 0.01).log2().round() as i64).clamp(8, 31) as u32
}

/// Runs `job`, which has geared moves (see the [module doc](self)).
pub fn simulate_geared(
    path_file: &FsPath,
    options: &SimulationOptions,
    job: Job,
) -> Result<SimulationReport, String> {
    let located = |e: String| format!("{}: {e}", path_file.display());
    if let Some(what) = option_beyond_dda_build(options, false) {
        return Err(located(format!(
            "{what} cannot run with geared moves (G33, G33.1, G76): they run on motion_controller_dda_spindle, DDA only, without the soft limits, the analog outputs or the feed hold's window"
        )));
    }
    let started = Instant::now();
    let machine = job.machine;
    let mut settings = check_geared(&job.toolpath.items, &machine, options)
        .map_err(located)?
        .into_iter();
    let spm = machine.steps_per_mm;
    let start = to_steps(job.toolpath.start, spm);
    let target = to_steps(job.toolpath.end(), spm);
    let (tick_divisor, period_ticks) = period_settings(machine.period, options.clock_hz)?;
    let mut spindle = SpindleMotor::new(machine.spindle_counts_per_rev);
    spindle.ripple = options.spindle.ripple;
    spindle.load_dip = options.spindle.load_dip;
    let mut bus = RtlBus::with_spindle(
        options.backend,
        options.vcd.as_deref(),
        spindle,
        options.clock_hz,
    )
    .map_err(|e| e.to_string())?;
    watch_the_run(&mut bus, options, tick_divisor, period_ticks)?;
    // Step axes only (refused above otherwise): the DDA on each.
    let config = driver_config(options, tick_divisor, period_ticks, [None; 3]);
    let mut driver = Driver::new(bus, config).map_err(|e| e.to_string())?;
    driver
        .set_speed_window(speed_window_log2(options.clock_hz))
        .map_err(|e| e.to_string())?;
    // The controller counts from 0: positions relative to `start`.
    let mut chunk: Vec<Item> = Vec::new();
    let mut chunk_start = job.toolpath.start;
    let mut periods = 0;
    let mut underruns = 0;
    let mut threads: Vec<(ThreadKey, ThreadReport, Vec<PassErrors>)> = Vec::new();
    let run_chunk = |driver: &mut Driver<RtlBus>,
                     chunk: &mut Vec<Item>,
                     from: [f64; 3]|
     -> Result<(usize, usize), String> {
        if chunk.is_empty() {
            return Ok((0, 0));
        }
        let toolpath = Toolpath {
            start: from,
            items: std::mem::take(chunk),
            ..Toolpath::default()
        };
        let segments = plan_toolpath(&toolpath, &machine).map_err(|e| located(e.to_string()))?;
        let interpolation = interpolate(to_steps(from, spm), &segments, machine.period);
        let report = driver
            .run(&interpolation.counts, |_| {})
            .map_err(|e| e.to_string())?;
        Ok((report.periods, report.underruns))
    };
    let position_mm = |driver: &mut Driver<RtlBus>| -> Result<[f64; 3], String> {
        let (commanded, _) = driver.positions().map_err(|e| e.to_string())?;
        Ok(std::array::from_fn(|k| {
            (commanded[k] as i64 + start[k]) as f64 / spm[k]
        }))
    };
    let cpr = machine.spindle_counts_per_rev;
    for item in &job.toolpath.items {
        let m = match item {
            Item::Synced(m) => *m,
            other => {
                chunk.push(*other);
                continue;
            }
        };
        let (p, u) = run_chunk(&mut driver, &mut chunk, chunk_start)?;
        periods += p;
        underruns += u;
        let gear = settings
            .next()
            .expect("checked: one setting per geared move");
        let signed_rpm = if m.clockwise { m.rpm } else { -m.rpm };
        let spindle = driver
            .bus_mut()
            .spindle_mut()
            .expect("the spindle build has a spindle");
        if spindle.commanded_rpm() != signed_rpm {
            spindle.command(signed_rpm);
            wait_at_speed(
                &mut driver,
                signed_rpm,
                cpr,
                options.spindle.ripple,
                options.clock_hz,
                5.0,
            )
            .map_err(|e| located(format!("line {}: {e}", m.line)))?;
        }
        driver.bus_mut().start_gear_log(m.axis);
        // Three turns at the slowest speed, and a second.
        let rev_s = 60.0 / (m.rpm * (1.0 - options.spindle.ripple));
        let index_timeout = ((3.0 * rev_s + 1.0) * options.clock_hz) as u64;
        let depth = (to_steps(m.end, spm)[m.axis] - to_steps(m.start, spm)[m.axis]).abs();
        let mut phase = TapPhase::In;
        let mut deepest = 0i64;
        let result = driver.gear_run(&gear.run, index_timeout, |bus, status, position| {
            let spindle = bus.spindle_mut().expect("the spindle build has a spindle");
            spindle.set_load(status.phase >= 2);
            deepest = deepest.max(position as i64);
            if !m.rigid_tap {
                return GearAction::Continue;
            }
            tap_step(&mut phase, spindle, signed_rpm, position as i64, depth)
        });
        if let Some(spindle) = driver.bus_mut().spindle_mut() {
            spindle.set_load(false);
            if m.rigid_tap {
                spindle.command(signed_rpm);
            }
        }
        let log = driver.bus_mut().take_gear_log().unwrap_or_default();
        let report = result.map_err(|e| located(format!("line {}: {e}", m.line)))?;
        let key = thread_key(&m);
        let errors = (!m.rigid_tap)
            .then(|| pass_errors(&log, &report, &m, &gear, &machine))
            .flatten();
        let slot = match threads.iter().position(|(k, _, _)| *k == key) {
            Some(i) => i,
            None => {
                threads.push((
                    key,
                    ThreadReport {
                        line: m.line,
                        axis: m.axis,
                        passes: 0,
                        unlocked: 0,
                        gear,
                        figures: None,
                        deepest: m.rigid_tap.then_some(deepest),
                    },
                    Vec::new(),
                ));
                threads.len() - 1
            }
        };
        let (_, thread, passes) = &mut threads[slot];
        thread.passes += 1;
        match errors {
            Some(e) => passes.push(e),
            None if !m.rigid_tap => thread.unlocked += 1,
            None => {}
        }
        chunk_start = position_mm(&mut driver)?;
        if m.rigid_tap {
            // Place the tap back at its start exactly.
            chunk.push(Item::Move(Move {
                kind: MoveKind::Line,
                end: m.start,
                angles: job.toolpath.start_angles,
                feed: None,
                laser: LaserPower::OFF,
                line: m.line,
            }));
        }
    }
    let (p, u) = run_chunk(&mut driver, &mut chunk, chunk_start)?;
    periods += p;
    underruns += u;
    let (commanded, actual) = driver.positions().map_err(|e| e.to_string())?;
    let offset =
        |p: [i32; 3]| -> [i32; 3] { std::array::from_fn(|k| (p[k] as i64 + start[k]) as i32) };
    let bus = driver.bus();
    let threads = threads
        .into_iter()
        .map(|(_, mut t, passes)| {
            t.figures = ThreadFigures::of(&passes);
            t
        })
        .collect();
    Ok(SimulationReport {
        target,
        program_end: job.program_end,
        ignored: job.ignored,
        ending: job.ending,
        messages: job.messages,
        commanded: offset(commanded),
        actual: offset(actual),
        peak_rate: bus.peak_steps_per_clock().map(|r| r * options.clock_hz),
        following: [None; 3],
        settle_periods: 0,
        underruns,
        periods,
        cycles: bus.cycles(),
        seconds: started.elapsed().as_secs_f64(),
        figures: Vec::new(),
        hold: None,
        probes: Vec::new(),
        probe_plane: None,
        steps_per_mm: spm,
        threads,
        burns: Vec::new(),
        spi: SpiReport::of(bus, options.clock_hz, periods, machine.period),
    })
}

/// Where a rigid tap is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TapPhase {
    /// Going in, forward.
    In,
    /// The spindle reversed at the depth: following it out.
    Out,
    /// The spindle commanded forward again at the start: the axis
    /// follows it up to where it turns; `lowest` is the least position
    /// seen (the axis steps down, toward the start, as it comes out).
    Turning { lowest: i64 },
}

/// One poll of a rigid tap, from `GEAR_POSITION` alone: reverses the
/// spindle at `depth` steps, commands it forward at the start, and halts
/// the gearbox when the position turns (the spindle has stopped and
/// begins to turn forward: the axis stands, so the halt cuts no speed).
fn tap_step(
    phase: &mut TapPhase,
    spindle: &mut SpindleMotor,
    rpm: f64,
    position: i64,
    depth: i64,
) -> GearAction {
    match *phase {
        TapPhase::In if position >= depth => {
            spindle.command(-rpm);
            *phase = TapPhase::Out;
        }
        TapPhase::Out if position <= 0 => {
            spindle.command(rpm);
            *phase = TapPhase::Turning { lowest: position };
        }
        TapPhase::Turning { lowest } if position > lowest => return GearAction::Halt,
        TapPhase::Turning { lowest } => {
            *phase = TapPhase::Turning {
                lowest: lowest.min(position),
            }
        }
        _ => {}
    }
    GearAction::Continue
}
