//! `pulse_counter`: RTL against the model, an exhaustive sweep of a 4-bit
//! counter, a position monitor that never loses a pulse, and cross-simulation.

use motion_hdl::blocks::pulse_counter::model::{
    PulseCounterInputs, PulseCounterModel, PulseCounterOutputs,
};
use motion_hdl::blocks::pulse_counter::PulseCounter;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Random pulses (dense and sparse, both directions, simultaneous up and
/// down), with clears, loads and resets landing on pulses, loads near the
/// wrap point, and compare values near the count so that matches happen.
fn random_stimulus(rng: &mut StdRng, cycles: usize, width: u32) -> Vec<PulseCounterInputs> {
    let mask = motion_hdl::blocks::width_mask(width);
    // The model only steers the compare values towards the count.
    let mut shadow = PulseCounterModel::new(width);
    let mut count = 0u64;
    let (mut p_up, mut p_down) = (0.5, 0.5);
    let mut stimulus = Vec::with_capacity(cycles);
    for cycle in 0..cycles {
        if cycle % 1000 == 0 {
            p_up = rng.gen_range(0.0..1.0);
            p_down = rng.gen_range(0.0..1.0);
        }
        let near = count.wrapping_add(rng.gen_range(0..5)).wrapping_sub(2) & mask;
        let inputs = PulseCounterInputs {
            reset: rng.gen_ratio(1, 20_000),
            up: rng.gen_bool(p_up),
            down: rng.gen_bool(p_down),
            clear: rng.gen_ratio(1, 500),
            load: rng.gen_ratio(1, 500),
            load_value: if rng.gen_bool(0.5) {
                rng.gen::<u64>() & mask
            } else {
                mask - rng.gen_range(0..3)
            },
            compare_value: if rng.gen_bool(0.9) {
                near
            } else {
                rng.gen::<u64>() & mask
            },
        };
        count = shadow.step(inputs).count;
        stimulus.push(inputs);
    }
    stimulus
}

fn run_against_model<const W: usize>(stimulus: &[PulseCounterInputs]) {
    let mut pair = Lockstep::harness(
        "pulse_counter",
        PulseCounter::<W>::default(),
        PulseCounterModel::new(W as u32),
    );
    pair.run_all(stimulus, |_, _, _| {})
        .unwrap_or_else(|e| panic!("W={W}: {e}"));
}

#[test]
fn rtl_matches_model_on_a_million_random_cycles() {
    let mut rng = StdRng::seed_from_u64(0xc0_47e2);
    run_against_model::<32>(&random_stimulus(&mut rng, 1_000_000, 32));
}

#[test]
fn narrow_rtl_matches_model() {
    let mut rng = StdRng::seed_from_u64(8);
    run_against_model::<8>(&random_stimulus(&mut rng, 200_000, 8));
}

/// A 4-bit counter: from every count, every combination of the five control
/// inputs, every load value and every compare value.
#[test]
fn every_transition_of_a_4_bit_counter() {
    let mut harness = Harness::new("pulse_counter", PulseCounter::<4>::default()).unwrap();
    for start in 0..16u64 {
        for controls in 0..32u32 {
            for value in 0..256u64 {
                let (load_value, compare_value) = (value & 15, value >> 4);
                let set = PulseCounterInputs {
                    load: true,
                    load_value: start,
                    ..Default::default()
                };
                harness.step_vector(&set.to_vector()).unwrap();
                let bit = |n: u32| controls >> n & 1 != 0;
                let inputs = PulseCounterInputs {
                    reset: bit(0),
                    up: bit(1),
                    down: bit(2),
                    clear: bit(3),
                    load: bit(4),
                    load_value,
                    compare_value,
                };
                let got = PulseCounterOutputs::from_vector(
                    &harness.step_vector(&inputs.to_vector()).unwrap(),
                );
                let mut model = PulseCounterModel::new(4);
                model.step(set);
                assert_eq!(got, model.step(inputs), "from {start}: {inputs:?}");
            }
        }
    }
}

/// An independent position monitor, written from the port contract: it
/// tracks the position from the pulses as a signed integer and checks that
/// the counter equals it (mod 2^32) after every edge, and that every pulse
/// the counter did not count (a net pulse under clear or load) is reported
/// by `pulse_overridden`, and no other edge is.
#[test]
fn no_pulse_is_lost_or_invented_silently() {
    let mut rng = StdRng::seed_from_u64(77);
    let stimulus = random_stimulus(&mut rng, 300_000, 32);
    let mut harness = Harness::new("pulse_counter", PulseCounter::<32>::default()).unwrap();
    let mut position: i64 = 0;
    for (cycle, inputs) in stimulus.iter().enumerate() {
        let out =
            PulseCounterOutputs::from_vector(&harness.step_vector(&inputs.to_vector()).unwrap());
        let net = inputs.up as i64 - inputs.down as i64;
        if inputs.reset || inputs.clear {
            position = 0;
        } else if inputs.load {
            position = inputs.load_value as u32 as i32 as i64;
        } else {
            position += net;
        }
        let overridden_pulse = net != 0 && !inputs.reset && (inputs.clear || inputs.load);
        assert_eq!(
            out.pulse_overridden, overridden_pulse,
            "cycle {cycle}: pulse_overridden"
        );
        assert_eq!(
            out.count,
            position as u64 & 0xffff_ffff,
            "cycle {cycle}: count differs from the position"
        );
        assert_eq!(
            out.compare_match,
            out.count == inputs.compare_value,
            "cycle {cycle}: compare"
        );
    }
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc051);
    check_instance::<PulseCounter<32>>(
        Instance::Exported("pulse_counter"),
        random_stimulus(&mut rng, 20_000, 32)
            .iter()
            .map(PulseCounterInputs::to_vector),
    );
}

#[test]
fn narrow_12_bit_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc052);
    check_instance::<PulseCounter<12>>(
        Instance::Generated("pulse_counter_w12"),
        random_stimulus(&mut rng, 20_000, 12)
            .iter()
            .map(PulseCounterInputs::to_vector),
    );
}
