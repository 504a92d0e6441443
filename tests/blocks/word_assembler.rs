//! `WordAssembler` on its own: RTL against the model with a narrow strobe
//! on most clocks (reads and writes back to back and together, which the
//! pin synchronizer never produces), for 32/16, 32/8 and 16/8 bits.

use motion_hdl::blocks::word_assembler::model::{
    PartGeometry, WordAssemblerInputs, WordAssemblerModel,
};
use motion_hdl::blocks::word_assembler::WordAssembler;
use motion_hdl::sim::Lockstep;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn lockstep<const NA: usize, const N: usize, const W: usize>(seed: u64, cycles: u32) {
    let geometry = PartGeometry {
        narrow_bits: N as u32,
        wide_bits: W as u32,
        address_bits: 4,
    };
    // The wide strobes are combinational from the narrow ones: the model
    // gives them during the clock, and the pair compares them before its edge.
    let mut pair = Lockstep::harness(
        "word_assembler",
        WordAssembler::<4, NA, N, W>::default(),
        WordAssemblerModel::new(geometry),
    );
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut writes, mut reads, mut errors, mut latched) = (0, 0, 0, 0);
    let mut register = 0;
    let mut part = 0;
    for _ in 0..cycles {
        // Mostly the parts of one register in order, sometimes anything.
        if rng.gen_ratio(1, 8) {
            register = rng.gen_range(0..16);
        }
        part = if rng.gen_ratio(1, 6) {
            rng.gen_range(0..geometry.parts())
        } else {
            (part + 1) % geometry.parts()
        };
        let i = WordAssemblerInputs {
            reset: rng.gen_ratio(1, 20_000),
            narrow_address: geometry.narrow_address(register, part),
            narrow_write_data: rng.gen::<u64>() & motion_hdl::blocks::width_mask(N as u32),
            narrow_write: rng.gen_ratio(1, 2),
            narrow_read: rng.gen_ratio(1, 2),
            bus_read_data: rng.gen::<u64>() & motion_hdl::blocks::width_mask(W as u32),
        };
        let rtl = pair.step(&i).unwrap_or_else(|e| panic!("{W}/{N}: {e}"));
        writes += rtl.bus_write as u32;
        reads += rtl.bus_read as u32;
        errors += rtl.order_error as u32;
        latched += (i.narrow_read && part > 0 && !rtl.bus_read) as u32;
    }
    assert!(
        writes > 5_000 && reads > 5_000 && errors > 5_000 && latched > 5_000,
        "{W}/{N}: {writes} writes, {reads} reads, {errors} errors, {latched} latched answers"
    );
}

#[test]
fn rtl_matches_model_32_over_16() {
    lockstep::<5, 16, 32>(0x3216, 400_000);
}

#[test]
fn rtl_matches_model_32_over_8() {
    lockstep::<6, 8, 32>(0x3208, 400_000);
}

#[test]
fn rtl_matches_model_16_over_8() {
    lockstep::<5, 8, 16>(0x1608, 400_000);
}
