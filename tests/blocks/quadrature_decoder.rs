//! `quadrature_decoder`: RTL against the model on random encoder walks, the
//! count checked against the true position from the pins alone, counter
//! mode, index handling, clear/count collisions, latency, and
//! cross-simulation.

use motion_hdl::blocks::quadrature_decoder::model::{
    QuadratureDecoderInputs, QuadratureDecoderModel, QuadratureDecoderOutputs,
};
use motion_hdl::blocks::quadrature_decoder::QuadratureDecoder;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

type Decoder = QuadratureDecoder<32, 8, 16>;

fn harness() -> Harness<Decoder> {
    Harness::new("quadrature_decoder", Decoder::default()).unwrap()
}

fn run(h: &mut Harness<Decoder>, i: &QuadratureDecoderInputs) -> QuadratureDecoderOutputs {
    QuadratureDecoderOutputs::from_vector(&h.step_vector(&i.to_vector()).unwrap())
}

use motion_hdl::sim::quadrature_state as gray;

/// Random encoder walks with everything the field does: reversals at every
/// state, dwell times from one clock up, glitches on any input shorter and
/// longer than the filter, illegal double changes, clears, index pulses,
/// re-arms, and settings (filter, sample rate, mode, index options) that
/// change at random. Not constrained to be countable: the model decides.
fn random_stimulus(seed: u64, cycles: usize, sample_mask: u64) -> Vec<QuadratureDecoderInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(cycles);
    let mut s = QuadratureDecoderInputs::default();
    let mut phase = 0i64;
    let mut forward = true;
    let mut dwell_scale = 1u32;
    while out.len() < cycles {
        if rng.gen_ratio(1, 200) {
            s.filter = [0, 1, 2, 3, 15, rng.gen_range(0..16)][rng.gen_range(0..6)];
            s.sample_rate = [0, 0, 1, 3, rng.gen::<u64>() & sample_mask][rng.gen_range(0..5)];
            s.counter_mode = rng.gen_ratio(1, 4);
            s.index_invert = rng.gen_bool(0.5);
            s.index_clear = rng.gen_bool(0.5);
            s.index_latch = rng.gen_bool(0.5);
            s.index_once = rng.gen_bool(0.5);
            dwell_scale = [1, 2, 5, 20, 60][rng.gen_range(0..5)];
        }
        if rng.gen_ratio(1, 8) {
            forward = !forward;
        }
        let mut next = phase + if forward { 1 } else { -1 };
        let (mut a, mut b) = gray(next);
        if rng.gen_ratio(1, 100) {
            // Illegal: both channels change at once.
            next = phase + 2;
            (a, b) = gray(next);
        }
        phase = next;
        let dwell = rng.gen_range(1..=dwell_scale * 4);
        let glitch_at = rng.gen_range(0..dwell.max(1) * 2);
        let glitch_len = rng.gen_range(1..dwell_scale * 3 + 2);
        let glitch_channel = rng.gen_range(0..3);
        for t in 0..dwell {
            let mut i = s;
            (i.a, i.b) = (a, b);
            i.index = s.index_invert;
            if t >= glitch_at && t < glitch_at + glitch_len {
                match glitch_channel {
                    0 => i.a = !i.a,
                    1 => i.b = !i.b,
                    _ => i.index = !i.index,
                }
            }
            i.clear = rng.gen_ratio(1, 3000);
            i.index_rearm = rng.gen_ratio(1, 2000);
            i.clear_error = rng.gen_ratio(1, 1500);
            i.reset = rng.gen_ratio(1, 100_000);
            out.push(i);
        }
    }
    out.truncate(cycles);
    out
}

#[test]
fn rtl_matches_model_on_random_encoder_walks() {
    let stimulus = random_stimulus(0x9ad, 1_000_000, 0xff);
    let mut pair = Lockstep::harness(
        "quadrature_decoder",
        Decoder::default(),
        QuadratureDecoderModel::new(32, 8, 16),
    );
    let (mut errors, mut index_clears, mut changes) = (0, 0, 0);
    let mut last = QuadratureDecoderOutputs::default();
    pair.run_all(&stimulus, |_, _, &rtl| {
        errors += (rtl.error && !last.error) as u32;
        index_clears += (rtl.index_seen && !last.index_seen) as u32;
        changes += (rtl.count != last.count) as u32;
        last = rtl;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        errors > 100 && index_clears > 100 && changes > 10_000,
        "coverage: {errors} errors, {index_clears} index events, {changes} count changes"
    );
}

/// Drives the decoder from a pin-level description and keeps the inputs.
struct Bench {
    h: Harness<Decoder>,
    inputs: QuadratureDecoderInputs,
    phase: i64,
    cycle: u64,
}

impl Bench {
    fn new(settings: QuadratureDecoderInputs) -> Self {
        let mut bench = Self {
            h: harness(),
            inputs: settings,
            phase: 0,
            cycle: 0,
        };
        bench.hold(10);
        bench
    }

    fn clock(&mut self) -> QuadratureDecoderOutputs {
        self.cycle += 1;
        let out = run(&mut self.h, &self.inputs);
        self.inputs.clear = false;
        self.inputs.index_rearm = false;
        self.inputs.clear_error = false;
        out
    }

    fn hold(&mut self, clocks: u64) -> QuadratureDecoderOutputs {
        let mut out = QuadratureDecoderOutputs::default();
        for _ in 0..clocks {
            out = self.clock();
        }
        out
    }

    /// One quadrature transition forward or backward.
    fn move_by(&mut self, forward: bool) {
        self.phase += if forward { 1 } else { -1 };
        (self.inputs.a, self.inputs.b) = gray(self.phase);
    }

    /// `steps` transitions, each held `dwell` clocks; returns the outputs
    /// after the last clock.
    fn walk(&mut self, steps: i64, dwell: u64) -> QuadratureDecoderOutputs {
        let mut out = self.hold(0);
        for _ in 0..steps.abs() {
            self.move_by(steps > 0);
            out = self.hold(dwell);
        }
        out
    }
}

/// Walks at exactly the documented rate limit for random filter lengths
/// and sample rates, with glitches shorter than the filter on either
/// channel and clears while the encoder rests: after every dwell the count
/// equals the true position, computed from the pins alone.
#[test]
fn count_equals_the_true_position_whenever_the_input_is_stable() {
    let mut rng = StdRng::seed_from_u64(0x7e57);
    let mut checked = 0u64;
    let mut total_cycles = 0u64;
    while total_cycles < 1_000_000 {
        let k = rng.gen_range(0..16u8);
        let rate = [0u64, 0, 1, 3, 7][rng.gen_range(0..5)];
        let mut bench = Bench::new(QuadratureDecoderInputs {
            filter: k,
            sample_rate: rate,
            ..Default::default()
        });
        let sample_period = rate + 1;
        // The documented rate limit, exactly: every level is held
        // max(k, 1) samples' worth of clocks, so it is seen by max(k, 1)
        // samples and the next change falls on a later sample.
        let need = k.max(1) as u64 * sample_period;
        let latency = 6 + sample_period;
        let mut truth = 0i64;
        let mut forward = true;
        for _ in 0..rng.gen_range(50..400) {
            if rng.gen_ratio(1, 5) {
                forward = !forward;
            }
            // A burst of transitions at the maximum rate.
            for _ in 0..rng.gen_range(1..8) {
                if rng.gen_ratio(1, 6) {
                    forward = !forward;
                }
                bench.move_by(forward);
                truth += if forward { 1 } else { -1 };
                bench.hold(need);
            }
            if k >= 2 && rng.gen_ratio(1, 3) {
                // A glitch seen by at most k - 1 samples.
                let width = rng.gen_range(1..=(k as u64 - 1) * sample_period);
                let channel = rng.gen_bool(0.5);
                let flip = |b: &mut Bench| {
                    if channel {
                        b.inputs.a = !b.inputs.a
                    } else {
                        b.inputs.b = !b.inputs.b
                    }
                };
                flip(&mut bench);
                bench.hold(width);
                flip(&mut bench);
                bench.hold(need);
            }
            let out = bench.hold(latency + rng.gen_range(0..need));
            assert_eq!(
                out.count as u32 as i32 as i64, truth,
                "k {k} rate {rate} cycle {}",
                bench.cycle
            );
            assert!(!out.error, "error flag on a legal walk");
            checked += 1;
            if rng.gen_ratio(1, 50) {
                bench.inputs.clear = true;
                truth = 0;
            }
        }
        total_cycles += bench.cycle;
    }
    assert!(checked > 5_000, "only {checked} checks");
}

/// Counter mode reads step/dir: pulses on `a` count +1 with `b` high and
/// -1 with `b` low, with `b` changed only while `a` is low.
#[test]
fn counter_mode_counts_rising_edges_of_a_with_b_as_direction() {
    let mut rng = StdRng::seed_from_u64(0xc0de);
    for run_index in 0..20 {
        let k = rng.gen_range(0..4u8);
        let mut bench = Bench::new(QuadratureDecoderInputs {
            filter: k,
            counter_mode: true,
            ..Default::default()
        });
        let need = k.max(1) as u64 + 1;
        let mut truth = 0i64;
        for _ in 0..500 {
            let up = rng.gen_bool(0.6);
            bench.inputs.b = up;
            bench.hold(need + rng.gen_range(0..3));
            bench.inputs.a = true;
            bench.hold(need + rng.gen_range(0..3));
            bench.inputs.a = false;
            bench.hold(need + rng.gen_range(0..3));
            truth += if up { 1 } else { -1 };
        }
        let out = bench.hold(10);
        assert_eq!(out.count as u32 as i32 as i64, truth, "run {run_index}");
        assert!(!out.error);
    }
}

#[test]
fn a_double_change_counts_nothing_and_sets_error_until_clear() {
    let mut bench = Bench::new(QuadratureDecoderInputs::default());
    bench.walk(5, 3);
    bench.phase += 2;
    (bench.inputs.a, bench.inputs.b) = gray(bench.phase);
    let out = bench.hold(10);
    assert!(out.error);
    assert_eq!(out.count, 5, "a double change was counted");
    bench.walk(3, 3);
    let out = bench.hold(10);
    assert!(out.error, "error is sticky");
    assert_eq!(out.count, 8, "the decoder continues from the new state");
    // clear_error acknowledges the error and keeps the position.
    bench.inputs.clear_error = true;
    let out = bench.hold(2);
    assert!(!out.error && out.count == 8, "clear_error keeps the count");
    bench.phase += 2;
    (bench.inputs.a, bench.inputs.b) = gray(bench.phase);
    let out = bench.hold(10);
    assert!(out.error, "a new error after clear_error");
    bench.inputs.clear = true;
    let out = bench.hold(2);
    assert!(!out.error && out.count == 0);
}

/// Latency from the clock that first presents a pin change to the clock
/// after which `count` shows it, with the filter off (the datasheet's
/// figure).
#[test]
fn pin_to_count_latency_is_five_edges_with_the_filter_off() {
    let mut bench = Bench::new(QuadratureDecoderInputs::default());
    bench.move_by(true);
    let mut edges = 0;
    loop {
        edges += 1;
        if bench.clock().count == 1 {
            break;
        }
        assert!(edges < 20);
    }
    assert_eq!(
        edges,
        motion_hdl::blocks::quadrature_decoder::PIN_TO_COUNT_EDGES
    );
}

/// An index pulse long enough for the filter, at rest at `position`.
fn index_pulse(bench: &mut Bench) -> QuadratureDecoderOutputs {
    bench.inputs.index = !bench.inputs.index_invert;
    bench.hold(4);
    bench.inputs.index = bench.inputs.index_invert;
    bench.hold(10)
}

#[test]
fn index_latches_the_count_with_either_polarity() {
    for invert in [false, true] {
        let mut bench = Bench::new(QuadratureDecoderInputs {
            index: invert,
            index_invert: invert,
            index_latch: true,
            ..Default::default()
        });
        let out = bench.walk(7, 3);
        assert!(!out.index_seen, "no index yet");
        let out = index_pulse(&mut bench);
        assert!(out.index_seen);
        assert_eq!(out.index_count, 7, "invert {invert}");
        assert_eq!(out.count, 7, "a latch does not clear");
        // Move while the index is active: only its active edge latches.
        bench.inputs.index = !invert;
        bench.hold(4);
        bench.walk(-3, 3);
        bench.inputs.index = invert;
        let out = bench.hold(10);
        assert_eq!(out.count, 4);
        assert_eq!(out.index_count, 7, "the inactive edge latched");
        let out = index_pulse(&mut bench);
        assert_eq!(out.index_count, 4, "every index latches");
    }
}

#[test]
fn index_clear_once_ignores_later_index_pulses_until_rearmed() {
    let mut bench = Bench::new(QuadratureDecoderInputs {
        index_clear: true,
        index_latch: true,
        index_once: true,
        ..Default::default()
    });
    bench.walk(9, 3);
    let out = index_pulse(&mut bench);
    assert_eq!((out.count, out.index_count, out.index_seen), (0, 9, true));
    bench.walk(4, 3);
    let out = index_pulse(&mut bench);
    assert_eq!((out.count, out.index_count), (4, 9), "a second index acted");
    bench.inputs.index_rearm = true;
    let out = bench.hold(2);
    assert!(!out.index_seen);
    bench.walk(2, 3);
    let out = index_pulse(&mut bench);
    assert_eq!((out.count, out.index_count, out.index_seen), (0, 6, true));
}

/// A clear on every clock around one transition: the count after settling
/// is 1 when the clear comes at or before the clock at which the transition
/// is counted, 0 after it. The transition on the clear's own clock is kept
/// (the known field bug loses it).
#[test]
fn a_count_on_the_clock_of_a_clear_is_never_lost() {
    for index_clear in [false, true] {
        for offset in 0..12u64 {
            let mut bench = Bench::new(QuadratureDecoderInputs {
                index_clear,
                ..Default::default()
            });
            bench.walk(3, 4);
            bench.hold(10);
            bench.move_by(true);
            for clock in 0..20 {
                if clock == offset {
                    if index_clear {
                        // The index event reaches the count stage 5 edges
                        // after its pin, like a transition.
                        bench.inputs.index = true;
                    } else {
                        bench.inputs.clear = true;
                    }
                }
                bench.clock();
            }
            let expected = if index_clear {
                // Index and transition pins together land on one clock.
                if offset == 0 {
                    1
                } else {
                    0
                }
            } else if offset < motion_hdl::blocks::quadrature_decoder::PIN_TO_COUNT_EDGES {
                1
            } else {
                0
            };
            let out = bench.hold(10);
            assert_eq!(
                out.count, expected,
                "index_clear {index_clear}: clear {offset} clocks after the pin"
            );
        }
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<Decoder>(
        Instance::Exported("quadrature_decoder"),
        random_stimulus(0xc05e, 40_000, 0xff)
            .iter()
            .map(QuadratureDecoderInputs::to_vector),
    );
}

#[test]
fn narrow_8_bit_count_matches_rust_in_icarus_and_verilator() {
    check_instance::<QuadratureDecoder<8, 3, 5>>(
        Instance::Generated("quadrature_decoder_w8_s3_t5"),
        random_stimulus(0xc05f, 30_000, 0x7)
            .iter()
            .map(QuadratureDecoderInputs::to_vector),
    );
}

/// An index event on the very clock of a re-arm is acted on (latched,
/// cleared) and leaves `index_seen` set: a re-arm never loses an index.
#[test]
fn an_index_on_the_clock_of_a_rearm_is_acted_on() {
    for offset in 0..10u64 {
        let mut bench = Bench::new(QuadratureDecoderInputs {
            index_latch: true,
            index_once: true,
            ..Default::default()
        });
        bench.walk(5, 3);
        index_pulse(&mut bench);
        bench.walk(2, 3);
        bench.hold(10);
        // Second index pulse with a re-arm at every offset around its
        // arrival at the count stage (5 edges after the pin).
        bench.inputs.index = true;
        let mut acted = false;
        for clock in 0..20 {
            if clock == offset {
                bench.inputs.index_rearm = true;
            }
            let out = bench.clock();
            acted |= out.index_count == 7;
            if clock == 4 {
                bench.inputs.index = false;
            }
        }
        let out = bench.hold(10);
        // Re-armed at or before the event's edge: it acts. After: it was
        // ignored (once mode) and the re-arm leaves index_seen clear.
        if offset < motion_hdl::blocks::quadrature_decoder::PIN_TO_COUNT_EDGES {
            assert!(acted && out.index_seen, "offset {offset}: index lost");
        } else {
            assert!(!acted && !out.index_seen, "offset {offset}");
        }
    }
}

/// From the pins alone: an encoder resting at any state through reset does
/// not count; `dir` follows the last transition; `count_time` is the
/// timestamp of the clock before the count changed.
#[test]
fn start_up_dir_and_timestamp_from_the_pins() {
    for phase in 0..4 {
        let mut h = harness();
        let (a, b) = gray(phase);
        let resting = QuadratureDecoderInputs {
            a,
            b,
            ..Default::default()
        };
        let mut reset = resting;
        reset.reset = true;
        run(&mut h, &reset);
        for _ in 0..20 {
            let out = run(&mut h, &resting);
            assert_eq!(
                (out.count, out.error),
                (0, false),
                "resting at {:?}",
                (a, b)
            );
        }
    }
    let mut bench = Bench::new(QuadratureDecoderInputs::default());
    let mut last = bench.hold(1);
    let mut changes = 0;
    for (steps, dir) in [(3i64, true), (-2, false), (1, true)] {
        for clock in 0..(steps.unsigned_abs() * 3 + 12) {
            if clock % 3 == 0 && clock < steps.unsigned_abs() * 3 {
                bench.move_by(steps > 0);
            }
            let out = bench.clock();
            if out.count != last.count {
                assert_eq!(out.count_time, last.timestamp, "count_time");
                changes += 1;
            }
            last = out;
        }
        assert_eq!(last.dir, dir, "dir after {steps}");
    }
    assert_eq!((last.count, changes), (2, 6));
}
