//! Tests of `motion_hdl::tools::synth` (`src/tools/synth.rs`).

use motion_hdl::tools::synth::final_stat;

#[test]
fn reads_the_last_stat_block() {
    let log = "Number of cells: 3\n  $_AND_ 3\n\n=== top ===\n   Number of cells:        5\n     SB_CARRY    2\n     SB_DFFE     1\n     SB_LUT4     2\n\n";
    assert_eq!(
        final_stat(log),
        vec![
            ("SB_CARRY".into(), 2),
            ("SB_DFFE".into(), 1),
            ("SB_LUT4".into(), 2)
        ]
    );
}
