//! The datasheets hold each port's meaning once: in `PORT_DOCS`, from
//! which the port tables are generated (their freshness is checked with
//! the rest of the export in `rtl_out.rs`). These tests keep the other
//! places a port is named from restating it.

use motion_hdl::blocks::port_doc::eval_width;
use motion_hdl::export::datasheet::datasheets;
use motion_hdl::tools::repo_root;
use regex::Regex;

/// The `///` lines right above line `i`.
fn doc_above(lines: &[&str], i: usize) -> Vec<String> {
    let mut doc = vec![];
    let mut j = i;
    while j > 0 && lines[j - 1].trim_start().starts_with("///") {
        j -= 1;
        doc.insert(0, lines[j].trim().to_string());
    }
    doc
}

/// A port field's rustdoc is one short line: its meaning is the port
/// table's, so a longer text would be a second copy that can drift.
#[test]
fn port_fields_have_one_line_docs() {
    let field = Regex::new(r"^\s*pub (\w+): Signal<(In|Out|InOut),").unwrap();
    let mut long = vec![];
    for spec in datasheets() {
        let path = repo_root()
            .join("src/blocks")
            .join(spec.block)
            .join("mod.rs");
        let source = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = source.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            if let Some(c) = field.captures(line) {
                let doc = doc_above(&lines, i);
                if doc.len() != 1 || doc[0].len() > 100 {
                    long.push(format!("{}.{}: {doc:?}", spec.block, &c[1]));
                }
            }
        }
    }
    assert!(
        long.is_empty(),
        "port field docs longer than one line: {long:#?}"
    );
}

/// Where a model's field doc states a width, "(N bits)", for a field named
/// as a port of its block, it is the port's width in the datasheet's
/// instance (`dac_interface`'s model once said 4 bits of a 5-bit address).
#[test]
fn widths_in_model_docs_are_the_ports() {
    let field = Regex::new(r"^\s*pub (\w+): ").unwrap();
    let width = Regex::new(r"\((\d+) bits\)").unwrap();
    let mut checked = 0;
    let mut wrong = vec![];
    for spec in datasheets() {
        let path = repo_root()
            .join("src/blocks")
            .join(spec.block)
            .join("model.rs");
        let Ok(source) = std::fs::read_to_string(&path) else {
            continue;
        };
        let lines: Vec<&str> = source.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let Some(name) = field.captures(line).map(|c| c[1].to_string()) else {
                continue;
            };
            let Some(port) = spec.port_docs.iter().find(|d| d.name == name) else {
                continue;
            };
            for doc in doc_above(&lines, i) {
                for stated in width.captures_iter(&doc) {
                    let stated: usize = stated[1].parse().unwrap();
                    let actual = eval_width(port.width, spec.parameters).unwrap();
                    checked += 1;
                    if stated != actual {
                        wrong.push(format!(
                            "{}::{name}: the model says {stated} bits, the port has {actual}",
                            spec.block
                        ));
                    }
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    assert!(
        checked > 0,
        "no model states a port width: the test checks nothing"
    );
}

/// Vendor capacities, not measurements: quoted beside the reports so
/// that a reader can set one against the other.
const CAPACITIES: &[&str] = &["7680", "8640", "20736", "24288"];

/// Measured figures live in the reports (`rtl-out/synthesis-report.md`,
/// `rtl-out/scaling-report.md`): every resource count or Fmax that the
/// README or a rustdoc quotes must be one of theirs, so a quote cannot
/// outlive the measurement (the README once said 6,717 LC at 88.5 MHz
/// where the report said 6,761 and 99.5).
#[test]
fn quoted_figures_are_in_the_reports() {
    let figure = Regex::new(
        r"(\d{2,}\.\d+) ?MHz|(\d[\d,]*(?:\.\d+)?) ?(?:LC\b|logic cells|LUT4|DFF|flip-flops|TRELLIS_COMB)",
    )
    .unwrap();
    let number = Regex::new(r"\d+(?:\.\d+)?").unwrap();
    let mut reported = std::collections::BTreeSet::new();
    for report in ["synthesis-report.md", "scaling-report.md"] {
        let text = std::fs::read_to_string(repo_root().join("rtl-out").join(report)).unwrap();
        reported.extend(number.find_iter(&text).map(|m| m.as_str().to_string()));
    }
    let mut quoted = vec![("README.md".to_string(), {
        std::fs::read_to_string(repo_root().join("README.md")).unwrap()
    })];
    for entry in crate::rust_files(&repo_root().join("src")) {
        let text = std::fs::read_to_string(&entry).unwrap();
        let docs: String = text
            .lines()
            .filter(|l| l.trim_start().starts_with("//!") || l.trim_start().starts_with("///"))
            .map(|l| format!("{l}\n"))
            .collect();
        quoted.push((entry.display().to_string(), docs));
    }
    let mut stale = vec![];
    let mut checked = 0;
    for (file, text) in &quoted {
        for c in figure.captures_iter(text) {
            let value = c.get(1).or(c.get(2)).unwrap().as_str().replace(',', "");
            checked += 1;
            if !reported.contains(&value) && !CAPACITIES.contains(&value.as_str()) {
                stale.push(format!("{file}: `{}`", &c[0]));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "figures quoted outside the reports, not in them (quote the report, or link to it): {stale:#?}"
    );
    assert!(checked > 0, "no figure found: the test checks nothing");
}
