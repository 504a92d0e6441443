//! # `jog_generator`: a constant-speed jog built from motion-hdl's blocks
//!
//! An example of a user's own block: motion-hdl's `FreqDivider` requests a
//! step every `divisor` clocks, and its `StepOutput` turns the requests
//! into step/dir (or up/down, or quadrature) pulses with the drive's
//! timing enforced. A handwheel-less jog button on a manual machine needs
//! nothing more.
//!
//! ## Ports
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A step is requested at the edge after each divider strobe (the
//! divider's strobe is registered), and the output stage starts its pulse
//! as its timers allow: see the two blocks' datasheets. `dir` is sampled
//! with each request. The block's model, [`JogModel`], is the two blocks'
//! models composed the same way, and the tests compare them clock by
//! clock.

use motion_hdl::blocks::freq_divider::model::{FreqDividerInputs, FreqDividerModel};
use motion_hdl::blocks::freq_divider::{self, FreqDivider};
use motion_hdl::blocks::port_doc::{port, PortDoc};
use motion_hdl::blocks::step_output::model::{StepOutputInputs, StepOutputModel};
use motion_hdl::blocks::step_output::{self, StepOutput};
use rust_hdl::prelude::*;

/// Width of the exported divisor.
pub const DIVISOR_BITS: usize = 24;
/// Width of the exported timing inputs.
pub const TIMER_BITS: usize = 16;
/// Width of the exported pending-step count.
pub const PENDING_BITS: usize = 8;

/// Meaning of every port: the ones the jog passes through are the blocks'
/// own, taken with [`PortDoc::same_as`] so that they stay written once.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: both blocks in their power-up state",
    ),
    port(
        "enable",
        "1",
        "the jog runs while high; while low no new step is requested",
    ),
    PortDoc::same_as(freq_divider::PORT_DOCS, "divisor")
        .with_meaning("D: one step requested every D enabled clocks; 0 = no steps"),
    port("dir", "1", "direction of the jog: 1 = forward"),
    PortDoc::same_as(step_output::PORT_DOCS, "mode")
        .with_meaning("0 step/dir, 1 up/down (CW/CCW), 2 quadrature, 3 reserved (acts as 0)"),
    PortDoc::same_as(step_output::PORT_DOCS, "step_len"),
    PortDoc::same_as(step_output::PORT_DOCS, "step_space"),
    PortDoc::same_as(step_output::PORT_DOCS, "dir_setup"),
    PortDoc::same_as(step_output::PORT_DOCS, "dir_hold"),
    PortDoc::same_as(step_output::PORT_DOCS, "out_a"),
    PortDoc::same_as(step_output::PORT_DOCS, "out_b"),
    PortDoc::same_as(step_output::PORT_DOCS, "busy"),
];

/// A constant-speed jog: a `W`-bit divider feeding an output stage with
/// `T`-bit timers and a `P`-bit pending count.
#[derive(Clone, Debug, Default, LogicBlock)]
pub struct JogGenerator<const W: usize, const T: usize, const P: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// The jog runs while high.
    pub enable: Signal<In, Bit>,
    /// Clocks per step.
    pub divisor: Signal<In, Bits<W>>,
    /// Jog direction.
    pub dir: Signal<In, Bit>,
    /// Output mode.
    pub mode: Signal<In, Bits<2>>,
    /// Pulse high time.
    pub step_len: Signal<In, Bits<T>>,
    /// Minimum low time.
    pub step_space: Signal<In, Bits<T>>,
    /// Direction setup time.
    pub dir_setup: Signal<In, Bits<T>>,
    /// Direction hold time.
    pub dir_hold: Signal<In, Bits<T>>,
    /// Step, up or A.
    pub out_a: Signal<Out, Bit>,
    /// Dir, down or B.
    pub out_b: Signal<Out, Bit>,
    /// Steps pending or a timing interval running.
    pub busy: Signal<Out, Bit>,
    divider: FreqDivider<W>,
    stage: StepOutput<T, P>,
}

impl<const W: usize, const T: usize, const P: usize> Logic for JogGenerator<W, T, P> {
    #[hdl_gen]
    fn update(&mut self) {
        self.divider.clock.next = self.clock.val();
        self.divider.reset.next = self.reset.val();
        self.divider.enable.next = self.enable.val();
        self.divider.divisor.next = self.divisor.val();
        self.stage.clock.next = self.clock.val();
        self.stage.reset.next = self.reset.val();
        self.stage.step.next = self.divider.strobe.val();
        self.stage.dir.next = self.dir.val();
        self.stage.mode.next = self.mode.val();
        self.stage.step_len.next = self.step_len.val();
        self.stage.step_space.next = self.step_space.val();
        self.stage.dir_setup.next = self.dir_setup.val();
        self.stage.dir_hold.next = self.dir_hold.val();
        self.stage.clear_overrun.next = false;
        self.stage.flush.next = false;
        self.out_a.next = self.stage.out_a.val();
        self.out_b.next = self.stage.out_b.val();
        self.busy.next = self.stage.busy.val();
    }
}

motion_hdl::vector_ports!(impl[const W: usize, const T: usize, const P: usize] JogGenerator<W, T, P> {
    inputs: [reset, enable, divisor, dir, mode, step_len, step_space, dir_setup, dir_hold],
    outputs: [out_a, out_b, busy],
});

/// The exported jog: 24-bit divisor, 16-bit timers, 8-bit pending count.
pub type JogGenerator24 = JogGenerator<DIVISOR_BITS, TIMER_BITS, PENDING_BITS>;

/// Inputs of one clock, in the order of the RTL's input vector.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JogInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The jog runs.
    pub enable: bool,
    /// Clocks per step.
    pub divisor: u64,
    /// Jog direction.
    pub dir: bool,
    /// Output mode.
    pub mode: u8,
    /// Pulse high time.
    pub step_len: u64,
    /// Minimum low time.
    pub step_space: u64,
    /// Direction setup time.
    pub dir_setup: u64,
    /// Direction hold time.
    pub dir_hold: u64,
}

impl JogInputs {
    /// The RTL's input vector.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.enable as u64,
            self.divisor,
            self.dir as u64,
            self.mode as u64,
            self.step_len,
            self.step_space,
            self.dir_setup,
            self.dir_hold,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JogOutputs {
    /// Step, up or A.
    pub out_a: bool,
    /// Dir, down or B.
    pub out_b: bool,
    /// Steps pending or a timing interval running.
    pub busy: bool,
}

impl JogOutputs {
    /// From the RTL's output vector.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            out_a: v[0] != 0,
            out_b: v[1] != 0,
            busy: v[2] != 0,
        }
    }
}

/// The jog's reference model: the two blocks' models, wired as the RTL.
#[derive(Clone, Debug)]
pub struct JogModel {
    divider: FreqDividerModel,
    stage: StepOutputModel,
}

impl JogModel {
    /// A jog of the given widths, in its power-up state.
    pub fn new(divisor_bits: u32, timer_bits: u32, pending_bits: u32) -> Self {
        Self {
            divider: FreqDividerModel::new(divisor_bits),
            stage: StepOutputModel::new(timer_bits, pending_bits),
        }
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: JogInputs) -> JogOutputs {
        // The stage sees the divider's registered strobe of the last edge.
        let request = self.divider.strobe();
        self.divider.step(FreqDividerInputs {
            reset: i.reset,
            enable: i.enable,
            divisor: i.divisor,
        });
        let o = self.stage.step(StepOutputInputs {
            reset: i.reset,
            step: request,
            dir: i.dir,
            mode: i.mode,
            step_len: i.step_len,
            step_space: i.step_space,
            dir_setup: i.dir_setup,
            dir_hold: i.dir_hold,
            clear_overrun: false,
            flush: false,
        });
        JogOutputs {
            out_a: o.out_a,
            out_b: o.out_b,
            busy: o.busy,
        }
    }
}

motion_hdl::lockstep_model!(JogModel {
    inputs: JogInputs,
    outputs: JogOutputs,
    step: |model, inputs| model.step(*inputs),
});

/// The exported jog's Verilog, top module `jog_generator`, with its
/// submodules named `jog_generator__*`.
pub fn verilog() -> Result<String, motion_hdl::export::VerilogError> {
    let mut block = JogGenerator24::default();
    motion_hdl::export::module_verilog("jog_generator", &mut block)
}

/// The datasheet's port table (`src/ports.md`), generated from
/// [`PORT_DOCS`] and checked against the RTL as motion-hdl's own.
pub fn port_table() -> Result<String, motion_hdl::export::datasheet::DatasheetError> {
    motion_hdl::export::datasheet::port_table(&motion_hdl::export::datasheet::DatasheetSpec {
        block: "jog_generator",
        port_docs: PORT_DOCS,
        parameters: &[("W", DIVISOR_BITS), ("T", TIMER_BITS)],
        build: || Box::new(JogGenerator24::default()),
    })
}
