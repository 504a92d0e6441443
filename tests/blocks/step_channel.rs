//! `step_channel`: RTL against the composed model, the end-to-end step
//! count checked from the pins alone, and cross-simulation.

use motion_hdl::blocks::step_channel::model::{
    StepChannelInputs, StepChannelModel, StepChannelOutputs,
};
use motion_hdl::blocks::step_channel::StepChannel;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Runs of one J/M/direction and one set of timings, with random tick
/// density; rates from far below to far above what the timing allows (so
/// the pending count grows and saturates too), J > M, mode changes, clears
/// and rare resets.
fn random_stimulus(
    seed: u64,
    cycles: usize,
    dda_bits: u32,
    timer_bits: u32,
) -> Vec<StepChannelInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let dda_mask = motion_hdl::blocks::width_mask(dda_bits);
    let timer_mask = motion_hdl::blocks::width_mask(timer_bits);
    let mut out = Vec::with_capacity(cycles);
    let mut settings = StepChannelInputs::default();
    while out.len() < cycles {
        let mut modulus = match rng.gen_range(0..5) {
            0 => 0,
            1 => rng.gen_range(1..50),
            _ => rng.gen::<u64>() & dda_mask,
        };
        let mut integrand = match rng.gen_range(0..6) {
            0 => 0,
            1 => modulus.wrapping_add(1) & dda_mask,
            _ if modulus == 0 => rng.gen::<u64>() & dda_mask,
            _ => rng.gen_range(0..=modulus),
        };
        if rng.gen_ratio(1, 4) {
            let timer = |rng: &mut StdRng| match rng.gen_range(0..6) {
                0 => 0,
                1 => rng.gen_range(10..40) & timer_mask,
                _ => rng.gen_range(1..4),
            };
            settings.mode = rng.gen_range(0..4);
            settings.step_len = timer(&mut rng);
            settings.step_space = timer(&mut rng);
            settings.dir_setup = timer(&mut rng);
            settings.dir_hold = timer(&mut rng);
        }
        let mut density = [1.0, 0.5, 0.1][rng.gen_range(0..3)];
        let dir = rng.gen_bool(0.5);
        let mut length = rng.gen_range(1..2000);
        if rng.gen_ratio(1, 40) {
            // A flood: one step per clock against 1000-clock pulses fills
            // the pending count until it saturates.
            (integrand, modulus, density, length) = (1, 1, 1.0, 40_000);
            settings.mode = 0;
            settings.step_len = 1000;
        }
        for _ in 0..length {
            let mut inputs = settings;
            inputs.tick = rng.gen_bool(density);
            inputs.integrand = integrand;
            inputs.modulus = modulus;
            // The direction may flip at any clock, not only with a tick.
            inputs.dir = if rng.gen_ratio(1, 300) { !dir } else { dir };
            inputs.clear_overrange = rng.gen_ratio(1, 500);
            inputs.reset = rng.gen_ratio(1, 100_000);
            out.push(inputs);
        }
    }
    out.truncate(cycles);
    out
}

#[test]
fn rtl_matches_the_composed_model_cycle_by_cycle() {
    let stimulus = random_stimulus(0xc4a1, 300_000, 32, 16);
    let mut pair = Lockstep::harness(
        "step_channel",
        StepChannel::<32, 16>::default(),
        StepChannelModel::new(32, 16),
    );
    let (mut high, mut overruns) = (0u64, 0u64);
    pair.run_all(&stimulus, |_, _, rtl| {
        high += rtl.out_a as u64;
        overruns += rtl.overrun as u64;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    // The stimulus must reach both the normal and the saturated regime.
    assert!(
        high > 10_000 && overruns > 1_000,
        "coverage: out_a high {high} clocks, overrun {overruns} clocks"
    );
}

/// From reset, t ticks of constant J/M in one direction, then a drain: the
/// step/dir pins show exactly floor(t * J / M) steps, all in that
/// direction, whatever the timing (kept slow enough not to saturate).
#[test]
fn pins_show_exactly_floor_t_j_over_m_steps_in_the_ticks_direction() {
    let mut rng = StdRng::seed_from_u64(0x5e7);
    for run in 0..200 {
        let mut harness = Harness::new("step_channel", StepChannel::<32, 16>::default()).unwrap();
        let modulus: u64 = rng.gen_range(1..1000);
        let integrand = rng.gen_range(0..=modulus);
        let dir = rng.gen_bool(0.5);
        let ticks: u64 = rng.gen_range(0..3000);
        let settings = StepChannelInputs {
            integrand,
            modulus,
            dir,
            step_len: rng.gen_range(0..4),
            step_space: rng.gen_range(0..4),
            dir_setup: rng.gen_range(0..4),
            dir_hold: rng.gen_range(0..4),
            ..Default::default()
        };
        let (mut steps, mut last_a) = (0u64, false);
        let mut cycle = 0u64;
        loop {
            let mut inputs = settings;
            inputs.tick = cycle < ticks;
            let out =
                StepChannelOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap());
            if out.out_a && !last_a {
                assert_eq!(out.out_b, dir, "run {run}: a step in the wrong direction");
                steps += 1;
            }
            last_a = out.out_a;
            assert!(!out.overrun, "run {run}: overrun");
            cycle += 1;
            if cycle > ticks + 4 && !out.busy {
                break;
            }
            assert!(cycle < 100_000, "run {run}: never idle");
        }
        assert_eq!(
            steps,
            ticks * integrand / modulus,
            "run {run}: J {integrand} M {modulus} t {ticks}"
        );
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<StepChannel<32, 16>>(
        Instance::Exported("step_channel"),
        random_stimulus(0xc4a2, 30_000, 32, 16)
            .iter()
            .map(StepChannelInputs::to_vector),
    );
}

#[test]
fn narrow_8_bit_dda_6_bit_timers_match_rust_in_icarus_and_verilator() {
    check_instance::<StepChannel<8, 6>>(
        Instance::Generated("step_channel_w8_t6"),
        random_stimulus(0xc4a3, 20_000, 8, 6)
            .iter()
            .map(StepChannelInputs::to_vector),
    );
}
