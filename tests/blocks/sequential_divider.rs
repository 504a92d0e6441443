//! `sequential_divider`: every 8-bit operand pair, random 32-bit streams
//! against the cycle model, and cross-simulation.

use motion_hdl::blocks::sequential_divider::model::{
    expected_result, SequentialDividerInputs, SequentialDividerModel, SequentialDividerOutputs,
};
use motion_hdl::blocks::sequential_divider::SequentialDivider;
use motion_hdl::sim::{Harness, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Operands that stress the algorithm: 0, 1, all ones, powers of two, equal
/// operands, dividend below divisor, and plain random values.
fn operand(rng: &mut StdRng, mask: u64) -> u64 {
    match rng.gen_range(0..8) {
        0 => 0,
        1 => 1,
        2 => mask,
        3 => 1u64 << rng.gen_range(0..mask.count_ones()),
        4 => rng.gen_range(0..16),
        _ => rng.gen::<u64>() & mask,
    }
}

/// A cycle stream: starts at random times (often while busy, sometimes in
/// the `done` cycle), operands that change while busy, and rare resets.
fn random_stimulus(rng: &mut StdRng, cycles: usize, width: u32) -> Vec<SequentialDividerInputs> {
    let mask = motion_hdl::blocks::width_mask(width);
    (0..cycles)
        .map(|_| SequentialDividerInputs {
            reset: rng.gen_ratio(1, 3000),
            start: rng.gen_bool(0.3),
            dividend: operand(rng, mask),
            divisor: operand(rng, mask),
        })
        .collect()
}

/// One clock of the RTL, out of reset.
fn clock<const N: usize, const D: usize>(
    h: &mut Harness<SequentialDivider<N, D>>,
    dividend: u64,
    divisor: u64,
    start: bool,
) -> SequentialDividerOutputs {
    let inputs = SequentialDividerInputs {
        reset: false,
        start,
        dividend,
        divisor,
    };
    SequentialDividerOutputs::from_vector(&h.step_vector(&inputs.to_vector()).unwrap())
}

/// Runs a stream through the RTL and the model, cycle by cycle, and checks
/// every result against plain arithmetic.
fn run_against_model<const N: usize, const D: usize>(
    stimulus: &[SequentialDividerInputs],
) -> usize {
    let mut pair = Lockstep::harness(
        "sequential_divider",
        SequentialDivider::<N, D>::default(),
        SequentialDividerModel::new(N as u32, D as u32),
    );
    let mut operands = None;
    let mut results = 0;
    for inputs in stimulus {
        let was_busy = pair.model().outputs().busy;
        let rtl = pair
            .step(inputs)
            .unwrap_or_else(|e| panic!("N={N} D={D}: {e}"));
        if inputs.reset {
            operands = None;
        } else if inputs.start && !was_busy {
            operands = Some((inputs.dividend, inputs.divisor));
        }
        if rtl.done {
            let (dividend, divisor) = operands.expect("done without a start");
            let (q, r, by_zero) = expected_result(dividend, divisor, N as u32, D as u32);
            assert_eq!(
                (rtl.quotient, rtl.remainder, rtl.divide_by_zero),
                (q, r, by_zero),
                "{dividend}/{divisor}"
            );
            results += 1;
        }
    }
    results
}

#[test]
fn every_8_bit_operand_pair_with_exact_latency() {
    let mut harness =
        Harness::new("sequential_divider", SequentialDivider::<8, 8>::default()).unwrap();
    let idle = |h: &mut Harness<SequentialDivider<8, 8>>| clock(h, 0, 0, false);
    for dividend in 0..256u64 {
        for divisor in 0..256u64 {
            let first = clock(&mut harness, dividend, divisor, true);
            assert!(
                first.busy && !first.done,
                "{dividend}/{divisor}: busy after the start edge"
            );
            for clock in 1..8 {
                let o = idle(&mut harness);
                assert!(o.busy && !o.done, "{dividend}/{divisor}: clock {clock}");
            }
            let last = idle(&mut harness);
            assert!(
                !last.busy && last.done,
                "{dividend}/{divisor}: done W+1 clocks after start"
            );
            let expected = expected_result(dividend, divisor, 8, 8);
            assert_eq!(
                (last.quotient, last.remainder, last.divide_by_zero),
                expected,
                "{dividend}/{divisor}"
            );
        }
    }
}

/// Every 8-bit dividend with every 4-bit divisor, on an 8-by-4-bit divider.
#[test]
fn every_8_by_4_bit_operand_pair() {
    let mut harness =
        Harness::new("sequential_divider", SequentialDivider::<8, 4>::default()).unwrap();
    for dividend in 0..256u64 {
        for divisor in 0..16u64 {
            clock(&mut harness, dividend, divisor, true);
            for _ in 1..8 {
                clock(&mut harness, 0, 0, false);
            }
            let last = clock(&mut harness, 0, 0, false);
            assert!(last.done, "{dividend}/{divisor}");
            let expected = expected_result(dividend, divisor, 8, 4);
            assert_eq!(
                (last.quotient, last.remainder, last.divide_by_zero),
                expected,
                "{dividend}/{divisor}"
            );
        }
    }
}

#[test]
fn random_32_bit_streams_match_the_model_and_arithmetic() {
    let mut rng = StdRng::seed_from_u64(0xd1_71de);
    let results = run_against_model::<32, 32>(&random_stimulus(&mut rng, 300_000, 32));
    assert!(results > 5_000, "only {results} divisions completed");
}

#[test]
fn narrow_widths_match_the_model_and_arithmetic() {
    let mut rng = StdRng::seed_from_u64(3);
    run_against_model::<12, 12>(&random_stimulus(&mut rng, 100_000, 12));
    run_against_model::<2, 2>(&random_stimulus(&mut rng, 20_000, 2));
    // A divisor narrower than the dividend (the interpolator's 32-by-24).
    run_against_model::<32, 24>(&random_stimulus(&mut rng, 100_000, 32));
    run_against_model::<12, 5>(&random_stimulus(&mut rng, 100_000, 12));
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc053);
    check_instance::<SequentialDivider<32, 32>>(
        Instance::Exported("sequential_divider"),
        random_stimulus(&mut rng, 20_000, 32)
            .iter()
            .map(SequentialDividerInputs::to_vector),
    );
}

#[test]
fn narrow_12_bit_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0xc054);
    check_instance::<SequentialDivider<12, 12>>(
        Instance::Generated("sequential_divider_w12"),
        random_stimulus(&mut rng, 20_000, 12)
            .iter()
            .map(SequentialDividerInputs::to_vector),
    );
}
