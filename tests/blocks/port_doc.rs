//! Tests of `motion_hdl::blocks::port_doc` (`src/blocks/port_doc.rs`).

use motion_hdl::blocks::port_doc::*;

const DOCS: &[PortDoc] = &[
    port("a", "W", "the a input"),
    port("b", "1", "the b output"),
];

#[test]
fn same_as_copies_the_named_port() {
    const B: PortDoc = PortDoc::same_as(DOCS, "b");
    assert_eq!(B, DOCS[1]);
    assert_eq!(PortDoc::same_as(DOCS, "a").with_width("T").width, "T");
}

#[test]
fn widths_evaluate() {
    let p = [("N", 4), ("K", 3), ("T", 16)];
    assert_eq!(eval_width("32", &p), Ok(32));
    assert_eq!(eval_width("T", &p), Ok(16));
    assert_eq!(eval_width("N+1", &p), Ok(5));
    assert_eq!(eval_width("32K", &p), Ok(96));
    assert!(eval_width("X", &p).is_err());
    assert!(eval_width("N+", &p).is_err());
    assert!(eval_width("0", &p).is_err());
}
