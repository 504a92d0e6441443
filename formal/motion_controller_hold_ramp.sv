// motion_controller, the feed hold's ramp and tick gate (HoldRamp): the
// gate never creates a tick, and the velocity factor ramps as the datasheet
// states it (src/blocks/motion_controller/hold_ramp.rs, "Ports" and
// "Timing"; the controller's "Feed hold").
//
// Every axis's interpolator, the period counter and so the FIFOs run on
// `tick_out`, and the axes emit steps only on their ticks: a gate that
// passes only base ticks, at most one per base tick, never creates a step
// and never makes an axis step faster than it does at full speed (the
// axes' own proofs, formal/motion_controller_axis.sv, take every tick
// pattern).
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's register.
//
// Environment: none assumed. Every input is free at every clock: reset,
// tick, hold and rate (0 too).
//
// The contract, per clock:
// * `tick_out` only with `tick` (never a tick that is not a base tick);
//   none while the factor is 0; every tick while it is UNITY.
// * The factor stays within 0 to UNITY; `slowed` and `stopped` say where.
// * After an edge in reset (and at power-up): factor UNITY, phase 0.
// * After an edge without a tick: factor and phase unchanged.
// * After an edge with a tick, with the factor f, the phase p and the gate
//   g of that clock: the fraction is carried, p' + UNITY x g = p + f
//   exactly; and the factor moves one step of `rate` (0: UNITY) toward 0
//   under `hold`, toward UNITY without, clamped: never further.

localparam [16:0] F_UNITY = 17'h10000;

reg f_past_valid = 1'b0;
reg f_edge_reset = 1'b0;
reg f_edge_tick = 1'b0;
reg f_edge_hold = 1'b0;
reg f_edge_gate = 1'b0;
reg [15:0] f_edge_rate = 16'd0;
reg [16:0] f_edge_factor = 17'd0;
reg [15:0] f_edge_phase = 16'd0;
always @(posedge clock) begin
    f_past_valid <= 1'b1;
    f_edge_reset <= reset;
    f_edge_tick <= tick;
    f_edge_hold <= hold;
    f_edge_gate <= tick_out;
    f_edge_rate <= rate;
    f_edge_factor <= factor;
    f_edge_phase <= phase;
end

// The step of the last edge's rate, RATE 0 acting as UNITY.
wire [16:0] f_step = (f_edge_rate == 16'd0) ? F_UNITY : {1'b0, f_edge_rate};
wire [16:0] f_down = (f_edge_factor > f_step) ? f_edge_factor - f_step : 17'd0;
wire [17:0] f_up_sum = {1'b0, f_edge_factor} + {1'b0, f_step};
wire [16:0] f_up = (f_up_sum >= {1'b0, F_UNITY}) ? F_UNITY : f_up_sum[16:0];

always @(*) begin
    assert(!tick_out || tick);
    assert(factor <= F_UNITY);
    if (factor == 17'd0)
        assert(!tick_out);
    if (factor == F_UNITY)
        assert(tick_out == tick);
    assert(slowed == (factor != F_UNITY));
    assert(stopped == (factor == 17'd0));
    if (!f_past_valid) begin
        // Power-up: every register 0, full speed.
        assert(factor == F_UNITY);
        assert(phase == 16'd0);
    end else if (f_edge_reset) begin
        assert(factor == F_UNITY);
        assert(phase == 16'd0);
    end else if (!f_edge_tick) begin
        assert(factor == f_edge_factor);
        assert(phase == f_edge_phase);
    end else begin
        assert({2'b0, phase} + (f_edge_gate ? {1'b0, F_UNITY} : 18'd0)
            == {2'b0, f_edge_phase} + {1'b0, f_edge_factor});
        if (f_edge_hold)
            assert(factor == f_down);
        else
            assert(factor == f_up);
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the register is the deficit UNITY - factor, never
// above UNITY; the summary holds the last edge's outputs.
always @(*) begin
    assert(deficit__q <= F_UNITY);
    if (f_past_valid)
        assert(f_edge_factor <= F_UNITY);
end
`endif
