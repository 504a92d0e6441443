// quadrature_decoder with the filter off: the count, exactly, as its
// datasheet states it (src/blocks/quadrature_decoder/mod.rs, "Ports",
// "Counting", "Timing", "Index", "Collisions", "Bad input").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers.
//
// Environment (each stated in the datasheet's "Formal proof" section):
// * the filter is off: `filter` <= 1 at every clock (0 and 1 both accept a
//   change at its first sample);
// * `counter_mode` and `index_invert` are configuration: each holds one
//   value through the trace (either value).
// Everything else is free at every clock: `reset`, the pins, `clear`,
// `clear_error`, every sample rate and every index option.
//
// The model follows each pin through the documented stages, one edge each
// ("Timing": PIN_TO_COUNT_EDGES = 5):
// 1, 2. two synchronizer flip-flops (0 after reset);
// 3. the filter: at a sample edge the filtered level takes the
//    synchronized pin and a change is accepted; a sample comes at the first
//    edge after reset and then every `sample_rate` + 1 edges, the rate taken
//    at the sample ("a new sample_rate applies from the next sample"); the
//    3 start-up edges after reset (and power-up) load the levels without
//    accepting a change;
// 4. the decode of the accepted changes into a step ("Counting":
//    quadrature 00 -> 10 -> 11 -> 01 -> 00 counts +1 a transition, the
//    reverse -1, a and b both changing counts nothing and is an error;
//    counter mode: a rising edge of a counts +1 with b high, -1 with b low,
//    and is an error if b changed on that sample); the index event (an
//    accepted change of the index to its active level) is decoded here too,
//    so it reaches the count on the same clock as a transition sampled with
//    it;
// 5. the count: the step is added, or, on a clear (`clear`, or an acted-on
//    index event with `index_clear`), the count becomes 0 and the step is
//    added at the next edge ("Collisions").
//
// The contract, per clock edge (after an edge in reset: count, error, dir,
// index_seen, index_count and timestamp 0):
// * clear: a clear edge leaves count 0;
// * count: at any other edge the count moves by the step that reached it
//   (+1, -1 or 0) plus a step carried over a clear at the edge before: so
//   each legal transition counts once in its direction, 5 edges after the
//   pin change is first sampled (sample_rate 0), a double change counts
//   nothing, and no count is lost to a clear;
// * at most one per sample: at an edge with no clear and no step carried
//   from a clear at the edge before, the count moves by -1, 0 or +1 (and,
//   by the count item, only at the edge 2 after a sample edge);
// * error: set by a double change reaching the count stage, else kept
//   unless `clear` or `clear_error` (a new error wins over a clear);
// * dir: 1 after an up step, 0 after a down step, else kept;
// * index: an index event reaching the count stage is acted on when
//   `index_once` is 0, `index_seen` is 0 or `index_rearm` is 1; it sets
//   index_seen (which index_rearm clears otherwise) and, with
//   `index_latch`, latches the count before the edge into index_count;
// * timestamp: +1 at each sample edge.

localparam F_W = $bits(count);
localparam F_S = $bits(sample_rate);
localparam F_TS = $bits(timestamp);

// ---------------------------------------------------------------------
// Environment.
reg f_past = 1'b0;
reg f_counter_mode = 1'b0;
reg f_index_invert = 1'b0;
always @(posedge clock) begin
    f_past <= 1'b1;
    f_counter_mode <= counter_mode;
    f_index_invert <= index_invert;
end
always @(*) begin
    assume(filter <= 4'd1);
    if (f_past) begin
        assume(counter_mode == f_counter_mode);
        assume(index_invert == f_index_invert);
    end
end

// ---------------------------------------------------------------------
// The pins through the stages. Each register is what the last edge left
// in that stage; power-up is the reset state.

// Stages 1 and 2: the pins as the last edge and the one before saw them.
reg f_a1 = 1'b0, f_b1 = 1'b0, f_i1 = 1'b0;
reg f_a2 = 1'b0, f_b2 = 1'b0, f_i2 = 1'b0;
// Start-up edges left; edges left before the next sample.
reg [1:0] f_startup = 2'd3;
reg [F_S-1:0] f_wait = {F_S{1'b0}};
wire f_priming = f_startup != 2'd0;      // the next edge loads the levels
wire f_sample = f_wait == {F_S{1'b0}};   // the next edge is a sample
// Stage 3: the filtered levels, and whether the last edge accepted a change.
reg f_la = 1'b0, f_lb = 1'b0, f_li = 1'b0;
reg f_ca = 1'b0, f_cb = 1'b0, f_ci = 1'b0;
// Stage 4: the decoded step (up, down), double change and index event.
reg f_up = 1'b0, f_dn = 1'b0, f_dbl = 1'b0, f_ie = 1'b0;
// Stage 5: a step carried over a clear at the last edge.
reg f_cu = 1'b0, f_cd = 1'b0;

// The decode of the last accepted changes (the next edge registers it).
wire f_a0 = f_la ^ f_ca;                 // the levels before the change
wire f_b0 = f_lb ^ f_cb;
// (Comparisons, not a `case`: yosys turns a case of constants into a ROM,
// whose contents the induction does not constrain.)
wire [3:0] f_move = {f_a0, f_b0, f_la, f_lb};
wire f_forward = f_move == 4'b00_10 || f_move == 4'b10_11 || f_move == 4'b11_01 || f_move == 4'b01_00;
wire f_reverse = f_move == 4'b00_01 || f_move == 4'b01_11 || f_move == 4'b11_10 || f_move == 4'b10_00;
wire f_rise = f_ca && f_la;               // counter mode: a rose
wire f_up_d = counter_mode ? f_rise && f_lb : f_forward;
wire f_dn_d = counter_mode ? f_rise && !f_lb : f_reverse;
wire f_dbl_d = counter_mode ? f_rise && f_cb : f_ca && f_cb;
wire f_ie_d = f_ci && (f_li != index_invert);

// The count stage at the next edge.
wire f_index_act = f_ie && (!index_once || !index_seen || index_rearm);
wire f_clear_now = clear || (f_index_act && index_clear);
wire [F_W-1:0] f_step = f_up ? {{(F_W-1){1'b0}}, 1'b1} : f_dn ? {F_W{1'b1}} : {F_W{1'b0}};
wire [F_W-1:0] f_carry = f_cu ? {{(F_W-1){1'b0}}, 1'b1} : f_cd ? {F_W{1'b1}} : {F_W{1'b0}};

always @(posedge clock) begin
    if (reset) begin
        {f_a1, f_b1, f_i1, f_a2, f_b2, f_i2} <= 6'b0;
        f_startup <= 2'd3;
        f_wait <= {F_S{1'b0}};
        {f_la, f_lb, f_li, f_ca, f_cb, f_ci} <= 6'b0;
        {f_up, f_dn, f_dbl, f_ie} <= 4'b0;
        {f_cu, f_cd} <= 2'b0;
    end else begin
        {f_a1, f_b1, f_i1} <= {a, b, index};
        {f_a2, f_b2, f_i2} <= {f_a1, f_b1, f_i1};
        if (f_priming)
            f_startup <= f_startup - 1'b1;
        f_wait <= f_sample ? sample_rate : f_wait - 1'b1;
        {f_ca, f_cb, f_ci} <= 3'b0;
        if (f_priming) begin
            {f_la, f_lb, f_li} <= {f_a2, f_b2, f_i2};
        end else if (f_sample) begin
            {f_la, f_lb, f_li} <= {f_a2, f_b2, f_i2};
            {f_ca, f_cb, f_ci} <= {f_a2 != f_la, f_b2 != f_lb, f_i2 != f_li};
        end
        {f_up, f_dn, f_dbl, f_ie} <= {f_up_d, f_dn_d, f_dbl_d, f_ie_d};
        {f_cu, f_cd} <= {f_clear_now && f_up, f_clear_now && f_dn};
    end
end

// ---------------------------------------------------------------------
// What the last edge saw at the count stage, and the outputs before it.
reg f_edge_reset = 1'b0;
reg f_edge_clear_now = 1'b0;
reg f_edge_carried = 1'b0;
reg [F_W-1:0] f_edge_move = {F_W{1'b0}};   // step + carry
reg f_edge_up = 1'b0, f_edge_dn = 1'b0, f_edge_dbl = 1'b0;
reg f_edge_error_kept = 1'b0;
reg f_edge_act = 1'b0, f_edge_latch = 1'b0, f_edge_rearm = 1'b0;
reg f_edge_sample = 1'b0;
reg [F_W-1:0] f_edge_count = {F_W{1'b0}};
reg [F_W-1:0] f_edge_index_count = {F_W{1'b0}};
reg f_edge_error = 1'b0, f_edge_dir = 1'b0, f_edge_index_seen = 1'b0;
reg [F_TS-1:0] f_edge_timestamp = {F_TS{1'b0}};
always @(posedge clock) begin
    f_edge_reset <= reset;
    f_edge_clear_now <= f_clear_now;
    f_edge_carried <= f_cu || f_cd;
    f_edge_move <= f_step + f_carry;
    {f_edge_up, f_edge_dn, f_edge_dbl} <= {f_up, f_dn, f_dbl};
    f_edge_error_kept <= !clear && !clear_error;
    {f_edge_act, f_edge_latch, f_edge_rearm} <= {f_index_act, index_latch, index_rearm};
    f_edge_sample <= f_sample;
    f_edge_count <= count;
    f_edge_index_count <= index_count;
    {f_edge_error, f_edge_dir, f_edge_index_seen} <= {error, dir, index_seen};
    f_edge_timestamp <= timestamp;
end

wire [F_W-1:0] f_moved = count - f_edge_count;

always @(*) begin
    if (f_edge_reset) begin
        assert(count == {F_W{1'b0}});
        assert(!error);
        assert(!dir);
        assert(!index_seen);
        assert(index_count == {F_W{1'b0}});
        assert(timestamp == {F_TS{1'b0}});
    end else begin
        // Clear: the count becomes 0 (the step that came with it is carried).
        if (f_edge_clear_now)
            assert(count == {F_W{1'b0}});
        // Count: each legal transition once, in its direction, 5 edges after
        // the pins; a double change nothing; plus the step carried over a
        // clear at the edge before.
        else
            assert(count == f_edge_count + f_edge_move);
        // At most one per sample (a carry over a clear aside).
        if (!f_edge_clear_now && !f_edge_carried)
            assert(f_moved == {F_W{1'b0}} || f_moved == {{(F_W-1){1'b0}}, 1'b1} || f_moved == {F_W{1'b1}});
        // Error: a double change sets it, a clear or clear_error on another
        // edge clears it.
        if (f_edge_dbl)
            assert(error);
        else
            assert(error == (f_edge_error && f_edge_error_kept));
        // Dir: the direction of the last step.
        assert(dir == (f_edge_up || (f_edge_dir && !f_edge_dn)));
        // Index: an acted-on event sets index_seen and latches the count
        // before the edge.
        assert(index_seen == ((f_edge_index_seen && !f_edge_rearm) || f_edge_act));
        assert(index_count == ((f_edge_act && f_edge_latch) ? f_edge_count : f_edge_index_count));
        // Timestamp: +1 per sample.
        assert(timestamp == f_edge_timestamp + f_edge_sample);
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the model's stages.
// The filters' run counters are inside the GlitchFilter submodules, out of
// reach of this file (yosys 0.23 reads no hierarchical references; a
// `hierconn` wire, as in narrow_bus_adapter.sv, would reach them and let
// the exported S = 8 close: not done yet). With
// `filter` <= 1 a filter reloads its counter with 0 or 1 at every sample
// that accepts or sees no change, and a stale counter would refuse a change
// at a sample, breaking the filtered-level invariant at the next edge: so
// an induction window longer than the longest sample interval (2^S clocks:
// 4 for S = 2, depth 5) starts only from states where the counters are
// harmless.
always @(*) begin
    assert({a_meta__q, b_meta__q, index_meta__q} == {f_a1, f_b1, f_i1});
    assert({a_sync__q, b_sync__q, index_sync__q} == {f_a2, f_b2, f_i2});
    assert(startup__q == 2'd3 - f_startup);
    assert(sample_left__q == f_wait);
    assert(sample_wait__q == !f_sample);
    assert({filter_a__filtered, filter_b__filtered, filter_index__filtered} == {f_la, f_lb, f_li});
    assert({filter_a__changed, filter_b__changed, filter_index__changed} == {f_ca, f_cb, f_ci});
    assert({up__q, down__q, double__q, index_event__q} == {f_up, f_dn, f_dbl, f_ie});
    // The registered change: the decoded step plus the one carried.
    assert(delta__q == f_step + f_carry);
    // The model's own invariants: one direction at a time.
    assert(!(f_up && f_dn));
    assert(!(f_cu && f_cd));
end
`endif
