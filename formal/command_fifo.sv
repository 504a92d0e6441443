// command_fifo: level, flags, refusals and the order of the entries, as
// its datasheet states them (src/blocks/command_fifo/mod.rs, the module
// summary, "Ports" and "Timing").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers and its RAM's
// ports.
//
// Environment: none assumed. Every input is free at every clock, `reset`
// included: writes and pops may come on any clock, together, full or
// empty. The induction takes one premise about rust-hdl's RAM, which this
// file cannot see (see RAM PREMISE below); formal/command_fifo_ram.sv
// proves it on the RAM. The bounded check without the invariants (the
// mutation tests) runs without it.
//
// The contract, per clock edge ("taken": a pop when not empty; a write
// when not full, or when full with a pop taken on the same edge):
// * `level` never exceeds the depth 2^N; `empty`, `full` and `low` are
//   `level` == 0, `level` == 2^N and `level` <= `low_water`;
// * after an edge in reset (power-up is the same state) the FIFO is empty
//   and both flags are low;
// * otherwise `level` grows by one for a write taken, shrinks by one for
//   a pop taken (both: unchanged): a refused write or pop changes nothing;
// * a refused write sets `overflow`, a refused pop `underflow`; a flag
//   stays set until `clear_flags` (a flag set on the clock of
//   `clear_flags` stays set), and is set by nothing else;
// * a refused write (it has no pop) leaves `head` as it was;
// * until the first write taken since power-up, `head` is 0;
// * entries come out in order, with their data. The proof follows one
//   write taken, chosen freely (`f_pick`, any value at any clock: every
//   write taken is followed in some trace): it records its data and the
//   entries held before it (those still there after a pop on the same
//   edge). While followed, the entry is held (`empty` low, `level` above
//   the entries before it), each pop taken removes one entry before it,
//   and once none is left it is on `head` with its data until it is
//   popped. As any write may be the chosen one, every entry comes out
//   with its data, after exactly the entries written before it.

localparam F_LW = $bits(level);
localparam F_W = $bits(head);
localparam [F_LW-1:0] F_DEPTH = {1'b1, {(F_LW-1){1'b0}}};

// Taken, at the coming edge.
wire f_pop_taken = pop && !empty;
wire f_write_taken = write && (!full || f_pop_taken);

// What the last clock edge saw: its inputs, registered here, and the
// outputs before it. Power-up counts as an edge in reset.
reg f_edge_reset = 1'b1;
reg f_edge_write = 1'b0;
reg f_edge_pop = 1'b0;
reg f_edge_write_taken = 1'b0;
reg f_edge_pop_taken = 1'b0;
reg f_edge_clear_flags = 1'b0;
reg [F_LW-1:0] f_level_before = {F_LW{1'b0}};
reg [F_W-1:0] f_head_before = {F_W{1'b0}};
reg f_overflow_before = 1'b0;
reg f_underflow_before = 1'b0;
always @(posedge clock) begin
    f_edge_reset <= reset;
    f_edge_write <= write;
    f_edge_pop <= pop;
    f_edge_write_taken <= f_write_taken;
    f_edge_pop_taken <= f_pop_taken;
    f_edge_clear_flags <= clear_flags;
    f_level_before <= level;
    f_head_before <= head;
    f_overflow_before <= overflow;
    f_underflow_before <= underflow;
end

always @(*) begin
    assert(level <= F_DEPTH);
    assert(empty == (level == {F_LW{1'b0}}));
    assert(full == (level == F_DEPTH));
    assert(low == (level <= low_water));
    if (f_edge_reset) begin
        assert(level == {F_LW{1'b0}});
        assert(!overflow);
        assert(!underflow);
    end else begin
        if (f_edge_write_taken && !f_edge_pop_taken)
            assert(level == f_level_before + 1'b1);
        else if (f_edge_pop_taken && !f_edge_write_taken)
            assert(level == f_level_before - 1'b1);
        else
            assert(level == f_level_before);
        assert(overflow == ((f_edge_write && !f_edge_write_taken)
                            || (f_overflow_before && !f_edge_clear_flags)));
        assert(underflow == ((f_edge_pop && !f_edge_pop_taken)
                             || (f_underflow_before && !f_edge_clear_flags)));
        if (f_edge_write && !f_edge_write_taken)
            assert(head == f_head_before);
    end
end

// The RAM carries `no_rw_check`: a word read at an edge that writes the
// same address is undefined on iCE40. The FIFO never shows one: after such
// an edge, a non-empty FIFO's head is the bypass register.
reg f_collided = 1'b0;
always @(posedge clock)
    f_collided <= ram__read_enable && ram__write_enable
        && ram__read_address == ram__write_address;
always @(*) begin
    if (f_collided && !empty)
        assert(bypass__q);
end

// Before the first write taken since power-up, `head` is 0 (from the
// first clock edge on: the RAM's read register has no initial value in
// the Verilog, so the state before any edge is not covered).
reg f_edge_seen = 1'b0;
reg f_written = 1'b0;
always @(posedge clock) begin
    f_edge_seen <= 1'b1;
    if (f_write_taken)
        f_written <= 1'b1;
end
always @(*) begin
    if (f_edge_seen && !f_written)
        assert(head == {F_W{1'b0}});
end

// The followed entry: its data and the entries held before it.
(* anyseq *) reg f_pick;
reg f_followed = 1'b0;
reg [F_W-1:0] f_data = {F_W{1'b0}};
reg [F_LW-1:0] f_before = {F_LW{1'b0}};
wire f_picked = !reset && !f_followed && f_write_taken && f_pick;
always @(posedge clock) begin
    if (reset) begin
        f_followed <= 1'b0;
    end else if (f_followed) begin
        if (f_pop_taken) begin
            if (f_before == {F_LW{1'b0}})
                f_followed <= 1'b0;
            else
                f_before <= f_before - 1'b1;
        end
    end else if (f_picked) begin
        f_followed <= 1'b1;
        f_data <= write_data;
        f_before <= level - f_pop_taken;
    end
end

always @(*) begin
    if (f_followed) begin
        assert(!empty);
        assert(f_before < level);
        if (f_before == {F_LW{1'b0}})
            assert(head == f_data);
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the contract's
// summary.
localparam F_N = F_LW - 1;
reg [F_N-1:0] f_slot = {F_N{1'b0}};
reg [F_W-1:0] f_slot_word = {F_W{1'b0}};
always @(*) begin
    // The pointers are `level` apart (modulo 2^N).
    assert(write_pointer__q - read_pointer__q == level[F_N-1:0]);
    // Nothing written since power-up: the FIFO is empty, its pointers
    // have not moved and the head comes from the RAM.
    if (!f_written) begin
        assert(level == {F_LW{1'b0}});
        assert(read_pointer__q == {F_N{1'b0}});
        assert(!bypass__q);
    end
    // The followed entry's RAM slot is the read pointer plus the entries
    // before it, and no write has hit it since the entry's.
    if (f_followed) begin
        assert(f_slot == read_pointer__q + f_before[F_N-1:0]);
        assert(f_slot_word == f_data);
    end
end

// RAM PREMISE (assumed here, proved by formal/command_fifo_ram.sv on the
// same RAM: an assume-guarantee pair). The followed entry may wait
// behind the head for any number of clocks, held only in the RAM's array,
// and the array is in rust-hdl's RAM submodule, which this file cannot
// name (yosys 0.23 reads no hierarchical references, and a `hierconn`
// wire reaches a submodule's wire, not its memory array). So the induction
// takes the RAM's own contract as a premise, on its ports: a read-first
// synchronous RAM, whose read at an edge returns the word last written to
// its address before that edge. Stated for the followed entry's slot
// only: `f_slot_word` is the word last written to it since the entry was
// written there. The RAM's proof states it for every address, from
// power-up; here it is needed only for the followed entry's slot.
reg f_read_slot = 1'b0;
reg [F_W-1:0] f_read_word = {F_W{1'b0}};
always @(posedge clock) begin
    if (f_picked) begin
        f_slot <= ram__write_address;
        f_slot_word <= ram__write_data;
    end else if (ram__write_enable && ram__write_address == f_slot) begin
        f_slot_word <= ram__write_data;
    end
    f_read_slot <= f_followed && ram__read_address == f_slot;
    f_read_word <= f_slot_word;
end
always @(*) begin
    if (f_read_slot)
        assume(ram__read_data == f_read_word);
end
`endif
