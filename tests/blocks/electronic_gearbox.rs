//! `electronic_gearbox`: the RTL against the model (Verilator for 10^7
//! clocks, rust-hdl for 10^5), an exhaustive sweep of small ratios, an
//! independent monitor of the contract at the pins with the mutations it
//! catches, the same geared motion at any spindle speed, and
//! cross-simulation.

use motion_hdl::blocks::electronic_gearbox::model::{
    GearboxInputs, GearboxModel, GearboxOutputs, GearboxWidths, Phase, ENGINE_CLOCKS,
};
use motion_hdl::blocks::electronic_gearbox::{ElectronicGearbox, ElectronicGearbox24};
use motion_hdl::sim::{Backend, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const EXPORTED: GearboxWidths = GearboxWidths::EXPORTED;

/// A ratio the stimulus arms with: mostly valid, of every kind, and some
/// invalid.
fn ratio(rng: &mut StdRng, w: GearboxWidths) -> (u64, u64, u64) {
    let top = (1u64 << w.w) - 1;
    let d = match rng.gen_range(0..10) {
        0 => top,
        1 => rng.gen_range(1..=top),
        2 => 0,
        3 | 4 => rng.gen_range(1..=4000.min(top)),
        _ => rng.gen_range(1..=300.min(top)),
    };
    let n = match rng.gen_range(0..10) {
        0 => d,
        1 => rng.gen_range(0..=top),
        2 => 0,
        _ => rng.gen_range(0..=d),
    };
    let shortest = (n >> w.ramp_shift()) + 1;
    let ramp = match rng.gen_range(0..10) {
        0 => 0,
        1 => rng.gen_range(0..=top),
        2 => shortest.saturating_sub(1),
        _ => {
            // A ramp-in of 1 to 100 counts.
            let counts = rng.gen_range(1..=100u64);
            (n / counts).max(shortest).max(1).min(top)
        }
    };
    (n, d, ramp)
}

/// A spindle turning at a varying speed (a count every 1 to 40 clocks, or
/// at every clock), reversing now and then, with an index every
/// `per_rev` counts; arms, stops, halts and resets at random, lengths
/// from none to a few hundred steps.
fn random_inputs(seed: u64, cycles: usize, w: GearboxWidths) -> Vec<GearboxInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let lmask = (1u64 << w.l) - 1;
    let mut angle: i64 = 0;
    let mut per_rev: i64 = 64;
    let mut gap = 4u32;
    let mut wait = 0u32;
    let mut backward = false;
    let mut spindle_reverse = false;
    let mut base = GearboxInputs::default();
    let mut out = Vec::with_capacity(cycles);
    for cycle in 0..cycles {
        if cycle % 3000 == 0 {
            // Mostly at or below the engine's rate (a count every 32 clocks
            // or slower), sometimes faster, so that counts wait and overrun.
            gap = match rng.gen_range(0..40) {
                0 => rng.gen_range(0..4),
                1..=6 => rng.gen_range(16..31),
                _ => rng.gen_range(31..50),
            };
            per_rev = rng.gen_range(8..100);
            spindle_reverse = rng.gen_bool(0.3);
        }
        if rng.gen_ratio(1, 20_000) {
            backward = !backward;
        }
        let mut i = GearboxInputs {
            spindle_reverse,
            axis_reverse: rng.gen_bool(0.5),
            ..base
        };
        if wait == 0 {
            let step = if backward { -1 } else { 1 };
            angle += step;
            let up = (step > 0) != spindle_reverse;
            i.count_up = up;
            i.count_down = !up;
            if rng.gen_ratio(1, 500) {
                i.count_up = true;
                i.count_down = true;
            }
            i.index = angle.rem_euclid(per_rev) == 0;
            // A spindle with some jitter: the gap, up to half more, now and
            // then a burst.
            wait = if gap < 4 || rng.gen_ratio(1, 200) {
                rng.gen_range(0..4)
            } else {
                gap + rng.gen_range(0..=gap / 2)
            };
        } else {
            wait -= 1;
            // A count in both directions in one clock is no count.
            i.count_up = false;
            i.count_down = false;
        }
        if rng.gen_ratio(1, 300) {
            let (n, d, ramp) = ratio(&mut rng, w);
            base.numerator = n;
            base.denominator = d;
            base.ramp = ramp;
            i.numerator = n;
            i.denominator = d;
            i.ramp = ramp;
            i.arm = true;
        }
        if rng.gen_ratio(1, 700) {
            base.length = match rng.gen_range(0..8) {
                0 => 0,
                1 => rng.gen::<u64>() & lmask,
                _ => rng.gen_range(1..400),
            };
            i.length = base.length;
        }
        i.stop = rng.gen_ratio(1, 8_000);
        i.halt = rng.gen_ratio(1, 60_000);
        i.reset = rng.gen_ratio(1, 100_000);
        out.push(i);
    }
    out
}

/// The contract at the pins, checked by a monitor that knows only the
/// inputs, the outputs and the datasheet:
/// * the engine's timing: a count is taken in a clock the engine is idle
///   and the gearbox engaged (a waiting count first), its step shows
///   `ENGINE_CLOCKS` clocks later and nowhere else; one count waits while
///   the engine works, and a second is an overrun that halts;
/// * a step goes the count's way, and the position is the net of the steps;
/// * locked, the axis is 0 or 1 step behind floor(n m / d), m the net
///   counts since the engaging index, and the lock comes within its bound;
/// * the rate changes by at most `ramp` per count (seen as the second
///   difference of the steps over windows of counts, at rest before the
///   engage and after the end);
/// * a run that reaches its length ends exactly there.
struct Monitor {
    w: GearboxWidths,
    previous: GearboxOutputs,
    /// The ratio, ramp, length and directions of the last accepted arm.
    armed: Option<GearboxInputs>,
    position: i64,
    /// Clocks until the count in work shows; 0 = idle.
    timer: u32,
    /// The count in work and the waiting one: true = forward.
    in_work: Option<bool>,
    slot: Option<bool>,
    /// Net forward counts since the engaging index, as the engine took them.
    counts: i64,
    /// Steps after each forward count since the engage, for the rate
    /// check; cleared by a backward count or a halt.
    trace: Vec<i64>,
    forward_since_engage: i64,
    locks: u64,
    lock_checks: u64,
    rate_checks: u64,
    lengths_reached: u64,
    overruns: u64,
    waits: u64,
}

impl Monitor {
    fn new(w: GearboxWidths) -> Self {
        Self {
            w,
            previous: GearboxOutputs::default(),
            armed: None,
            position: 0,
            timer: 0,
            in_work: None,
            slot: None,
            counts: 0,
            trace: Vec::new(),
            forward_since_engage: 0,
            locks: 0,
            lock_checks: 0,
            rate_checks: 0,
            lengths_reached: 0,
            overruns: 0,
            waits: 0,
        }
    }

    fn check(&mut self, i: &GearboxInputs, o: &GearboxOutputs) -> Result<(), String> {
        let lmask = (1u64 << self.w.l) - 1;
        let wmask = (1u64 << self.w.w) - 1;
        let was = self.previous.phase;
        let engaged_before = was.is_engaged();
        let stepped = o.step_up || o.step_down;
        if i.reset {
            *self = Self {
                locks: self.locks,
                lock_checks: self.lock_checks,
                rate_checks: self.rate_checks,
                lengths_reached: self.lengths_reached,
                overruns: self.overruns,
                waits: self.waits,
                ..Self::new(self.w)
            };
            if stepped || o.phase != Phase::Idle || o.position != 0 || o.overrun {
                return Err(format!("after reset: {o:?}"));
            }
            self.previous = *o;
            return Ok(());
        }
        if o.step_up && o.step_down {
            return Err("a step up and down in one clock".into());
        }
        let count = match (i.count_up, i.count_down) {
            (true, false) => Some(true),
            (false, true) => Some(false),
            _ => None,
        };
        // The arm: accepted when idle goes to armed.
        let valid = self
            .w
            .valid(i.numerator & wmask, i.denominator & wmask, i.ramp & wmask);
        if was == Phase::Idle && o.phase == Phase::Armed {
            if !valid || !i.arm || o.overrun || o.done || o.invalid {
                return Err(format!("armed without a valid arm: {i:?} {o:?}"));
            }
            self.armed = Some(*i);
            self.position = 0;
        }
        if was == Phase::Idle && i.arm && !i.stop && !i.halt && o.phase == Phase::Idle {
            if valid || !o.invalid {
                return Err(format!("an arm neither armed nor flagged: {i:?} {o:?}"));
            }
        }
        // The engine's timing.
        let mut committed = None;
        if i.halt {
            if stepped {
                return Err("a step in a halt's clock".into());
            }
            self.timer = 0;
            self.in_work = None;
            self.slot = None;
            self.trace.clear();
        } else if self.timer > 0 {
            if let Some(up) = count {
                if self.slot.is_some() {
                    if !o.overrun || o.phase != Phase::Idle || stepped {
                        return Err(format!("a third count did not overrun: {o:?}"));
                    }
                    self.overruns += 1;
                    self.timer = 0;
                    self.in_work = None;
                    self.slot = None;
                    self.trace.clear();
                    self.previous = *o;
                    return Ok(());
                }
                self.slot = Some(up);
                self.waits += 1;
            }
            self.timer -= 1;
            if self.timer == 0 {
                committed = self.in_work.take();
            }
        } else if engaged_before {
            let take = match self.slot.take() {
                Some(waiting) => {
                    self.slot = count;
                    Some(waiting)
                }
                None => count,
            };
            if take.is_some() {
                self.timer = ENGINE_CLOCKS;
                self.in_work = take;
            }
        } else {
            self.slot = None;
        }
        if o.overrun && !self.previous.overrun {
            return Err("overrun without a third count".into());
        }
        let Some(ratio) = self.armed else {
            if stepped || o.phase != Phase::Idle {
                return Err(format!("a step or a phase before any arm: {o:?}"));
            }
            self.previous = *o;
            return Ok(());
        };
        let up_is_forward = !ratio.spindle_reverse;
        if stepped {
            let Some(up) = committed else {
                return Err(format!("a step in no count's clock: was {was:?}, {i:?}"));
            };
            let forward = up == up_is_forward;
            let step_up = forward != ratio.axis_reverse;
            if o.step_up != step_up {
                return Err(format!("a step against its count: {i:?} {o:?}"));
            }
            self.position += if forward { 1 } else { -1 };
        }
        if o.position != (self.position as u64 & lmask) {
            return Err(format!(
                "position {} is not the net of the steps, {}",
                o.position, self.position
            ));
        }
        // The engage, and the counts after it.
        if was == Phase::Armed && o.phase == Phase::RampIn {
            if !i.index {
                return Err("engaged without an index".into());
            }
            let k = Self::window(ratio.denominator, ratio.ramp);
            self.counts = 0;
            // At rest before the engage: the windows start on zeros.
            self.trace = vec![0; 2 * k + 1];
            self.forward_since_engage = 0;
        }
        if let Some(up) = committed {
            if up == up_is_forward {
                self.counts += 1;
                self.forward_since_engage += 1;
                if !self.trace.is_empty() {
                    self.trace.push(self.position);
                    self.check_rate(ratio.numerator, ratio.denominator, ratio.ramp)?;
                }
            } else {
                self.counts -= 1;
                self.trace.clear();
                // The lock's time bound is for a spindle turning forward.
                self.forward_since_engage = i64::MIN / 2;
            }
        }
        let (n, d, ramp) = (ratio.numerator, ratio.denominator, ratio.ramp);
        // The lock's bound.
        if o.locked {
            self.lock_checks += 1;
            if !self.previous.locked {
                self.locks += 1;
            }
            let ideal = (n as i128 * self.counts as i128).div_euclid(d as i128) as i64;
            if ramp <= d && !(ideal - 1..=ideal).contains(&self.position) {
                return Err(format!(
                    "locked at {} steps, ideal floor(n m / d) = {ideal} (n {n}, d {d}, m {})",
                    self.position, self.counts
                ));
            }
        }
        // The lock comes: ramp-in, then the catch-up of its lag.
        if o.phase == Phase::Track && !o.locked && ramp > 0 && n + ramp <= d && ramp <= d {
            let ramp_in = n.div_ceil(ramp) as f64;
            let lag = n as f64 * (ramp_in + 1.0);
            let headroom = ((d - n) / ramp * ramp).max(1) as f64;
            let bound = ramp_in + 3.0 * (lag / ramp as f64).sqrt() + lag / headroom + 16.0;
            if self.forward_since_engage as f64 > bound {
                return Err(format!(
                    "no lock after {} forward counts (bound {bound:.0}; n {n}, d {d}, ramp {ramp})",
                    self.forward_since_engage
                ));
            }
        }
        // A run that reached its length ended there.
        if o.done && !self.previous.done {
            if !(engaged_before && o.phase == Phase::Idle) || ratio.length == 0 {
                return Err(format!("done without a run's end at a length: {i:?} {o:?}"));
            }
            let at = if stepped {
                self.position == ratio.length as i64
            } else {
                self.position >= ratio.length as i64
            };
            if !at {
                return Err(format!(
                    "done at {} steps, length {}",
                    self.position, ratio.length
                ));
            }
            self.lengths_reached += 1;
        }
        if o.phase == Phase::Idle {
            // At rest after a run's end (not a halt's): the windows end
            // on the final position.
            if engaged_before && !i.halt && !self.trace.is_empty() {
                for _ in 0..2 * Self::window(d, ramp) {
                    self.trace.push(self.position);
                    self.check_rate(n, d, ramp)?;
                }
            }
            self.trace.clear();
        }
        self.previous = *o;
        Ok(())
    }
}

impl Monitor {
    /// The window of the rate check: k = ceil(sqrt(4 d / ramp)) counts.
    fn window(d: u64, ramp: u64) -> usize {
        ((4.0 * d as f64 / ramp.max(1) as f64).sqrt().ceil() as usize).max(1)
    }

    /// The rate's change per count: over windows of k forward counts, the
    /// steps of two neighbouring windows differ by at most k^2 ramp / d + 2.
    fn check_rate(&mut self, n: u64, d: u64, ramp: u64) -> Result<(), String> {
        let k = Self::window(d, ramp);
        let t = &self.trace;
        if ramp == 0 || t.len() <= 2 * k {
            return Ok(());
        }
        let j = t.len() - 1;
        let second = t[j] - 2 * t[j - k] + t[j - 2 * k];
        let bound = (k * k) as f64 * ramp as f64 / d as f64 + 2.0;
        self.rate_checks += 1;
        if second.unsigned_abs() as f64 > bound {
            return Err(format!(
                "the rate changed faster than ramp: second difference {second} over {k} counts, bound {bound:.1} (n {n}, d {d}, ramp {ramp})"
            ));
        }
        Ok(())
    }
}

fn monitor_run(
    w: GearboxWidths,
    stimulus: &[GearboxInputs],
    mut step: impl FnMut(&GearboxInputs) -> GearboxOutputs,
) -> Result<Monitor, String> {
    let mut monitor = Monitor::new(w);
    for (cycle, i) in stimulus.iter().enumerate() {
        let o = step(i);
        monitor
            .check(i, &o)
            .map_err(|e| format!("cycle {cycle}: {e}"))?;
    }
    Ok(monitor)
}

#[test]
fn rtl_matches_model_and_the_monitor_in_verilator() {
    let stimulus = random_inputs(0x6ea7, 10_000_000, EXPORTED);
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "electronic_gearbox",
        ElectronicGearbox24::default(),
        GearboxModel::new(EXPORTED),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut monitor = Monitor::new(EXPORTED);
    let mut steps = 0u64;
    let mut phases = [0u64; 5];
    pair.run_all(&stimulus, |cycle, i, o| {
        monitor
            .check(i, o)
            .unwrap_or_else(|e| panic!("cycle {cycle}: {e}"));
        steps += (o.step_up || o.step_down) as u64;
        phases[o.phase as usize] += 1;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    println!(
        "{steps} steps, {} locks, {} lock checks, {} rate checks, {} lengths, {} waits, {} overruns, phases {phases:?}",
        monitor.locks, monitor.lock_checks, monitor.rate_checks, monitor.lengths_reached, monitor.waits, monitor.overruns
    );
    assert!(
        steps > 30_000
            && monitor.locks > 200
            && monitor.lock_checks > 1_000_000
            && monitor.rate_checks > 25_000
            && monitor.lengths_reached > 10
            && monitor.waits > 1_000
            && monitor.overruns > 10
            && phases.iter().all(|&p| p > 500_000),
        "{steps} steps, {} locks, {} lock checks, {} rate checks, {} lengths, phases {phases:?}",
        monitor.locks,
        monitor.lock_checks,
        monitor.rate_checks,
        monitor.lengths_reached
    );
}

#[test]
fn the_rust_hdl_rtl_matches_the_model() {
    let stimulus = random_inputs(0x6ea8, 100_000, EXPORTED);
    let mut pair = Lockstep::harness(
        "electronic_gearbox",
        ElectronicGearbox24::default(),
        GearboxModel::new(EXPORTED),
    );
    pair.run_all(&stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("{e}"));
}

/// W = 4, E = 8, L = 6: every ratio n <= d < 16 with every ramp, armed,
/// engaged with the spindle turning and run to a length, a stop and a
/// reversal, in Verilator against the model and the monitor.
#[test]
fn every_small_ratio_and_ramp() {
    let w = GearboxWidths { w: 4, e: 8, l: 6 };
    let mut stimulus = Vec::new();
    for d in 0..16u64 {
        for n in 0..16u64 {
            for ramp in 0..16u64 {
                let base = GearboxInputs {
                    numerator: n,
                    denominator: d,
                    ramp,
                    length: (n + d + ramp) % 40,
                    ..Default::default()
                };
                stimulus.push(GearboxInputs { arm: true, ..base });
                let mut angle = 0u64;
                for t in 0..100u64 {
                    let backward = (70..75).contains(&t);
                    angle += 1;
                    stimulus.push(GearboxInputs {
                        count_up: !backward,
                        count_down: backward,
                        index: angle.is_multiple_of(7),
                        ..base
                    });
                    for k in 0..31 {
                        stimulus.push(GearboxInputs {
                            stop: t == 85 && k == 3,
                            ..base
                        });
                    }
                }
                stimulus.push(GearboxInputs { halt: true, ..base });
            }
        }
    }
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "electronic_gearbox_small",
        ElectronicGearbox::<4, 8, 6>::default(),
        GearboxModel::new(w),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut monitor = Monitor::new(w);
    pair.run_all(&stimulus, |cycle, i, o| {
        monitor
            .check(i, o)
            .unwrap_or_else(|e| panic!("cycle {cycle}: {e}"));
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        monitor.locks > 500 && monitor.lengths_reached > 500,
        "{} locks, {} lengths",
        monitor.locks,
        monitor.lengths_reached
    );
}

/// The monitor fails a ratio one count off, a ramp that is not there, a
/// step dropped, a step a clock late and a step in the wrong direction.
#[test]
fn the_monitor_catches_a_wrong_ratio_a_missing_ramp_and_a_lost_step() {
    let stimulus = random_inputs(0x6ea9, 200_000, EXPORTED);
    let run = |mutate: &dyn Fn(&GearboxInputs) -> GearboxInputs,
               corrupt: &dyn Fn(u64, GearboxOutputs) -> GearboxOutputs| {
        let mut model = GearboxModel::new(EXPORTED);
        let mut clock = 0u64;
        monitor_run(EXPORTED, &stimulus, |i| {
            clock += 1;
            corrupt(clock, model.step(mutate(i)))
        })
        .map(|_| ())
    };
    let same = |i: &GearboxInputs| *i;
    let clean = |_, o| o;
    assert_eq!(run(&same, &clean), Ok(()));

    let valid = |i: &GearboxInputs| EXPORTED.valid(i.numerator, i.denominator, i.ramp);
    let n_plus_one = run(
        &|i: &GearboxInputs| {
            let more = GearboxInputs {
                numerator: i.numerator + 1,
                ..*i
            };
            if valid(i) && valid(&more) {
                more
            } else {
                *i
            }
        },
        &clean,
    );
    assert!(
        n_plus_one.as_ref().is_err_and(|e| e.contains("locked at")),
        "{n_plus_one:?}"
    );

    let no_ramp = run(
        &|i: &GearboxInputs| {
            if valid(i) {
                GearboxInputs { ramp: 0, ..*i }
            } else {
                *i
            }
        },
        &clean,
    );
    assert!(
        no_ramp.as_ref().is_err_and(|e| e.contains("rate changed")),
        "{no_ramp:?}"
    );

    let dropped_one = std::cell::Cell::new(false);
    let dropped = run(&same, &|clock, mut o: GearboxOutputs| {
        if clock >= 100_000 && o.step_up && !dropped_one.get() {
            o.step_up = false;
            dropped_one.set(true);
        }
        o
    });
    assert!(
        dropped
            .as_ref()
            .is_err_and(|e| e.contains("net of the steps")),
        "{dropped:?}"
    );

    // Every step one clock late: the engine's timing is part of the contract.
    // (with the position that goes with it).
    let late_step = std::cell::Cell::new((false, false, 0u64));
    let late = run(&same, &|_, mut o: GearboxOutputs| {
        let (up, down, position) = late_step.replace((o.step_up, o.step_down, o.position));
        (o.step_up, o.step_down, o.position) = (up, down, position);
        o
    });
    assert!(
        late.as_ref().is_err_and(|e| e.contains("no count's clock")),
        "{late:?}"
    );

    let flipped = run(&same, &|clock, mut o: GearboxOutputs| {
        if clock > 50_000 && o.step_up {
            (o.step_up, o.step_down) = (false, true);
        }
        o
    });
    assert!(
        flipped
            .as_ref()
            .is_err_and(|e| e.contains("against its count")),
        "{flipped:?}"
    );
}

/// The geared motion is a function of the spindle's angle alone: the same
/// ratio engaged at three spindle speeds (a count every 32 clocks, every
/// 51 clocks, and at a randomly varying rate) makes the same step at the same
/// count, through ramp-in, catch-up, lock and ramp-out to the length.
#[test]
fn the_same_steps_at_every_spindle_speed() {
    let (n, d, ramp) = (1234u64, 4096u64, 41u64);
    let length = 2500u64;
    let runs: Vec<Vec<(u64, i64)>> = [31u32, 50, 99]
        .iter()
        .map(|&gap| {
            let mut rng = StdRng::seed_from_u64(gap as u64);
            let mut model = GearboxModel::new(EXPORTED);
            let base = GearboxInputs {
                numerator: n,
                denominator: d,
                ramp,
                length,
                ..Default::default()
            };
            model.step(GearboxInputs { arm: true, ..base });
            let mut angle = 17u64;
            let mut at_count = Vec::new();
            let mut position = 0i64;
            loop {
                angle += 1;
                let o = model.step(GearboxInputs {
                    count_up: true,
                    index: angle.is_multiple_of(1024),
                    ..base
                });
                position += o.step_up as i64 - o.step_down as i64;
                // Each count's step shows before the next count comes.
                let wait = if gap == 99 {
                    rng.gen_range(31..90)
                } else {
                    gap
                };
                let mut last = o;
                for _ in 0..wait {
                    last = model.step(base);
                    position += last.step_up as i64 - last.step_down as i64;
                }
                at_count.push((angle, position));
                if (last.phase == Phase::Idle && angle > 4096) || angle > 40_000 {
                    break;
                }
            }
            at_count
        })
        .collect();
    assert!(
        runs[0].last().unwrap().1 == length as i64,
        "{:?}",
        runs[0].last()
    );
    for (k, run) in runs.iter().enumerate().skip(1) {
        let common = run.len().min(runs[0].len());
        if let Some(j) = (0..common).find(|&j| run[j] != runs[0][j]) {
            panic!(
                "run {k} leaves run 0 at count {j}: {:?} against {:?} (last {:?})",
                run[j],
                runs[0][j],
                run.last()
            );
        }
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<ElectronicGearbox24>(
        Instance::Exported("electronic_gearbox"),
        random_inputs(0x6eaa, 30_000, EXPORTED)
            .iter()
            .map(GearboxInputs::to_vector),
    );
}

#[test]
fn narrow_verilog_matches_rust_in_icarus_and_verilator() {
    let w = GearboxWidths { w: 6, e: 10, l: 8 };
    check_instance::<ElectronicGearbox<6, 10, 8>>(
        Instance::Generated("electronic_gearbox_w6"),
        random_inputs(0x6eab, 30_000, w)
            .iter()
            .map(GearboxInputs::to_vector),
    );
}

/// A halt wins over a count that would overrun in its clock: the count is
/// dropped with the rest, `overrun` stays clear (found in the controller's
/// lockstep, where an abort met a spindle counting every clock).
#[test]
fn a_count_that_meets_a_halt_is_dropped_not_an_overrun() {
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "electronic_gearbox",
        ElectronicGearbox24::default(),
        GearboxModel::new(EXPORTED),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let ratio = GearboxInputs {
        numerator: 1,
        denominator: 8,
        ramp: 1,
        ..Default::default()
    };
    let mut step = |i: GearboxInputs| pair.step(&i).unwrap_or_else(|e| panic!("{e}"));
    step(GearboxInputs {
        reset: true,
        ..ratio
    });
    step(GearboxInputs { arm: true, ..ratio });
    step(GearboxInputs {
        index: true,
        ..ratio
    });
    // Counts every clock: the engine takes one, the slot holds the next.
    for _ in 0..2 {
        step(GearboxInputs {
            count_up: true,
            ..ratio
        });
    }
    let out = step(GearboxInputs {
        count_up: true,
        halt: true,
        ..ratio
    });
    assert_eq!(out.phase, Phase::Idle);
    assert!(!out.overrun, "a halted count is not an overrun");
    // Without the halt the same count overruns.
    step(GearboxInputs { arm: true, ..ratio });
    step(GearboxInputs {
        index: true,
        ..ratio
    });
    for _ in 0..2 {
        step(GearboxInputs {
            count_up: true,
            ..ratio
        });
    }
    let out = step(GearboxInputs {
        count_up: true,
        ..ratio
    });
    assert!(out.overrun);
    assert_eq!(out.phase, Phase::Idle);
}
