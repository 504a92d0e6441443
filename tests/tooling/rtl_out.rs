//! `rtl-out/` and `testbench/` are the product: they must be exactly what
//! `motion-hdl export` writes now, and every module must lint clean.

use std::collections::BTreeSet;

use motion_hdl::export::{catalog, generated_files, OutputDir};
use motion_hdl::tools::lint::lint;
use motion_hdl::tools::{repo_root, report};

/// Also the export's determinism: the committed files were written by
/// another process (`motion-hdl export`), whose hash maps had other random
/// seeds, so an export that depended on iteration order or addresses
/// would differ here. (A second export in this process, compared with the
/// first, cost 30 s more and caught less.)
#[test]
fn committed_export_is_fresh() {
    let root = repo_root();
    let mut stale = vec![];
    for file in generated_files().unwrap_or_else(|e| panic!("{e}")) {
        let dir = match file.dir {
            OutputDir::Rtl => "rtl-out",
            OutputDir::Testbench => "testbench",
            OutputDir::Datasheets => "src/blocks",
            OutputDir::Boards => "boards",
        };
        let path = root.join(dir).join(&file.file_name);
        if std::fs::read_to_string(&path).ok().as_deref() != Some(file.contents.as_str()) {
            stale.push(path.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "stale or missing (run `cargo run --release -- export`): {stale:?}"
    );
}

#[test]
fn rtl_out_holds_no_module_that_is_not_exported() {
    let exported: BTreeSet<String> = catalog().iter().map(|s| format!("{}.v", s.name)).collect();
    let present: BTreeSet<String> = std::fs::read_dir(repo_root().join("rtl-out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".v"))
        .collect();
    assert_eq!(present, exported, "rtl-out/*.v differs from the catalog");
}

#[test]
fn module_names_are_unique_across_all_files_and_free_of_dollars() {
    let mut seen = BTreeSet::new();
    for spec in catalog() {
        let text =
            std::fs::read_to_string(repo_root().join("rtl-out").join(format!("{}.v", spec.name)))
                .unwrap();
        for line in text.lines().filter(|l| l.starts_with("module ")) {
            let name = line["module ".len()..]
                .split('(')
                .next()
                .unwrap()
                .trim()
                .to_string();
            assert!(
                name == spec.name || name.starts_with(&format!("{}__", spec.name)),
                "{name} in {}.v",
                spec.name
            );
            assert!(
                seen.insert(name.clone()),
                "module {name} defined twice in rtl-out/"
            );
        }
        let code: String = text.lines().filter(|l| !l.starts_with("//")).collect();
        assert!(
            !code.contains("$ ") && !code.contains("$."),
            "hierarchy `$` left in {}.v",
            spec.name
        );
    }
}

#[test]
fn every_exported_module_passes_verilator_lint_wall() {
    for spec in catalog() {
        let rtl = repo_root().join("rtl-out").join(format!("{}.v", spec.name));
        lint(&rtl, spec.name).unwrap_or_else(|e| panic!("{}: {e}", spec.name));
    }
}

#[test]
fn committed_synthesis_report_covers_every_exported_module() {
    let report = std::fs::read_to_string(repo_root().join("rtl-out").join("synthesis-report.md"))
        .expect("rtl-out/synthesis-report.md is missing: run `cargo run --release -- report`");
    let listed: BTreeSet<String> = report::listed_modules(&report).into_iter().collect();
    let exported: BTreeSet<String> = catalog().iter().map(|s| s.name.to_string()).collect();
    assert_eq!(
        listed, exported,
        "synthesis-report.md is stale: run `cargo run --release -- report`"
    );
}

/// No top-level port of an exported module contains `__` (VHDL forbids
/// it, Verilator mangles it), except `dda_interpolator`'s per-axis ports,
/// documented once as `__i`.
#[test]
fn exported_port_names_have_no_double_underscore() {
    for spec in catalog()
        .into_iter()
        .filter(|s| s.name != "dda_interpolator")
    {
        let block = (spec.build)();
        let top: Vec<String> = motion_hdl::export::top_ports(block.as_ref())
            .into_iter()
            .map(|p| p.name)
            .collect();
        assert!(top.len() > 3, "{}: {top:?}", spec.name);
        assert!(
            top.iter().all(|p| !p.contains("__")),
            "{}: a port name with `__`: {top:?}",
            spec.name
        );
    }
}

/// Every exported block's datasheet shows its generated port table, and
/// has no hand-written one beside it.
#[test]
fn every_datasheet_includes_its_generated_port_table() {
    let datasheets = motion_hdl::export::datasheet::datasheets();
    for spec in catalog() {
        assert!(
            datasheets.iter().any(|d| d.block == spec.block),
            "{}: no datasheet port table for block {}",
            spec.name,
            spec.block
        );
    }
    for spec in datasheets {
        let source =
            std::fs::read_to_string(repo_root().join(format!("src/blocks/{}/mod.rs", spec.block)))
                .unwrap();
        assert!(
            source.contains("#![doc = include_str!(\"ports.md\")]"),
            "{}: the datasheet does not include ports.md",
            spec.block
        );
        assert!(
            !source.contains("//! | port | dir |"),
            "{}: a hand-written port table beside the generated one",
            spec.block
        );
    }
}
