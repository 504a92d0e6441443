//! Every exported module synthesizes and places on iCE40 HX8K. The figures
//! go to `target/synthesis-report.md`; timing is reported, not asserted
//! (`motion-hdl report` measures the median over 5 seeds).

use std::process::Command;

use motion_hdl::export::catalog;
use motion_hdl::tools::{repo_root, report};

#[test]
fn every_exported_module_synthesizes_and_places_on_ice40_hx8k() {
    let specs = catalog();
    let seeds = [1];
    let rows = report::measure(&specs, &repo_root().join("rtl-out"), &seeds)
        .unwrap_or_else(|e| panic!("{e}"));
    for row in &rows {
        let f = &row.figures;
        assert!(
            f.lut4 > 0 && f.dff > 0 && f.logic_cells > 0,
            "{}: empty netlist {f:?}",
            row.module
        );
        assert!(
            f.fmax_mhz.iter().all(|&mhz| mhz > 0.0),
            "{}: no Fmax {f:?}",
            row.module
        );
    }
    let text = report::render(&rows, &seeds).unwrap_or_else(|e| panic!("{e}"));
    // `target/` is not there when cargo builds elsewhere (CARGO_TARGET_DIR).
    let dir = repo_root().join("target");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("synthesis-report.md"), &text).unwrap();
    println!("{text}");

    // yosys is deterministic, so the committed report's cell counts must be
    // today's. (Fmax depends on the placement seeds and is not compared.)
    let committed =
        std::fs::read_to_string(repo_root().join("rtl-out").join("synthesis-report.md")).unwrap();
    for row in &rows {
        let f = &row.figures;
        let counts = report::cell_counts(&committed, &row.module).unwrap_or_else(|| {
            panic!("{} is missing from rtl-out/synthesis-report.md", row.module)
        });
        assert_eq!(
            counts,
            (f.lut4, f.dff, f.carry, f.ram),
            "{}: rtl-out/synthesis-report.md is stale (LUT4, DFF, carry, RAM); run `cargo run --release -- report`",
            row.module
        );
    }
}

/// The README's board example (`boards/ice40-hx8k-breakout`): the
/// controller behind the DSP bus adapter, with a PLL and every machine
/// input and output on a pin, synthesizes and places with its pin file at
/// its 48 MHz clock, with the commands in `motion_board.v`'s header.
///
/// The board fills about 91 % of the HX8K's logic cells (96 % before
/// #19). With yosys's
/// defaults (every enable on the cells' clock enable, which the 8 cells of
/// a tile share) nextpnr could not legalise the placement ("Unable to find
/// legal placement for all cells", 97 %); `-dffe_min_ce_use 4`, which puts
/// an enable shared by fewer than 4 flip-flops into their LUTs, places.
#[test]
fn the_board_example_places_with_its_pin_file() {
    let board = repo_root().join("boards").join("ice40-hx8k-breakout");
    let rtl = repo_root().join("rtl-out");
    let dir = tempfile::tempdir().unwrap();
    let netlist = dir.path().join("board.json");
    let yosys = Command::new("yosys")
        .arg("-q")
        .arg("-p")
        .arg(format!(
            "read_verilog {} {} {}; synth_ice40 -dffe_min_ce_use 4 -top motion_board -json {}",
            board.join("motion_board.v").display(),
            rtl.join("motion_controller.v").display(),
            rtl.join("external_bus_adapter.v").display(),
            netlist.display()
        ))
        .output()
        .expect("yosys runs");
    assert!(yosys.status.success(), "{}", String::from_utf8_lossy(&yosys.stderr));
    let nextpnr = Command::new("nextpnr-ice40")
        .args(["--hx8k", "--package", "ct256", "--freq", "48", "--pcf"])
        .arg(board.join("motion_board.pcf"))
        .arg("--json")
        .arg(&netlist)
        .arg("--asc")
        .arg(dir.path().join("board.asc"))
        .output()
        .expect("nextpnr-ice40 runs");
    let log = String::from_utf8_lossy(&nextpnr.stderr);
    assert!(nextpnr.status.success(), "nextpnr failed (pins or timing at 48 MHz):\n{log}");
    assert!(log.contains("PASS at 48.00 MHz"), "{log}");
}
