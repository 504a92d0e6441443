//! Proofs of the motion controller's safety rules (`formal/motion_controller_*.sv`).
//!
//! The whole controller does not close, so the rules are proved on the
//! sub-blocks that decide them, with the rest of the controller abstracted
//! (their inputs free): the limit gate of an axis (`AxisIo`), the axis
//! around it (`MotionAxis`: its request register and the output stage's
//! flush), the premise the axis's induction takes of its output stage
//! (`StepOutput<16, 8>`, assume-guarantee) and the machine I/O
//! (`MachineIo`: the E-stop's conditioning and latch). The datasheet's
//! "Formal proof" says how the parts compose into the controller's
//! pin-to-pin bounds.

use super::FormalSpec;
use crate::blocks::motion_controller::axis::MotionAxis;
use crate::blocks::motion_controller::axis_io::AxisIo;
use crate::blocks::motion_controller::hold_ramp::HoldRamp;
use crate::blocks::motion_controller::machine_io::MachineIo;
use crate::blocks::motion_controller::{registers, STAGE_PENDING_BITS};
use crate::blocks::step_output::StepOutput;

/// Axis 0 of the exported `motion_controller` (uniform generators, no
/// analog outputs), with the narrowest FIFO the controller takes (N = 2)
/// and the gearbox's step input of a `SPINDLE` build, free at every clock
/// like every other input.
fn exported_axis() -> MotionAxis<2, 3> {
    let map = registers::register_map(1, 2, registers::BuildOptions::MOTION_CONTROLLER)
        .expect("the controller's own register map validates");
    let axis_config = map
        .register("AXIS_CONFIG")
        .expect("the controller's AXIS_CONFIG")
        .rw_mask();
    MotionAxis::new(0, true, false, true, axis_config)
}

pub(super) fn specs() -> Vec<FormalSpec> {
    vec![
        FormalSpec {
            name: "motion_controller_hold_ramp",
            block: "motion_controller",
            module: "hold_ramp",
            property_file: "motion_controller_hold_ramp.sv",
            instance: "HoldRamp (the feed hold's factor and tick gate; no generics)",
            properties: "the gate never creates a tick: tick_out only with tick, none at factor 0, every tick at UNITY; the factor within 0 to UNITY; the fraction carried at every tick (phase' + UNITY x tick_out = phase + factor); the factor moves exactly one step of RATE (0: UNITY) per tick toward 0 under hold and toward UNITY without, clamped, and not between ticks; reset and power-up at UNITY",
            bmc_depth: 6,
            induction_depth: 2,
            build: || Box::new(HoldRamp::default()),
        },
        FormalSpec {
            name: "motion_controller_axis_io",
            block: "motion_controller",
            module: "axis_io",
            property_file: "motion_controller_axis_io.sv",
            instance: "AxisIo (an axis's limit gate; no generics)",
            properties: "limits: a direction is blocked exactly when its limit is active and IO_CONFIG.LIMIT_ENABLE (1 from power-up and reset) is set; a step toward it offered, requested or pending is cut in that clock, and only then; a cut sets the sticky trip that aborts every axis",
            bmc_depth: 6,
            induction_depth: 1,
            build: || Box::new(AxisIo::default()),
        },
        FormalSpec {
            name: "motion_controller_axis",
            block: "motion_controller",
            module: "motion_axis",
            property_file: "motion_controller_axis.sv",
            instance: "MotionAxis, N = 2, uniform generator, no analog outputs (an axis of the exported motion_controller, with a 4-entry FIFO)",
            properties: "abort and limit cut on the step path: no request enters the output stage after an abort clock or toward a direction blocked in the clock that made it; the stage is flushed exactly on an abort or a step toward a blocked direction (pending, requested or offered); no step reaches the pins at the edge after an abort clock; no step leaves toward a direction blocked in the clock before it was decided (given the stage premise, proved below)",
            bmc_depth: 8,
            induction_depth: 2,
            build: || Box::new(exported_axis()),
        },
        FormalSpec {
            name: "motion_controller_stage",
            block: "motion_controller",
            module: "axis_stage",
            property_file: "motion_controller_stage.sv",
            instance: "StepOutput, T = 16, P = 8 (an axis's output stage, as the axis builds it)",
            properties: "the axis's stage premise: a reported step goes the way of the pending count's sign; the count turns forward (backward) only through a forward (backward) request at an edge without reset or flush",
            bmc_depth: 4,
            induction_depth: 1,
            build: || Box::new(StepOutput::<16, STAGE_PENDING_BITS>::default()),
        },
        FormalSpec {
            name: "motion_controller_machine_io",
            block: "motion_controller",
            module: "machine_io",
            property_file: "motion_controller_machine_io.sv",
            instance: "MachineIo, K = 1 (its E-stop path is the same at every K)",
            properties: "E-stop: at the reset INPUT_FILTER, a pin held from clock c is active at c + latency::switch(4, 0) = c + 5 and latched at c + 6; the latch sets on the filtered level, holds until a clear with the level low, and only reset clears it otherwise",
            bmc_depth: 8,
            induction_depth: 7,
            build: || Box::new(MachineIo::<1>::default()),
        },
    ]
}
