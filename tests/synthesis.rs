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
    let path = repo_root().join("target").join("synthesis-report.md");
    std::fs::write(&path, &text).unwrap();
    println!("{text}");
}
