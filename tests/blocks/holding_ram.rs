//! `HoldingRam`: the RTL against its model on random traffic with many
//! read-during-write collisions, the hold between reads, and the Verilog
//! (its custom RAM text) in Icarus and Verilator against the Rust
//! simulation.

use motion_hdl::blocks::holding_ram::{HoldingRam, HoldingRamModel};
use motion_hdl::sim::Harness;
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Eight words, so that reads and writes meet often.
type Ram = HoldingRam<rust_hdl::prelude::Bits<16>, 3>;

/// Random traffic: (read_enable, read_address, write_enable,
/// write_address, write_data), one vector per clock; every third write
/// goes to the address read in the same clock.
fn random_stimulus(rng: &mut StdRng, clocks: usize) -> Vec<Vec<u64>> {
    (0..clocks)
        .map(|_| {
            let read_address = rng.gen_range(0..8);
            let write_address = if rng.gen_ratio(1, 3) {
                read_address
            } else {
                rng.gen_range(0..8)
            };
            vec![
                rng.gen_ratio(1, 2) as u64,
                read_address,
                rng.gen_ratio(1, 2) as u64,
                write_address,
                rng.gen_range(0..1 << 16),
            ]
        })
        .collect()
}

#[test]
fn rtl_matches_model_on_random_traffic_with_collisions() {
    let mut rng = StdRng::seed_from_u64(0x4a11);
    let mut rtl = Harness::new("holding_ram", Ram::default()).unwrap();
    let mut model = HoldingRamModel::default();
    let (mut collisions, mut held) = (0, 0);
    for (clock, v) in random_stimulus(&mut rng, 100_000).iter().enumerate() {
        let write = (v[2] == 1).then_some((v[3], v[4]));
        collisions += (v[0] == 1 && write.is_some_and(|(a, _)| a == v[1])) as u32;
        held += (v[0] == 0) as u32;
        let expected = model.step(v[0] == 1, v[1], write);
        let out = rtl.step_vector(v).unwrap();
        assert_eq!(out, vec![expected], "clock {clock}: inputs {v:?}");
    }
    assert!(
        collisions > 5_000 && held > 40_000,
        "{collisions} collisions, {held} held"
    );
}

/// Mutation check of the comparison above: a model that reads after the
/// write (write-first) disagrees with the RTL within the same traffic.
#[test]
fn a_write_first_model_is_caught() {
    let mut rng = StdRng::seed_from_u64(0x4a11);
    let mut rtl = Harness::new("holding_ram", Ram::default()).unwrap();
    let mut model = HoldingRamModel::default();
    let caught = random_stimulus(&mut rng, 10_000).iter().any(|v| {
        let write = (v[2] == 1).then_some((v[3], v[4]));
        model.step(false, 0, write);
        let expected = model.step(v[0] == 1, v[1], None);
        rtl.step_vector(v).unwrap() != vec![expected]
    });
    assert!(caught, "a write-first RAM went unnoticed");
}

#[test]
fn verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(0x4a12);
    check_instance::<Ram>(
        Instance::Generated("holding_ram"),
        random_stimulus(&mut rng, 20_000),
    );
}
