// watchdog: expiry exactly `timeout` ticks after the last kick, as its
// datasheet states it (src/blocks/watchdog/mod.rs, "Ports", "Timing" and
// "Bad input").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers.
//
// Environment: none assumed. Every input is free at every clock, `reset`
// included: any timeout (0 too), any kick, tick and clear pattern.
//
// The contract, per clock edge. A tick edge has `tick` high. A kick at an
// edge arms the watchdog with T = `timeout` at that edge, or disarms it if
// T = 0; reset (and power-up) disarms it.
// * expired: set at the T-th tick edge after the kick that armed the
//   watchdog, if no kick comes before or at that edge (the tick at the
//   kick's own edge is not one of the T: the kick reloads); the expiry
//   disarms the watchdog. At any other edge `expired` keeps its value,
//   cleared by `clear` (a kick does not clear it). So no expiry while
//   kicked in time, none with T = 0, none before the T-th tick edge; and
//   none after an expiry until the next kick arms the watchdog again.
//   After an edge in reset: `expired` 0.
// * armed: 1 from a kick with T != 0 up to the expiry; 0 after reset, after
//   a kick with T = 0 and after an expiry.
// The datasheet does not say what a `clear` on an expiring edge does: the
// expiry is a new event, so `expired` is set (as for the decoder's error
// flag); nor that `clear` leaves a running counter armed, which "clear
// `expired`" alone implies. Both are stated in the datasheet's "Formal
// proof" section.

localparam F_W = $bits(timeout);

// What the last clock edge saw: its inputs, registered here, and `expired`
// before it.
reg f_edge_reset = 1'b0;
reg f_edge_kick = 1'b0;
reg f_edge_tick = 1'b0;
reg f_edge_clear = 1'b0;
reg f_edge_expired = 1'b0;
reg [F_W-1:0] f_edge_timeout = {F_W{1'b0}};
always @(posedge clock) begin
    f_edge_reset <= reset;
    f_edge_kick <= kick;
    f_edge_tick <= tick;
    f_edge_clear <= clear;
    f_edge_expired <= expired;
    f_edge_timeout <= timeout;
end

// A summary of the edges up to the last one: whether the watchdog is
// armed, the T of the kick that armed it and the tick edges since that
// kick (fewer than T while armed). `f_*` is the summary before the last
// edge, `f_*_now` with it; power-up is the reset state (disarmed).
reg f_armed = 1'b0;
reg [F_W-1:0] f_t = {F_W{1'b0}};
reg [F_W-1:0] f_ticks = {F_W{1'b0}};
reg f_armed_now;
reg [F_W-1:0] f_t_now;
reg [F_W-1:0] f_ticks_now;
// The last edge was the T-th tick edge after the arming kick, with no kick.
wire f_expiry = !f_edge_reset && !f_edge_kick && f_edge_tick && f_armed
    && {1'b0, f_ticks} + 1'b1 == {1'b0, f_t};
always @(*) begin
    f_armed_now = f_armed;
    f_t_now = f_t;
    f_ticks_now = f_ticks;
    if (f_edge_reset) begin
        f_armed_now = 1'b0;
    end else if (f_edge_kick) begin
        f_armed_now = f_edge_timeout != {F_W{1'b0}};
        f_t_now = f_edge_timeout;
        f_ticks_now = {F_W{1'b0}};
    end else if (f_expiry) begin
        f_armed_now = 1'b0;
    end else if (f_edge_tick && f_armed) begin
        f_ticks_now = f_ticks + 1'b1;
    end
end
always @(posedge clock) begin
    f_armed <= f_armed_now;
    f_t <= f_t_now;
    f_ticks <= f_ticks_now;
end

always @(*) begin
    if (f_edge_reset) begin
        assert(!expired);
        assert(!armed);
    end else begin
        // Exactly on time: the T-th tick edge after the kick sets it.
        if (f_expiry)
            assert(expired);
        // Never otherwise: not early, not while kicked in time, not with
        // T = 0; sticky until `clear`.
        else
            assert(expired == (f_edge_expired && !f_edge_clear));
        assert(armed == f_armed_now);
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the summary. While
// armed, the block's down-counter holds the ticks left (T minus the ticks
// seen), and its registered "next tick expires" flag says whether one is
// left.
always @(*) begin
    assert(armed_reg__q == f_armed_now);
    if (f_armed_now) begin
        assert(left__q == f_t_now - f_ticks_now);
        assert(last__q == (left__q == {{(F_W-1){1'b0}}, 1'b1}));
    end
    // The summary's own invariant: fewer than T ticks seen while armed.
    if (f_armed)
        assert(f_ticks < f_t);
end
`endif
