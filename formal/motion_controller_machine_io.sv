// motion_controller, the machine I/O (MachineIo): the E-stop input, from
// its pin through its conditioning to the latch that aborts every axis, as
// the datasheet states it (src/blocks/motion_controller/mod.rs, "Machine
// I/O and safety": "Inputs" and "E-stop"; `latency::switch`).
//
// The controller is too large to prove whole; this is the first half of
// the E-stop's pin-to-step bound (see the datasheet's "Formal proof"): the
// controller registers `estop_latched` once more (abort_hold) and the axes
// are proved to make no step from the clock after their `abort`
// (formal/motion_controller_axis.sv).
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the block's registers.
//
// Environment: none assumed. Every input is free at every clock: reset,
// every pin, the bus (INPUT_FILTER may be written any value at any time),
// `estop_clear` (the decoded STATUS.ESTOP write) and the watchdog.
//
// The contract, per clock edge:
// * The latch: `estop_latched` is set at an edge whose clock had the
//   filtered E-stop level (`estop_active`) high, and then stays set until
//   an edge with `estop_clear` high and the filtered level low; reset clears
//   it. `estop_latched_next` is the latch after the next edge, and
//   `estop_event` is high in a clock whose level sets a clear latch.
// * The conditioning ("A level held from clock c is acted on from c +
//   latency::switch"): with INPUT_FILTER at its reset value (LENGTH 4,
//   SAMPLE_RATE 0: nothing else written since the last reset or power-up),
//   an E-stop pin held high in clocks c to c + 5 (no reset among them) makes
//   `estop_active` high after the edge of clock c + latency::switch(4, 0) =
//   c + 5, so the latch is set after the edge of clock c + 6. Other
//   INPUT_FILTER settings are not proved (see the datasheet).

localparam [7:0] F_A_INPUT_FILTER = 8'h0e;     // global::INPUT_FILTER
localparam [31:0] F_FILTER_MASK = 32'h0000ff0f;  // LENGTH 3..0, SAMPLE_RATE 15..8
localparam [31:0] F_FILTER_RESET = 32'h00000004; // LENGTH 4, SAMPLE_RATE 0
// latency::switch(4, 0): the tests check this against the Rust constant.
localparam F_SWITCH = 5;

// What the last clock edge saw.
reg f_reset_1 = 1'b0;
reg f_active_1 = 1'b0;
reg f_latched_1 = 1'b0;
reg f_clear_1 = 1'b0;
always @(posedge clock) begin
    f_reset_1 <= reset;
    f_active_1 <= estop_active;
    f_latched_1 <= estop_latched;
    f_clear_1 <= estop_clear;
end

// INPUT_FILTER has held its reset value since the last reset or power-up.
reg f_filter_default = 1'b1;
always @(posedge clock) begin
    if (reset)
        f_filter_default <= 1'b1;
    else if (write && address == F_A_INPUT_FILTER
             && (write_data & F_FILTER_MASK) != F_FILTER_RESET)
        f_filter_default <= 1'b0;
end

// Consecutive edges, up to the last one, with the E-stop pin high and no
// reset (saturating at F_SWITCH + 2).
reg [3:0] f_estop_run = 4'd0;
always @(posedge clock) begin
    if (!estop || reset)
        f_estop_run <= 4'd0;
    else if (f_estop_run != F_SWITCH + 2)
        f_estop_run <= f_estop_run + 4'd1;
end

always @(*) begin
    // The latch.
    assert(estop_latched == (!f_reset_1 && (f_active_1 || (f_latched_1 && !f_clear_1))));
    assert(estop_latched_next == (!reset && (estop_active || (estop_latched && !estop_clear))));
    assert(estop_event == (estop_active && !estop_latched));
    // The conditioning's latency, at the reset filter setting.
    if (f_filter_default && f_estop_run >= F_SWITCH + 1)
        assert(estop_active);
    if (f_filter_default && f_estop_run >= F_SWITCH + 2)
        assert(estop_latched);
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: INPUT_FILTER stored XOR its reset value, and the
// sample counter at the reset setting (a sample every clock). The
// conditioner's own registers are not visible here (a sub-block): the
// induction depth covers them (its filter reloads LENGTH at the last
// sample of the old level).
always @(*) begin
    if (f_filter_default) begin
        assert((filter_x__q & F_FILTER_MASK) == 32'd0);
        assert(sample_count__q == 8'd0);
    end
    assert(f_estop_run <= F_SWITCH + 2);
end
`endif
