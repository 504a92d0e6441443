//! `InterruptController`: RTL against the model, and from the ports alone:
//! no event is lost to a clear, and `irq` is the registered OR of the
//! enabled status bits.

use motion_hdl::blocks::interrupt_controller::model::InterruptControllerModel;
use motion_hdl::blocks::interrupt_controller::InterruptController;
use motion_hdl::sim::Harness;
use motion_hdl::tools::cosim::cross_simulate_generated;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const N: usize = 6;
const MASK: u64 = (1 << N) - 1;

fn random_inputs(seed: u64, cycles: usize) -> Vec<[u64; 5]> {
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
            let clear = rng.gen_ratio(1, 4) as u64;
            [
                rng.gen_ratio(1, 20_000) as u64,
                events,
                clear,
                rng.gen::<u64>() & MASK,
                enable,
            ]
        })
        .collect()
}

#[test]
fn rtl_matches_model_and_never_loses_an_event() {
    let mut h = Harness::new("irq", InterruptController::<N>::default()).unwrap();
    let mut model = InterruptControllerModel::new();
    let mut last_status = 0;
    let (mut collisions, mut irqs) = (0, 0);
    for (cycle, v) in random_inputs(0x1a, 1_000_000).iter().enumerate() {
        let out = h.step_vector(v).unwrap();
        let clear = (v[2] != 0).then_some(v[3]);
        assert_eq!(
            (out[0], out[1] != 0),
            model.step(v[0] != 0, v[1], clear, v[4]),
            "cycle {cycle}"
        );
        if v[0] == 0 {
            // From the ports: every event bit is set after its edge, even
            // when the same edge clears it.
            assert_eq!(out[0] & v[1], v[1], "cycle {cycle}: an event was lost");
            collisions += (clear.unwrap_or(0) & v[1] != 0) as u32;
            // irq is registered from the status before this edge.
            assert_eq!(out[1] != 0, last_status & v[4] != 0, "cycle {cycle}: irq");
        }
        irqs += out[1] as u32;
        last_status = out[0];
    }
    assert!(collisions > 10_000 && irqs > 100_000, "{collisions} {irqs}");
}

#[test]
fn generated_verilog_matches_rust_in_icarus_and_verilator() {
    let stimulus: Vec<Vec<u64>> = random_inputs(0x1b, 20_000)
        .iter()
        .map(|v| v.to_vec())
        .collect();
    cross_simulate_generated(
        "interrupt_controller_n6",
        InterruptController::<N>::default(),
        &stimulus,
    )
    .unwrap_or_else(|e| panic!("{e}"));
}
