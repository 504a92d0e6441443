//! Simulation speed: the stepping harness against rust-hdl's threaded
//! `Simulation`, on the same 32-bit block. Figures, not assertions.
//!
//!     cargo bench --bench simulation_speed

use std::time::Instant;

use motion_hdl::blocks::dda_integrator::DdaIntegrator;
use motion_hdl::blocks::dda_interpolator::DdaInterpolator;
use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::blocks::quadrature_decoder::QuadratureDecoder;
use motion_hdl::blocks::step_channel::StepChannel;
use motion_hdl::sim::{Harness, VectorPorts};
use rust_hdl::prelude::*;

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
        &[0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
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
