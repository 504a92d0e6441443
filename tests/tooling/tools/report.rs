//! Tests of `motion_hdl::tools::report` (`src/tools/report.rs`).

use motion_hdl::tools::families::HEADING as FAMILIES_HEADING;
use motion_hdl::tools::report::*;

const ICE40: &str = "# Synthesis report\n\n| module | LUT4 | area budget | DFF | carry | RAM |\n|---|\n| `a` | 1 | - | 2 | 3 | 0 |\n| `b` | 4 | - | 5 | 6 | 0 |\n";

fn families(rows: &str) -> String {
    format!("{FAMILIES_HEADING}\n\ntext\n\n| module | x |\n|---|\n{rows}")
}

#[test]
fn readers_see_only_the_ice40_table() {
    let report = assemble(ICE40, &families("| `a` | 9 |\n| `c` | 9 |\n"));
    assert_eq!(listed_modules(&report), vec!["a", "b"]);
    assert_eq!(cell_counts(&report, "b"), Some((4, 5, 6, 0)));
    assert_eq!(cell_counts(&report, "c"), None);
    assert!(sections(&report)
        .1
        .is_some_and(|f| f.starts_with(FAMILIES_HEADING)));
}

#[test]
fn merge_keeps_unmeasured_rows_in_both_tables() {
    let previous = assemble(ICE40, &families("| `a` | 1 |\n| `b` | 2 |\n"));
    let fresh = assemble(
        "# Synthesis report\n\n| module |\n|---|\n| `b` | 40 | - | 50 | 60 | 0 |\n",
        &families("| `b` | 20 |\n"),
    );
    let merged = merge(&previous, &fresh, &["a", "b"]);
    assert_eq!(cell_counts(&merged, "a"), Some((1, 2, 3, 0)));
    assert_eq!(cell_counts(&merged, "b"), Some((40, 50, 60, 0)));
    let families_part = sections(&merged).1.unwrap_or_default();
    assert!(
        families_part.contains("| `a` | 1 |\n| `b` | 20 |\n"),
        "{merged}"
    );
    // A report without a families section keeps working.
    let old = merge(ICE40, &fresh, &["a", "b"]);
    assert!(sections(&old).1.is_some_and(|f| f.contains("| `b` | 20 |")));
}
