//! `uniform_pulse_gen`: RTL against the model (exhaustively for T = 4000
//! in both orders, and on random 32-bit T, N and load timing), every
//! period's pulse train checked from the pins alone, and cross-simulation.

use motion_hdl::blocks::uniform_pulse_gen::model::{
    PulsePlan, UniformPulseGenInputs, UniformPulseGenModel, UniformPulseGenOutputs,
};
use motion_hdl::blocks::uniform_pulse_gen::{load_to_ready, UniformPulseGen, LOAD_TO_READY};
use motion_hdl::sim::{Backend, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// RTL and model side by side; every clock is compared.
struct Pair<const W: usize = 32> {
    pair: Lockstep<UniformPulseGenModel>,
    cycle: u64,
    /// The outputs after the last clock (power-up: only `ready`).
    last: UniformPulseGenOutputs,
}

impl<const W: usize> Pair<W> {
    /// On the backend `MOTION_HDL_BACKEND` names (rust-hdl by default).
    fn new() -> Self {
        Self::on(Backend::from_env_or(Backend::RustHdl).unwrap())
    }

    fn on(backend: Backend) -> Self {
        let pair = Lockstep::on(
            backend,
            "uniform_pulse_gen",
            UniformPulseGen::<W>::default(),
            UniformPulseGenModel::with_width(W as u32),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        Self {
            pair,
            cycle: 0,
            last: UniformPulseGenOutputs {
                ready: true,
                ..Default::default()
            },
        }
    }

    fn clock(&mut self, i: &UniformPulseGenInputs) -> UniformPulseGenOutputs {
        let rtl = self.pair.step(i).unwrap_or_else(|e| panic!("{e}"));
        self.cycle += 1;
        self.last = rtl;
        rtl
    }
}

/// Checks one period's output samples (one per tick) against the plan,
/// from the levels alone: N rising edges, each pulse high exactly as long
/// as it is low, only Tp1 and Tp2 pulse periods with exactly N1 and N2 of
/// each, no idle tick, and (interleaved) every rising edge within 2 ticks
/// of i * T / N.
fn check_period(levels: &[bool], plan: &PulsePlan, interleaved: bool, what: &str) {
    assert_eq!(levels.len() as u64, plan.period, "{what}: period length");
    if plan.count == 0 {
        assert!(levels.iter().all(|&l| !l), "{what}: a pulse with N = 0");
        return;
    }
    let mut pulses = Vec::new();
    let mut t = 0;
    while t < levels.len() {
        assert!(levels[t], "{what}: idle tick at {t}");
        let rise = t;
        while t < levels.len() && levels[t] {
            t += 1;
        }
        let high = t - rise;
        while t < levels.len() && !levels[t] {
            t += 1;
        }
        let low = t - rise - high;
        pulses.push((rise, high, low));
    }
    assert_eq!(pulses.len() as u64, plan.count, "{what}: rising edges");
    let (mut short, mut long) = (0, 0);
    for (i, &(rise, high, low)) in pulses.iter().enumerate() {
        assert_eq!(high, low, "{what}: pulse {i} high {high} low {low}");
        match 2 * high as u64 {
            p if p == plan.short_period() => short += 1,
            p if p == plan.short_period() + 2 => long += 1,
            p => panic!("{what}: pulse {i} period {p}"),
        }
        if interleaved {
            let ideal = i as f64 * plan.period as f64 / plan.count as f64;
            // The datasheet's bound: 0 to 2 ticks before the ideal edge.
            let lead = ideal - rise as f64;
            assert!(
                (0.0..2.0).contains(&lead),
                "{what}: pulse {i} rises at {rise}, ideal {ideal}"
            );
        }
    }
    assert_eq!(
        (short, long),
        (plan.short_pulses, plan.long_pulses),
        "{what}: N1, N2"
    );
}

/// Loads `periods` back to back (each as soon as `ready` allows) with tick
/// high every `tick_every` clocks, and returns the output samples of each
/// period, one per tick (taken after each tick edge).
fn run_back_to_back(
    pair: &mut Pair,
    periods: &[(u64, u64, bool)],
    tick_every: u64,
) -> Vec<Vec<bool>> {
    let mut queue = periods.iter();
    let mut windows: Vec<Vec<bool>> = Vec::new();
    let mut running = false;
    let mut pending = queue.next();
    loop {
        let mut i = UniformPulseGenInputs {
            tick: pair.cycle.is_multiple_of(tick_every),
            ..Default::default()
        };
        if let Some(&(period, count, mode)) = pending {
            if pair.last.ready {
                (i.period, i.count, i.mode, i.load) = (period, count, mode, true);
                pending = queue.next();
            }
        }
        let out = pair.clock(&i);
        if !i.tick {
            assert!(!out.period_done, "period_done between ticks");
            continue;
        }
        if out.period_done && !windows.is_empty() {
            if windows.len() == periods.len() {
                assert!(!out.running, "a period ran after the last");
                return windows;
            }
            windows.push(Vec::new());
        }
        if out.running && !running && windows.is_empty() {
            windows.push(Vec::new());
        }
        assert!(
            out.running || windows.is_empty(),
            "idle between back-to-back periods at cycle {}",
            pair.cycle
        );
        running = out.running;
        if let Some(w) = windows.last_mut() {
            w.push(out.pulse);
        }
    }
}

/// The datasheet's sweep: T = 4000, every N from 0 to 2000, in both
/// orders, three back-to-back periods each (N, then two neighbours), with
/// the RTL compared to the model on every clock: 48M clocks, so the RTL
/// runs compiled by Verilator (166 s on rust-hdl; the same sweep passes
/// there with `MOTION_HDL_BACKEND=rust-hdl`).
#[test]
fn every_n_for_t_4000_in_both_orders_back_to_back() {
    const T: u64 = 4000;
    // The two orders in parallel: the machine has two cores.
    let sweeps: Vec<_> = [false, true]
        .into_iter()
        .map(|interleaved| {
            std::thread::spawn(move || {
                let backend = Backend::from_env_or(Backend::Verilator).unwrap();
                let mut pair = Pair::<32>::on(backend);
                for n in 0..=T / 2 {
                    let periods = [
                        (T, n, interleaved),
                        (T, (n + 1) % (T / 2 + 1), interleaved),
                        (T, (n + 977) % (T / 2 + 1), interleaved),
                    ];
                    let windows = run_back_to_back(&mut pair, &periods, 1);
                    for (window, &(t, count, mode)) in windows.iter().zip(&periods) {
                        let (plan, overrange) = PulsePlan::new(t, count);
                        assert!(!overrange);
                        let what = format!("T {t} N {count} interleaved {mode}");
                        check_period(window, &plan, mode, &what);
                        assert_eq!(window, &plan.train(mode), "{what}: the model's train");
                    }
                }
                pair.cycle
            })
        })
        .collect();
    for sweep in sweeps {
        let cycles = sweep.join().expect("sweep failed");
        assert!(cycles > 3 * 2001 * T);
    }
}

/// Random T and N over the whole 32-bit range (odd, too small, N > T/2),
/// random tick density, loads at random times (including while not
/// ready), flag clears and resets, against the model.
#[test]
fn rtl_matches_model_on_random_32_bit_periods_and_load_timing() {
    random_periods_against_model::<32>(0x0f1, 1_500_000);
}

/// The 16-bit generator of the motion controller's axes: the same stimulus
/// with T and N reaching past 16 bits (they are truncated to the port).
#[test]
fn a_16_bit_generator_matches_its_model() {
    random_periods_against_model::<16>(0x16, 1_000_000);
}

fn random_periods_against_model<const W: usize>(seed: u64, cycles: u32) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut pair = Pair::<W>::new();
    let (mut starts, mut rejected, mut underruns) = (0, 0, 0);
    let mut density = 1.0;
    let mut starved = false;
    for _ in 0..cycles {
        if rng.gen_ratio(1, 5000) {
            density = [1.0, 1.0, 0.5, 0.05][rng.gen_range(0..4)];
            // Starved phases: loads come late, so periods underrun.
            starved = rng.gen_ratio(1, 3);
        }
        // A huge T holds the generator for the rest of the run (until a
        // reset), so it is rare.
        let period = match rng.gen_range(0..300) {
            0 => rng.gen::<u32>() as u64,
            1..=20 => rng.gen_range(0..4),
            _ => rng.gen_range(2..3000),
        };
        let count = match rng.gen_range(0..5) {
            0 => rng.gen::<u32>() as u64,
            1 => period / 2 + rng.gen_range(0..3),
            _ => rng.gen_range(0..=period / 2 + 1),
        };
        let i = UniformPulseGenInputs {
            tick: rng.gen_bool(density),
            period,
            count,
            mode: rng.gen_bool(0.5),
            load: rng.gen_ratio(
                1,
                match (pair.last.ready, starved) {
                    (true, false) => 40,
                    (true, true) => 3000,
                    (false, _) => 400,
                },
            ),
            clear_flags: rng.gen_ratio(1, 3000),
            reset: rng.gen_ratio(1, 40_000),
        };
        let before = pair.last;
        let out = pair.clock(&i);
        starts += (out.running && !before.running) as u32 + (out.period_done && out.running) as u32;
        rejected += (i.load && !before.ready) as u32;
        underruns += (out.period_done && !out.running) as u32;
    }
    assert!(
        starts > 200 && rejected > 100 && underruns > 50,
        "coverage: {starts} starts, {rejected} rejected loads, {underruns} underruns"
    );
}

/// A load from idle starts its period at the first tick edge after
/// LOAD_TO_READY clocks: the datasheet's latency.
#[test]
fn a_period_loaded_from_idle_starts_load_to_ready_plus_one_clocks_later() {
    latency_from_idle::<32>();
    latency_from_idle::<16>();
}

fn latency_from_idle<const W: usize>() {
    let mut pair = Pair::<W>::new();
    let load = UniformPulseGenInputs {
        tick: true,
        period: 100,
        count: 7,
        load: true,
        ..Default::default()
    };
    pair.clock(&load);
    let mut clocks = 0;
    loop {
        clocks += 1;
        let out = pair.clock(&UniformPulseGenInputs {
            tick: true,
            ..Default::default()
        });
        if out.running {
            assert!(out.pulse, "the first pulse rises with the start");
            break;
        }
        assert!(clocks < 100);
    }
    assert_eq!(clocks, load_to_ready(W as u32) + 1);
    if W == 32 {
        assert_eq!(clocks, LOAD_TO_READY + 1);
    }
}

/// Random cross-simulation vectors: periods from `period`, counts up to
/// just past T/2, loads mostly while the model's slot is free, rare flag
/// clears and resets.
fn cosim_stimulus(
    seed: u64,
    mut model: UniformPulseGenModel,
    cycles: usize,
    mut period: impl FnMut(&mut StdRng) -> u64,
) -> Vec<Vec<u64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut ready = true;
    (0..cycles)
        .map(|_| {
            let period = period(&mut rng);
            let i = UniformPulseGenInputs {
                tick: rng.gen_ratio(9, 10),
                period,
                count: rng.gen_range(0..=period / 2 + 2),
                mode: rng.gen_bool(0.5),
                load: rng.gen_ratio(1, if ready { 20 } else { 300 }),
                clear_flags: rng.gen_ratio(1, 2000),
                reset: rng.gen_ratio(1, 20_000),
            };
            ready = model.step(i).ready;
            i.to_vector()
        })
        .collect()
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0xc0c0, UniformPulseGenModel::new(), 40_000, |rng| {
        rng.gen_range(0..300)
    });
    check_instance::<UniformPulseGen<32>>(Instance::Exported("uniform_pulse_gen"), stimulus);
}

/// A narrow 12-bit instance in Icarus and Verilator: truncated ports and
/// the sign bit of a 12-bit Bresenham error.
#[test]
fn narrow_12_bit_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus(0x12b, UniformPulseGenModel::with_width(12), 30_000, |rng| {
        [rng.gen_range(0..300), rng.gen_range(0..5000)][rng.gen_range(0..2)]
    });
    check_instance::<UniformPulseGen<12>>(Instance::Generated("uniform_pulse_gen_12"), stimulus);
}

/// The same pin-level checks with a sparse time base (a tick every third
/// clock): every count is measured in ticks, not clocks.
#[test]
fn sparse_ticks_keep_every_period_exact() {
    let mut pair = Pair::<32>::new();
    for (t, n) in [
        (100u64, 0u64),
        (100, 1),
        (100, 33),
        (100, 50),
        (4000, 1301),
        (4000, 1999),
    ] {
        for interleaved in [false, true] {
            let periods = [
                (t, n, interleaved),
                (t, n / 2, interleaved),
                (t, n, interleaved),
            ];
            let windows = run_back_to_back(&mut pair, &periods, 3);
            for (window, &(t, count, mode)) in windows.iter().zip(&periods) {
                let (plan, _) = PulsePlan::new(t, count);
                check_period(
                    window,
                    &plan,
                    mode,
                    &format!("sparse T {t} N {count} {mode}"),
                );
            }
        }
    }
}

/// The shared period planner alone, exhaustively at 8 bits: every T/2 the
/// generator can ask with (1 to 127) and every N (0 to 255), checked at
/// `done` against the model's plan (N clamped to T/2, its half, N2 and
/// -N1 in two's complement, a clamped one in the clock after `done`),
/// with `done` exactly 8 clocks after the start edge.
#[test]
fn the_period_planner_gives_the_models_plan_for_every_8_bit_request() {
    use motion_hdl::blocks::uniform_pulse_gen::PeriodPlanner;
    use motion_hdl::sim::Harness;
    const W: usize = 8;
    let mut rtl = Harness::new("period_planner", PeriodPlanner::<W>::default()).unwrap();
    let mut plans = 0;
    for half_period in 1..=127u64 {
        for count in 0..=255u64 {
            let mut out = rtl.step_vector(&[0, 1, half_period, count]).unwrap();
            let mut clocks = 1;
            while out[1] == 0 {
                out = rtl.step_vector(&[0, 0, 0, 0]).unwrap();
                clocks += 1;
                assert!(clocks <= W + 2, "no done");
            }
            // The start's edge and W more: `done` follows edge s + W.
            assert_eq!(clocks, W + 1, "done W clocks after the start edge");
            let (plan, _) = PulsePlan::new(2 * half_period, count);
            let [_, _, half, long, short_negated, half_is_one, has_pulses, clamped] = out[..]
            else {
                panic!("eight outputs")
            };
            let request = format!("T/2 = {half_period}, N = {count}");
            assert_eq!(has_pulses != 0, count > 0, "{request}");
            assert_eq!(clamped != 0, count > half_period, "{request}");
            if count == 0 {
                continue;
            }
            assert_eq!(half, plan.half, "{request}");
            assert_eq!(half_is_one != 0, plan.half == 1, "{request}");
            if clamped == 0 {
                assert_eq!(long, plan.long_pulses, "{request}");
            } else {
                assert_eq!(plan.long_pulses, 0, "{request}: the generator clears N2");
            }
            // A clamped N's -N1 comes in the clock after `done`.
            let short_negated = if clamped == 0 {
                short_negated
            } else {
                rtl.step_vector(&[0, 0, 0, 0]).unwrap()[4]
            };
            assert_eq!(
                short_negated,
                plan.short_pulses.wrapping_neg() & 0xff,
                "{request}"
            );
            plans += 1;
        }
    }
    assert_eq!(plans, 127 * 255);
}
