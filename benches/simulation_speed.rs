//! Simulation speed: the stepping harness against rust-hdl's threaded
//! `Simulation`, on the same 32-bit block; then the whole controller on the
//! rust-hdl harness, on the compiled backend through its Rust interface, and
//! in a plain C++ loop over the same Verilator model, on one stimulus.
//! Figures, not assertions.
//!
//!     cargo bench --bench simulation_speed

use std::time::Instant;

use motion_hdl::blocks::dda_integrator::DdaIntegrator;
use motion_hdl::blocks::dda_interpolator::DdaInterpolator;
use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::blocks::motion_controller::model::ControllerInputs;
use motion_hdl::blocks::motion_controller::registers::register_map;
use motion_hdl::blocks::motion_controller::MotionController3;
use motion_hdl::blocks::quadrature_decoder::QuadratureDecoder;
use motion_hdl::blocks::step_channel::StepChannel;
use motion_hdl::sim::compiled::plain_loop;
use motion_hdl::sim::{CompiledStepper, Harness, Stepper, VectorPorts};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

type Controller = MotionController3;

/// `cycles` clocks of controller traffic: firmware set-up (base tick every
/// clock, 100-tick periods, RUN), then random bus traffic (a third of it
/// FIFO writes of small step counts, the rest any register, written or
/// read) and random encoder movement, as in the controller's chaos test.
fn controller_stimulus(cycles: usize) -> Vec<Vec<u64>> {
    let map = register_map(
        3,
        4,
        motion_hdl::blocks::motion_controller::registers::BuildOptions::MOTION_CONTROLLER,
    )
    .unwrap();
    let address = |name: &str, i: u32| map.register(name).unwrap().address_of(i).unwrap();
    let mut rng = StdRng::seed_from_u64(0x5eed);
    let mut phases = [0u8; 3];
    let setup = [
        (address("TICK_DIVISOR", 0), 1),
        (address("PERIOD_TICKS", 0), 100),
        (address("CONTROL", 0), 1),
    ];
    (0..cycles)
        .map(|c| {
            let mut i = ControllerInputs {
                encoders: vec![(false, false, false); 3],
                ..Default::default()
            };
            if let Some(&(a, v)) = setup.get(c) {
                (i.address, i.write_data, i.write) = (a, v, true);
            } else if rng.gen_bool(0.05) {
                i.address = rng.gen_range(0..256);
                match rng.gen_range(0..3) {
                    0 => {
                        i.address = address("FIFO_WRITE", rng.gen_range(0..3));
                        i.write_data = rng.gen_range(-25i32..=25) as u32;
                        i.write = true;
                    }
                    1 => (i.write_data, i.write) = (rng.gen(), true),
                    _ => i.read = true,
                }
            }
            for (k, e) in i.encoders.iter_mut().enumerate() {
                if rng.gen_ratio(1, 50) {
                    phases[k] = (phases[k] + 1) % 4;
                }
                let (a, b) = motion_hdl::sim::quadrature_state(phases[k] as i64);
                *e = (a, b, false);
            }
            i.to_vector()
        })
        .collect()
}

/// The median of `values`.
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Cycles per second of `sim` on `stimulus`.
fn stepper_rate(sim: &mut dyn Stepper, stimulus: &[Vec<u64>]) -> f64 {
    let mut outputs = vec![0; sim.output_count()];
    let start = Instant::now();
    for inputs in stimulus {
        sim.step_into(inputs, &mut outputs).unwrap();
    }
    stimulus.len() as f64 / start.elapsed().as_secs_f64()
}

/// The controller on the three simulators, each run from power-up on the
/// same stimulus: medians of 3 harness runs over its first 10k cycles, of 5
/// compiled runs and of 5 plain-loop runs over all 200k.
fn controller_rates() {
    let stimulus = controller_stimulus(200_000);
    let rust_hdl = median(
        (0..3)
            .map(|_| {
                let mut harness = Harness::new("motion_controller", Controller::default()).unwrap();
                stepper_rate(&mut harness, &stimulus[..10_000])
            })
            .collect(),
    );
    // The stimulus is in vector order, which is the Verilog port order the
    // plain loop reads (the cosim tests check that), and both fold the
    // model's output words in Verilog order: the checksums must agree.
    let mut folds = Vec::new();
    let through_rust = median(
        (0..5)
            .map(|_| {
                let mut compiled =
                    CompiledStepper::new("motion_controller", Controller::default(), false)
                        .unwrap_or_else(|e| panic!("{e}"));
                let mut outputs = vec![0; compiled.output_count()];
                let mut fold = 0u64;
                let start = Instant::now();
                for inputs in &stimulus {
                    compiled.step_into(inputs, &mut outputs).unwrap();
                    fold = compiled.model().fold_outputs(fold);
                }
                let rate = stimulus.len() as f64 / start.elapsed().as_secs_f64();
                folds.push(fold);
                rate
            })
            .collect(),
    );
    let plain = plain_loop(
        "motion_controller",
        &mut Controller::default(),
        &stimulus,
        5,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let plain_rate = median(plain.iter().map(|p| p.cycles as f64 / p.seconds).collect());
    let same = folds
        .iter()
        .chain(plain.iter().map(|p| &p.checksum))
        .all(|&f| f == folds[0]);
    println!("motion_controller (3 axes), cycles per second, one stimulus, medians:");
    println!(
        "  rust-hdl harness (3 runs of 10k cycles)      {:>12.0}",
        rust_hdl
    );
    println!(
        "  compiled backend through Stepper (5 x 200k)  {:>12.0}",
        through_rust
    );
    println!(
        "  plain C++ loop, same model (5 x 200k)        {:>12.0}",
        plain_rate
    );
    println!(
        "  compiled / rust-hdl                          {:>12.1}x",
        through_rust / rust_hdl
    );
    println!(
        "  compiled / plain C++ loop                    {:>12.2}",
        through_rust / plain_rate
    );
    println!(
        "  outputs identical in all compiled runs       {:>12}",
        if same { "yes" } else { "NO" }
    );
}

fn harness_rate(cycles: u64) -> f64 {
    let mut harness = Harness::new("freq_divider", FreqDivider::<32>::default()).unwrap();
    harness.step_vector(&[1, 1, 7]).unwrap();
    let start = Instant::now();
    let mut strobes = 0u64;
    for i in 0..cycles {
        strobes += harness.step_vector(&[0, 1, 7 + (i >> 16)]).unwrap()[0];
    }
    let rate = cycles as f64 / start.elapsed().as_secs_f64();
    assert!(strobes > 0);
    rate
}

/// Cycles per second of `block` stepped by the harness on a fixed vector.
fn stepping_rate<B: VectorPorts>(name: &str, block: B, vector: &[u64], cycles: u64) -> f64 {
    let mut harness = Harness::new(name, block).unwrap();
    let start = Instant::now();
    for _ in 0..cycles {
        harness.step_vector(vector).unwrap();
    }
    cycles as f64 / start.elapsed().as_secs_f64()
}

fn threaded_rate(cycles: u64) -> f64 {
    let mut sim = simple_sim!(FreqDivider<32>, clock, 100_000_000, ep, {
        let mut x = ep.init()?;
        x.reset.next = true;
        x.enable.next = true;
        x.divisor.next = 7u64.into();
        wait_clock_cycle!(ep, clock, x);
        x.reset.next = false;
        wait_clock_cycles!(ep, clock, x, cycles);
        ep.done(x)
    });
    let start = Instant::now();
    sim.run(Box::new(FreqDivider::<32>::default()), 1_000_000_000_000)
        .unwrap();
    cycles as f64 / start.elapsed().as_secs_f64()
}

fn main() {
    controller_rates();
    let harness = harness_rate(3_000_000);
    let threaded = threaded_rate(50_000);
    println!("32-bit freq_divider, cycles per second (release build):");
    println!("  motion_hdl::sim::Harness      {:>12.0}", harness);
    println!("  rust-hdl threaded Simulation  {:>12.0}", threaded);
    println!(
        "  ratio                         {:>12.1}x",
        harness / threaded
    );
    // A 32-bit DDA ticking every clock (J/M = 3/7), and the 3-axis
    // interpolator idle-ticking (its per-cycle cost does not depend on load).
    let dda = stepping_rate(
        "dda_integrator",
        DdaIntegrator::<32>::default(),
        &[0, 1, 3, 7, 0],
        2_000_000,
    );
    let interpolator = stepping_rate(
        "dda_interpolator",
        DdaInterpolator::<3>::default(),
        &[0, 1, 0, 100, 1, 2, 3, 0],
        500_000,
    );
    // The step channel at full rate: a step every tick into 1-clock pulses
    // (reset, tick, J, M, dir, clear, mode, len, space, setup, hold).
    let channel = stepping_rate(
        "step_channel",
        StepChannel::<32, 16>::default(),
        &[0, 1, 1, 2, 1, 0, 0, 1, 1, 1, 1],
        1_000_000,
    );
    // The quadrature decoder with its filter off, fed a constant state.
    let decoder = stepping_rate(
        "quadrature_decoder",
        QuadratureDecoder::<32, 8, 16>::default(),
        &[0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        1_000_000,
    );
    println!("  dda_integrator (32-bit), harness      {:>12.0}", dda);
    println!("  quadrature_decoder (32-bit), harness  {:>12.0}", decoder);
    println!("  step_channel (32/16-bit), harness     {:>12.0}", channel);
    println!(
        "  dda_interpolator (3 axes), harness    {:>12.0}",
        interpolator
    );
}
