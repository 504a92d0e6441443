//! Every exported module synthesizes and places on iCE40 HX8K. The figures
//! go to `target/synthesis-report.md`; timing is reported, not asserted
//! (`motion-hdl report` measures the median over 5 seeds).

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
