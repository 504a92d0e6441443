// freq_divider: the strobe, exactly, as its datasheet states it
// (src/blocks/freq_divider/mod.rs, "Timing" and "Bad input").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers.
//
// Environment: none assumed. Every input is free at every clock,
// `reset` included: the datasheet allows any divisor, any enable pattern.
//
// The contract, per clock edge (an enabled edge has `enable` high):
// * no strobe follows an edge in reset or with `enable` low;
// * after reset (power-up is the same state), the first enabled edge with
//   D != 0 strobes;
// * after a strobe that latched D, the next strobe comes exactly D
//   enabled edges later if D != 0 there, and otherwise (the divider
//   stopped with D = 0 and parked) at the first later enabled edge with
//   D != 0. No strobe comes before D enabled edges.

localparam F_W = $bits(divisor);

// What the last clock edge saw: its inputs, registered here, and its
// result, `strobe` (registered in the block).
reg f_edge_enable = 1'b0;
reg f_edge_reset = 1'b0;
reg [F_W-1:0] f_edge_divisor = {F_W{1'b0}};
always @(posedge clock) begin
    f_edge_enable <= enable;
    f_edge_reset <= reset;
    f_edge_divisor <= divisor;
end

// A summary of the edges up to the last one: whether one strobed since
// reset, the D it latched, and how many enabled edges came after it
// (saturating at D: only "fewer than D" matters). `f_*` is the summary
// before the last edge, `f_*_now` with it.
reg f_strobed = 1'b0;
reg [F_W-1:0] f_latched = {F_W{1'b0}};
reg [F_W-1:0] f_after = {F_W{1'b0}};
reg f_strobed_now;
reg [F_W-1:0] f_latched_now;
reg [F_W-1:0] f_after_now;
always @(*) begin
    f_strobed_now = f_strobed;
    f_latched_now = f_latched;
    f_after_now = f_after;
    if (f_edge_reset) begin
        f_strobed_now = 1'b0;
    end else if (f_edge_enable) begin
        if (strobe) begin
            f_strobed_now = 1'b1;
            f_latched_now = f_edge_divisor;
            f_after_now = {F_W{1'b0}};
        end else if (f_after != f_latched) begin
            f_after_now = f_after + 1'b1;
        end
    end
end
always @(posedge clock) begin
    f_strobed <= f_strobed_now;
    f_latched <= f_latched_now;
    f_after <= f_after_now;
end

// Enabled edges since the last strobe, the last edge included.
wire [F_W:0] f_interval = {1'b0, f_after} + 1'b1;
wire f_interval_done = !f_strobed || f_interval >= {1'b0, f_latched};

always @(*) begin
    if (f_edge_reset || !f_edge_enable)
        assert(!strobe);
    else
        assert(strobe == (f_edge_divisor != {F_W{1'b0}} && f_interval_done));
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the summary. Mid
// interval, the block's latched D is the strobe's D and its count runs 2
// ahead of the enabled edges seen since; out of an interval, the last one
// has run out.
always @(*) begin
    if (mid_interval__q) begin
        assert(f_strobed_now);
        assert(latched_divisor__q == f_latched_now);
        assert({1'b0, count__q} == {1'b0, f_after_now} + 2'd2);
        assert({1'b0, count__q} <= {1'b0, f_latched_now});
    end else if (f_strobed_now) begin
        assert({1'b0, f_after_now} + 1'b1 >= {1'b0, f_latched_now});
    end
    // The summary's own invariant: the count saturates at a non-zero D.
    if (f_strobed) begin
        assert(f_after <= f_latched);
        assert(f_latched != {F_W{1'b0}});
    end
end
`endif
