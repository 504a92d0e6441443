//! `SoftLimits` (the controller's soft-limit check): RTL against the
//! model, and a monitor of the contract from the ports alone: at the end
//! of every turn the axis's `BEYOND` bit is (Δ − MARGIN) × P <= |J| × G'
//! for the values taken at its load, with G' from the length of a stop
//! at the present RATE (computed here by running a plain ramp, not by the
//! block's gauge), and 0 for an axis that stands, is disabled, analog, or
//! when the controller is not running.

use motion_hdl::blocks::motion_controller::hold_ramp::UNITY;
use motion_hdl::blocks::motion_controller::registers::{axis, global, AXIS_BASE, AXIS_STRIDE};
use motion_hdl::blocks::motion_controller::soft_limits::{
    check_latency, reach_ticks, stop_length, SoftLimits, SoftLimitsInputs, SoftLimitsModel,
    SoftLimitsOutputs, CHECK_CLOCKS, MARGIN, REACH_MAX,
};
use motion_hdl::sim::{Backend, Lockstep};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const K: usize = 3;

/// A stop from full speed at `rate` (0 as UNITY) starting at `phase`:
/// its length in ticks and the ticks it lets through the gate.
fn stop(rate: u16, phase: u32) -> (u64, u64) {
    let step = if rate == 0 { UNITY } else { rate as u32 };
    let (mut factor, mut phase, mut length, mut ticks) = (UNITY, phase, 0u64, 0u64);
    while factor > 0 {
        length += 1;
        if phase + factor >= UNITY {
            ticks += 1;
        }
        phase = (phase + factor) % UNITY;
        factor = factor.saturating_sub(step);
    }
    (length, ticks)
}

/// The stop's reach the contract gives once `rate` is measured, from a
/// plain ramp's length.
fn reach(rate: u16) -> u64 {
    stop(rate, 0).0 / 2 + 1 + check_latency(K as u32) as u64
}

fn min_address(k: usize) -> u32 {
    AXIS_BASE + k as u32 * AXIS_STRIDE + axis::SOFT_MIN
}

fn max_address(k: usize) -> u32 {
    AXIS_BASE + k as u32 * AXIS_STRIDE + axis::SOFT_MAX
}

fn sign24(v: i64) -> u32 {
    (v as u32) & 0xff_ffff
}

/// Random traffic that puts most loads near the verdict's threshold: the
/// stimulus follows the turn schedule, so it knows which axis loads.
fn random_inputs(seed: u64, cycles: usize) -> Vec<SoftLimitsInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let rates = [0u16, 1, 3, 100, 700, 4096, 30000, 65535];
    let mut rate = 700u16;
    let mut period = 8u16;
    let mut window = [(-5000i64, 5000i64); K];
    let mut clock = 0u64;
    let mut out = Vec::with_capacity(cycles);
    let mut pending: Vec<(u32, u32)> = Vec::new();
    for k in 0..K {
        pending.push((min_address(k), sign24(window[k].0)));
        pending.push((max_address(k), sign24(window[k].1)));
    }
    pending.push((global::SOFT_LIMIT, 0b111));
    let mut load = SoftLimitsInputs::default();
    for _ in 0..cycles {
        let step = clock % CHECK_CLOCKS as u64;
        let k = (clock / CHECK_CLOCKS as u64) as usize % K;
        if step == 0 {
            if rng.gen_ratio(1, 300) {
                rate = rates[rng.gen_range(0..rates.len())];
            }
            if rng.gen_ratio(1, 200) {
                period = [0, 1, 2, 8, 100, 65535][rng.gen_range(0..6)];
            }
            let magnitude: u16 = match rng.gen_range(0..10) {
                0 => 0,
                1 => rng.gen(),
                _ => rng.gen_range(1..=period.max(1)),
            };
            let negative = rng.gen_bool(0.5);
            let threshold =
                (magnitude as i64 * reach(rate) as i64) / period.max(1) as i64 + MARGIN as i64;
            let offset = match rng.gen_range(0..4) {
                0 => rng.gen_range(-3000..3000),
                _ => threshold + rng.gen_range(-3..=3),
            };
            let (low, high) = window[k];
            let position = if negative {
                low + offset
            } else {
                high - offset
            };
            load = SoftLimitsInputs {
                position: sign24(position),
                magnitude,
                negative,
                step_axis: !rng.gen_ratio(1, 20),
                ..load
            };
            if rng.gen_ratio(1, 50) {
                let centre = rng.gen_range(-8_000_000i64..8_000_000);
                let span = rng.gen_range(-10i64..100_000);
                window[k] = (centre - span, centre + span);
                pending.push((min_address(k), sign24(window[k].0)));
                pending.push((max_address(k), sign24(window[k].1)));
            }
            if rng.gen_ratio(1, 100) {
                pending.push((global::SOFT_LIMIT, rng.gen_range(0..16)));
            }
        }
        let mut write = match step {
            5..=15 => pending.pop(),
            _ => None,
        };
        // A window rewritten a step or two off in the turn's first clocks:
        // mostly the bound the load reads, in the load's own clock (the
        // check must take the word written), else the other bound or
        // another axis's window (the check must not take those), and
        // later in the turn (the check keeps the word of its load).
        if step <= 4 && rng.gen_ratio(1, 10) {
            let nudge = rng.gen_range(-2..=2);
            let (j, minimum) = match rng.gen_range(0..4) {
                0 | 1 => (k, load.negative),
                2 => (k, !load.negative),
                _ => ((k + rng.gen_range(1..K)) % K, rng.gen_bool(0.5)),
            };
            write = Some(match minimum {
                true => {
                    window[j].0 += nudge;
                    (min_address(j), sign24(window[j].0))
                }
                false => {
                    window[j].1 += nudge;
                    (max_address(j), sign24(window[j].1))
                }
            });
        } else if step <= 4 && rng.gen_ratio(1, 200) {
            // ENABLE written at a load or in the clocks after it.
            write = Some((global::SOFT_LIMIT, rng.gen_range(0..8)));
        }
        // Window reads, some in the clock of a write (to the same word:
        // the bus has one address), none in a verdict's clock.
        let read = match step {
            5..=21 => rng.gen_ratio(1, 4),
            _ => false,
        };
        let j = rng.gen_range(0..K);
        let (read_address, word) = match rng.gen_range(0..3) {
            0 => (min_address(j), Some(window[j].0)),
            1 => (max_address(j), Some(window[j].1)),
            _ => (rng.gen_range(0..256), None),
        };
        // Some of them rewrite the word (with its own value: the verdicts'
        // stimulus stays as planned).
        if let (true, None, Some(word)) = (read, write, word) {
            if rng.gen_ratio(1, 4) {
                write = Some((read_address, sign24(word)));
            }
        }
        let reset = rng.gen_ratio(1, 100_000);
        out.push(SoftLimitsInputs {
            reset,
            address: write.map_or(
                if read {
                    read_address
                } else {
                    global::SOFT_LIMIT
                },
                |w| w.0,
            ),
            write: write.is_some(),
            write_data: write.map_or(rng.gen(), |w| w.1),
            read,
            running: !rng.gen_ratio(1, 2000),
            rate,
            period,
            ..load
        });
        clock = if reset { 0 } else { clock + 1 };
    }
    out
}

/// The contract at the ports, clock by clock; the first violation.
struct Monitor {
    clock: u64,
    minimum: [u32; K],
    maximum: [u32; K],
    enable: u32,
    /// The rate and the clocks it has been steady for.
    rate: u16,
    steady: u64,
    /// The load of the turn in progress, and G' candidates at s = 3.
    load: SoftLimitsInputs,
    /// The bound the load heads for, as it was then.
    bound: u32,
    live: bool,
    reaches: Vec<u64>,
    period: u64,
    /// `window_data` as the last read leaves it.
    window_data: u32,
    verdicts: u64,
    beyond: u64,
    /// Window reads checked, and those in the clock of a write.
    window_reads: u64,
    colliding_reads: u64,
}

impl Monitor {
    fn new() -> Self {
        Self {
            clock: 0,
            minimum: [0; K],
            maximum: [0; K],
            enable: 0,
            rate: 0,
            steady: 0,
            load: SoftLimitsInputs::default(),
            bound: 0,
            live: false,
            reaches: vec![],
            period: 1,
            window_data: 0,
            verdicts: 0,
            beyond: 0,
            window_reads: 0,
            colliding_reads: 0,
        }
    }

    fn check(&mut self, i: &SoftLimitsInputs, o: &SoftLimitsOutputs) -> Result<(), String> {
        let signed = |v: u32| ((v << 8) as i32 >> 8) as i64;
        let step = self.clock % CHECK_CLOCKS as u64;
        let k = (self.clock / CHECK_CLOCKS as u64) as usize % K;
        // After the edge: the axis of the next clock's turn.
        let next = ((self.clock + 1) / CHECK_CLOCKS as u64) as usize % K;
        if o.select != next as u32 && !i.reset {
            return Err(format!(
                "select {} after the edge, expected {next}",
                o.select
            ));
        }
        if i.rate == self.rate {
            self.steady += 1;
        } else {
            (self.rate, self.steady) = (i.rate, 0);
        }
        if step == 0 {
            self.load = *i;
            let address = match i.negative {
                true => min_address(k),
                false => max_address(k),
            };
            self.bound = match (i.negative, i.write && i.address == address) {
                (_, true) => i.write_data & 0xff_ffff,
                (true, false) => self.minimum[k],
                (false, false) => self.maximum[k],
            };
            self.live = i.running && self.enable >> k & 1 != 0 && i.step_axis && i.magnitude != 0;
        }
        if step == 3 {
            // Measured once the gauge has seen the rate through two stops.
            let settle = 2 * (UNITY.div_ceil(self.rate.max(1) as u32) as u64 + 3);
            self.reaches = match self.steady > settle {
                true => vec![reach(i.rate)],
                false => vec![reach(i.rate), REACH_MAX as u64],
            };
            self.period = (i.period as u64).max(1);
        }
        let enable_now = match i.write && i.address == global::SOFT_LIMIT {
            true => i.write_data & 0b111,
            false => self.enable,
        };
        let verdict_clock = step == CHECK_CLOCKS as u64 - 1;
        if verdict_clock && !i.reset && !i.write && i.address == global::SOFT_LIMIT {
            let bit = o.read_data >> (8 + k) & 1 != 0;
            let bound = signed(self.bound);
            let position = signed(self.load.position);
            let delta = match self.load.negative {
                true => position - bound,
                false => bound - position,
            } - MARGIN as i64;
            let delta = delta.clamp(-(1 << 19) + 1, 1 << 19) as i128;
            let allowed: Vec<bool> = self
                .reaches
                .iter()
                .map(|&g| {
                    self.live
                        && i.running
                        && enable_now >> k & 1 != 0
                        && delta * self.period as i128 <= self.load.magnitude as i128 * g as i128
                })
                .collect();
            if !allowed.contains(&bit) {
                return Err(format!(
                    "axis {k}: BEYOND {bit}, the rule says {allowed:?} (delta - margin {delta}, P {}, |J| {}, G' {:?}, live {})",
                    self.period, self.load.magnitude, self.reaches, self.live
                ));
            }
            self.verdicts += 1;
            self.beyond += bit as u64;
        }
        if i.read {
            self.window_data = 0;
            for k in 0..K {
                let word = match i.address {
                    a if a == min_address(k) => self.minimum[k],
                    a if a == max_address(k) => self.maximum[k],
                    _ => continue,
                };
                self.window_reads += 1;
                self.colliding_reads += i.write as u64;
                if !i.write {
                    self.window_data = signed(word) as u32;
                }
            }
        }
        if o.window_data != self.window_data && !i.reset {
            return Err(format!(
                "window_data {:#x}, expected {:#x}",
                o.window_data, self.window_data
            ));
        }
        if i.write {
            for k in 0..K {
                if i.address == min_address(k) {
                    self.minimum[k] = i.write_data & 0xff_ffff;
                }
                if i.address == max_address(k) {
                    self.maximum[k] = i.write_data & 0xff_ffff;
                }
            }
        }
        self.enable = enable_now;
        self.clock += 1;
        if i.reset {
            *self = Self {
                verdicts: self.verdicts,
                beyond: self.beyond,
                window_reads: self.window_reads,
                colliding_reads: self.colliding_reads,
                ..Self::new()
            };
        }
        Ok(())
    }
}

fn monitor_run(
    stimulus: &[SoftLimitsInputs],
    mut step: impl FnMut(&SoftLimitsInputs) -> SoftLimitsOutputs,
) -> Result<(u64, u64), String> {
    let mut monitor = Monitor::new();
    for (cycle, i) in stimulus.iter().enumerate() {
        let o = step(i);
        monitor
            .check(i, &o)
            .map_err(|e| format!("cycle {cycle}: {e}"))?;
    }
    Ok((monitor.verdicts, monitor.beyond))
}

#[test]
fn rtl_matches_model_and_every_verdict_keeps_the_rule() {
    let stimulus = random_inputs(0x5017, 400_000);
    let mut pair = Lockstep::on(
        Backend::Verilator,
        "soft_limits",
        SoftLimits::<K>::default(),
        SoftLimitsModel::new(K),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut monitor = Monitor::new();
    let mut events = 0u64;
    pair.run_all(&stimulus, |cycle, i, o| {
        monitor
            .check(i, o)
            .unwrap_or_else(|e| panic!("cycle {cycle}: {e}"));
        events += o.tripped as u64;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    let (verdicts, beyond) = (monitor.verdicts, monitor.beyond);
    assert!(
        verdicts > 10_000 && beyond > 2_000 && verdicts - beyond > 2_000 && events > 500,
        "{verdicts} verdicts, {beyond} beyond, {events} events"
    );
    let (reads, colliding) = (monitor.window_reads, monitor.colliding_reads);
    assert!(
        reads > 20_000 && colliding > 1_000,
        "{reads} window reads, {colliding} in a write's clock"
    );
}

/// Delays every write that `collides` says collides to the next clock,
/// in place of that clock's own write if it has one.
fn delaying_collisions(
    collides: impl Fn(u64, &SoftLimitsInputs) -> bool,
) -> impl FnMut(&SoftLimitsInputs) -> SoftLimitsInputs {
    let mut clock = 0u64;
    let mut delayed: Option<SoftLimitsInputs> = None;
    move |i| {
        let mut fed = *i;
        if let Some(w) = delayed.take() {
            (fed.address, fed.write, fed.write_data) = (w.address, true, w.write_data);
        }
        if i.write && collides(clock % CHECK_CLOCKS as u64, i) {
            delayed = Some(*i);
            fed.write = false;
        }
        clock = if i.reset { 0 } else { clock + 1 };
        fed
    }
}

#[test]
fn the_rust_hdl_rtl_matches_the_model() {
    let stimulus = random_inputs(0x5018, 20_000);
    let mut pair = Lockstep::harness(
        "soft_limits",
        SoftLimits::<K>::default(),
        SoftLimitsModel::new(K),
    );
    pair.run_all(&stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The monitor fails a verdict one step off (the position taken one step
/// further in), a reach without the latency, and a flipped verdict.
#[test]
fn the_monitor_catches_an_off_by_one_distance_and_a_short_reach() {
    let stimulus = random_inputs(0x5019, 200_000);
    let mut model = SoftLimitsModel::new(K);
    assert!(monitor_run(&stimulus, |i| model.step(i)).is_ok());

    // One step further in than the pins say.
    let mut model = SoftLimitsModel::new(K);
    let shifted = monitor_run(&stimulus, |i| {
        let inward = if i.negative { 1 } else { -1i32 };
        model.step(&SoftLimitsInputs {
            position: (i.position as i32 + inward) as u32 & 0xff_ffff,
            ..*i
        })
    });
    assert!(
        shifted.as_ref().is_err_and(|e| e.contains("BEYOND")),
        "{shifted:?}"
    );

    // A period 1 longer: the reach shrinks by |J| G' / P(P + 1).
    let mut model = SoftLimitsModel::new(K);
    let longer = monitor_run(&stimulus, |i| {
        model.step(&SoftLimitsInputs {
            period: i.period.max(1).saturating_add(1),
            ..*i
        })
    });
    assert!(
        longer.as_ref().is_err_and(|e| e.contains("BEYOND")),
        "{longer:?}"
    );

    // A flipped verdict bit.
    let mut model = SoftLimitsModel::new(K);
    let mut flipped = false;
    let flip = monitor_run(&stimulus, |i| {
        let mut o = model.step(i);
        // Right after a verdict that turned beyond.
        if !flipped && o.tripped {
            o.read_data ^= 0b111 << 8;
            flipped = true;
        }
        o
    });
    assert!(flip.is_err(), "{flip:?}");

    // The check taking the old word when its load's clock writes it.
    let mut model = SoftLimitsModel::new(K);
    let mut feed = delaying_collisions(|step, _| step == 0);
    let old_bound = monitor_run(&stimulus, |i| model.step(&feed(i)));
    assert!(
        old_bound.as_ref().is_err_and(|e| e.contains("BEYOND")),
        "{old_bound:?}"
    );

    // A window read in the clock of its write giving the old word.
    let mut model = SoftLimitsModel::new(K);
    let mut feed = delaying_collisions(|_, i| i.read);
    let old_word = monitor_run(&stimulus, |i| model.step(&feed(i)));
    assert!(
        old_word.as_ref().is_err_and(|e| e.contains("window_data")),
        "{old_word:?}"
    );
}

/// Every rate's gauge: the reach the block uses, read back through the
/// verdict's threshold, is the contract's (exhaustive over the rates that
/// the stimulus does not cover is too long; a sweep of 64 rates).
#[test]
fn the_gauge_measures_every_swept_rate() {
    let mut model = SoftLimitsModel::new(1);
    for rate in (0..=u16::MAX).step_by(1021).chain([1, 2, 65535]) {
        let steady = SoftLimitsInputs {
            rate,
            ..Default::default()
        };
        let settle = 2 * (UNITY.div_ceil(rate.max(1) as u32) as u64 + 3) + 4;
        for _ in 0..settle {
            model.step(&steady);
        }
        assert_eq!(
            model.reach() as u64,
            stop(rate, 0).0 / 2 + 1 + check_latency(1) as u64,
            "rate {rate}"
        );
        assert_eq!(model.reach(), reach_ticks(rate, 1), "rate {rate}");
    }
}

/// The reach's floor(N / 2) + 1 covers the ticks a stop lets through at
/// every rate, from the phase that lets the most through (the gate passes
/// floor((phase + sum of the factors) / UNITY) ticks, so the largest phase
/// passes the most), and it is never more than one tick above the ticks
/// of a stop from phase 0 plus 1 (the first version's measured reach).
#[test]
fn the_reach_covers_every_rate_from_any_phase() {
    for rate in 0..=u16::MAX {
        let (length, from_zero) = stop(rate, 0);
        let (_, most) = stop(rate, UNITY - 1);
        let covered = length / 2 + 1;
        assert!(
            most <= covered,
            "rate {rate}: {most} ticks through, {covered} covered"
        );
        assert!(
            covered <= from_zero + 1,
            "rate {rate}: {covered} against {from_zero} + 1"
        );
        assert_eq!(length, stop_length(rate) as u64, "rate {rate}");
    }
}
