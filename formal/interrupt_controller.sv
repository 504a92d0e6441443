// interrupt_controller: the status bits and `irq`, exactly, as its
// datasheet states them (src/blocks/interrupt_controller/mod.rs, the
// module summary, "Ports" and "Timing").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports.
//
// Environment: none assumed. Every input is free at every clock, `reset`
// included; events, clears and the mask may change on any clock.
//
// The contract, per clock edge, for every status bit i ("W1C of bit i":
// `clear` high with `clear_bits[i]` high at that edge):
// * after an edge in reset, `status` is 0 and `irq` low (power-up is the
//   same state);
// * an event at the edge sets bit i, a W1C of bit i on the same edge
//   notwithstanding: no event is ever lost to a clear;
// * a set bit stays set unless the edge has a W1C of it;
// * a clear bit becomes set only by its event;
// * a W1C of bit i without its event clears it;
// * `irq` after the edge is high exactly when a status bit that was set
//   before the edge is enabled at the edge: registered, so an event shows
//   in `status` after its edge and in `irq` one edge later, and a change
//   of `enable` shows in `irq` after the edge that sees it.

localparam F_N = $bits(events);

// What the last clock edge saw: its inputs, registered here, and the
// status before it. Power-up counts as an edge in reset.
reg f_edge_reset = 1'b1;
reg [F_N-1:0] f_edge_events = {F_N{1'b0}};
reg f_edge_clear = 1'b0;
reg [F_N-1:0] f_edge_clear_bits = {F_N{1'b0}};
reg [F_N-1:0] f_edge_enable = {F_N{1'b0}};
reg [F_N-1:0] f_status_before = {F_N{1'b0}};
always @(posedge clock) begin
    f_edge_reset <= reset;
    f_edge_events <= events;
    f_edge_clear <= clear;
    f_edge_clear_bits <= clear_bits;
    f_edge_enable <= enable;
    f_status_before <= status;
end

// The bits the last edge wrote 1 to (W1C).
wire [F_N-1:0] f_w1c = f_edge_clear ? f_edge_clear_bits : {F_N{1'b0}};

always @(*) begin
    if (f_edge_reset) begin
        assert(status == {F_N{1'b0}});
        assert(!irq);
    end else begin
        // An event sets its bit, even on the clock of its W1C.
        assert((status & f_edge_events) == f_edge_events);
        // A set bit is cleared only by a W1C of it.
        assert((status & f_status_before & ~f_w1c) == (f_status_before & ~f_w1c));
        // A bit is set only by its event.
        assert((status & ~f_status_before & ~f_edge_events) == {F_N{1'b0}});
        // A W1C without the event clears its bit.
        assert((status & f_w1c & ~f_edge_events) == {F_N{1'b0}});
        // The level interrupt, one edge after the status it reflects.
        assert(irq == ((f_status_before & f_edge_enable) != {F_N{1'b0}}));
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: none needed. Every output is a register whose
// next value the contract states from the inputs and the status at the
// edge, so the contract is 1-inductive on its own.
`endif
