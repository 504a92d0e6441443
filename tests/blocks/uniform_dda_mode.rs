//! The DDA mode of `UniformPulseCore` (the controller axes' DDA, in the
//! uniform generator's engine), with and without the generator: RTL
//! against its model, the `DdaIntegrator` model it stands in for, under
//! stimulus that keeps its contract (J and M change only between whole
//! periods); every 4-bit J and M; and the contract check's own failure.

use motion_hdl::blocks::dda_integrator::model::{PeriodDdaInputs, PeriodDdaModel};
use motion_hdl::blocks::uniform_pulse_gen::UniformPulseCore;
use motion_hdl::blocks::width_mask;
use motion_hdl::sim::Lockstep;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Appends one reload of (J, M) and `periods` whole periods of M ticks at
/// the given tick density (J = 0: a few ticks, any number). A tick in the
/// reload clock is the new period's first.
fn push_periods(
    out: &mut Vec<PeriodDdaInputs>,
    rng: &mut StdRng,
    width: u32,
    (integrand, modulus): (u64, u64),
    periods: u64,
    density: f64,
) {
    let modulus_negated = modulus.wrapping_neg() & width_mask(width + 1);
    let ticks = if integrand == 0 {
        rng.gen_range(0..40)
    } else {
        periods * modulus
    };
    let mut taken = 0;
    let mut first = true;
    while taken < ticks || first {
        let tick = taken < ticks && rng.gen_bool(density);
        taken += tick as u64;
        out.push(PeriodDdaInputs {
            reset: false,
            tick,
            reload: first,
            integrand,
            modulus_negated,
            clear_overrange: rng.gen_ratio(1, 2000),
        });
        first = false;
    }
}

/// Periods of random J and M (small and large M; J of 0, up to M, M
/// itself, and above M), ticks from every clock to sparse, rare resets
/// (each followed by a reload, as the controller's halt is) and overrange
/// clears.
fn random_stimulus(rng: &mut StdRng, cycles: usize, width: u32) -> Vec<PeriodDdaInputs> {
    let mask = width_mask(width);
    let mut out = Vec::with_capacity(cycles + 70_000);
    while out.len() < cycles {
        let modulus = match rng.gen_range(0..5) {
            0 => rng.gen_range(1..4),
            1 => mask,
            2 => rng.gen_range(1..=mask),
            _ => rng.gen_range(1..200).min(mask),
        };
        let integrand = match rng.gen_range(0..8) {
            0 => 0,
            1 => modulus,
            2 => (modulus + rng.gen_range(1..4)).min(mask),
            3 => rng.gen_range(0..4).min(mask),
            _ => rng.gen_range(0..=modulus),
        };
        let density = if modulus > 5000 {
            1.0
        } else {
            [1.0, 1.0, 0.5, 0.1][rng.gen_range(0..4)]
        };
        let periods = rng.gen_range(1..4);
        push_periods(&mut out, rng, width, (integrand, modulus), periods, density);
        if rng.gen_ratio(1, 40) {
            // A halt: reset with J set to 0, reloaded in the next clock.
            let mut halt = *out.last().unwrap();
            halt.reset = true;
            halt.reload = false;
            out.push(halt);
            push_periods(&mut out, rng, width, (0, modulus), 1, 1.0);
        }
    }
    out
}

/// The core under test: `W` data bits, with its generator or without.
fn core(width: u32, generator: bool) -> Lockstep<PeriodDdaModel> {
    let model = PeriodDdaModel::new(width);
    match (width, generator) {
        (16, true) => {
            Lockstep::harness("uniform_dda", UniformPulseCore::<16, 17>::default(), model)
        }
        (16, false) => Lockstep::harness(
            "uniform_dda",
            UniformPulseCore::<16, 17>::without_generator(),
            model,
        ),
        (4, true) => Lockstep::harness("uniform_dda", UniformPulseCore::<4, 5>::default(), model),
        (4, false) => Lockstep::harness(
            "uniform_dda",
            UniformPulseCore::<4, 5>::without_generator(),
            model,
        ),
        _ => unreachable!("widths under test: 4 and 16"),
    }
}

fn run(width: u32, stimulus: &[PeriodDdaInputs]) {
    for generator in [true, false] {
        run_core(width, generator, stimulus);
    }
}

fn run_core(width: u32, generator: bool, stimulus: &[PeriodDdaInputs]) {
    let mut pair = core(width, generator);
    pair.run_all(stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("W={width}, generator {generator}: {e}"));
    assert_eq!(pair.cycles(), stimulus.len() as u64);
    assert_eq!(
        pair.model().broken_contract(),
        None,
        "the stimulus broke the reload contract"
    );
}

#[test]
fn rtl_matches_the_dda_model_on_a_million_clocks_of_whole_periods() {
    let mut rng = StdRng::seed_from_u64(0xd0da);
    run(16, &random_stimulus(&mut rng, 1_000_000, 16));
}

/// Every (J, M) of a 4-bit block, J = 0 to 15 (above M: clamped and
/// flagged), M = 1 to 15, two periods each, with ticks on every clock and
/// with gaps, one after the other.
#[test]
fn every_4_bit_integrand_and_modulus_matches_the_dda_model() {
    let mut rng = StdRng::seed_from_u64(4);
    let mut stimulus = vec![];
    for modulus in 1..16 {
        for integrand in 0..16 {
            for density in [1.0, 0.5] {
                push_periods(&mut stimulus, &mut rng, 4, (integrand, modulus), 2, density);
            }
        }
    }
    run(4, &stimulus);
}

/// The model's contract check fails on a reload in the middle of a
/// period, and the core then pulses differently from the DDA: the
/// contract is what lets it keep no accumulator.
#[test]
fn a_reload_in_the_middle_of_a_period_breaks_the_contract() {
    let mut rng = StdRng::seed_from_u64(5);
    let mut stimulus = vec![];
    push_periods(&mut stimulus, &mut rng, 4, (5, 13), 1, 1.0);
    stimulus.truncate(6);
    push_periods(&mut stimulus, &mut rng, 4, (3, 7), 2, 1.0);
    let mut pair = core(4, true);
    let outcome = pair.run_all(&stimulus, |_, _, _| {});
    assert!(pair.model().broken_contract().is_some());
    assert!(
        outcome.is_err(),
        "the block matched the DDA with a phase left over"
    );
}
