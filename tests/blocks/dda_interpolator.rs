//! `dda_interpolator`: RTL against the cycle model on long random command
//! streams, an independent exact-arithmetic checker of every step, the
//! underrun and refusal rules, and cross-simulation.

use std::collections::VecDeque;

use motion_hdl::blocks::dda_interpolator::model::{
    InterpolatorInputs, InterpolatorModel, InterpolatorOutputs,
};
use motion_hdl::blocks::dda_interpolator::DdaInterpolator;
use motion_hdl::sim::{stepper, Backend, Harness, Lockstep, Stepper};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const K: usize = 3;
/// Clocks from a used tick's edge to the edge after which its step shows.
const STEP_LATENCY: usize = 3;

/// A random period: mostly long enough for the division to finish in time,
/// sometimes too short (underruns), deltas from fractional to the one step
/// per tick limit, both signs, and now and then out of range.
fn random_command(rng: &mut StdRng, k: usize) -> (u32, Vec<i32>) {
    let period: u32 = match rng.gen_range(0..10) {
        0 => rng.gen_range(1..40),
        1 => rng.gen_range(1000..5000),
        _ => rng.gen_range(150..600),
    };
    let limit = (period as i64 * 65536).min(i32::MAX as i64);
    let deltas = (0..k)
        .map(|_| {
            let d: i64 = match rng.gen_range(0..12) {
                0 => 0,
                1 => limit,
                2 => -limit,
                3 => rng.gen_range(-65536..65536), // under one step
                4 => limit + rng.gen_range(1..100_000), // more than one step per tick
                5 => rng.gen_range(-3..4) * 65536,
                _ => rng.gen_range(-limit..=limit),
            };
            d.clamp(i32::MIN as i64, i32::MAX as i64) as i32
        })
        .collect();
    (period, deltas)
}

/// A closed-loop command stream, the way firmware drives the block: it waits
/// a random time after `ready` before loading (sometimes too long, which
/// underruns), now and then loads while not ready or with P = 0, and ticks
/// at a density that changes. `ready` comes from `observe`, so the same
/// generator drives the model or the RTL.
struct Driver {
    rng: StdRng,
    k: usize,
    wait: u32,
    density: f64,
    loads: usize,
}

impl Driver {
    fn new(seed: u64, k: usize) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            k,
            wait: 0,
            density: 1.0,
            loads: 0,
        }
    }

    fn next(&mut self, ready: bool) -> InterpolatorInputs {
        let rng = &mut self.rng;
        if rng.gen_ratio(1, 5000) {
            self.density = [1.0, 1.0, 0.5, 0.05][rng.gen_range(0..4)];
        }
        let mut inputs = InterpolatorInputs {
            reset: rng.gen_ratio(1, 200_000),
            tick: rng.gen_bool(self.density),
            next_delta: vec![0; self.k],
            clear_status: rng.gen_ratio(1, 3000),
            ..Default::default()
        };
        let bad_load = rng.gen_ratio(1, 400);
        if ready && self.wait == 0 {
            self.wait = if rng.gen_ratio(1, 30) {
                rng.gen_range(500..3000)
            } else {
                rng.gen_range(1..60)
            };
        }
        if ready && self.wait > 0 {
            self.wait -= 1;
            if self.wait == 0 {
                let (period, deltas) = random_command(rng, self.k);
                inputs.load = true;
                inputs.next_period = if rng.gen_ratio(1, 100) { 0 } else { period };
                inputs.next_delta = deltas;
                self.loads += 1;
            }
        } else if bad_load {
            inputs.load = true;
            inputs.next_period = rng.gen_range(1..100);
        }
        if inputs.load && rng.gen_ratio(1, 200) {
            inputs.next_period |= 1 << rng.gen_range(24..32); // too long: refused
        }
        inputs
    }
}

/// The RTL for the long runs, on the backend `MOTION_HDL_BACKEND` names
/// (default: Verilator, for speed).
fn long_run_rtl() -> Box<dyn Stepper> {
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    stepper(
        backend,
        "dda_interpolator",
        DdaInterpolator::<K>::default(),
        None,
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn rtl_matches_model_cycle_by_cycle_over_a_thousand_periods() {
    let mut driver = Driver::new(0x1e7, K);
    let mut pair = Lockstep::new(long_run_rtl(), InterpolatorModel::new(K));
    let mut periods = 0;
    while periods < 1200 {
        let inputs = driver.next(pair.model().outputs().ready);
        let rtl = pair.step(&inputs).unwrap_or_else(|e| panic!("{e}"));
        periods += rtl.period_done as usize;
    }
    let cycle = pair.cycles();
    println!(
        "{periods} periods in {cycle} cycles, {} loads",
        driver.loads
    );
}

/// One axis's exact expectation, from arithmetic alone: t ticks into a period
/// of length P with delta d (2^-16 steps, clamped to one step per tick), the
/// position in whole steps is floor((base * P + d * t) / (P * 2^16)), where
/// base is the position in 2^-16 steps at the period's start.
#[derive(Clone, Copy, Debug)]
struct Command {
    period: u64,
    deltas: [i64; K],
}

#[test]
fn every_step_is_where_exact_arithmetic_puts_it() {
    let mut driver = Driver::new(0xa11, K);
    let mut harness = long_run_rtl();
    let mut queue: VecDeque<Command> = VecDeque::new();
    let mut current: Option<(Command, u64)> = None; // command, ticks used so far
    let mut base = [0i64; K]; // position in 2^-16 steps at the current period's start
    let mut expected_steps: VecDeque<(usize, [i64; K])> = VecDeque::new(); // (cycle, positions)
    let mut position = [0i64; K]; // from the step and dir outputs
    let mut last = InterpolatorOutputs::from_vector(
        &harness
            .step_vector(&driver.next(false).to_vector())
            .unwrap(),
    );
    let mut periods = 0;
    let mut checked = 0u64;
    for cycle in 1..1_200_000usize {
        let mut inputs = driver.next(last.ready);
        inputs.reset = false; // the checker follows one continuous run
        let accepted =
            inputs.load && last.ready && inputs.next_period != 0 && inputs.next_period < 1 << 24;
        let used_tick = inputs.tick && last.running;
        let out =
            InterpolatorOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap());
        if accepted {
            let period = inputs.next_period as u64;
            let limit = period as i64 * 65536;
            let mut deltas = [0i64; K];
            for (d, &raw) in deltas.iter_mut().zip(&inputs.next_delta) {
                *d = (raw as i64).clamp(-limit, limit);
            }
            queue.push_back(Command { period, deltas });
        }
        if used_tick {
            let (command, ticks) = current
                .as_mut()
                .expect("a tick was used with no period running");
            *ticks += 1;
            let t = *ticks as i64;
            let p = command.period as i64;
            let mut at = [0i64; K];
            for axis in 0..K {
                at[axis] = (base[axis] * p + command.deltas[axis] * t).div_euclid(p * 65536);
            }
            expected_steps.push_back((cycle + STEP_LATENCY, at));
            assert_eq!(
                out.period_done,
                *ticks == command.period,
                "cycle {cycle}: period_done"
            );
            if *ticks == command.period {
                for axis in 0..K {
                    base[axis] += command.deltas[axis];
                }
                current = None;
                periods += 1;
            }
        } else {
            assert!(
                !out.period_done,
                "cycle {cycle}: period_done without a used tick"
            );
        }
        // A period starts (running rises or continues) when a command is queued.
        if current.is_none() && out.running {
            current = Some((
                queue.pop_front().expect("running with no accepted command"),
                0,
            ));
        }
        for axis in 0..K {
            if out.step[axis] {
                position[axis] += if out.dir[axis] { 1 } else { -1 };
            }
        }
        while expected_steps.front().is_some_and(|(due, _)| *due == cycle) {
            let (_, at) = expected_steps.pop_front().unwrap();
            assert_eq!(
                position, at,
                "cycle {cycle}: positions differ from exact arithmetic"
            );
            checked += 1;
        }
        last = out;
    }
    assert!(periods > 1000, "only {periods} periods ran");
    println!("{periods} periods, {checked} ticks checked");
}

#[test]
fn underrun_stops_without_inventing_steps_and_resumes_exactly() {
    let mut harness = Harness::new("dda_interpolator", DdaInterpolator::<1>::default()).unwrap();
    let mut step = |load: bool, period: u32, delta: i32| {
        let inputs = InterpolatorInputs {
            tick: true,
            load,
            next_period: period,
            next_delta: vec![delta],
            ..Default::default()
        };
        InterpolatorOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap())
    };
    // 2.5 steps over 100 ticks, then nothing queued.
    let mut steps = 0;
    step(true, 100, 5 << 15);
    let mut cycles = 0;
    loop {
        let out = step(false, 0, 0);
        steps += out.step[0] as i32;
        cycles += 1;
        if out.underrun {
            assert!(!out.running, "running after an underrun");
            break;
        }
        assert!(cycles < 1000, "no underrun");
    }
    for _ in 0..500 {
        let out = step(false, 0, 0);
        steps += out.step[0] as i32;
        assert!(!out.running && out.ready && out.underrun);
    }
    assert_eq!(steps, 2, "2.5 steps give 2 whole steps, no more");
    // The half step carried over: another 0.5 makes the third step.
    step(true, 100, 1 << 15);
    for _ in 0..400 {
        steps += step(false, 0, 0).step[0] as i32;
    }
    assert_eq!(steps, 3);
}

#[test]
fn loads_while_busy_and_zero_periods_are_refused_and_flagged() {
    let mut harness = Harness::new("dda_interpolator", DdaInterpolator::<2>::default()).unwrap();
    let mut apply = |load: bool, period: u32, clear: bool| {
        let inputs = InterpolatorInputs {
            load,
            next_period: period,
            next_delta: vec![65536, -65536],
            clear_status: clear,
            ..Default::default()
        };
        InterpolatorOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap())
    };
    let out = apply(true, 0, false);
    assert!(out.load_error && out.ready, "P = 0 must be refused");
    let out = apply(false, 0, true);
    assert!(!out.load_error, "clear_status clears load_error");
    let out = apply(true, 50, false);
    assert!(!out.ready && !out.load_error, "a good load is taken");
    let out = apply(true, 60, false);
    assert!(out.load_error, "a load while not ready is refused");
    let mut harness = Harness::new("dda_interpolator", DdaInterpolator::<2>::default()).unwrap();
    let inputs = InterpolatorInputs {
        load: true,
        next_period: 1 << 24,
        next_delta: vec![0, 0],
        ..Default::default()
    };
    let out = InterpolatorOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap());
    assert!(
        out.load_error && out.ready,
        "P = 2^24 does not fit and must be refused"
    );
}

/// Stimulus for cross-simulation: the closed-loop stream of the model,
/// replayed open-loop into the RTL and the Verilog.
fn cosim_stimulus<const N: usize>(seed: u64, cycles: usize) -> Vec<Vec<u64>> {
    let mut driver = Driver::new(seed, N);
    let mut model = InterpolatorModel::new(N);
    (0..cycles)
        .map(|_| {
            let inputs = driver.next(model.outputs().ready);
            model.step(&inputs);
            inputs.to_vector()
        })
        .collect()
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus::<K>(0xc057, 30_000);
    check_instance::<DdaInterpolator<K>>(Instance::Exported("dda_interpolator"), stimulus);
}

#[test]
fn single_axis_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus = cosim_stimulus::<1>(0xc058, 20_000);
    check_instance::<DdaInterpolator<1>>(Instance::Generated("dda_interpolator_k1"), stimulus);
}
