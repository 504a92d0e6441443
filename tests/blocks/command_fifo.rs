//! `CommandFifo`: RTL against a queue model on random writes and pops
//! (every fill level, full and empty collisions, flushes), and generated
//! cross-simulation of a small and a 256-entry instance.

use motion_hdl::blocks::command_fifo::model::{
    CommandFifoInputs, CommandFifoModel, CommandFifoOutputs,
};
use motion_hdl::blocks::command_fifo::CommandFifo;
use motion_hdl::sim::{Backend, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// One clock's inputs per clock, in phases that fill, drain, hover at full
/// and at empty.
fn random_inputs(seed: u64, cycles: usize, capacity: u64) -> Vec<CommandFifoInputs> {
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut p_write, mut p_pop) = (0.5, 0.5);
    let mut low_water = capacity / 4;
    (0..cycles)
        .map(|_| {
            // Phases long enough to fill and drain the deepest FIFO.
            if rng.gen_ratio(1, (capacity as u32 * 4).max(300)) {
                (p_write, p_pop) = [(0.9, 0.1), (0.1, 0.9), (0.5, 0.5), (1.0, 1.0), (0.7, 0.6)]
                    [rng.gen_range(0..5)];
                low_water = rng.gen_range(0..=capacity);
            }
            CommandFifoInputs {
                reset: rng.gen_ratio(1, 20_000),
                write: rng.gen_bool(p_write),
                write_data: rng.gen::<u32>() as u64,
                pop: rng.gen_bool(p_pop),
                low_water,
                clear_flags: rng.gen_ratio(1, 500),
            }
        })
        .collect()
}

/// `cycles` random clocks against the model, on the backend
/// `MOTION_HDL_BACKEND` names (default: Verilator, for speed).
fn run<const N: usize, const NP1: usize, const W: usize>(seed: u64, cycles: usize) {
    let capacity = 1u64 << N;
    let backend = Backend::from_env_or(Backend::Verilator).unwrap();
    let mut pair = Lockstep::on(
        backend,
        "command_fifo",
        CommandFifo::<N, NP1, W>::default(),
        CommandFifoModel::new(capacity as usize),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (mut fulls, mut empties, mut overflows, mut underflows, mut heads) = (0, 0, 0, 0, 0);
    // The three read-during-write cases of the head bypass, counted from
    // the ports: a write into an empty FIFO, write and pop at level 1,
    // write and pop when full.
    let (mut into_empty, mut at_one, mut when_full) = (0, 0, 0);
    let mut last = CommandFifoOutputs::default();
    // The model leaves `head` unspecified while empty (`agrees`).
    let mut stimulus = random_inputs(seed, cycles, capacity);
    for inputs in &mut stimulus {
        inputs.write_data &= (1u64 << W) - 1;
    }
    pair.run_all(&stimulus, |_, v, &rtl| {
        if !v.reset && v.write {
            into_empty += (last.level == 0) as u32;
            at_one += (v.pop && last.level == 1) as u32;
            when_full += (v.pop && last.full) as u32;
        }
        heads += !rtl.empty as u32;
        fulls += rtl.full as u32;
        empties += rtl.empty as u32;
        overflows += (rtl.overflow && !last.overflow) as u32;
        underflows += (rtl.underflow && !last.underflow) as u32;
        last = rtl;
    })
    .unwrap_or_else(|e| panic!("capacity {capacity}: {e}"));
    assert!(
        fulls > 1000 && empties > 1000 && overflows > 20 && underflows > 20 && heads > 100_000,
        "coverage: {fulls} full, {empties} empty, {overflows} overflows, {underflows} underflows"
    );
    assert!(
        into_empty > 1000 && at_one > 1000 && when_full > 1000,
        "bypass coverage: {into_empty} into empty, {at_one} at level 1, {when_full} when full"
    );
}

#[test]
fn rtl_matches_the_queue_model_at_depth_4() {
    run::<2, 3, 32>(0xf1f0, 500_000);
}

#[test]
fn rtl_matches_the_queue_model_at_depth_16_and_256() {
    run::<4, 5, 32>(0xf1f1, 500_000);
    run::<8, 9, 32>(0xf1f2, 500_000);
}

/// The motion controller's FIFOs hold 18-bit compressed entries.
#[test]
fn rtl_matches_the_queue_model_with_18_bit_entries() {
    run::<4, 5, 18>(0xf1f5, 500_000);
}

#[test]
fn generated_verilog_matches_rust_in_icarus_and_verilator() {
    check_instance::<CommandFifo<2, 3, 32>>(
        Instance::Generated("command_fifo_4"),
        random_inputs(0xf1f3, 20_000, 4)
            .iter()
            .map(CommandFifoInputs::to_vector),
    );
    check_instance::<CommandFifo<8, 9, 32>>(
        Instance::Generated("command_fifo_256"),
        random_inputs(0xf1f4, 20_000, 256)
            .iter()
            .map(CommandFifoInputs::to_vector),
    );
}

/// The FIFO's memory is block RAM on iCE40, not flip-flops: 256 x 32 bits
/// is two SB_RAM40_4K.
#[test]
fn a_256_entry_fifo_synthesizes_into_two_block_rams() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("command_fifo_256.v");
    let mut fifo = CommandFifo::<8, 9, 32>::default();
    let verilog = motion_hdl::export::module_verilog("command_fifo_256", &mut fifo).unwrap();
    std::fs::write(&path, verilog).unwrap();
    let figures = motion_hdl::tools::synth::synthesize(&path, "command_fifo_256", &[1], 100.0)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(figures.ram, 2, "{figures:?}");
    assert!(figures.dff < 200, "memory in flip-flops? {figures:?}");
}
