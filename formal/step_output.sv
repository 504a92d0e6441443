// step_output: the pins' timing and the step count, as the datasheet
// states them (src/blocks/step_output/mod.rs, "Ports", "Timing", "Bad
// input" and "Flush").
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers. The one
// exception is the width P of the pending count, which no port carries:
// it is read as `$bits(pending__q)` (the instance's parameter, not its
// state).
//
// Environment: none assumed. Every input is free at every clock: reset,
// step and dir, mode (taken only when the datasheet says), the four timing
// settings (any value, changing at any clock), clear_overrun and flush.
//
// Edges. Each clock edge is one of: a reset; a mode take (the first clock
// after power-up, or `mode`, with 3 read as 0, differing from the active
// mode while `busy` was low: "Bad input"); the start clock that follows
// either; or an ordinary edge. Steps are read from the pins on ordinary
// edges: mode 0 a rise of out_a (forward if out_b is high), mode 1 a rise
// of out_a (forward) or out_b (backward), mode 2 a Gray move of
// (out_a, out_b), 00 -> 10 -> 11 -> 01 -> 00 forward.
//
// The contract, per clock edge:
// * Count ("Bad input", "Flush"): a request is accepted unless it is
//   forward with the count at 2^(P-1) - 1 or backward at -2^(P-1); the
//   pending count is accepted requests minus pin steps since the last
//   reset or flush (both empty it; a flush drops its clock's request).
//   Every pin step goes the way of the count's sign before it (none with
//   nothing pending), and pending_forward / pending_backward are the
//   count's sign: no step is lost or invented. `overrun` is set by a
//   dropped request, cleared by clear_overrun (unless a request is dropped
//   in the same clock) and by reset. `emitted` / `emitted_forward` report
//   the pin step of the last edge.
// * After a reset or a mode take, the outputs are low, and the start clock
//   keeps them low ("Timing": it only loads the timers).
// * Mode 0: out_a stays high exactly max(step_len, 1) clocks (step_len as
//   sampled at the rise); it rises at least max(step_space, 1) clocks
//   after the last fall (step_space at the fall) or after the start clock
//   (step_space there); at least max(dir_setup, 1) clocks after out_b last
//   turned or after the start clock (dir_setup there), and not at an edge
//   that turns out_b; out_b never turns while out_a is high, at its fall,
//   or less than max(dir_hold, 1) clocks after the fall (dir_hold there).
// * Mode 1: the same length and space on out_a | out_b; never both high;
//   a pulse keeps its output.
// * Mode 2: every move is one Gray step, and a state lasts at least
//   max(step_len, 1) clocks (step_len at the move into it, or at the start
//   clock).
// * A mode take is an edge like any other for these timing rules: it never
//   cuts a pulse, a quadrature state or a direction hold short. A reset
//   is not: it sets the outputs low at once ("Ports": reset), and the
//   rules start again from its start clock.
// * `busy` is high while steps are pending, a pulse (mode 0/1) is high, or
//   an interval above is still running (the direction ones in mode 0).
// * mode_invalid is `mode == 3`.

localparam F_T = $bits(step_len);
localparam F_P = $bits(pending__q);
localparam [F_P-1:0] F_MAX = {1'b0, {(F_P-1){1'b1}}};
localparam [F_P-1:0] F_MIN = {1'b1, {(F_P-1){1'b0}}};

// Clocks a setting v makes an interval last after the edge that starts
// it, beyond the first: max(v, 1) - 1. Also one clock off such a count.
function [F_T-1:0] f_dec(input [F_T-1:0] v);
    f_dec = (v == {F_T{1'b0}}) ? {F_T{1'b0}} : v - 1'b1;
endfunction

// What the last clock edge saw: its inputs, registered here, and the pins
// and `busy` before it. f_past_valid: there was a last edge.
reg f_past_valid = 1'b0;
reg f_edge_reset = 1'b0;
reg f_edge_step = 1'b0;
reg f_edge_dir = 1'b0;
reg [1:0] f_edge_mode = 2'd0;
reg [F_T-1:0] f_edge_len = {F_T{1'b0}};
reg [F_T-1:0] f_edge_space = {F_T{1'b0}};
reg [F_T-1:0] f_edge_setup = {F_T{1'b0}};
reg [F_T-1:0] f_edge_hold = {F_T{1'b0}};
reg f_edge_clear = 1'b0;
reg f_edge_flush = 1'b0;
reg f_edge_busy = 1'b0;
reg f_was_a = 1'b0;
reg f_was_b = 1'b0;
always @(posedge clock) begin
    f_past_valid <= 1'b1;
    f_edge_reset <= reset;
    f_edge_step <= step;
    f_edge_dir <= dir;
    f_edge_mode <= mode;
    f_edge_len <= step_len;
    f_edge_space <= step_space;
    f_edge_setup <= dir_setup;
    f_edge_hold <= dir_hold;
    f_edge_clear <= clear_overrun;
    f_edge_flush <= flush;
    f_edge_busy <= busy;
    f_was_a <= out_a;
    f_was_b <= out_b;
end

// The summary of the edges before the last one (`f_*`), and with it
// (`f_*_now`): the active mode and whether one was taken, whether the next
// edge is a start clock, the pending count, the overrun flag, and the
// clocks each interval still forbids its event (f_hi: the pulse must stay
// high; f_gap: no rise (mode 0/1) or move (mode 2); f_su: no rise, mode 0
// setup; f_ho: out_b must not turn, mode 0 hold). f_su and f_ho also run
// in modes 1 and 2 (a setup from the start clock, a hold from each fall),
// where no rule reads them: only the invariants do.
reg [1:0] f_mode = 2'd0;
reg f_mode_taken = 1'b0;
reg f_start = 1'b0;
reg [F_P-1:0] f_pending = {F_P{1'b0}};
reg f_overrun = 1'b0;
reg [F_T-1:0] f_hi = {F_T{1'b0}};
reg [F_T-1:0] f_gap = {F_T{1'b0}};
reg [F_T-1:0] f_su = {F_T{1'b0}};
reg [F_T-1:0] f_ho = {F_T{1'b0}};

// The kind of the last edge.
wire [1:0] f_req_mode = (f_edge_mode == 2'd3) ? 2'd0 : f_edge_mode;
wire f_take = f_past_valid && !f_edge_reset
    && (!f_mode_taken || (!f_edge_busy && f_req_mode != f_mode));
wire f_restart = f_past_valid && (f_edge_reset || f_take);
wire f_start_edge = f_past_valid && !f_restart && f_start;
wire f_normal = f_past_valid && !f_restart && !f_start;

// The pins across the last edge, read in the mode before it.
wire f_pulse_mode = f_mode != 2'd2;
wire f_x_was = (f_mode == 2'd1) ? (f_was_a || f_was_b) : f_was_a;
wire f_x = (f_mode == 2'd1) ? (out_a || out_b) : out_a;
wire f_rise = f_pulse_mode && !f_x_was && f_x;
wire f_fall = f_pulse_mode && f_x_was && !f_x;
wire f_b_turn = f_mode == 2'd0 && out_b != f_was_b;
wire f_move = f_mode == 2'd2 && (out_a != f_was_a || out_b != f_was_b);
wire f_gray_fwd = out_a == !f_was_b && out_b == f_was_a;
wire f_gray_bwd = out_a == f_was_b && out_b == !f_was_a;
// The pin step of the last edge, if any.
wire f_step_fwd = f_normal && (f_mode == 2'd2 ? f_gray_fwd
    : f_mode == 2'd1 ? f_rise && out_a : f_rise && out_b);
wire f_step_bwd = f_normal && (f_mode == 2'd2 ? f_gray_bwd
    : f_mode == 2'd1 ? f_rise && out_b && !out_a : f_rise && !out_b);

// The requests of the last edge.
wire f_acc_fwd = f_edge_step && f_edge_dir && f_pending != F_MAX;
wire f_acc_bwd = f_edge_step && !f_edge_dir && f_pending != F_MIN;
wire f_drop = f_edge_step && !f_acc_fwd && !f_acc_bwd;

wire f_pending_pos = !f_pending[F_P-1] && f_pending != {F_P{1'b0}};
wire f_pending_neg = f_pending[F_P-1];

reg [1:0] f_mode_now;
reg f_mode_taken_now;
reg f_start_now;
reg [F_P-1:0] f_pending_now;
reg f_overrun_now;
reg [F_T-1:0] f_hi_now;
reg [F_T-1:0] f_gap_now;
reg [F_T-1:0] f_su_now;
reg [F_T-1:0] f_ho_now;
always @(*) begin
    f_mode_now = f_mode;
    f_mode_taken_now = f_mode_taken;
    f_start_now = f_start;
    f_pending_now = f_pending;
    f_overrun_now = f_overrun;
    f_hi_now = f_hi;
    f_gap_now = f_gap;
    f_su_now = f_su;
    f_ho_now = f_ho;
    if (f_past_valid) begin
        f_mode_taken_now = 1'b1;
        f_start_now = f_restart;
        if (f_restart)
            f_mode_now = f_req_mode;
        if (f_edge_reset || f_edge_flush)
            f_pending_now = {F_P{1'b0}};
        else
            f_pending_now = f_pending + f_acc_fwd - f_acc_bwd - f_step_fwd + f_step_bwd;
        if (f_edge_reset)
            f_overrun_now = 1'b0;
        else if (f_drop)
            f_overrun_now = 1'b1;
        else if (f_edge_clear)
            f_overrun_now = 1'b0;
        f_hi_now = f_dec(f_hi);
        f_gap_now = f_dec(f_gap);
        f_su_now = f_dec(f_su);
        f_ho_now = f_dec(f_ho);
        if (f_restart) begin
            f_hi_now = {F_T{1'b0}};
            f_gap_now = {F_T{1'b0}};
            f_su_now = {F_T{1'b0}};
            f_ho_now = {F_T{1'b0}};
        end else if (f_start_edge) begin
            // As if a pulse had just ended (quadrature: a state had just
            // begun) and out_b had just turned.
            f_gap_now = f_dec(f_mode == 2'd2 ? f_edge_len : f_edge_space);
            f_su_now = f_dec(f_edge_setup);
        end else begin
            if (f_rise)
                f_hi_now = f_dec(f_edge_len);
            if (f_fall) begin
                // The hold follows; in mode 0 no setup runs at a fall (the
                // rise needed it over), in mode 1 none applies.
                f_gap_now = f_dec(f_edge_space);
                f_su_now = {F_T{1'b0}};
                f_ho_now = f_dec(f_edge_hold);
            end
            if (f_b_turn)
                f_su_now = f_dec(f_edge_setup);
            if (f_move)
                f_gap_now = f_dec(f_edge_len);
        end
    end
end
always @(posedge clock) begin
    f_mode <= f_mode_now;
    f_mode_taken <= f_mode_taken_now;
    f_start <= f_start_now;
    f_pending <= f_pending_now;
    f_overrun <= f_overrun_now;
    f_hi <= f_hi_now;
    f_gap <= f_gap_now;
    f_su <= f_su_now;
    f_ho <= f_ho_now;
end

wire f_x_now = (f_mode_now == 2'd1) ? (out_a || out_b) : out_a;

// Each assertion is one line: yosys names a failed one by a source range,
// which runs from the end of the statement before (the `if` on the same
// line, where there is one) to the assertion's own line.
always @(*) begin
    assert(mode_invalid == (mode == 2'd3));

    // The step count: no step lost or invented. Every pin step goes the
    // way of the pending count's sign, and the flags are that sign.
    if (f_step_fwd) assert(f_pending_pos);
    if (f_step_bwd) assert(f_pending_neg);
    assert(pending_forward == (!f_pending_now[F_P-1] && f_pending_now != {F_P{1'b0}}));
    assert(pending_backward == f_pending_now[F_P-1]);
    assert(emitted == (f_step_fwd || f_step_bwd));
    if (emitted) assert(emitted_forward == f_step_fwd);
    assert(overrun == f_overrun_now);

    // Reset, mode take, start clock: outputs low.
    if (f_restart || f_start_edge) assert(!out_a && !out_b);

    // Timing, at every edge but a reset (mode takes included).
    // A pulse lasts exactly its step_len.
    if (f_past_valid && !f_edge_reset && f_pulse_mode && f_x_was) assert(f_x == (f_hi != {F_T{1'b0}}));
    // Space (mode 0/1), state length (mode 2).
    if (f_past_valid && !f_edge_reset && (f_rise || f_move)) assert(f_gap == {F_T{1'b0}});
    // Direction setup before a rise, and no turn at the rise.
    if (f_past_valid && !f_edge_reset && f_mode == 2'd0 && f_rise) assert(f_su == {F_T{1'b0}} && !f_b_turn);
    // Direction hold: no turn while high, at the fall, or within dir_hold
    // after it.
    if (f_past_valid && !f_edge_reset && f_b_turn) assert(!f_was_a && f_ho == {F_T{1'b0}});

    // Mode 1: never both high, and a pulse keeps its output.
    if (f_mode_taken_now && f_mode_now == 2'd1) assert(!(out_a && out_b));
    if (f_normal && f_mode == 2'd1 && f_x_was && f_x) assert(out_a == f_was_a && out_b == f_was_b);
    // Mode 2: every move is one Gray step.
    if (f_normal && f_move) assert(f_gray_fwd || f_gray_bwd);

    // busy covers everything a mode change must not cut.
    if (f_pending_now != {F_P{1'b0}} || (f_mode_now != 2'd2 && f_x_now)
            || f_hi_now != {F_T{1'b0}} || f_gap_now != {F_T{1'b0}}
            || (f_mode_now == 2'd0 && (f_su_now != {F_T{1'b0}} || f_ho_now != {F_T{1'b0}}))) assert(busy);
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the summary.
always @(*) begin
    assert(f_mode != 2'd3);
    assert(pending__q == f_pending_now);
    assert(nonzero__q == (f_pending_now != {F_P{1'b0}}));
    assert(at_max__q == (f_pending_now == F_MAX));
    assert(at_min__q == (f_pending_now == F_MIN));
    assert(overrun_reg__q == f_overrun_now);
    assert(active_mode__q == f_mode_now);
    assert(mode_taken__q == f_mode_taken_now);
    if (!f_mode_taken_now) begin
        // Power-up: nothing has happened.
        assert(!f_past_valid);
        assert(!a_reg__q && !b_reg__q && !high__q && !started__q);
        assert(!phase_done__q && !dir_done__q && !timing_setup__q && !setup_wait__q);
        assert(!emitted_reg__q);
        assert(f_hi_now == 0 && f_gap_now == 0 && f_su_now == 0 && f_ho_now == 0);
    end else if (f_start_now) begin
        assert(!started__q);
        assert(!a_reg__q && !b_reg__q && !high__q);
        assert(!phase_done__q && !dir_done__q && !timing_setup__q && !setup_wait__q);
        assert(f_hi_now == 0 && f_gap_now == 0 && f_su_now == 0 && f_ho_now == 0);
    end else begin
        assert(started__q);
        if (f_mode_now == 2'd2)
            assert(!high__q);
        else
            assert(high__q == f_x_now);
        if (f_mode_now == 2'd1)
            assert(!(a_reg__q && b_reg__q));
        // The level's counter.
        if (high__q) begin
            assert(f_gap_now == 0);
            assert(phase_done__q == (f_hi_now == 0));
            if (!phase_done__q)
                assert(phase_count__q == f_hi_now + 1'b1);
        end else begin
            assert(f_hi_now == 0);
            assert(phase_done__q == (f_gap_now == 0));
            if (!phase_done__q)
                assert(phase_count__q == f_gap_now + 1'b1);
        end
        // The direction counter.
        if (timing_setup__q) begin
            assert(f_ho_now == 0);
            assert(dir_done__q == (f_su_now == 0));
            if (!dir_done__q)
                assert(dir_count__q == f_su_now + 1'b1);
        end else begin
            assert(f_su_now == 0);
            assert(dir_done__q == (f_ho_now == 0));
            if (!dir_done__q)
                assert(dir_count__q == f_ho_now + 1'b1);
        end
        assert(setup_wait__q == (timing_setup__q && !dir_done__q));
    end
end
`endif
