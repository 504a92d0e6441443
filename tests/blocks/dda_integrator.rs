//! `dda_integrator`: RTL against the model, the Bresenham contract checked
//! exhaustively on a 4-bit DDA, and cross-simulation.

use motion_hdl::blocks::dda_integrator::model::{
    DdaIntegratorInputs, DdaIntegratorModel, DdaIntegratorOutputs,
};
use motion_hdl::blocks::dda_integrator::DdaIntegrator;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Pulse latency after the tick edge, from the datasheet.
const LATENCY: usize = 2;

/// Runs of constant J and M (small, large, J > M, J = 0, M = 0, M lowered
/// below the accumulator), tick densities from sparse to every clock, and
/// rare overrange clears and resets.
fn random_stimulus(rng: &mut StdRng, cycles: usize, width: u32) -> Vec<DdaIntegratorInputs> {
    let mask = motion_hdl::blocks::width_mask(width);
    let mut out = Vec::with_capacity(cycles);
    while out.len() < cycles {
        let modulus = match rng.gen_range(0..6) {
            0 => 0,
            1 => rng.gen_range(1..20),
            _ => rng.gen::<u64>() & mask,
        } & mask;
        let integrand = match rng.gen_range(0..8) {
            0 => 0,
            1 => modulus.wrapping_add(rng.gen_range(1..4)) & mask, // J > M
            2 => modulus,
            3 => rng.gen_range(0..4),
            _ => {
                if modulus == 0 {
                    rng.gen::<u64>() & mask
                } else {
                    rng.gen_range(0..=modulus)
                }
            }
        };
        let density = [1.0, 1.0, 0.5, 0.1][rng.gen_range(0..4)];
        for _ in 0..rng.gen_range(1..3000) {
            out.push(DdaIntegratorInputs {
                reset: rng.gen_ratio(1, 50_000),
                tick: rng.gen_bool(density),
                integrand,
                modulus,
                clear_overrange: rng.gen_ratio(1, 2000),
            });
        }
    }
    out.truncate(cycles);
    out
}

fn run_against_model<const W: usize>(stimulus: &[DdaIntegratorInputs]) {
    let mut pair = Lockstep::harness(
        "dda_integrator",
        DdaIntegrator::<W>::default(),
        DdaIntegratorModel::new(W as u32),
    );
    pair.run_all(stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("W={W}: {e}"));
}

#[test]
fn rtl_matches_model_on_a_million_random_cycles() {
    let mut rng = StdRng::seed_from_u64(0xdda);
    run_against_model::<32>(&random_stimulus(&mut rng, 1_000_000, 32));
}

#[test]
fn narrow_rtl_matches_model() {
    let mut rng = StdRng::seed_from_u64(0xdda1);
    run_against_model::<12>(&random_stimulus(&mut rng, 200_000, 12));
    run_against_model::<3>(&random_stimulus(&mut rng, 100_000, 3));
}

/// Every (J, M) of a 4-bit DDA, with ticks on every clock and with gaps: after
/// t ticks exactly floor(t*J/M) pulses (J clamped to M), each pulse exactly
/// `LATENCY` clocks after its tick, and consecutive pulses floor(M/J) or
/// ceil(M/J) ticks apart. Checked against arithmetic, not the model.
#[test]
fn bresenham_contract_for_every_4_bit_integrand_and_modulus() {
    for modulus in 0..16u64 {
        let m = if modulus == 0 { 16 } else { modulus };
        for integrand in 0..16u64 {
            let j = integrand.min(m);
            for gap in [0usize, 2] {
                let mut harness =
                    Harness::new("dda_integrator", DdaIntegrator::<4>::default()).unwrap();
                let reset = DdaIntegratorInputs {
                    reset: true,
                    ..Default::default()
                };
                harness.step_vector(&reset.to_vector()).unwrap();
                let ticks = 3 * m as usize;
                let mut pulse_ticks = vec![];
                let mut tick_cycles = vec![];
                let mut cycle = 0usize;
                let total_cycles = ticks * (gap + 1) + LATENCY + 1;
                while cycle < total_cycles {
                    let tick = cycle.is_multiple_of(gap + 1) && tick_cycles.len() < ticks;
                    if tick {
                        tick_cycles.push(cycle);
                    }
                    let inputs = DdaIntegratorInputs {
                        tick,
                        integrand,
                        modulus,
                        ..Default::default()
                    };
                    let out = DdaIntegratorOutputs::from_vector(
                        &harness.step_vector(&inputs.to_vector()).unwrap(),
                    );
                    if out.pulse {
                        let source = cycle
                            .checked_sub(LATENCY - 1)
                            .expect("pulse before any tick");
                        let tick_index = tick_cycles
                            .iter()
                            .position(|&c| c == source)
                            .unwrap_or_else(|| {
                                panic!("J={integrand} M={modulus}: pulse at {cycle} has no tick")
                            });
                        pulse_ticks.push(tick_index as u64 + 1);
                    }
                    assert_eq!(
                        out.overrange,
                        integrand > m && !tick_cycles.is_empty() && cycle > tick_cycles[0]
                    );
                    cycle += 1;
                }
                for (t, _) in tick_cycles.iter().enumerate() {
                    let t = t as u64 + 1;
                    let emitted = pulse_ticks.iter().filter(|&&p| p <= t).count() as u64;
                    assert_eq!(
                        emitted,
                        t * j / m,
                        "J={integrand} M={modulus} gap={gap}: pulses after {t} ticks"
                    );
                }
                if let Some(shortest) = m.checked_div(j) {
                    for pair in pulse_ticks.windows(2) {
                        let spacing = pair[1] - pair[0];
                        assert!(
                            spacing == shortest || spacing == m.div_ceil(j),
                            "J={integrand} M={modulus}: spacing {spacing}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc055);
    check_instance::<DdaIntegrator<32>>(
        Instance::Exported("dda_integrator"),
        random_stimulus(&mut rng, 30_000, 32)
            .iter()
            .map(DdaIntegratorInputs::to_vector),
    );
}

#[test]
fn narrow_12_bit_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc056);
    check_instance::<DdaIntegrator<12>>(
        Instance::Generated("dda_integrator_w12"),
        random_stimulus(&mut rng, 30_000, 12)
            .iter()
            .map(DdaIntegratorInputs::to_vector),
    );
}
