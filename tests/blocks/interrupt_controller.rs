//! `InterruptController`: RTL against the model, and from the ports alone:
//! no event is lost to a clear, and `irq` is the registered OR of the
//! enabled status bits.

use motion_hdl::blocks::interrupt_controller::model::{
    InterruptControllerInputs, InterruptControllerModel,
};
use motion_hdl::blocks::interrupt_controller::InterruptController;
use motion_hdl::sim::Lockstep;
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const N: usize = 6;
const MASK: u64 = (1 << N) - 1;

fn random_inputs(seed: u64, cycles: usize) -> Vec<InterruptControllerInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut enable = MASK;
    (0..cycles)
        .map(|_| {
            if rng.gen_ratio(1, 100) {
                enable = rng.gen::<u64>() & MASK;
            }
            // Sparse events on random bits, frequent clears of random bits.
            let events = (0..N)
                .filter(|_| rng.gen_ratio(1, 12))
                .fold(0, |e, b| e | 1 << b);
            let clear = rng.gen_ratio(1, 4);
            InterruptControllerInputs {
                reset: rng.gen_ratio(1, 20_000),
                events,
                clear,
                clear_bits: rng.gen::<u64>() & MASK,
                enable,
            }
        })
        .collect()
}

#[test]
fn rtl_matches_model_and_never_loses_an_event() {
    let mut pair = Lockstep::harness(
        "irq",
        InterruptController::<N>::default(),
        InterruptControllerModel::new(),
    );
    let mut last_status = 0;
    let (mut collisions, mut irqs) = (0, 0);
    pair.run_all(&random_inputs(0x1a, 1_000_000), |cycle, v, out| {
        let clear = v.clear.then_some(v.clear_bits);
        if !v.reset {
            // From the ports: every event bit is set after its edge, even
            // when the same edge clears it.
            assert_eq!(
                out.status & v.events,
                v.events,
                "cycle {cycle}: an event was lost"
            );
            collisions += (clear.unwrap_or(0) & v.events != 0) as u32;
            // irq is registered from the status before this edge.
            assert_eq!(out.irq, last_status & v.enable != 0, "cycle {cycle}: irq");
        }
        irqs += out.irq as u32;
        last_status = out.status;
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(collisions > 10_000 && irqs > 100_000, "{collisions} {irqs}");
}

#[test]
fn generated_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<InterruptController<N>>(
        Instance::Generated("interrupt_controller_n6"),
        random_inputs(0x1b, 20_000)
            .iter()
            .map(InterruptControllerInputs::to_vector),
    );
}
