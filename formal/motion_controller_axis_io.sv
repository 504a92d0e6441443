// motion_controller, one axis's machine I/O (AxisIo): the limit gate, as
// the datasheet states it (src/blocks/motion_controller/mod.rs, "Machine
// I/O and safety": "Limits"; the register map's IO_CONFIG and IO_COMMAND).
//
// The controller is too large to prove whole; the limit rule is decided in
// three places, each proved on its own block (see the datasheet's "Formal
// proof"): this block decides which direction is blocked and which steps
// are cut, the axis (formal/motion_controller_axis.sv) keeps blocked steps
// out of its output stage and flushes the stage on a cut, and the stage
// (formal/step_output.sv) never moves a pin once flushed.
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers.
//
// Environment: none assumed. Every input is free at every clock, reset
// included: the filtered limit levels, the bus (already decoded by the
// axis into `selected` and the I/O half's word `offset`), and the three
// places of the step path the axis shows this block (the step offered to
// its request register, `pulse`; the registered request the stage takes,
// `request`; the stage's pending direction, `pending_*`), in any
// combination, including ones the axis never makes.
//
// The contract, per clock:
// * IO_CONFIG.LIMIT_ENABLE (bit 0 of offset 0) reads 1 from power-up and
//   after reset, and what was last written otherwise; a direction is
//   blocked exactly when its limit level is active and LIMIT_ENABLE is 1
//   (`block_forward` / `block_backward`);
// * `cut` is high exactly when a step toward a blocked direction is
//   offered, requested or pending ("cut in the clock it is seen"; "a limit
//   that closes while its axis moves away, or stands still, cuts nothing");
// * a cut sets that direction's sticky trip flag at its edge (a trip on
//   the clock of an IO_COMMAND.CLEAR_LIMITS wins, reset clears it), and
//   `limit_held` (the flag the controller aborts every axis on) is the OR of
//   the two flags; `limit_event` is high when a cut finds its flag clear.

localparam [3:0] F_OFF_IO_CONFIG = 4'h0;   // axis::IO_CONFIG - axis::IO_CONFIG
localparam [3:0] F_OFF_IO_COMMAND = 4'h2;  // axis::IO_COMMAND - axis::IO_CONFIG

// IO_CONFIG.LIMIT_ENABLE as a read returns it.
reg f_limit_enable = 1'b1;
always @(posedge clock) begin
    if (reset)
        f_limit_enable <= 1'b1;
    else if (write && selected && offset == F_OFF_IO_CONFIG)
        f_limit_enable <= write_data[0];
end

// The blocked directions, and a step toward one at any of the three places.
wire f_block_forward = limit_forward && f_limit_enable;
wire f_block_backward = limit_backward && f_limit_enable;
wire f_cut_forward = f_block_forward
    && (pending_forward || (request && request_forward) || (pulse && pulse_forward));
wire f_cut_backward = f_block_backward
    && (pending_backward || (request && !request_forward) || (pulse && !pulse_forward));

// The sticky trip flags (IO_STATUS.LIMIT_POS_TRIPPED / LIMIT_NEG_TRIPPED).
wire f_clear_limits = write && selected && offset == F_OFF_IO_COMMAND && write_data[0];
reg f_tripped_forward = 1'b0;
reg f_tripped_backward = 1'b0;
always @(posedge clock) begin
    if (reset) begin
        f_tripped_forward <= 1'b0;
        f_tripped_backward <= 1'b0;
    end else begin
        f_tripped_forward <= f_cut_forward || (f_tripped_forward && !f_clear_limits);
        f_tripped_backward <= f_cut_backward || (f_tripped_backward && !f_clear_limits);
    end
end

always @(*) begin
    assert(block_forward == f_block_forward);
    assert(block_backward == f_block_backward);
    assert(cut == (f_cut_forward || f_cut_backward));
    assert(limit_held == (f_tripped_forward || f_tripped_backward));
    assert(limit_event == ((f_cut_forward && !f_tripped_forward) || (f_cut_backward && !f_tripped_backward)));
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the block's registers against the summary.
// IO_CONFIG is stored XOR its reset value (LIMIT_ENABLE's reset value is 1).
always @(*) begin
    assert(io_config_x__q[0] == !f_limit_enable);
    assert(limit_forward_tripped__q == f_tripped_forward);
    assert(limit_backward_tripped__q == f_tripped_backward);
end
`endif
