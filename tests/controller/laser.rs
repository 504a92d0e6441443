//! The laser build (`motion_controller_dda_laser`): the laser FIFO and the
//! PWM tied to the path inside the controller, against the model under
//! random traffic, at the pins against an independent energy monitor (with
//! a mutation it must catch), off on an E-stop and on the hold's stop
//! within the stated clocks, and cross-simulated.

use crate::bench::Bench;
use crate::motion_controller::ChaosDriver;
use motion_hdl::blocks::motion_controller::laser::LASER_LAG;
use motion_hdl::blocks::motion_controller::registers::{self, fields};
use motion_hdl::blocks::motion_controller::{latency, MotionController3DdaLaser};
use motion_hdl::tools::cosim::{check_instance_with, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The exported laser build.
type Laser3 = Bench<3, 4, 5, false, false, true, false, false, true>;

/// One interpolation period of a burn: the three axes' steps and the
/// laser's (POWER, FEED in 1/16 step).
#[derive(Clone, Copy, Debug)]
struct Period {
    steps: [i32; 3],
    power: u32,
    feed16: u32,
}

/// Configures `b` for a burn: every base tick a clock, periods of
/// `period` ticks, step/dir pins with one-clock timing, the laser on
/// axes 0 and 1 with a PWM of `pwm` clocks, dynamic or not.
fn setup(b: &mut Laser3, period: u32, pwm: u32, dynamic: bool) {
    b.write("TICK_DIVISOR", 0, 1);
    b.write("PERIOD_TICKS", 0, period);
    for axis in 0..3 {
        for timer in ["STEP_LEN", "STEP_SPACE", "DIR_SETUP", "DIR_HOLD"] {
            b.write(timer, axis, 1);
        }
    }
    b.write("LASER_PWM_PERIOD", 0, pwm);
    let control = b.pack(
        "LASER_CONTROL",
        &[
            ("ENABLE", 1),
            ("DYNAMIC", dynamic as u64),
            ("AXIS_A", 0),
            ("AXIS_B", 1),
        ],
    );
    b.write("LASER_CONTROL", 0, control);
}

/// Writes the next period's four entries when the FIFOs have room (only
/// the axes' three when the power is by register: `LASER_CONTROL.SOURCE`).
fn feed_fifos(b: &mut Laser3, periods: &[Period], next: &mut usize) {
    let control = b.model().laser().read(registers::laser::LASER_CONTROL);
    let by_register = control >> fields::LASER_SOURCE & 1 != 0;
    while *next < periods.len() && b.model().axes()[0].fifo_level() < 12 {
        let p = periods[*next];
        for (axis, steps) in p.steps.iter().enumerate() {
            b.write("FIFO_WRITE", axis as u32, *steps as u32);
        }
        if !by_register {
            let entry = b.pack(
                "LASER_FIFO",
                &[("POWER", p.power as u64), ("FEED", p.feed16 as u64)],
            );
            b.write("LASER_FIFO", 0, entry);
        }
        *next += 1;
    }
}

/// What the pins showed, clock by clock: `laser_pwm` and each step of
/// axes 0 and 1.
#[derive(Clone, Debug, Default)]
struct Trace {
    laser: Vec<bool>,
    /// (clock, axis) of each step edge.
    steps: Vec<(usize, usize)>,
    /// Clocks with the laser FIFO in the run (`LASER_STATUS.ACTIVE`).
    active_clocks: usize,
}

/// Runs `periods` as a burn on `b`, holding the feed from `hold.0` to
/// `hold.1` (clocks after RUN; the pin, released by HOLD_CONTROL once
/// low), and records the pins until the axes are idle.
fn burn(b: &mut Laser3, periods: &[Period], hold: Option<(usize, usize)>) -> Trace {
    let mut next = 0;
    feed_fifos(b, periods, &mut next);
    b.write("CONTROL", 0, 1);
    let mut trace = Trace::default();
    let mut previous = [false; 2];
    let mut clock = 0usize;
    loop {
        if let Some((from, to)) = hold {
            b.pins.feed_hold = clock >= from && clock < to;
            if clock == to + 200 {
                let release = b.pack("HOLD_CONTROL", &[("RELEASE", 1), ("RATE", 8)]);
                b.write("HOLD_CONTROL", 0, release);
            }
        }
        feed_fifos(b, periods, &mut next);
        let out = b.clock(false, 0, 0, false, false).clone();
        trace.laser.push(out.laser);
        let status = b.model().laser().read(registers::laser::LASER_STATUS);
        trace.active_clocks += (status >> fields::LASER_ACTIVE & 1) as usize;
        for (axis, was) in previous.iter_mut().enumerate() {
            if out.steps[axis].0 && !*was {
                trace.steps.push((trace.laser.len() - 1, axis));
            }
            *was = out.steps[axis].0;
        }
        clock += 1;
        if !out.active && next == periods.len() && clock > 100 {
            return trace;
        }
        assert!(clock < 5_000_000, "the burn did not end");
    }
}

/// A burn through a 90 degree corner, per period: accelerate along axis 0
/// to `feed` steps a period, run, slow to 30 % while turning, run along
/// axis 1, slow to a stop. Power `power` at the feed.
fn corner(feed: f64, power: u32) -> Vec<Period> {
    let mut speed: Vec<(f64, f64)> = Vec::new();
    for k in 1..=8 {
        speed.push((feed * k as f64 / 8.0, 0.0));
    }
    speed.extend(std::iter::repeat_n((feed, 0.0), 16));
    for k in 1..=8 {
        speed.push((feed * (1.0 - 0.7 * k as f64 / 8.0), 0.0));
    }
    for k in 0..=8 {
        speed.push((feed * 0.3, std::f64::consts::FRAC_PI_2 * k as f64 / 8.0));
    }
    for k in 1..=8 {
        speed.push((
            feed * (0.3 + 0.7 * k as f64 / 8.0),
            std::f64::consts::FRAC_PI_2,
        ));
    }
    speed.extend(std::iter::repeat_n((feed, std::f64::consts::FRAC_PI_2), 24));
    for k in (0..8).rev() {
        speed.push((feed * k as f64 / 8.0, std::f64::consts::FRAC_PI_2));
    }
    // Whole steps per period, the fractions carried, as a host plans them.
    let (mut x, mut y) = (0.0f64, 0.0f64);
    let (mut sx, mut sy) = (0i64, 0i64);
    speed
        .iter()
        .map(|&(v, angle)| {
            x += v * angle.cos();
            y += v * angle.sin();
            let (a, bb) = (x.round() as i64 - sx, y.round() as i64 - sy);
            (sx, sy) = (sx + a, sy + bb);
            Period {
                steps: [a as i32, bb as i32, 0],
                power,
                feed16: (feed * 16.0).round() as u32,
            }
        })
        .collect()
}

/// The energy per step in windows of `window` steps of path length,
/// starting every `stride` steps, away from the burn's first and last
/// `margin` steps: (worst relative error against `expected`, windows).
fn energy_spread(
    trace: &Trace,
    window: f64,
    stride: f64,
    margin: f64,
    expected: f64,
) -> (f64, usize) {
    // Path length at each step edge, and the high clocks before it.
    let mut highs = vec![0u64; trace.laser.len() + 1];
    for (k, &on) in trace.laser.iter().enumerate() {
        highs[k + 1] = highs[k] + on as u64;
    }
    // The path's length: chords between every 8th step (a chord of a
    // staircase is its straight line; 8 steps of a turn are nearly
    // straight), as the laser measures a period's steps.
    let (mut x, mut y) = (0i64, 0i64);
    let mut points: Vec<(f64, usize)> = vec![(0.0, 0)];
    let (mut last_x, mut last_y) = (0i64, 0i64);
    let mut length = 0.0;
    for (n, &(clock, axis)) in trace.steps.iter().enumerate() {
        if axis == 0 {
            x += 1;
        } else {
            y += 1;
        }
        if (n + 1) % 8 == 0 {
            length += (((x - last_x).pow(2) + (y - last_y).pow(2)) as f64).sqrt();
            (last_x, last_y) = (x, y);
            points.push((length, clock));
        }
    }
    let total = length;
    let point_at = |s: f64| -> (f64, usize) {
        let i = points.partition_point(|p| p.0 < s);
        points[i.min(points.len() - 1)]
    };
    let (mut worst, mut windows) = (0.0f64, 0usize);
    let mut start = margin;
    while start + window <= total - margin {
        let ((l0, c0), (l1, c1)) = (point_at(start), point_at(start + window));
        let energy = (highs[c1] - highs[c0]) as f64 / (l1 - l0);
        worst = worst.max((energy / expected - 1.0).abs());
        windows += 1;
        start += stride;
    }
    (worst, windows)
}

const PERIOD: u32 = 4096;
const PWM: u32 = 256;
const FEED: f64 = 16.0;
const POWER: u32 = 128;
/// Windows of 64 steps (0.1 mm at 640 steps/mm), every 8 steps, away from
/// the first and last 64.
const WINDOW: f64 = 64.0;

/// High clocks of `laser_pwm` per step at the feed: power / PWM x clocks
/// per step.
fn expected_energy() -> f64 {
    POWER as f64 / PWM as f64 * PERIOD as f64 / FEED
}

/// Burns `path` on `b` (set up for it) with a feed hold a third into the
/// run along axis 1, and checks at the pins that every step arrived and
/// that the energy per step stays within 5 % of power / PWM x clocks per
/// step at the feed, in windows of [`WINDOW`] steps.
fn burn_the_corner_through_a_hold(b: &mut Laser3, path: &[Period], label: &str) -> Trace {
    let expected = expected_energy();
    let rate = b.pack("HOLD_CONTROL", &[("RATE", 8)]);
    b.write("HOLD_CONTROL", 0, rate);
    let hold_from = 50 * PERIOD as usize;
    let trace = burn(b, path, Some((hold_from, hold_from + 40_000)));
    let net: i64 = path
        .iter()
        .map(|p| p.steps[0] as i64 + p.steps[1] as i64)
        .sum();
    assert_eq!(trace.steps.len() as i64, net, "every step reached the pins");
    let (worst, windows) = energy_spread(&trace, WINDOW, 8.0, WINDOW, expected);
    println!(
        "{label}: energy per step through the corner and the hold: worst {:.2} % over {windows} windows",
        worst * 100.0
    );
    assert!(windows > 40, "{windows}");
    assert!(
        worst <= 0.05,
        "{label}: energy per step off by {:.1} %",
        worst * 100.0
    );
    trace
}

/// The figure of merit at the controller's pins: the energy per
/// step (high clocks of `laser_pwm` per step of path length) through an
/// acceleration, a 90 degree corner at 30 % speed, a feed hold with its
/// stop and resume, and the deceleration stays within 5 % of power /
/// PWM x clocks per step at the feed. A constant power (M3) on the same
/// burn fails the monitor in the corner.
#[test]
fn dynamic_power_keeps_the_energy_per_step_through_a_corner_and_a_hold_at_the_pins() {
    let expected = expected_energy();
    let path = corner(FEED, POWER);
    let mut b = Laser3::new();
    setup(&mut b, PERIOD, PWM, true);
    let trace = burn_the_corner_through_a_hold(&mut b, &path, "laser FIFO");
    // The hold stopped the laser: a long stretch without a pulse.
    let mut run = 0;
    let longest = trace.laser.iter().fold(0, |m, &on| {
        run = if on { 0 } else { run + 1 };
        m.max(run)
    });
    assert!(longest > 20_000, "{longest}");

    // Mutation: the same burn at constant power.
    let mut m = Laser3::new();
    setup(&mut m, PERIOD, PWM, false);
    let trace = burn(&mut m, &path, None);
    let (worst, _) = energy_spread(&trace, WINDOW, 8.0, WINDOW, expected);
    assert!(worst > 0.5, "constant power passed the monitor: {worst}");
}

/// A period's dynamic duty reaches the pin within [`LASER_LAG`] clocks
/// of the period's start, and a larger one from the next PWM period on (a
/// pulse that has ended does not restart): at the feed, every PWM period
/// of the rest of the period has the period's POWER high clocks.
#[test]
fn a_periods_power_reaches_the_pin_within_the_stated_lag() {
    let mut b = Laser3::new();
    setup(&mut b, 2000, 100, true);
    let powers = [0u32, 30, 100, 55, 0, 100, 10];
    let path: Vec<Period> = powers
        .iter()
        .map(|&power| Period {
            steps: [10, 0, 0],
            power,
            feed16: 160,
        })
        .collect();
    let trace = burn(&mut b, &path, None);
    // The first boundary is the first clock of the run (the trace's
    // first); period k starts 2000 k clocks later. After the lag, any 100
    // clocks (one PWM period, wherever it starts) hold `power` high
    // clocks, up to the next boundary.
    for (k, &power) in powers.iter().enumerate() {
        let from = k * 2000 + 1 + LASER_LAG as usize + 100;
        let to = (k + 1) * 2000;
        for first in from..to - 100 {
            let highs = trace.laser[first..first + 100]
                .iter()
                .filter(|&&h| h)
                .count();
            assert!(
                (highs as i64 - power as i64).abs() <= 1,
                "period {k}, clocks {first}..+100: {highs} high, power {power}"
            );
        }
    }
}

/// The power by register (`LASER_CONTROL.SOURCE` = 1, one `LASER_POWER`
/// write for the whole burn): the same corner and hold as
/// [`dynamic_power_keeps_the_energy_per_step_through_a_corner_and_a_hold_at_the_pins`]
/// with the axes' FIFOs alone pacing the run. The laser FIFO stays out
/// (ACTIVE 0, no entry, no underrun) and the energy per step holds.
#[test]
fn the_power_by_register_keeps_the_energy_per_step_without_the_laser_fifo() {
    let path = corner(FEED, POWER);
    let mut b = Laser3::new();
    setup(&mut b, PERIOD, PWM, true);
    let control = b.read("LASER_CONTROL", 0) | 1 << fields::LASER_SOURCE;
    b.write("LASER_CONTROL", 0, control);
    let power = b.pack(
        "LASER_POWER",
        &[("POWER", POWER as u64), ("FEED", (FEED * 16.0) as u64)],
    );
    b.write("LASER_POWER", 0, power);
    assert_eq!(b.read("LASER_POWER", 0), power);
    let trace = burn_the_corner_through_a_hold(&mut b, &path, "power by register");
    assert_eq!(trace.active_clocks, 0, "the laser FIFO took part");
}

/// A `LASER_POWER` write during a run is the duty in force within
/// [`LASER_LAG`] clocks, constant power: from one PWM period after the
/// lag, every PWM period has the written POWER high clocks, until the
/// next write.
#[test]
fn a_power_written_by_register_reaches_the_pin_within_the_stated_lag() {
    let mut b = Laser3::new();
    setup(&mut b, 2000, 100, false);
    let control = b.read("LASER_CONTROL", 0) | 1 << fields::LASER_SOURCE;
    b.write("LASER_CONTROL", 0, control);
    let path: Vec<Period> = (0..8)
        .map(|_| Period {
            steps: [10, 0, 0],
            power: 0,
            feed16: 0,
        })
        .collect();
    let mut next = 0;
    feed_fifos(&mut b, &path, &mut next);
    b.write("CONTROL", 0, 1);
    // Writes 1500 clocks apart, not aligned with the periods.
    let powers = [30u32, 100, 0, 55, 120, 7];
    let address = b.address("LASER_POWER", 0);
    let mut laser = Vec::new();
    let mut writes = Vec::new();
    for clock in 0..powers.len() * 1500 + 300 {
        feed_fifos(&mut b, &path, &mut next);
        let out = if clock % 1500 == 300 {
            let power = powers[clock / 1500];
            writes.push((clock, power));
            b.clock(false, address, power | 40 << 16, true, false)
        } else {
            b.clock(false, 0, 0, false, false)
        };
        laser.push(out.laser);
        assert!(out.running, "clock {clock}: RUN fell (an underrun?)");
    }
    let status = b.model().laser().read(registers::laser::LASER_STATUS);
    assert_eq!(
        status >> fields::LASER_ACTIVE & 1,
        0,
        "ACTIVE without the FIFO"
    );
    for (k, &(at, power)) in writes.iter().enumerate() {
        let from = at + 1 + LASER_LAG as usize + 100;
        let to = writes.get(k + 1).map_or(laser.len(), |w| w.0);
        // Full power (at or above the PWM period) is a steady high.
        let expected = power.min(100) as i64;
        for first in from..to - 100 {
            let highs = laser[first..first + 100].iter().filter(|&&h| h).count();
            assert!(
                (highs as i64 - expected).abs() <= 1,
                "write {k}, clocks {first}..+100: {highs} high, power {power}"
            );
        }
    }
}

/// An E-stop turns `laser_pwm` off at s + [`latency::LASER_OFF`] after its
/// filtered level is set at s; the hold's stop turns it off in the clock
/// after the factor reaches 0.
#[test]
fn an_estop_and_the_holds_stop_turn_the_laser_off_within_the_stated_clocks() {
    let steady = |power: u32| -> Vec<Period> {
        (0..40)
            .map(|_| Period {
                steps: [4, 0, 0],
                power,
                feed16: 64,
            })
            .collect()
    };
    // Full power (a steady high), E-stop at clock c.
    let mut b = Laser3::new();
    setup(&mut b, 1000, 50, false);
    let path = steady(50);
    let mut next = 0;
    feed_fifos(&mut b, &path, &mut next);
    b.write("CONTROL", 0, 1);
    for _ in 0..3000 {
        feed_fifos(&mut b, &path, &mut next);
        b.idle(1);
    }
    assert!(
        b.clock(false, 0, 0, false, false).laser,
        "firing before the E-stop"
    );
    b.pins.estop = true;
    let c = b.cycles;
    let s = c + latency::switch(fields::FILTER_LENGTH_RESET, 0);
    let mut off = None;
    for _ in 0..40 {
        let out = b.clock(false, 0, 0, false, false).clone();
        if !out.laser && off.is_none() {
            off = Some(b.cycles - 1);
        }
        if off.is_some() {
            assert!(!out.laser, "the laser fired again after the E-stop");
        }
    }
    assert_eq!(off, Some(s + latency::LASER_OFF), "E-stop at {c}");

    // The hold's stop: off in the clock after STATE.HELD.
    let mut b = Laser3::new();
    setup(&mut b, 1000, 50, false);
    let rate = b.pack("HOLD_CONTROL", &[("RATE", 64)]);
    b.write("HOLD_CONTROL", 0, rate);
    let path = steady(50);
    let mut next = 0;
    feed_fifos(&mut b, &path, &mut next);
    b.write("CONTROL", 0, 1);
    b.idle(3000);
    b.pins.feed_hold = true;
    let mut fired_while_moving = false;
    for _ in 0..3000 {
        let held = b.model().feed_hold().held();
        let out = b.clock(false, 0, 0, false, false).clone();
        if held {
            assert!(!out.laser, "the laser fired while held");
        } else {
            fired_while_moving |= out.laser;
        }
    }
    assert!(b.model().feed_hold().held() && fired_while_moving);
}

/// Random traffic to the laser's registers: enables, modes, sources,
/// planes (axes beyond K too), PWM periods, FIFO entries, register
/// powers, overflow clears, reads of every register and junk in the
/// unit's unused words.
fn laser_bus(rng: &mut StdRng, b: &Laser3) -> (bool, u32, u32, bool, bool) {
    let w = |name: &str, value: u32| (false, b.address(name, 0), value, true, false);
    match rng.gen_range(0..100) {
        0..=29 => {
            let name = [
                "LASER_CONTROL",
                "LASER_PWM_PERIOD",
                "LASER_STATUS",
                "LASER_OUTPUT",
                "LASER_FIFO",
                "LASER_POWER",
            ][rng.gen_range(0..6)];
            (false, b.address(name, 0), 0, false, true)
        }
        30..=37 => {
            let word = b.pack(
                "LASER_CONTROL",
                &[
                    ("ENABLE", !rng.gen_ratio(1, 5) as u64),
                    ("DYNAMIC", rng.gen_ratio(2, 3) as u64),
                    ("CLEAR_OVERFLOW", rng.gen_ratio(1, 4) as u64),
                    ("SOURCE", rng.gen_ratio(1, 3) as u64),
                    ("AXIS_A", [0, 0, 1, 2, 5][rng.gen_range(0..5)]),
                    ("AXIS_B", [1, 1, 0, 2, 7][rng.gen_range(0..5)]),
                ],
            );
            w("LASER_CONTROL", word | (rng.gen_ratio(1, 10) as u32) << 20)
        }
        38..=41 => w(
            "LASER_PWM_PERIOD",
            [0u32, 1, 2, 7, 40, 100, 1000, 70_000][rng.gen_range(0..8)],
        ),
        42..=49 => {
            let power = [0, rng.gen_range(0..60), rng.gen_range(0..0x10000)][rng.gen_range(0..3)];
            let feed = [0, rng.gen_range(1..800), rng.gen_range(0..0x10000)][rng.gen_range(0..3)];
            w("LASER_POWER", power | feed << 16)
        }
        50..=89 => {
            let power = match rng.gen_range(0..6) {
                0 => 0,
                1 => rng.gen_range(0..0x10000),
                _ => rng.gen_range(0..120),
            };
            let feed = match rng.gen_range(0..6) {
                0 => 0,
                1 => rng.gen_range(0..0x10000),
                _ => rng.gen_range(1..800),
            };
            w("LASER_FIFO", power | feed << 16)
        }
        // Junk in the unit's unused words.
        _ => (false, 0xf6 + rng.gen_range(0..10), rng.gen(), true, false),
    }
}

/// What a lockstep run of the laser build exercised.
#[derive(Debug, Default)]
struct Coverage {
    high_clocks: u64,
    /// Clocks with a duty in force between 0 and the period's power.
    scaled_clocks: u64,
    running_active: u64,
    /// Clocks high with the power by register (`SOURCE`).
    register_high_clocks: u64,
    overflows: u64,
}

/// The laser build against its model for `clocks` clocks: first a stream
/// of periods for every axis and the laser with holds and resumes, then
/// the controller's chaos traffic mixed with the laser's (aborts, resets,
/// underruns, FIFO overflows).
fn laser_chaos(b: &mut Laser3, seed: u64, clocks: u64) -> Coverage {
    let mut driver = ChaosDriver::new(seed, 3);
    let mut rng = StdRng::seed_from_u64(seed ^ 0x1a5e);
    let mut cover = Coverage::default();
    setup(b, 150, 40, true);
    let mut overflow = false;
    let mut word = 0u32;
    for clock in 0..clocks {
        let chaos = clock >= clocks / 2;
        b.encoders = driver.encoders();
        let pins = driver.machine_pins(3);
        if chaos {
            b.pins = pins;
        } else if rng.gen_ratio(1, if b.pins.feed_hold { 2000 } else { 30_000 }) {
            b.pins.feed_hold = !b.pins.feed_hold;
        }
        let calm_stream = !chaos && b.model().axes()[0].fifo_level() < 10;
        let release = !chaos && b.model().feed_hold().held() && !b.pins.feed_hold;
        let restart = !chaos && !b.model().running();
        let (reset, address, data, write, read) = if restart && rng.gen_ratio(1, 50) {
            (false, b.address("CONTROL", 0), 1, true, false)
        } else if release && rng.gen_ratio(1, 50) {
            let word = b.pack("HOLD_CONTROL", &[("RELEASE", 1), ("RATE", 40)]);
            (false, b.address("HOLD_CONTROL", 0), word, true, false)
        } else if calm_stream {
            // One period's entries in turn, one word a clock.
            let target = word % 4;
            word += 1;
            if target < 3 {
                (
                    false,
                    b.address("FIFO_WRITE", target),
                    rng.gen_range(-60i32..60) as u32,
                    true,
                    false,
                )
            } else if target == 3 {
                let power = rng.gen_range(0..60u32);
                let feed =
                    [0, rng.gen_range(1..2000u32), rng.gen_range(16..1000u32)][rng.gen_range(0..3)];
                (
                    false,
                    b.address("LASER_FIFO", 0),
                    power | feed << 16,
                    true,
                    false,
                )
            } else {
                (false, 0, 0, false, false)
            }
        } else if rng.gen_ratio(1, if chaos { 6 } else { 60 }) {
            laser_bus(&mut rng, b)
        } else if chaos {
            driver.bus(b)
        } else {
            (false, 0, 0, false, false)
        };
        let out = b.clock(reset, address, data, write, read).clone();
        // The contract at the pins: the laser fires only while `running`.
        assert!(
            !out.laser || out.running,
            "clock {clock}: laser_pwm high without running"
        );
        let laser = b.model().laser();
        cover.high_clocks += out.laser as u64;
        let status = laser.read(registers::laser::LASER_STATUS);
        let flag = |bit: u32| status >> bit & 1 != 0;
        cover.running_active += (b.model().running() && flag(fields::LASER_ACTIVE)) as u64;
        let control = laser.read(registers::laser::LASER_CONTROL);
        cover.register_high_clocks +=
            (out.laser && control >> fields::LASER_SOURCE & 1 != 0) as u64;
        let now = flag(fields::LASER_OVERFLOW);
        cover.overflows += (now && !overflow) as u64;
        overflow = now;
        cover.scaled_clocks += (laser.duty() > 0 && laser.duty() < 60 && out.laser) as u64;
    }
    cover
}

#[test]
fn laser_build_matches_its_model_under_random_traffic() {
    let mut b = Laser3::new();
    let cover = laser_chaos(&mut b, 0x1a5e, 400_000);
    println!("laser build, 400 000 clocks: {cover:?}");
    assert!(cover.high_clocks > 10_000, "{cover:?}");
    assert!(cover.scaled_clocks > 1_000, "{cover:?}");
    assert!(cover.running_active > 10_000, "{cover:?}");
    assert!(cover.register_high_clocks > 1_000, "{cover:?}");
    assert!(cover.overflows > 0, "{cover:?}");
}

#[test]
#[ignore = "about 2 minutes: ten million clocks of the compiled laser build against the model"]
fn laser_build_matches_its_model_for_ten_million_clocks() {
    let mut b = Laser3::new();
    let cover = laser_chaos(&mut b, 0x7e4e, 10_000_000);
    println!("laser build, 10^7 clocks: {cover:?}");
    assert!(cover.high_clocks > 100_000, "{cover:?}");
}

/// The exported laser build in Icarus and Verilator against the Rust
/// simulation, over the controller's and the laser's traffic.
#[test]
fn exported_laser_build_matches_rust_in_icarus_and_verilator() {
    let mut b = Laser3::new();
    b.recording = Some(Vec::new());
    laser_chaos(&mut b, 0xc0de, 6_000);
    let stimulus = b.recording.take().unwrap();
    check_instance_with::<MotionController3DdaLaser>(
        Instance::Exported("motion_controller_dda_laser"),
        stimulus,
        2_000,
    );
}
