//! Tests of `motion_hdl::tools::families` (`src/tools/families.rs`).

use motion_hdl::tools::families::CellClass::{BlockRam, FlipFlop, Free, LutRam};
use motion_hdl::tools::families::*;
use motion_hdl::tools::synth::final_stat;

/// The tail of a real `synth_xilinx` log (freq_divider) with an earlier
/// `stat` block before it, as yosys prints them.
const XILINX_LOG: &str = "\
   Number of cells:                 40
     $_AND_                         40

=== freq_divider ===

   Number of wires:                 97
   Number of cells:                224
     BUFG                            1
     CARRY4                          8
     FDRE                           66
     IBUF                           35
     INV                             1
     LUT2                           11
     LUT3                           35
     LUT4                           38
     LUT6                           19
     MUXF7                           7
     MUXF8                           2
     OBUF                            1
     RAMB18E1                        2

End of script.
";

#[test]
fn sorts_a_xilinx_stat_block() {
    let cells = tally(&XILINX_7, &final_stat(XILINX_LOG));
    assert_eq!(cells.lut, 1 + 11 + 35 + 38 + 19);
    assert_eq!(cells.ff, 66);
    assert_eq!(
        cells.special,
        vec![("CARRY4".to_string(), 8), ("RAMB18E1".to_string(), 2)]
    );
    assert_eq!(cells.count(&XILINX_7, BlockRam), 2);
    assert!(cells.unclassified.is_empty());
}

#[test]
fn reports_cells_yosys_left_unmapped() {
    let log = "   Number of cells:      717\n     $mux      7\n     $not      1\n     cycloneive_lcell_comb      544\n     dffeas      165\n";
    let cells = tally(&CYCLONE_IV_E, &final_stat(log));
    assert_eq!((cells.lut, cells.ff), (544, 165));
    assert_eq!(cells.unclassified, vec![("$mux".to_string(), 7)]);
}

#[test]
fn gowin_and_ecp5_rules() {
    assert_eq!(classify(&GOWIN, "DFFRE"), Some(FlipFlop));
    assert_eq!(classify(&GOWIN, "MUX2_LUT5"), Some(Free));
    assert_eq!(classify(&GOWIN, "SDPB"), Some(BlockRam));
    assert_eq!(classify(&GOWIN, "RAM16SDP4"), Some(LutRam));
    assert_eq!(classify(&ECP5, "TRELLIS_DPR16X4"), Some(LutRam));
    assert_eq!(classify(&ECP5, "LUT5"), None);
}

#[test]
fn reads_an_ecp5_report() {
    let text = r#"{"fmax": {"$glbnet$clock": {"achieved": 204.5, "constraint": 125}},
            "utilization": {"TRELLIS_COMB": {"available": 24288, "used": 101},
                            "TRELLIS_FF": {"available": 24288, "used": 66}}}"#;
    let (fmax, comb, ff) = read_ecp5_report(text).unwrap();
    assert_eq!((fmax, comb, ff), (204.5, (101, 24288), 66));
    assert!(read_ecp5_report("{}").is_err());
}

#[test]
fn placed_cells_give_the_share_and_every_seed() {
    let placement = Placement {
        lut: 143,
        lut_available: 20736,
        ff: 66,
        fmax_mhz: vec![362.58, 349.0, 351.2],
    };
    assert_eq!(
        placed_cells(Some(&placement)),
        " 143 (0.7 %) / 66 | 351.2 | 362.6, 349.0, 351.2 |"
    );
    assert_eq!(placed_cells(None), " not measured | not measured | - |");
}
