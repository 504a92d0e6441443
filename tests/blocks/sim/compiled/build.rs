//! Tests of `motion_hdl::sim::compiled::build` (`src/sim/compiled/build.rs`).

use motion_hdl::sim::compiled::Design;

#[test]
fn clocked_blocks_take_both_edges_unless_traced_or_one_is_not_a_plain_rising_edge() {
    let rtl = "module m(input clock);\nalways @(posedge clock) q <= d;\nalways @(posedge read_clock) r <= s;\nalways @(*) x = y;\nendmodule";
    let design = Design::prepare(rtl, false);
    assert!(design.both_edges);
    assert_eq!(
        design.verilog,
        "module m(input clock);\nalways @(posedge clock or negedge clock) q <= d;\nalways @(posedge read_clock or negedge read_clock) r <= s;\nalways @(*) x = y;\nendmodule"
    );
    let traced = Design::prepare(rtl, true);
    assert!(!traced.both_edges);
    assert_eq!(traced.verilog, rtl);
    // A falling edge, an asynchronous reset or a spacing the rewrite does
    // not know: the design as it is, two `eval`s a cycle.
    for kept in [
        rtl.replace("posedge read_clock", "negedge read_clock"),
        rtl.replace(
            "@(posedge read_clock)",
            "@(posedge read_clock or posedge reset)",
        ),
        rtl.replace("@(posedge read_clock)", "@ (posedge read_clock)"),
    ] {
        let design = Design::prepare(&kept, false);
        assert!(!design.both_edges, "{kept}");
        assert_eq!(design.verilog, kept);
    }
}
