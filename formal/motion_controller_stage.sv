// motion_controller, an axis's output stage (StepOutput<16, 8>, built as
// the axis builds it): the premise that formal/motion_controller_axis.sv's
// induction takes, proved here on the stage's own ports. Together the two
// files are an assume-guarantee proof of the axis's limit rule: this file
// guarantees what that one assumes.
//
// The stage's whole contract is formal/step_output.sv's (at narrow
// widths); this file proves, at the controller's widths, the two of its
// consequences that the axis's limit rule rests on (src/blocks/step_output/
// mod.rs, "Ports": `emitted`, `pending_*`; "Flush"; "Bad input"):
// * a step reported by `emitted` went the way of the pending count's sign
//   in the clock that decided it (`pending_forward` / `pending_backward`
//   then);
// * the count is forward (backward) only after an edge with no reset and no
//   flush, at which it was already forward (backward) or a forward
//   (backward) step was requested: it turns forward through nothing else.
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the stage's registers.
//
// Environment: none assumed. Every input is free at every clock.

localparam F_P = $bits(pending__q);
localparam [F_P-1:0] F_MAX = {1'b0, {(F_P-1){1'b1}}};
localparam [F_P-1:0] F_MIN = {1'b1, {(F_P-1){1'b0}}};

// What the last clock edge saw.
reg f_reset_1 = 1'b0;
reg f_flush_1 = 1'b0;
reg f_step_1 = 1'b0;
reg f_dir_1 = 1'b0;
reg f_pending_forward_1 = 1'b0;
reg f_pending_backward_1 = 1'b0;
always @(posedge clock) begin
    f_reset_1 <= reset;
    f_flush_1 <= flush;
    f_step_1 <= step;
    f_dir_1 <= dir;
    f_pending_forward_1 <= pending_forward;
    f_pending_backward_1 <= pending_backward;
end

always @(*) begin
    if (emitted)
        assert(emitted_forward ? f_pending_forward_1 : f_pending_backward_1);
    if (pending_forward)
        assert(!f_reset_1 && !f_flush_1 && (f_pending_forward_1 || (f_step_1 && f_dir_1)));
    if (pending_backward)
        assert(!f_reset_1 && !f_flush_1 && (f_pending_backward_1 || (f_step_1 && !f_dir_1)));
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the registered zero test and limit flags of the
// pending count agree with the count.
always @(*) begin
    assert(nonzero__q == (pending__q != {F_P{1'b0}}));
    assert(at_max__q == (pending__q == F_MAX));
    assert(at_min__q == (pending__q == F_MIN));
end
`endif
