//! Tests of `motion_hdl::export::datasheet` (`src/export/datasheet.rs`).

use motion_hdl::blocks::freq_divider::{self, FreqDivider};
use motion_hdl::blocks::port_doc::port;
use motion_hdl::blocks::port_doc::PortDoc;
use motion_hdl::export::datasheet::*;

fn table(port_docs: &'static [PortDoc]) -> Result<String, DatasheetError> {
    port_table(&DatasheetSpec {
        block: "freq_divider",
        port_docs,
        parameters: &[("W", 32)],
        build: || Box::new(FreqDivider::<32>::default()),
    })
}

#[test]
fn the_shipped_table_passes() {
    let md = table(freq_divider::PORT_DOCS).unwrap();
    assert!(md.contains("| `divisor` | in | W |"), "{md}");
}

// Each mutation of a correct table must be refused.
#[test]
fn a_wrong_width_is_refused() {
    const DOCS: &[PortDoc] = &[
        port("clock", "1", "c"),
        port("reset", "1", "r"),
        port("enable", "1", "e"),
        port("divisor", "16", "d"),
        port("strobe", "1", "s"),
    ];
    let e = table(DOCS).unwrap_err().to_string();
    assert!(
        e.contains("`divisor` is documented as 16 = 16 bits, the RTL has 32"),
        "{e}"
    );
}

#[test]
fn an_undocumented_port_is_refused() {
    const DOCS: &[PortDoc] = &[
        port("clock", "1", "c"),
        port("reset", "1", "r"),
        port("divisor", "W", "d"),
        port("strobe", "1", "s"),
    ];
    let e = table(DOCS).unwrap_err().to_string();
    assert!(e.contains("undocumented ports [\"enable\"]"), "{e}");
}

#[test]
fn a_port_the_rtl_lacks_is_refused() {
    const DOCS: &[PortDoc] = &[
        port("clock", "1", "c"),
        port("reset", "1", "r"),
        port("enable", "1", "e"),
        port("divisor", "W", "d"),
        port("strobe", "1", "s"),
        port("phase", "W", "p"),
    ];
    let e = table(DOCS).unwrap_err().to_string();
    assert!(e.contains("`phase` is not a port of the RTL"), "{e}");
}

#[test]
fn every_datasheet_renders() {
    for spec in datasheets() {
        port_table(&spec).unwrap_or_else(|e| panic!("{e}"));
    }
}
