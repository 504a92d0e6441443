//! `simulate` on a laser machine (`laser_s_max` in its settings): the
//! laser build (`motion_controller_dda_laser`) with `laser_pwm` recorded
//! at the pins, and the energy per millimetre of every burn.
//!
//! **Runs.** `LASER_CONTROL.DYNAMIC` is a register, so M3 and M4 do not
//! share a run: the toolpath is cut where the mode of a burning move
//! differs from the last burning move's, and each part is planned and
//! streamed as one run, which ends with the axes at rest (grbl, too,
//! changes the mode only between motions). Moves with the laser off join
//! the run they fall in.
//!
//! **Each period's entry** ([`laser_entries`]): the move the period ends
//! on gives it.
//! - POWER = S / `laser_s_max` x the PWM period in clocks, rounded; 0 on
//!   a rapid, after M5, or at S0.
//! - FEED = the programmed feed as a speed of the laser's plane (X, Y) in
//!   1/16 step per period: F x T x (the plane's steps per mm of path over
//!   the period's exact motion), rounded, at least 1. So the gateware's
//!   ratio, the plane's vector speed in steps over FEED, is the path speed
//!   over F on any direction and steps per mm. A move along Z alone has
//!   FEED 0: under M4 the laser is off, as the plane stands.
//! - **M4's headroom.** The gateware's speed is a period's whole steps:
//!   at 1.6 steps a period the counts run 1, 2, 2, 1, 2, and a period of 2
//!   steps is 25 % above the feed. The gateware caps the ratio at 1
//!   (POWER), which would clip those periods and burn 15 % short. So the
//!   host writes POWER and FEED both multiplied by k (up to
//!   [`M4_HEADROOM`], as far as 16 bits hold them): the duty, POWER x v /
//!   FEED, is the same, and the cap is k times the programmed power. A
//!   period then burns in proportion to the steps it takes, which is
//!   constant energy per step. The duty still cannot pass the PWM period:
//!   at S / `laser_s_max` above (steps a period) / (steps a period,
//!   rounded up) a period with the extra step is clipped, the more so
//!   below one step a period.
//!
//! **Burns and their energy** ([`super::laser_log`]): a burn is a run of
//! periods whose moves burn at one power, feed and mode; each is measured
//! at the pins in windows of path and printed as `energy per mm:
//! programmed X, min Y, max Z`.
//!
//! **A feed hold** (`--hold`) runs as on a step build: the controller
//! slows the path along itself, and under M4 the duty follows by the
//! hold's factor, so a burn through the hold keeps its energy per mm; at
//! the stop the laser is off. Its rate is `--hold-rate`, or the machine's
//! stop from its top speeds on the tick that gives it.
//!
//! Refused: geared moves (the laser build has no gearbox), `--uniform`,
//! `--servo`, `--soft-limit` and `--probe-plane` (the laser build is DDA
//! only, without soft limits); a PWM period outside 1 to 65535 clocks at
//! the clock; a feed beyond FEED's 4095 steps per period.

use std::path::Path as FsPath;
use std::time::Instant;

use super::driver::{HoldEvent, LaserEntry, LaserRun};
use super::hold_window::{hold_tick_settings, speeds_at_the_pins, stop_within_limits_s};
use super::interpolator::{interpolate, Interpolation};
use super::laser_log::{burn_energy, BurnEnergy};
use super::planner::{plan_toolpath, to_steps, PlannedSegment};
use super::simulation::{
    driver_config, option_beyond_dda_build, period_settings, watch_the_run, HoldReport, Job,
    SimulationOptions, SimulationReport, SpiReport,
};
use super::toolpath::{Item, Toolpath};
use super::{ControllerBus, Driver, MachineSettings, RtlBus};
use crate::plots::plot_energy;

/// The most an M4 entry's POWER and FEED are both multiplied by (see the
/// [module documentation](self)).
pub const M4_HEADROOM: u32 = 16;

/// The laser's plane: X and Y.
pub const LASER_PLANE: (usize, usize) = (0, 1);

/// The PWM period in clocks of `machine` at `clock_hz`; an error when it
/// does not fit `LASER_PWM_PERIOD`.
pub fn pwm_clocks(machine: &MachineSettings, clock_hz: f64) -> Result<u16, String> {
    let clocks = (machine.laser_pwm_period * clock_hz).round();
    if !(1.0..=65535.0).contains(&clocks) {
        return Err(format!(
            "laser_pwm_us {} is {clocks} clocks at {} MHz: LASER_PWM_PERIOD holds 1 to 65535",
            machine.laser_pwm_period * 1e6,
            clock_hz / 1e6
        ));
    }
    Ok(clocks as u16)
}

/// A period's motion from `before` to `point` (mm) on a machine of
/// `steps_per_mm`: its path length, mm, and its length in steps along the
/// laser's plane.
fn period_motion(before: [f64; 3], point: [f64; 3], steps_per_mm: [f64; 3]) -> (f64, f64) {
    let (a, b) = LASER_PLANE;
    let d: [f64; 3] = std::array::from_fn(|i| point[i] - before[i]);
    let length = d.iter().map(|v| v * v).sum::<f64>().sqrt();
    let plane = (d[a] * steps_per_mm[a]).hypot(d[b] * steps_per_mm[b]);
    (length, plane)
}

/// Each period's laser entry for a run planned as `segments` and
/// interpolated as `interpolation` from `start` (mm), on `machine` with a
/// PWM period of `pwm` clocks. An error names the line of a feed FEED
/// cannot hold.
pub fn laser_entries(
    segments: &[PlannedSegment],
    interpolation: &Interpolation,
    start: [f64; 3],
    machine: &MachineSettings,
    pwm: u16,
) -> Result<Vec<LaserEntry>, String> {
    let mut entries = Vec::with_capacity(interpolation.counts.len());
    let mut before = start;
    // The plane's steps per mm of path, of the last period that moved.
    let mut ratio = 0.0;
    for (k, point) in interpolation.points.iter().enumerate() {
        let (length, plane) = period_motion(before, *point, machine.steps_per_mm);
        before = *point;
        if length > 1e-12 {
            ratio = plane / length;
        }
        let Some(s) = segments.get(interpolation.moves[k]) else {
            entries.push(LaserEntry::default());
            continue;
        };
        if !s.laser.is_on() {
            entries.push(LaserEntry::default());
            continue;
        }
        let power = (s.laser.fraction.min(1.0) * pwm as f64).round() as u16;
        let feed = match s.feed {
            Some(f) => {
                let sixteenths = (f * machine.period * ratio * 16.0).round();
                if sixteenths > 65535.0 {
                    return Err(format!(
                        "line {}: the feed is {:.0} steps a period along the laser's plane, beyond the 4095 LASER_FIFO.FEED holds",
                        s.line,
                        sixteenths / 16.0
                    ));
                }
                (sixteenths as u16).max((ratio > 0.0) as u16)
            }
            None => 0,
        };
        // M4: both scaled by the headroom, so that a period's extra step
        // raises its duty instead of being clipped at POWER.
        let k = match s.laser.dynamic && feed > 0 {
            true => M4_HEADROOM
                .min(65535 / power.max(1) as u32)
                .min(65535 / feed as u32)
                .max(1),
            false => 1,
        };
        entries.push(LaserEntry {
            power: (power as u32 * k) as u16,
            feed: (feed as u32 * k) as u16,
        });
    }
    Ok(entries)
}

/// A burn's key: power, feed and mode.
fn burn_key(s: &PlannedSegment) -> Option<(u64, u64, bool)> {
    let feed = s.feed?;
    s.laser
        .is_on()
        .then_some((s.laser.fraction.to_bits(), feed.to_bits(), s.laser.dynamic))
}

/// One burn as planned.
#[derive(Clone, Debug, PartialEq)]
#[doc(hidden)]
pub struct PlannedBurn {
    pub line: usize,
    pub dynamic: bool,
    /// Programmed full-power seconds per mm.
    pub programmed: f64,
    /// The feed's steps a period along the plane, summed over the periods
    /// (weighted by their length).
    pub feed_steps: f64,
    /// The step index at its start.
    pub first: u64,
    /// Per period: the step index at its end and the path's length in it.
    pub periods: Vec<(u64, f64)>,
}

/// The burns of one run, steps counted from `base` at the run's start
/// (from `start`, mm).
#[doc(hidden)]
pub fn burns_of(
    segments: &[PlannedSegment],
    interpolation: &Interpolation,
    start: [f64; 3],
    base: u64,
    machine: &MachineSettings,
) -> Vec<PlannedBurn> {
    let mut burns = Vec::new();
    let mut steps = base;
    let mut before = start;
    let mut open: Option<((u64, u64, bool), PlannedBurn)> = None;
    for (k, counts) in interpolation.counts.iter().enumerate() {
        let s = &segments[interpolation.moves[k].min(segments.len() - 1)];
        let key = burn_key(s);
        let first = steps;
        steps += counts.iter().map(|c| c.unsigned_abs() as u64).sum::<u64>();
        let point = interpolation.points[k];
        let (mm, plane) = period_motion(before, point, machine.steps_per_mm);
        // The plane's steps along this period's motion, at the feed.
        let feed_steps = s.feed.unwrap_or(0.0) * machine.period * plane;
        before = point;
        match (&mut open, key) {
            (Some((open_key, burn)), Some(key)) if *open_key == key => {
                burn.periods.push((steps, mm));
                burn.feed_steps += feed_steps;
                continue;
            }
            _ => {}
        }
        if let Some((_, burn)) = open.take() {
            burns.push(burn);
        }
        if let (Some(key), Some(feed)) = (key, s.feed) {
            let burn = PlannedBurn {
                line: s.line,
                dynamic: s.laser.dynamic,
                programmed: s.laser.fraction / feed,
                feed_steps,
                first,
                periods: vec![(steps, mm)],
            };
            open = Some((key, burn));
        }
    }
    if let Some((_, burn)) = open {
        burns.push(burn);
    }
    burns
}

/// Runs `job` on a laser machine (see the [module doc](self)).
pub fn simulate_laser(
    path_file: &FsPath,
    options: &SimulationOptions,
    job: Job,
) -> Result<SimulationReport, String> {
    let located = |e: String| format!("{}: {e}", path_file.display());
    if let Some(what) = option_beyond_dda_build(options, true) {
        return Err(located(format!(
            "{what} cannot run on a laser machine (laser_s_max): it runs on motion_controller_dda_laser, DDA only, without the soft limits, the analog outputs or the probe plane"
        )));
    }
    if let Some(Item::Synced(m)) = job
        .toolpath
        .items
        .iter()
        .find(|i| matches!(i, Item::Synced(_)))
    {
        return Err(located(format!(
            "line {}: a geared move (G33, G33.1, G76) on a laser machine: the laser build has no gearbox",
            m.line
        )));
    }
    let started = Instant::now();
    let machine = job.machine;
    let spm = machine.steps_per_mm;
    let pwm = pwm_clocks(&machine, options.clock_hz).map_err(located)?;
    let start = to_steps(job.toolpath.start, spm);
    let target = to_steps(job.toolpath.end(), spm);
    // Every part planned first: a hold's tick needs the steps they take.
    let mut parts = Vec::new();
    let mut planned_peak_speed = 0.0f64;
    let mut from = job.toolpath.start;
    for part in split_by_mode(&job.toolpath.items) {
        let toolpath = Toolpath {
            start: from,
            items: part.items,
            ..Toolpath::default()
        };
        from = toolpath.end();
        let segments = plan_toolpath(&toolpath, &machine).map_err(|e| located(e.to_string()))?;
        if segments.is_empty() {
            continue;
        }
        let interpolation = interpolate(to_steps(toolpath.start, spm), &segments, machine.period);
        let entries = laser_entries(&segments, &interpolation, toolpath.start, &machine, pwm)
            .map_err(located)?;
        let peak = interpolation.speeds.iter().copied().fold(0.0, f64::max);
        planned_peak_speed = planned_peak_speed.max(peak);
        parts.push((
            part.dynamic,
            toolpath.start,
            segments,
            interpolation,
            entries,
        ));
    }
    // With a hold: the machine's stop from its top speeds, and the tick
    // that gives it (as `simulate` does for a step build).
    let stop_s = stop_within_limits_s(&machine, 0.0, machine.max_velocity);
    let (tick_divisor, period_ticks) = match options.hold {
        Some(h) if h.rate.is_none() => {
            let needed = parts
                .iter()
                .flat_map(|p| p.3.counts.iter())
                .flat_map(|c| c.iter().map(|v| v.unsigned_abs() as u64))
                .max()
                .unwrap_or(0);
            hold_tick_settings(machine.period, options.clock_hz, stop_s, needed)?
        }
        _ => period_settings(machine.period, options.clock_hz)?,
    };
    let mut bus =
        RtlBus::with_laser(options.backend, options.vcd.as_deref()).map_err(|e| e.to_string())?;
    watch_the_run(&mut bus, options, tick_divisor, period_ticks)?;
    let config = driver_config(options, tick_divisor, period_ticks, [None; 3]);
    let mut driver = Driver::new(bus, config).map_err(|e| e.to_string())?;
    let tick_hz = options.clock_hz / tick_divisor as f64;
    let hold_rate = options.hold.map(|h| h.rate(stop_s, tick_hz));
    if let Some(rate) = hold_rate {
        driver.set_hold_rate(rate).map_err(|e| e.to_string())?;
    }
    let holds: Vec<HoldEvent> = options
        .hold
        .map_or(Vec::new(), |h| h.events(options.clock_hz).to_vec());
    let mut held = Vec::new();
    driver.bus_mut().start_laser_log();
    let mut periods = 0;
    let mut underruns = 0;
    let mut burns = Vec::new();
    for (dynamic, start_mm, segments, interpolation, entries) in &parts {
        let base = driver.bus().laser_log().map_or(0, |l| l.steps);
        let laser = LaserRun {
            pwm_period: pwm,
            dynamic: *dynamic,
            plane: LASER_PLANE,
        };
        // The hold's events not yet due: a hold and its release may fall
        // in different parts.
        let now = driver.bus().cycles();
        let due: Vec<HoldEvent> = holds.iter().copied().filter(|e| e.clock >= now).collect();
        let report = driver
            .run_laser(&interpolation.counts, entries, laser, &due, |_| {})
            .map_err(|e| located(e.to_string()))?;
        periods += report.periods;
        held.extend_from_slice(&report.held);
        underruns += report.underruns;
        burns.extend(burns_of(segments, interpolation, *start_mm, base, &machine));
    }
    let (commanded, actual) = driver.positions().map_err(|e| e.to_string())?;
    let bus = driver.bus();
    let log = bus.laser_log().cloned().unwrap_or_default();
    let burns: Vec<BurnEnergy> = burns
        .into_iter()
        .map(|b| {
            let length_mm: f64 = b.periods.iter().map(|p| p.1).sum();
            BurnEnergy {
                line: b.line,
                dynamic: b.dynamic,
                programmed: b.programmed,
                length_mm,
                feed_steps: b.feed_steps / length_mm.max(f64::MIN_POSITIVE),
                windows: burn_energy(&log, b.first, &b.periods, options.clock_hz),
            }
        })
        .collect();
    let mut figures = Vec::new();
    if let Some(dir) = &options.out_dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let stem = path_file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("path");
        let energy = dir.join(format!("{stem}-energy.svg"));
        plot_energy(&burns, &energy).map_err(|e| e.to_string())?;
        figures.push(energy);
    }
    let offset =
        |p: [i32; 3]| -> [i32; 3] { std::array::from_fn(|k| (p[k] as i64 + start[k]) as i32) };
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
        figures,
        hold: options.hold.zip(hold_rate).map(|(h, rate)| {
            let window = (0.01 / machine.period).round() as usize;
            let speeds = speeds_at_the_pins(bus.samples(), spm, machine.period, window);
            HoldReport::measured(
                &h,
                (rate, tick_divisor),
                options.clock_hz,
                (bus.cycles(), &held),
                &speeds,
                (machine.period, planned_peak_speed),
            )
        }),
        probes: Vec::new(),
        probe_plane: None,
        steps_per_mm: spm,
        threads: Vec::new(),
        burns,
        spi: SpiReport::of(bus, options.clock_hz, periods, machine.period),
    })
}

/// A part of the toolpath that runs in one laser mode.
#[doc(hidden)]
pub struct ModePart {
    pub dynamic: bool,
    pub items: Vec<Item>,
}

/// Cuts `items` where a burning move's or dwell's mode differs from the
/// last burning one's.
#[doc(hidden)]
pub fn split_by_mode(items: &[Item]) -> Vec<ModePart> {
    let mut parts: Vec<ModePart> = Vec::new();
    let mut mode: Option<bool> = None;
    for item in items {
        let laser = match item {
            Item::Move(m) => m.laser,
            Item::Dwell { laser, .. } => *laser,
            Item::Synced(_) => continue,
        };
        let burning = laser.is_on().then_some(laser.dynamic);
        let new_part = match (mode, burning) {
            (_, None) | (None, Some(_)) => parts.is_empty(),
            (Some(m), Some(d)) => m != d,
        };
        if new_part {
            parts.push(ModePart {
                dynamic: burning.unwrap_or(false),
                items: Vec::new(),
            });
        }
        let part = parts.last_mut().expect("a part is open");
        if let (None, Some(d)) = (mode, burning) {
            part.dynamic = d;
        }
        if burning.is_some() {
            mode = burning;
        }
        part.items.push(*item);
    }
    parts
}
