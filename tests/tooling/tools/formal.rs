//! Tests of `motion_hdl::tools::formal` (`src/tools/formal/mod.rs`).

use motion_hdl::tools::formal::{failure_of, splice};

#[test]
fn the_property_file_is_included_before_the_top_modules_endmodule() {
    let verilog = "module top(a);\nendmodule // top\n\nmodule top__r(d);\nendmodule // top__r\n";
    assert_eq!(
        splice("top", verilog, "top.sv").unwrap(),
        "module top(a);\n`ifdef FORMAL\n`include \"top.sv\"\n`endif\nendmodule // top\n\nmodule top__r(d);\nendmodule // top__r\n"
    );
    assert!(splice("other", verilog, "other.sv").is_err());
}

#[test]
fn a_failure_reads_as_the_assertion_and_the_traces_length() {
    let bounded = "##   0:00:00  Checking assertions in step 0..\n##   0:00:00  Checking assertions in step 1..\n\
                       ##   0:00:00  Checking assertions in step 2..\n##   0:00:00  BMC failed!\n\
                       ##   0:00:00  Assert failed in top: top.sv:12.5-12.20 ($assert$top.sv:12$3)\n##   0:00:00  Status: FAILED\n";
    assert_eq!(
        failure_of(bounded, false, 20),
        (
            3,
            "top: top.sv:12.5-12.20 ($assert$top.sv:12$3)".to_string()
        )
    );
    let induction = "##   0:00:00  Trying induction in step 2..\n##   0:00:00  Trying induction in step 1..\n\
                         ##   0:00:00  Trying induction in step 0..\n##   0:00:00  Temporal induction failed!\n\
                         ##   0:00:00  Assert failed in top: top.sv:9.1-9.9 ($assert$top.sv:9$1)\n";
    assert_eq!(failure_of(induction, true, 2).0, 3);
}
