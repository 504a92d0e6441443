//! Tests of `motion_hdl::export::verilog` (`src/export/verilog.rs`).

use motion_hdl::export::strip_hierarchy_dollars;

#[test]
fn hierarchy_separators_become_double_underscores() {
    let text = "module top$child$q(a$b);\n assign x = $signed(y$z) + ($unsigned(w));\n";
    assert_eq!(
        strip_hierarchy_dollars(text),
        "module top__child__q(a__b);\n assign x = $signed(y__z) + ($unsigned(w));\n"
    );
}
