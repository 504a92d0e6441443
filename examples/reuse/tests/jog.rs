//! The jog generator against its model, its port table, and its Verilog.

use motion_hdl::sim::Lockstep;
use motion_hdl_reuse_example::{
    port_table, verilog, JogGenerator24, JogInputs, JogModel, JogOutputs, DIVISOR_BITS,
    PENDING_BITS, TIMER_BITS,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// RTL against the composed models, clock by clock on motion-hdl's
/// lockstep runner, with random settings changing every few hundred
/// clocks.
#[test]
fn rtl_matches_the_composed_models() {
    let mut pair = Lockstep::harness(
        "jog_generator",
        JogGenerator24::default(),
        JogModel::new(DIVISOR_BITS as u32, TIMER_BITS as u32, PENDING_BITS as u32),
    );
    let mut rng = StdRng::seed_from_u64(0x10c);
    let mut i = JogInputs::default();
    let (mut pulses, mut last_a) = (0u64, false);
    pair.run(
        |cycle, _| {
            if cycle % 500 == 0 {
                i = JogInputs {
                    reset: false,
                    enable: rng.gen_ratio(9, 10),
                    divisor: rng.gen_range(0..40),
                    dir: rng.gen(),
                    mode: 0,
                    step_len: rng.gen_range(0..4),
                    step_space: rng.gen_range(0..4),
                    dir_setup: rng.gen_range(0..4),
                    dir_hold: rng.gen_range(0..4),
                };
            }
            (cycle < 100_000).then_some(i)
        },
        |_, _, out: &JogOutputs| {
            pulses += (out.out_a && !last_a) as u64;
            last_a = out.out_a;
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        pulses > 2_000,
        "only {pulses} steps: the run exercised little"
    );
}

/// `src/ports.md` is what the port table generator writes now
/// (`UPDATE_PORT_TABLE=1` rewrites it).
#[test]
fn the_port_table_is_fresh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/ports.md");
    let table = port_table().unwrap_or_else(|e| panic!("{e}"));
    if std::env::var_os("UPDATE_PORT_TABLE").is_some() {
        std::fs::write(&path, &table).unwrap();
    }
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        table,
        "src/ports.md is stale: rerun with UPDATE_PORT_TABLE=1"
    );
}

/// The exported Verilog passes `verilator --lint-only -Wall` with
/// motion-hdl's waivers, as motion-hdl's own modules do.
#[test]
fn the_verilog_lints_clean() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("jog_generator.v");
    std::fs::write(&path, verilog().unwrap()).unwrap();
    motion_hdl::tools::lint::lint(&path, "jog_generator").unwrap_or_else(|e| panic!("{e}"));
}
