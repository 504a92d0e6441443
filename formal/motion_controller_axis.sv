// motion_controller, one axis (MotionAxis): the step path's side of the
// abort and the limit cut, as the datasheet states them
// (src/blocks/motion_controller/mod.rs, "Machine I/O and safety": "Abort"
// and "Limits"; the axis is src/blocks/motion_controller/axis.rs).
//
// The controller is too large to prove whole; the axis is proved with the
// rest of the controller abstracted: every input of the axis is free,
// `abort` and the filtered limit levels included. Inside the axis, the
// limit gate (AxisIo, formal/motion_controller_axis_io.sv) and the output
// stage (StepOutput, formal/step_output.sv) are proved on their own; this
// file proves how the axis connects them: which requests it lets into the
// stage, when it flushes the stage, that after an abort the pins make no
// step, and that the stage makes no step toward a direction blocked in the
// clock before it decided it. That last rule takes, in its induction only,
// a premise on the stage's ports that formal/motion_controller_stage.sv
// proves on the same stage (assume-guarantee, see INDUCTION_INVARIANTS).
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs). The axis is internal to the controller, so its
// contract names the ports of its sub-blocks as well as its own: the
// stage's request (`stage__step`, `stage__dir`), flush, pending direction
// and step report (`stage__emitted`, `stage__emitted_forward`), the limit
// gate's blocked directions (`io__block_*`), and the step the interpolator
// offers to the request register (`candidate`, `candidate_forward`). The
// INDUCTION_INVARIANTS section names the axis's registers.
//
// Environment: none assumed. Every input is free at every clock: reset,
// abort, halt, the period controls, the bus, the limit, alarm and home
// levels, the encoder.
//
// The contract, per clock:
// * "No new step enters [an output stage]" after an abort, and none toward
//   a blocked direction: a request the stage takes in this clock was made
//   in the last clock, with `abort` low and its direction not blocked then.
// * The stage is flushed exactly when `abort` is high or a step toward a
//   blocked direction is pending in the stage, in the request register
//   (the stage's request) or offered by the interpolator ("cut in the
//   clock it is seen"; nothing is flushed for a limit that closes while the
//   axis moves away or stands still).
// * After a clock with `abort` high, no pin moves for a step at the next
//   edge: neither out_a nor out_b rises, and the stage reports no step
//   (`emitted` low after it). A pulse already high may still fall (it keeps
//   its full length); with `abort` held high, no step ever leaves.
// * A step the stage reports (`stage__emitted`, the step whose first pin
//   edge came at the last edge; `stage__emitted_forward` its direction) is
//   not toward a direction that was blocked in the clock before the one
//   that decided it: the limit cut's latency at the step path, one clock
//   (latency::LIMIT_OWN_AXIS).

// What the last two clock edges saw.
reg f_abort_1 = 1'b0;
reg f_abort_2 = 1'b0;
reg f_block_forward_1 = 1'b0;
reg f_block_backward_1 = 1'b0;
reg f_block_forward_2 = 1'b0;
reg f_block_backward_2 = 1'b0;
reg f_out_a_1 = 1'b0;
reg f_out_b_1 = 1'b0;
always @(posedge clock) begin
    f_abort_1 <= abort;
    f_abort_2 <= f_abort_1;
    f_block_forward_1 <= io__block_forward;
    f_block_backward_1 <= io__block_backward;
    f_block_forward_2 <= f_block_forward_1;
    f_block_backward_2 <= f_block_backward_1;
    f_out_a_1 <= out_a;
    f_out_b_1 <= out_b;
end

// A step toward a blocked direction, at each place of the step path.
wire f_toward_block_pending = (io__block_forward && stage__pending_forward)
    || (io__block_backward && stage__pending_backward);
wire f_toward_block_request = stage__step
    && (stage__dir ? io__block_forward : io__block_backward);
wire f_toward_block_offered = candidate
    && (candidate_forward ? io__block_forward : io__block_backward);

always @(*) begin
    // Requests: none after an abort clock, none toward a direction blocked
    // in the clock that made it.
    if (stage__step) begin
        assert(!f_abort_1);
        assert(!(stage__dir ? f_block_forward_1 : f_block_backward_1));
    end
    // Flush.
    assert(stage__flush == (abort || f_toward_block_pending
        || f_toward_block_request || f_toward_block_offered));
    // Pins, the clock after an abort clock.
    if (f_abort_2) begin
        assert(!(out_a && !f_out_a_1));
        assert(!(out_b && !f_out_b_1));
        assert(!stage__emitted);
    end
    // Steps leaving toward a blocked direction.
    if (stage__emitted)
        assert(!(stage__emitted_forward ? f_block_forward_2 : f_block_backward_2));
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: in a build without the analog outputs, the axis is
// never analog, so no analog code direction is offered to the limit gate.
always @(*) begin
    if (!has_analog) begin
        assert(!analog_active__q);
        assert(!code_forward__q);
        assert(!code_backward__q);
    end
end

// STAGE PREMISE (assumed here, proved by formal/motion_controller_stage.sv
// on the same StepOutput<16, 8>: an assume-guarantee pair). The stage's
// pending count is in the stage, which this file cannot name: a reported
// step went the way of the count's sign in the clock that decided it, and
// the count turns forward (backward) only through a forward (backward)
// request at an edge without reset or flush. The bounded checks from
// power-up of the mutation tests run without it.
reg f_stage_forward_1 = 1'b0;
reg f_stage_backward_1 = 1'b0;
reg f_stage_step_1 = 1'b0;
reg f_stage_dir_1 = 1'b0;
reg f_stage_flush_1 = 1'b0;
reg f_reset_1 = 1'b0;
always @(posedge clock) begin
    f_stage_forward_1 <= stage__pending_forward;
    f_stage_backward_1 <= stage__pending_backward;
    f_stage_step_1 <= stage__step;
    f_stage_dir_1 <= stage__dir;
    f_stage_flush_1 <= stage__flush;
    f_reset_1 <= stage__reset;
end
always @(*) begin
    if (stage__emitted)
        assume(stage__emitted_forward ? f_stage_forward_1 : f_stage_backward_1);
    if (stage__pending_forward)
        assume(!f_reset_1 && !f_stage_flush_1
            && (f_stage_forward_1 || (f_stage_step_1 && f_stage_dir_1)));
    if (stage__pending_backward)
        assume(!f_reset_1 && !f_stage_flush_1
            && (f_stage_backward_1 || (f_stage_step_1 && !f_stage_dir_1)));
end
`endif
