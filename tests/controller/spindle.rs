//! The spindle build (`motion_controller_dda_spindle`): the spindle
//! encoder and the electronic gearbox inside the controller, against the
//! model under random traffic, at the pins against an independent monitor
//! (with mutations that it must catch), and cross-simulated.

use crate::bench::Bench;
use crate::motion_controller::ChaosDriver;
use motion_hdl::blocks::electronic_gearbox::model::Phase;
use motion_hdl::blocks::motion_controller::{latency, MotionController3DdaSpindle};
use motion_hdl::sim::quadrature_state;
use motion_hdl::tools::cosim::{check_instance_with, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The exported spindle build.
type Spindle3 = Bench<3, 4, 5, false, false, true, false, true>;

/// A spindle encoder: quadrature A/B at a given count period, an index one
/// count wide every `cpr` counts.
#[derive(Clone, Copy, Debug)]
struct SpindleEncoder {
    /// Counts from the start.
    position: i64,
    /// Clocks per count; 0 = stopped.
    period: u64,
    forward: bool,
    wait: u64,
    cpr: i64,
}

impl SpindleEncoder {
    fn new(period: u64, cpr: i64) -> Self {
        Self {
            position: 1,
            period,
            forward: true,
            wait: period,
            cpr,
        }
    }

    fn pins(&self) -> (bool, bool, bool) {
        let (a, b) = quadrature_state(self.position);
        (a, b, self.position.rem_euclid(self.cpr) == 0)
    }

    /// One clock: `Some(forward)` when the encoder counted.
    fn clock(&mut self) -> Option<bool> {
        if self.period == 0 {
            return None;
        }
        self.wait = self.wait.saturating_sub(1);
        if self.wait > 0 {
            return None;
        }
        self.wait = self.period;
        self.position += if self.forward { 1 } else { -1 };
        Some(self.forward)
    }
}

/// `clocks` idle clocks of `b` with `spindle` turning.
fn spin(b: &mut Spindle3, spindle: &mut SpindleEncoder, clocks: u64) {
    for _ in 0..clocks {
        spindle.clock();
        b.spindle = spindle.pins();
        b.idle(1);
    }
}

/// Random traffic to the spindle window: ratios valid and not, arms,
/// stops, halts, axes in and out of range, directions, encoder options and
/// speed windows, reads of every register.
fn spindle_bus(rng: &mut StdRng, b: &Spindle3) -> (bool, u32, u32, bool, bool) {
    let w = |name: &str, value: u32| (false, b.address(name, 0), value, true, false);
    match rng.gen_range(0..100) {
        0..=39 | 41 | 94..=99 => {
            let name = [
                "SPINDLE_POSITION",
                "SPINDLE_INDEX_POSITION",
                "SPINDLE_SPEED",
                "SPINDLE_CONFIG",
                "GEAR_CONTROL",
                "GEAR_STATUS",
                "GEAR_NUMERATOR",
                "GEAR_DENOMINATOR",
                "GEAR_RAMP",
                "GEAR_LENGTH",
                "GEAR_POSITION",
            ][rng.gen_range(0..11)];
            (false, b.address(name, 0), 0, false, true)
        }
        40 => {
            let strobe = rng.gen_range(0..20);
            let word = b.pack(
                "GEAR_CONTROL",
                &[
                    ("ARM", (strobe < 18) as u64),
                    ("STOP", (strobe == 18) as u64),
                    ("HALT", (strobe == 19) as u64),
                    ("CLEAR_ENCODER_ERROR", rng.gen_ratio(1, 4) as u64),
                    ("SPINDLE_REVERSE", rng.gen_ratio(1, 4) as u64),
                    ("AXIS_REVERSE", rng.gen_ratio(1, 3) as u64),
                    ("AXIS", [0, 1, 2, 2, 2, 2, 3, 7][rng.gen_range(0..8)]),
                ],
            );
            w("GEAR_CONTROL", word)
        }
        42..=53 => {
            let d = match rng.gen_range(0..10) {
                0 => [0u32, 100, 4000, 1 << 23][rng.gen_range(0..4)],
                _ => rng.gen_range(1..=8),
            };
            w("GEAR_DENOMINATOR", d)
        }
        54..=65 => {
            let n = match rng.gen_range(0..10) {
                0 => [0u32, 99, 4000][rng.gen_range(0..3)],
                _ => rng.gen_range(1..=6),
            };
            w("GEAR_NUMERATOR", n)
        }
        66..=77 => w(
            "GEAR_RAMP",
            [0u32, 1, 2, 5, 40, 1 << 20][rng.gen_range(0..6)],
        ),
        78..=89 => w(
            "GEAR_LENGTH",
            [0u32, 0, 5, 30, 300, 3000][rng.gen_range(0..6)],
        ),
        90..=91 => {
            let word = b.pack(
                "SPINDLE_CONFIG",
                &[
                    ("FILTER", rng.gen_range(0..4)),
                    ("COUNTER_MODE", rng.gen_ratio(1, 10) as u64),
                    ("INDEX_INVERT", rng.gen_ratio(1, 10) as u64),
                    ("SPEED_WINDOW", rng.gen_range(0..32)),
                ],
            );
            w("SPINDLE_CONFIG", word)
        }
        // Junk in the window's unused words and bits.
        _ => (false, 0xe0 + rng.gen_range(0..32), rng.gen(), true, false),
    }
}

/// What a lockstep run of the spindle build exercised.
#[derive(Debug, Default)]
struct Coverage {
    gear_steps: u64,
    locked_clocks: u64,
    engaged_clocks: u64,
    done: u64,
    invalid: u64,
    overrun: u64,
}

/// The spindle build against its model for `clocks` clocks of the
/// controller's chaos traffic mixed with the spindle window's, a spindle
/// that changes speed (past the gearbox's rate too) and direction. The
/// controller's own traffic and machine pins (limits, alarms, E-stop, the
/// watchdog: each trip aborts, which halts the gearbox until firmware
/// clears it) join in the second half.
fn spindle_chaos(b: &mut Spindle3, seed: u64, clocks: u64) -> Coverage {
    let mut driver = ChaosDriver::new(seed, 3);
    let mut rng = StdRng::seed_from_u64(seed ^ 0x5b1d);
    let mut spindle = SpindleEncoder::new(80, 40);
    let mut cover = Coverage::default();
    let (mut done, mut invalid, mut overrun) = (false, false, false);
    for clock in 0..clocks {
        if rng.gen_ratio(1, 20_000) {
            spindle.period = [0, 2, 20, 40, 50, 60, 80, 120, 200, 1000][rng.gen_range(0..10)];
        }
        if rng.gen_ratio(1, 50_000) {
            spindle.forward = !spindle.forward;
        }
        spindle.clock();
        b.spindle = spindle.pins();
        b.encoders = driver.encoders();
        let pins = driver.machine_pins(3);
        let chaos = clock >= clocks / 2;
        if chaos {
            b.pins = pins;
        }
        let (reset, address, data, write, read) = if rng.gen_ratio(1, 8) {
            spindle_bus(&mut rng, b)
        } else if chaos {
            driver.bus(b)
        } else {
            (false, 0, 0, false, false)
        };
        b.clock(reset, address, data, write, read);
        let gear = b.model().spindle().gearbox();
        cover.gear_steps += b.model().spindle().step_out().is_some() as u64;
        cover.locked_clocks += gear.locked as u64;
        cover.engaged_clocks += gear.phase.is_engaged() as u64;
        cover.done += (gear.done && !done) as u64;
        cover.invalid += (gear.invalid && !invalid) as u64;
        cover.overrun += (gear.overrun && !overrun) as u64;
        (done, invalid, overrun) = (gear.done, gear.invalid, gear.overrun);
    }
    cover
}

#[test]
fn spindle_build_matches_its_model_under_random_traffic() {
    let mut b = Spindle3::new();
    let cover = spindle_chaos(&mut b, 0x5e1d, 400_000);
    println!("spindle build, 400 000 clocks: {cover:?}");
    assert!(cover.gear_steps > 100, "{cover:?}");
    assert!(cover.locked_clocks > 1_000, "{cover:?}");
    assert!(
        cover.done > 0 && cover.invalid > 0 && cover.overrun > 0,
        "{cover:?}"
    );
}

#[test]
#[ignore = "about 2 minutes: ten million clocks of the compiled spindle build against the model"]
fn spindle_build_matches_its_model_for_ten_million_clocks() {
    let mut b = Spindle3::new();
    let cover = spindle_chaos(&mut b, 0x7e4d, 10_000_000);
    println!("spindle build, 10^7 clocks: {cover:?}");
    assert!(cover.gear_steps > 10_000, "{cover:?}");
}

/// A threading pass as firmware runs it, recorded at the pins: the
/// spindle's counts (from the encoder the test drives) and the geared
/// axis's steps (from its step/dir pins).
#[derive(Clone, Debug, Default)]
struct Pass {
    /// Clock of each spindle count (forward).
    counts: Vec<u64>,
    /// Clock of each index rise.
    indexes: Vec<u64>,
    /// Clock of each step of the geared axis, and its direction.
    steps: Vec<(u64, bool)>,
    /// Clock of the arm.
    armed: u64,
}

/// The pin-level contract of a locked gearbox at ratio n/d with a run of
/// `length` steps: the axis moves exactly `length` steps; from the first
/// index after the arm on, after `settle` counts, the axis is within
/// [-1, 2] steps behind floor(n x counts / d) (the gearbox's 0 or 1 step,
/// one more for the latency from the encoder's pins through the decoder
/// and the engine to the step pin, and one count either way for the
/// count that coincides with the index) until its last 3 steps (where it
/// ramps out to the crawl rate to end at `length`); and the steps all go
/// one way.
fn check_pass(pass: &Pass, n: i64, d: i64, length: i64, settle: usize) -> Result<(), String> {
    let net: i64 = pass.steps.iter().map(|s| if s.1 { 1 } else { -1 }).sum();
    if net != length {
        return Err(format!("the axis moved {net} steps, not {length}"));
    }
    if pass.steps.iter().any(|s| !s.1) {
        return Err("a step went backward".into());
    }
    let index = *pass
        .indexes
        .iter()
        .find(|&&t| t > pass.armed)
        .ok_or("no index after the arm")?;
    let counts: Vec<u64> = pass
        .counts
        .iter()
        .copied()
        .filter(|&t| t >= index)
        .collect();
    let mut steps = pass.steps.iter().peekable();
    let mut position = 0i64;
    for (c, &t) in counts.iter().enumerate() {
        while steps.peek().is_some_and(|s| s.0 <= t) {
            steps.next();
            position += 1;
        }
        let ideal = n * c as i64 / d;
        if c >= settle && position < length - 3 && !(-1..=2).contains(&(ideal - position)) {
            return Err(format!(
                "count {c} (clock {t}): the axis at {position}, floor(n c / d) = {ideal}"
            ));
        }
    }
    Ok(())
}

/// Runs one pass on the exported spindle build: spindle at `period` clocks
/// a count, `cpr` counts a turn, ratio n/d on axis 2, ramp, length.
fn run_pass(n: u32, d: u32, ramp: u32, length: u32, period: u64) -> (Pass, Spindle3) {
    let mut b = Spindle3::new().with_loopback();
    let mut spindle = SpindleEncoder::new(period, 400);
    let mut pass = Pass::default();
    let mut index_was = false;
    let mut clock = |b: &mut Spindle3, pass: &mut Pass, address, data, write, read| {
        if spindle.clock().is_some() {
            pass.counts.push(b.cycles);
        }
        b.spindle = spindle.pins();
        if b.spindle.2 && !index_was {
            pass.indexes.push(b.cycles);
        }
        index_was = b.spindle.2;
        let before = b.pin_steps(2);
        b.clock(false, address, data, write, read);
        let after = b.pin_steps(2);
        if after != before {
            pass.steps.push((b.cycles, after > before));
        }
    };
    let writes = [
        ("GEAR_NUMERATOR", n),
        ("GEAR_DENOMINATOR", d),
        ("GEAR_RAMP", ramp),
        ("GEAR_LENGTH", length),
    ];
    for (name, value) in writes {
        let address = b.address(name, 0);
        clock(&mut b, &mut pass, address, value, true, false);
    }
    // Spin up past an index first: the arm comes mid-turn.
    for _ in 0..period * 500 {
        clock(&mut b, &mut pass, 0, 0, false, false);
    }
    pass.armed = b.cycles;
    let arm = b.pack("GEAR_CONTROL", &[("ARM", 1), ("AXIS", 2)]);
    let address = b.address("GEAR_CONTROL", 0);
    clock(&mut b, &mut pass, address, arm, true, false);
    let turns = (length as u64 * d as u64 / n as u64) / 400 + 3;
    for _ in 0..period * 400 * turns {
        clock(&mut b, &mut pass, 0, 0, false, false);
    }
    (pass, b)
}

#[test]
fn a_threading_pass_tracks_the_spindle_and_ends_at_its_length_at_the_pins() {
    let (n, d, length) = (3, 8, 700);
    let (pass, mut b) = run_pass(n, d, 1, length, 60);
    check_pass(&pass, n as i64, d as i64, length as i64, 40).unwrap();
    // Every step follows the count that made it by the stated latency
    // (the first one clock later: the direction pin's setup after reset).
    let delays: std::collections::BTreeMap<u64, usize> = pass.steps[1..]
        .iter()
        .map(|&(t, _)| {
            let count = pass.counts.iter().rev().find(|&&c| c < t).unwrap();
            t - 1 - count
        })
        .fold(Default::default(), |mut m, d| {
            *m.entry(d).or_insert(0) += 1;
            m
        });
    println!("count-to-step delays: {delays:?}");
    assert_eq!(
        delays.keys().copied().collect::<Vec<_>>(),
        vec![latency::SPINDLE_COUNT_TO_STEP]
    );
    let status = b.read("GEAR_STATUS", 0);
    assert_eq!(b.field("GEAR_STATUS", "DONE", status), 1);
    assert_eq!(b.field("GEAR_STATUS", "PHASE", status), Phase::Idle as u64);
    assert_eq!(b.read("GEAR_POSITION", 0), length);
    assert_eq!(b.read("CMD_POSITION", 2), length);
    assert_eq!(b.model().spindle().gearbox().phase, Phase::Idle);

    // The monitor fails on each mutation of the pass.
    let mut dropped = pass.clone();
    dropped.steps.remove(pass.steps.len() / 2);
    assert!(
        check_pass(&dropped, 3, 8, 700, 40).is_err(),
        "a dropped step"
    );
    let mut extra = pass.clone();
    extra
        .steps
        .insert(pass.steps.len() / 2, pass.steps[pass.steps.len() / 2]);
    assert!(check_pass(&extra, 3, 8, 700, 40).is_err(), "an extra step");
    let mut late = pass.clone();
    for s in &mut late.steps[300..] {
        s.0 += 60 * 8;
    }
    assert!(
        check_pass(&late, 3, 8, 700, 40).is_err(),
        "a lag of 8 counts"
    );
    assert!(check_pass(&pass, 4, 8, 700, 40).is_err(), "another ratio");
    let mut backward = pass.clone();
    backward.steps[10].1 = false;
    assert!(
        check_pass(&backward, 3, 8, 700, 40).is_err(),
        "a reversed step"
    );
}

#[test]
fn fifo_entries_on_the_geared_axis_add_to_the_gearbox_steps() {
    let mut b = Spindle3::new().with_loopback();
    let mut spindle = SpindleEncoder::new(50, 100);
    b.write("TICK_DIVISOR", 0, 2);
    b.write("PERIOD_TICKS", 0, 200);
    b.write("GEAR_NUMERATOR", 0, 1);
    b.write("GEAR_DENOMINATOR", 0, 2);
    b.write("GEAR_RAMP", 0, 1);
    b.write("GEAR_LENGTH", 0, 150);
    let arm = b.pack("GEAR_CONTROL", &[("ARM", 1), ("AXIS", 1)]);
    b.write("GEAR_CONTROL", 0, arm);
    let entries = [5i32, -7, 20, 0, 33, -12, 9, 9, 9, 9];
    for n in entries {
        // Every axis pops at each boundary: the others stand still.
        b.write("FIFO_WRITE", 0, 0);
        b.write("FIFO_WRITE", 1, n as u32);
        b.write("FIFO_WRITE", 2, 0);
    }
    b.write("CONTROL", 0, 1);
    spin(&mut b, &mut spindle, 60_000);
    let fifo: i32 = entries.iter().sum();
    assert_eq!(b.read("GEAR_POSITION", 0), 150);
    assert_eq!(b.read("CMD_POSITION", 1) as i32, fifo + 150);
    assert_eq!(b.pin_steps(1), (fifo + 150) as i64);
}

#[test]
fn an_abort_halts_the_gearbox_and_the_estop_stops_its_steps() {
    let mut b = Spindle3::new().with_loopback();
    let mut spindle = SpindleEncoder::new(40, 50);
    b.write("GEAR_NUMERATOR", 0, 1);
    b.write("GEAR_DENOMINATOR", 0, 1);
    b.write("GEAR_RAMP", 0, 1);
    let arm = b.pack("GEAR_CONTROL", &[("ARM", 1), ("AXIS", 0)]);
    b.write("GEAR_CONTROL", 0, arm);
    spin(&mut b, &mut spindle, 20_000);
    assert!(b.pin_steps(0) > 100, "geared: {}", b.pin_steps(0));
    b.pins.estop = true;
    spin(&mut b, &mut spindle, 20);
    let at_stop = b.pin_steps(0);
    spin(&mut b, &mut spindle, 5_000);
    assert_eq!(b.pin_steps(0), at_stop, "no step after the E-stop");
    let status = b.read("GEAR_STATUS", 0);
    assert_eq!(b.field("GEAR_STATUS", "PHASE", status), Phase::Idle as u64);
}

#[test]
fn an_arm_for_an_axis_the_build_lacks_is_refused_and_flagged() {
    let mut b = Spindle3::new();
    b.write("IRQ_ENABLE", 0, b.pack("IRQ_ENABLE", &[("SPINDLE", 1)]));
    b.write("GEAR_NUMERATOR", 0, 1);
    b.write("GEAR_DENOMINATOR", 0, 1);
    let arm = b.pack("GEAR_CONTROL", &[("ARM", 1), ("AXIS", 3)]);
    b.write("GEAR_CONTROL", 0, arm);
    b.idle(3);
    assert!(b.last.irq);
    let status = b.read("GEAR_STATUS", 0);
    assert_eq!(b.field("GEAR_STATUS", "INVALID", status), 1);
    assert_eq!(b.field("GEAR_STATUS", "PHASE", status), 0);
    let arm = b.pack("GEAR_CONTROL", &[("ARM", 1), ("AXIS", 2)]);
    b.write("GEAR_CONTROL", 0, arm);
    let status = b.read("GEAR_STATUS", 0);
    assert_eq!(b.field("GEAR_STATUS", "INVALID", status), 0);
    assert_eq!(b.field("GEAR_STATUS", "PHASE", status), Phase::Armed as u64);
}

#[test]
fn the_spindle_speed_reads_the_counts_of_each_window() {
    let mut b = Spindle3::new();
    let mut spindle = SpindleEncoder::new(16, 1000);
    b.write(
        "SPINDLE_CONFIG",
        0,
        b.pack("SPINDLE_CONFIG", &[("SPEED_WINDOW", 12)]),
    );
    spin(&mut b, &mut spindle, 20_000);
    // 4096 clocks at one count per 16 clocks.
    assert_eq!(b.read("SPINDLE_SPEED", 0), 256);
    spindle.forward = false;
    spin(&mut b, &mut spindle, 20_000);
    assert_eq!(b.read("SPINDLE_SPEED", 0) as i32, -256);
}

/// The exported spindle build in Icarus and Verilator against the Rust
/// simulation, over the controller's and the spindle window's chaos.
#[test]
fn exported_spindle_build_matches_rust_in_icarus_and_verilator() {
    let mut b = Spindle3::new();
    b.recording = Some(Vec::new());
    spindle_chaos(&mut b, 0xc0de, 6_000);
    let stimulus = b.recording.take().unwrap();
    check_instance_with::<MotionController3DdaSpindle>(
        Instance::Exported("motion_controller_dda_spindle"),
        stimulus,
        2_000,
    );
}

#[test]
fn a_spindle_count_reaches_spindle_position_after_the_stated_decode_latency() {
    let mut b = Spindle3::new();
    b.idle(10);
    // One forward count: A rises at clock c.
    let (a, bb) = quadrature_state(1);
    b.spindle = (a, bb, false);
    let c = b.cycles;
    let mut seen = None;
    for _ in 0..20 {
        b.idle(1);
        if seen.is_none() && b.model().spindle().count() == 1 {
            // The outputs after the edge of clock b.cycles - 1.
            seen = Some(b.cycles - 1 - c);
        }
    }
    assert_eq!(seen, Some(latency::SPINDLE_DECODE));
    assert_eq!(b.read("SPINDLE_POSITION", 0), 1);
}
