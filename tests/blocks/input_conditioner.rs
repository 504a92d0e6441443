//! `InputConditioner`: RTL against the model on random pins for 1, 3 and 8
//! inputs, and an independent monitor of the port contract (priming,
//! latency, glitch rejection, edges) that knows only the pins, the settings
//! and the outputs, with proof by mutation that the monitor catches a
//! broken output stream.
//!
//! No cross-simulation here: the conditioner is an internal block (like the
//! `GlitchFilter` it is made of), exported only inside `motion_controller`,
//! whose cross-simulation covers it.

use motion_hdl::blocks::input_conditioner::model::{
    InputConditionerInputs, InputConditionerModel, InputConditionerOutputs,
};
use motion_hdl::blocks::input_conditioner::{InputConditioner, PRIME_CLOCKS};
use motion_hdl::sim::{Harness, Lockstep};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn harness<const W: usize>() -> Harness<InputConditioner<W>> {
    Harness::new("input_conditioner", InputConditioner::<W>::default()).unwrap()
}

/// One clock of the RTL with `inputs` applied.
fn rtl_clock<const W: usize>(
    h: &mut Harness<InputConditioner<W>>,
    inputs: &InputConditionerInputs,
) -> InputConditionerOutputs {
    InputConditionerOutputs::from_vector(&h.step_vector(&inputs.to_vector()).unwrap())
}

fn mask(width: u32) -> u32 {
    (u64::MAX >> (64 - width)) as u32
}

/// How the pins behave in one segment of the stimulus: each bit holds a
/// level for a random run length drawn from the segment's range.
#[derive(Clone, Copy, Debug)]
enum Pins {
    /// Long stable stretches.
    Stable,
    /// Every run 1 to 3 clocks: bounce, a broken wire.
    Chatter,
    /// Runs of 1 to 20 clocks, so run lengths meet every `length`.
    Mixed,
}

/// Random pins in segments of stable stretches and chatter, per bit.
struct PinDriver {
    rng: StdRng,
    width: u32,
    raw: u32,
    run_left: Vec<u32>,
    pins: Pins,
    segment_left: u32,
}

impl PinDriver {
    fn new(seed: u64, width: u32) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            width,
            raw: 0,
            run_left: vec![0; width as usize],
            pins: Pins::Mixed,
            segment_left: 0,
        }
    }

    /// The pins of the next clock.
    fn next(&mut self) -> u32 {
        let rng = &mut self.rng;
        if self.segment_left == 0 {
            self.pins =
                [Pins::Stable, Pins::Chatter, Pins::Mixed, Pins::Mixed][rng.gen_range(0..4)];
            self.segment_left = rng.gen_range(20..800);
            // A new segment starts new runs now.
            self.run_left.iter_mut().for_each(|r| *r = 0);
        }
        self.segment_left -= 1;
        for bit in 0..self.width as usize {
            if self.run_left[bit] == 0 {
                self.raw ^= rng.gen_bool(0.7) as u32 * (1 << bit);
                self.run_left[bit] = match self.pins {
                    Pins::Stable => rng.gen_range(30..3000),
                    Pins::Chatter => rng.gen_range(1..4),
                    Pins::Mixed => rng.gen_range(1..21),
                };
            }
            self.run_left[bit] -= 1;
        }
        self.raw & mask(self.width)
    }
}

/// The full random stimulus of the lockstep runs: the pins of a
/// [`PinDriver`], random `invert` changes, a sample strobe of random density
/// per segment, a random `length` that changes now and then, and resets
/// (some of them several clocks long).
struct Driver {
    pins: PinDriver,
    invert: u32,
    length: u8,
    sample_density: f64,
    sample_left: u32,
    reset_left: u32,
}

impl Driver {
    fn new(seed: u64, width: u32) -> Self {
        Self {
            pins: PinDriver::new(seed, width),
            invert: 0,
            length: 3,
            sample_density: 1.0,
            sample_left: 0,
            reset_left: 0,
        }
    }

    fn next(&mut self) -> InputConditionerInputs {
        let raw = self.pins.next();
        let width = self.pins.width;
        let rng = &mut self.pins.rng;
        if self.sample_left == 0 {
            self.sample_density = [1.0, 1.0, 0.5, 0.25, 0.9, 0.05][rng.gen_range(0..6)];
            self.sample_left = rng.gen_range(100..5000);
        }
        self.sample_left -= 1;
        if rng.gen_ratio(1, 700) {
            self.length = rng.gen_range(0..16);
        }
        if rng.gen_ratio(1, 900) {
            self.invert ^= 1 << rng.gen_range(0..width);
        }
        if rng.gen_ratio(1, 400) {
            self.invert = rng.gen::<u32>() & mask(width);
        }
        if self.reset_left == 0 && rng.gen_ratio(1, 4000) {
            self.reset_left = [1, 1, 2, 5][rng.gen_range(0..4)];
        }
        let reset = self.reset_left > 0;
        self.reset_left = self.reset_left.saturating_sub(1);
        InputConditionerInputs {
            reset,
            raw,
            invert: self.invert,
            sample: rng.gen_bool(self.sample_density),
            length: self.length,
        }
    }
}

/// Events seen in a lockstep run, so a run that never exercises a rule
/// cannot pass.
#[derive(Debug, Default)]
struct Seen {
    rises: u64,
    falls: u64,
    resets: u64,
    not_ready: u64,
    active_bits: u64,
}

fn lockstep<const W: usize>(seed: u64, cycles: u64) -> Seen {
    let mut driver = Driver::new(seed, W as u32);
    let mut pair = Lockstep::harness(
        "input_conditioner",
        InputConditioner::<W>::default(),
        InputConditionerModel::new(W as u32),
    );
    let mut seen = Seen::default();
    pair.run(
        |cycle, _| (cycle < cycles).then(|| driver.next()),
        |_, inputs, rtl| {
            seen.rises += rtl.rise.count_ones() as u64;
            seen.falls += rtl.fall.count_ones() as u64;
            seen.resets += inputs.reset as u64;
            seen.not_ready += !rtl.ready as u64;
            seen.active_bits += rtl.active.count_ones() as u64;
        },
    )
    .unwrap_or_else(|e| panic!("W {W}: {e}"));
    seen
}

fn assert_covered(seen: &Seen, width: u64, cycles: u64) {
    assert!(
        seen.rises > cycles * width / 200 && seen.falls > cycles * width / 200,
        "{seen:?}"
    );
    assert!(seen.resets > cycles / 8000, "{seen:?}");
    assert!(seen.not_ready > 3 * cycles / 8000, "{seen:?}");
    assert!(
        seen.active_bits > cycles * width / 5 && seen.active_bits < cycles * width * 4 / 5,
        "{seen:?}"
    );
}

#[test]
fn rtl_matches_model_with_1_input() {
    let cycles = 1_000_000;
    assert_covered(&lockstep::<1>(0x1c01, cycles), 1, cycles);
}

#[test]
fn rtl_matches_model_with_3_inputs() {
    let cycles = 600_000;
    assert_covered(&lockstep::<3>(0x1c03, cycles), 3, cycles);
}

#[test]
fn rtl_matches_model_with_8_inputs() {
    let cycles = 300_000;
    assert_covered(&lockstep::<8>(0x1c08, cycles), 8, cycles);
}

/// One clock as the monitor sees it: the pins, the settings and the outputs.
#[derive(Clone, Copy, Debug, Default)]
struct Observed {
    reset: bool,
    raw: u32,
    invert: u32,
    out: InputConditionerOutputs,
}

/// Rules checked, so a monitor that checks nothing cannot pass.
#[derive(Debug, Default)]
struct Checked {
    /// Accepted changes, each checked to have had its D samples.
    changes: u64,
    /// (bit, clock) pairs where a level had just been held D clocks and
    /// had to be on `active`: the latency bound, at its deadline.
    deadlines: u64,
    /// Pin runs shorter than D (with D >= 2) while primed: glitches.
    glitches: u64,
    /// Ends of priming.
    primings: u64,
}

/// The port contract of `InputConditioner` with a sample on every clock and
/// a fixed `length` k, checked from the pins and the outputs alone; D is
/// max(k, 1). Clock t means: the inputs of clock t applied, the outputs
/// read after its edge.
///
/// * `ready` is 1 exactly when none of clocks t - 2 ..= t is a reset and
///   t >= 2 (three priming edges after reset or power-up).
/// * While `ready` is 0, `active`, `rise` and `fall` are 0.
/// * At the first ready clock, `active` is the pins of clock t - 2 (the
///   synchronizer's content), polarity applied, with no `rise` or `fall`.
/// * Let level = `active` ^ `invert`. Once primed, level changes at t only
///   if the pins held the new level on clocks t - 1 - D ..= t - 2 (the D
///   samples at edges t - D + 1 ..= t, each after priming): a pin run
///   shorter than D clocks never appears, and no change is early.
/// * A pin level held on clocks c ..= c + D - 1 is on level at clock
///   c + 1 + D at the latest (if primed from clock c + 1 on): the latency
///   from the first edge that sees a pin change (edge c) is at most D + 1
///   clocks, i.e. max(k, 1) + 2 clocks from the last edge that saw the old
///   level. With the rule above it is exactly that.
/// * `rise` = changed level & `active`, `fall` = changed level & !`active`:
///   one clock per accepted change; a change of `invert` alone flips
///   `active` without an edge.
struct Monitor {
    mask: u32,
    d: usize,
    log: Vec<Observed>,
    run_start: Vec<usize>,
    checked: Checked,
}

impl Monitor {
    fn new(width: u32, k: u8) -> Self {
        Self {
            mask: mask(width),
            d: k.max(1) as usize,
            log: Vec::new(),
            run_start: vec![0; width as usize],
            checked: Checked::default(),
        }
    }

    fn ready_expected(&self, t: usize) -> bool {
        t >= 2 && self.log[t - 2..=t].iter().all(|o| !o.reset)
    }

    fn bit(word: u32, b: usize) -> bool {
        word >> b & 1 != 0
    }

    /// The pins of clocks `from ..= to` all have bit `b` at `v`.
    fn pins_held(&self, b: usize, v: bool, from: usize, to: usize) -> bool {
        self.log[from..=to].iter().all(|o| Self::bit(o.raw, b) == v)
    }

    fn level(&self, t: usize) -> u32 {
        (self.log[t].out.active ^ self.log[t].invert) & self.mask
    }

    /// Checks clock `o`, the next one.
    fn check(&mut self, o: Observed) -> Result<(), String> {
        self.log.push(o);
        let t = self.log.len() - 1;
        let out = o.out;
        let (d, mask) = (self.d, self.mask);
        let ready = self.ready_expected(t);

        // Glitch coverage: a pin run shorter than D, all of it while primed.
        for b in 0..self.run_start.len() {
            if t > 0 && Self::bit(o.raw, b) != Self::bit(self.log[t - 1].raw, b) {
                let start = self.run_start[b];
                if d >= 2
                    && t - start < d
                    && start >= 1
                    && self.log[start - 1..t].iter().all(|o| o.out.ready)
                {
                    self.checked.glitches += 1;
                }
                self.run_start[b] = t;
            }
        }

        if out.ready != ready {
            return Err(format!("clock {t}: ready {} expected {ready}", out.ready));
        }
        if (out.active | out.rise | out.fall) & !mask != 0 {
            return Err(format!("clock {t}: outputs beyond the width: {out:?}"));
        }
        if !ready {
            if out.active | out.rise | out.fall != 0 {
                return Err(format!(
                    "clock {t}: active/rise/fall while not ready: {out:?}"
                ));
            }
            return Ok(());
        }
        let level = self.level(t);
        if !self.log[t - 1].out.ready {
            // The third priming edge loaded the synchronizer's content.
            self.checked.primings += 1;
            let synchronized = self.log[t - 2].raw & mask;
            if level != synchronized || out.rise | out.fall != 0 {
                return Err(format!(
                    "clock {t}: primed to level {level:#x} (rise {:#x} fall {:#x}), pins two clocks ago {synchronized:#x}",
                    out.rise, out.fall
                ));
            }
            return Ok(());
        }
        let changed = level ^ self.level(t - 1);
        if out.rise != changed & out.active || out.fall != changed & !out.active & mask {
            return Err(format!(
                "clock {t}: level changed {changed:#x}, active {:#x}, but rise {:#x} fall {:#x}",
                out.active, out.rise, out.fall
            ));
        }
        for b in 0..self.run_start.len() {
            let v = Self::bit(level, b);
            // Every change needs the last D samples, all taken while primed.
            if Self::bit(changed, b) {
                self.checked.changes += 1;
                let sampled = t > d && self.log[t - d..t].iter().all(|o| o.out.ready);
                if !sampled || !self.pins_held(b, v, t - 1 - d, t - 2) {
                    return Err(format!(
                        "clock {t}: bit {b} changed to {v} without {d} samples of it (a glitch passed or an early change)"
                    ));
                }
            }
            // Every level held for D samples while primed is shown by now.
            if t > d && self.log[t - d..t].iter().all(|o| o.out.ready) {
                for v in [false, true] {
                    if self.pins_held(b, v, t - 1 - d, t - 2) {
                        if Self::bit(level, b) != v {
                            return Err(format!(
                                "clock {t}: bit {b} held {v} on clocks {}..={} but is not shown (too late)",
                                t - 1 - d,
                                t - 2
                            ));
                        }
                        if t >= d + 2 && Self::bit(self.log[t - 2 - d].raw, b) != v {
                            self.checked.deadlines += 1;
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// Pins for the monitor runs: run lengths around k (so both sides of the
/// threshold are hit), chatter, long stable stretches; rare `invert`
/// changes and resets.
fn monitor_stimulus(seed: u64, width: u32, k: u8, cycles: usize) -> Vec<InputConditionerInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut raw = 0u32;
    let mut run_left = vec![0u32; width as usize];
    let mut invert = 0u32;
    let d = k.max(1) as u32;
    (0..cycles)
        .map(|_| {
            for (b, left) in run_left.iter_mut().enumerate() {
                if *left == 0 {
                    raw ^= 1 << b;
                    *left = match rng.gen_range(0..10) {
                        0 => rng.gen_range(20..400),
                        1 | 2 => rng.gen_range(1..3),
                        _ => rng.gen_range(d.saturating_sub(2).max(1)..d + 3),
                    };
                }
                *left -= 1;
            }
            if rng.gen_ratio(1, 500) {
                invert ^= 1 << rng.gen_range(0..width);
            }
            InputConditionerInputs {
                reset: rng.gen_ratio(1, 1500),
                raw: raw & mask(width),
                invert,
                sample: true,
                length: k,
            }
        })
        .collect()
}

/// The RTL's outputs on `stimulus`, from power-up.
fn rtl_outputs<const W: usize>(
    stimulus: &[InputConditionerInputs],
) -> Vec<InputConditionerOutputs> {
    let mut h = harness::<W>();
    stimulus.iter().map(|i| rtl_clock(&mut h, i)).collect()
}

/// Runs `outputs` (for `stimulus`) through a monitor for k; the first
/// violation, or what was checked.
fn monitor(
    width: u32,
    k: u8,
    stimulus: &[InputConditionerInputs],
    outputs: &[InputConditionerOutputs],
) -> Result<Checked, String> {
    let mut m = Monitor::new(width, k);
    for (i, out) in stimulus.iter().zip(outputs) {
        m.check(Observed {
            reset: i.reset,
            raw: i.raw,
            invert: i.invert,
            out: *out,
        })?;
    }
    Ok(m.checked)
}

#[test]
fn pins_keep_the_port_contract_for_every_length() {
    let mut total = Checked::default();
    for k in 0..16u8 {
        let stimulus = monitor_stimulus(0x3e0 + k as u64, 3, k, 40_000);
        let outputs = rtl_outputs::<3>(&stimulus);
        let c = monitor(3, k, &stimulus, &outputs).unwrap_or_else(|e| panic!("k {k}: {e}"));
        assert!(
            c.changes > 1000 && c.deadlines > 1000 && c.primings > 10,
            "k {k}: {c:?}"
        );
        if k >= 2 {
            assert!(c.glitches > 1000, "k {k}: {c:?}");
        }
        total.changes += c.changes;
        total.deadlines += c.deadlines;
        total.glitches += c.glitches;
        total.primings += c.primings;
    }
    println!("checked over 16 lengths: {total:?}");
}

/// The latency stated in the rustdoc, exactly: a pin that rises before
/// clock c (low on clock c - 1, high from clock c on) for w clocks shows on
/// `active` from clock c + 1 + max(k, 1) on if w >= max(k, 1), with `rise`
/// at that clock only, and falls max(k, 1) + 1 clocks after it falls; a
/// pulse shorter than max(k, 1) never shows.
#[test]
fn latency_is_max_k_1_plus_1_after_the_first_edge_that_sees_the_pin() {
    for k in 0..16u8 {
        let d = k.max(1) as u64;
        for w in 1..20u64 {
            let mut h = harness::<1>();
            let c = 10u64;
            let (mut rose, mut fell, mut rises) = (None, None, 0);
            let mut last_active = 0;
            for clock in 0..c + w + d + 10 {
                let raw = (clock >= c && clock < c + w) as u32;
                let out = rtl_clock(
                    &mut h,
                    &InputConditionerInputs {
                        raw,
                        sample: true,
                        length: k,
                        ..Default::default()
                    },
                );
                assert_eq!(
                    out.ready,
                    clock >= PRIME_CLOCKS - 1,
                    "k {k} w {w} clock {clock}"
                );
                if out.active == 1 && last_active == 0 {
                    rose = Some(clock);
                }
                if out.active == 0 && last_active == 1 {
                    fell = Some(clock);
                }
                assert_eq!(out.rise, (out.active == 1 && last_active == 0) as u32);
                assert_eq!(out.fall, (out.active == 0 && last_active == 1) as u32);
                rises += out.rise;
                last_active = out.active;
            }
            if w >= d {
                assert_eq!(rose, Some(c + 1 + d), "k {k} w {w}: rise");
                assert_eq!(fell, Some(c + w + 1 + d), "k {k} w {w}: fall");
                assert_eq!(rises, 1, "k {k} w {w}");
            } else {
                assert_eq!(
                    (rose, rises),
                    (None, 0),
                    "k {k} w {w}: a short pulse passed"
                );
            }
        }
    }
}

/// A switch closed through a reset reads closed as soon as `ready` rises,
/// with no `rise`; before that it reads 0.
#[test]
fn a_level_held_through_reset_reads_at_once_without_an_edge() {
    for invert in [0u32, 0b101] {
        let mut h = harness::<3>();
        let pins = 0b011;
        let mut inputs = InputConditionerInputs {
            raw: pins,
            invert,
            sample: true,
            length: 15,
            ..Default::default()
        };
        for _ in 0..50 {
            rtl_clock(&mut h, &inputs);
        }
        inputs.reset = true;
        let out = rtl_clock(&mut h, &inputs);
        assert_eq!(
            (out.active, out.rise, out.fall, out.ready),
            (0, 0, 0, false)
        );
        inputs.reset = false;
        for clock in 1..=40u64 {
            let out = rtl_clock(&mut h, &inputs);
            let ready = clock >= PRIME_CLOCKS;
            assert_eq!(out.ready, ready, "clock {clock}");
            let active = if ready { pins ^ invert } else { 0 };
            assert_eq!(
                (out.active, out.rise, out.fall),
                (active, 0, 0),
                "clock {clock}"
            );
        }
    }
}

/// A change of `invert` flips `active` on the same clock, with no edge.
#[test]
fn changing_invert_flips_active_without_an_edge() {
    let mut h = harness::<8>();
    let mut inputs = InputConditionerInputs {
        raw: 0x5a,
        sample: true,
        length: 4,
        ..Default::default()
    };
    for _ in 0..10 {
        rtl_clock(&mut h, &inputs);
    }
    for invert in [0xffu32, 0x0f, 0x00, 0x81] {
        inputs.invert = invert;
        let out = rtl_clock(&mut h, &inputs);
        assert_eq!((out.active, out.rise, out.fall), (0x5a ^ invert, 0, 0));
    }
}

/// The monitor is not vacuous: each deliberately broken output stream is
/// reported, with the rule it breaks.
#[test]
fn the_monitor_reports_broken_output_streams() {
    const K: u8 = 4;
    // Pins low for the first clocks, so that power-up priming reads the
    // same in every variant and a latency bug is caught by the latency rule.
    let mut stimulus = monitor_stimulus(0x6d7, 3, K, 20_000);
    stimulus[..8].iter_mut().for_each(|i| i.raw = 0);
    let good = rtl_outputs::<3>(&stimulus);
    monitor(3, K, &stimulus, &good).expect("the real RTL passes");

    let expect_report =
        |name: &str, outputs: &[InputConditionerOutputs], rules: &[&str]| match monitor(
            3, K, &stimulus, outputs,
        ) {
            Ok(c) => panic!("mutation `{name}` was not reported ({c:?})"),
            Err(e) => {
                assert!(
                    rules.iter().any(|r| e.contains(r)),
                    "mutation `{name}`: reported as `{e}`, expected one of {rules:?}"
                );
                println!("mutation `{name}` reported: {e}");
            }
        };

    // One clock more latency on active/rise/fall (ready unchanged).
    let delayed: Vec<_> = (0..good.len())
        .map(|t| {
            let before = if t > 0 {
                good[t - 1]
            } else {
                Default::default()
            };
            InputConditionerOutputs {
                ready: good[t].ready,
                ..before
            }
        })
        .collect();
    expect_report("active one clock late", &delayed, &["too late"]);

    // A third synchronizer flip-flop: the RTL sees the pins one clock late.
    let late_pins: Vec<_> = (0..stimulus.len())
        .map(|t| InputConditionerInputs {
            raw: if t > 0 { stimulus[t - 1].raw } else { 0 },
            ..stimulus[t]
        })
        .collect();
    expect_report(
        "three-stage synchronizer",
        &rtl_outputs::<3>(&late_pins),
        &["too late"],
    );

    // A one-clock glitch let through on bit 0 where its pin was stable.
    let glitch_at = (40..good.len())
        .find(|&t| {
            (t - 30..t + 3).all(|s| {
                good[s].ready
                    && stimulus[s].raw == stimulus[t].raw
                    && stimulus[s].invert == stimulus[t].invert
            })
        })
        .expect("a stable stretch");
    let mut glitched = good.clone();
    let flipped = good[glitch_at].active ^ 1;
    glitched[glitch_at] = InputConditionerOutputs {
        active: flipped,
        rise: flipped & 1,
        fall: !flipped & 1,
        ..good[glitch_at]
    };
    glitched[glitch_at + 1].rise = good[glitch_at].active & 1;
    glitched[glitch_at + 1].fall = !good[glitch_at].active & 1;
    expect_report(
        "a one-clock glitch on active",
        &glitched,
        &["without 4 samples"],
    );

    // A filter one sample short: lets (k-1)-clock glitches through.
    let short: Vec<_> = stimulus
        .iter()
        .map(|i| InputConditionerInputs {
            length: K - 1,
            ..*i
        })
        .collect();
    expect_report(
        "filter length k - 1",
        &rtl_outputs::<3>(&short),
        &["without 4 samples"],
    );

    // A filter one sample long: a level held k clocks shows a clock late.
    let long: Vec<_> = stimulus
        .iter()
        .map(|i| InputConditionerInputs {
            length: K + 1,
            ..*i
        })
        .collect();
    expect_report(
        "filter length k + 1",
        &rtl_outputs::<3>(&long),
        &["too late"],
    );

    // `rise` stretched over two clocks.
    let stretched: Vec<_> = (0..good.len())
        .map(|t| InputConditionerOutputs {
            rise: good[t].rise | if t > 0 { good[t - 1].rise } else { 0 },
            ..good[t]
        })
        .collect();
    expect_report("rise two clocks long", &stretched, &["but rise"]);

    // `fall` never pulses.
    let no_fall: Vec<_> = good
        .iter()
        .map(|o| InputConditionerOutputs { fall: 0, ..*o })
        .collect();
    expect_report("fall missing", &no_fall, &["but rise"]);

    // The pins leak out one clock before `ready`.
    let leaky: Vec<_> = (0..good.len())
        .map(|t| match good.get(t + 1) {
            Some(next) if next.ready && !good[t].ready => InputConditionerOutputs {
                active: next.active,
                ..good[t]
            },
            _ => good[t],
        })
        .collect();
    expect_report("active before ready", &leaky, &["while not ready"]);

    // An edge at the end of priming (a closed switch reported as a rise).
    let primed_edge: Vec<_> = (0..good.len())
        .map(|t| {
            if t > 0 && good[t].ready && !good[t - 1].ready {
                InputConditionerOutputs {
                    rise: good[t].active,
                    ..good[t]
                }
            } else {
                good[t]
            }
        })
        .collect();
    expect_report("rise at the end of priming", &primed_edge, &["primed to"]);

    // `invert` applied before the filter instead of after it: an `invert`
    // change then makes a filtered change with edges, k clocks late.
    let before_filter: Vec<_> = {
        let moved: Vec<_> = stimulus
            .iter()
            .map(|i| InputConditionerInputs {
                raw: i.raw ^ i.invert,
                invert: 0,
                ..*i
            })
            .collect();
        rtl_outputs::<3>(&moved)
    };
    expect_report("invert before the filter", &before_filter, &["clock"]);

    // Four priming clocks instead of three.
    let slow_ready: Vec<_> = (0..good.len())
        .map(|t| {
            if t > 0 && good[t].ready && !good[t - 1].ready {
                InputConditionerOutputs::default()
            } else {
                good[t]
            }
        })
        .collect();
    expect_report(
        "ready one clock late",
        &slow_ready,
        &["ready false expected true"],
    );
}
