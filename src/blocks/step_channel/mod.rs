//! # `step_channel`: one DDA axis driving a step output stage
//!
//! The complete step channel of a DDA axis: a [`DdaIntegrator`] whose pulses
//! are requests to a [`StepOutput`]. The DDA sets the average step rate
//! (J / M steps per tick); the output stage turns each pulse into a step
//! with the programmed drive timing and counts, rather than drops, any step
//! the timing holds back. `dir` is sampled with the tick, like the
//! integrand, and travels with that tick's pulse through the DDA's latency,
//! so a direction change never applies to a pulse of an earlier tick.
//!
//! This block adds no logic of its own beyond the two direction delay
//! flip-flops: see the two blocks' datasheets for every timing and bad-input
//! rule.
//!
//! ## Ports (`W` = 32-bit DDA, `T` = 16-bit timers in the exported `step_channel`)
//!
#![doc = include_str!("ports.md")]
//!
//! ## Timing
//! A tick that overflows the accumulator at edge t is a step request at
//! edge t + 2 (the DDA's latency); the earliest rising edge of `out_a` that
//! it can cause is the edge after that (with every timer at its minimum).

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use crate::blocks::dda_integrator::DdaIntegrator;
use crate::blocks::step_output::{self, StepOutput};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str = "step channel: a dda_integrator driving a step_output";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port(
        "reset",
        "1",
        "synchronous, active high: both blocks in their power-up state",
    ),
    port("tick", "1", "DDA accumulate enable"),
    port(
        "integrand",
        "W",
        "J, steps per M ticks, sampled with `tick`",
    ),
    port("modulus", "W", "M, sampled with `tick`; 0 means 2^W"),
    port(
        "dir",
        "1",
        "direction of this tick's step: 1 = forward; sampled with `tick`",
    ),
    port(
        "clear_overrange",
        "1",
        "clears `overrange` (tie to 0 if unused)",
    ),
    PortDoc::same_as(step_output::PORT_DOCS, "mode"),
    PortDoc::same_as(step_output::PORT_DOCS, "step_len"),
    PortDoc::same_as(step_output::PORT_DOCS, "step_space"),
    PortDoc::same_as(step_output::PORT_DOCS, "dir_setup"),
    PortDoc::same_as(step_output::PORT_DOCS, "dir_hold"),
    PortDoc::same_as(step_output::PORT_DOCS, "out_a"),
    PortDoc::same_as(step_output::PORT_DOCS, "out_b"),
    PortDoc::same_as(step_output::PORT_DOCS, "overrun"),
    port(
        "overrange",
        "1",
        "sticky: a tick was processed with J > M (M != 0)",
    ),
    PortDoc::same_as(step_output::PORT_DOCS, "mode_invalid"),
    PortDoc::same_as(step_output::PORT_DOCS, "busy"),
];

/// The DDA's pulse latency in clocks, which `dir` is delayed by.
pub const DDA_LATENCY: usize = 2;

/// DDA integrator feeding a step output stage. See the
/// [module documentation](self).
#[derive(Clone, Debug, LogicBlock)]
pub struct StepChannel<const W: usize, const T: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// DDA accumulate enable.
    pub tick: Signal<In, Bit>,
    /// J.
    pub integrand: Signal<In, Bits<W>>,
    /// M; 0 means 2^W.
    pub modulus: Signal<In, Bits<W>>,
    /// Direction of this tick's step.
    pub dir: Signal<In, Bit>,
    /// Clears `overrange`.
    pub clear_overrange: Signal<In, Bit>,
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
    /// Step / up / A.
    pub out_a: Signal<Out, Bit>,
    /// Dir / down / B.
    pub out_b: Signal<Out, Bit>,
    /// Sticky: a step was dropped.
    pub overrun: Signal<Out, Bit>,
    /// Sticky: J > M was used.
    pub overrange: Signal<Out, Bit>,
    /// Mode 3 selected.
    pub mode_invalid: Signal<Out, Bit>,
    /// Steps pending or a pulse in progress.
    pub busy: Signal<Out, Bit>,
    dda: DdaIntegrator<W>,
    stage: StepOutput<T, 16>,
    /// `dir` one and two clocks after its tick.
    dir_sampled: DFF<Bit>,
    dir_aligned: DFF<Bit>,
}

impl<const W: usize, const T: usize> Default for StepChannel<W, T> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            integrand: Default::default(),
            modulus: Default::default(),
            dir: Default::default(),
            clear_overrange: Default::default(),
            mode: Default::default(),
            step_len: Default::default(),
            step_space: Default::default(),
            dir_setup: Default::default(),
            dir_hold: Default::default(),
            out_a: Default::default(),
            out_b: Default::default(),
            overrun: Default::default(),
            overrange: Default::default(),
            mode_invalid: Default::default(),
            busy: Default::default(),
            dda: Default::default(),
            stage: Default::default(),
            dir_sampled: Default::default(),
            dir_aligned: Default::default(),
        }
    }
}

impl<const W: usize, const T: usize> Logic for StepChannel<W, T> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, dir_sampled, dir_aligned);
        self.dda.clock.next = self.clock.val();
        self.stage.clock.next = self.clock.val();
        self.dda.reset.next = self.reset.val();
        self.dda.tick.next = self.tick.val();
        self.dda.integrand.next = self.integrand.val();
        self.dda.modulus.next = self.modulus.val();
        self.dda.clear_overrange.next = self.clear_overrange.val();
        self.dir_sampled.d.next = self.dir.val();
        self.dir_aligned.d.next = self.dir_sampled.q.val();
        if self.reset.val() {
            self.dir_sampled.d.next = false;
            self.dir_aligned.d.next = false;
        }
        self.stage.reset.next = self.reset.val();
        self.stage.step.next = self.dda.pulse.val();
        self.stage.dir.next = self.dir_aligned.q.val();
        self.stage.mode.next = self.mode.val();
        self.stage.step_len.next = self.step_len.val();
        self.stage.step_space.next = self.step_space.val();
        self.stage.dir_setup.next = self.dir_setup.val();
        self.stage.dir_hold.next = self.dir_hold.val();
        self.stage.clear_overrun.next = false;
        self.stage.flush.next = false;
        self.out_a.next = self.stage.out_a.val();
        self.out_b.next = self.stage.out_b.val();
        self.overrun.next = self.stage.overrun.val();
        self.overrange.next = self.dda.overrange.val();
        self.mode_invalid.next = self.stage.mode_invalid.val();
        self.busy.next = self.stage.busy.val();
    }
}

crate::vector_ports!(impl[const W: usize, const T: usize] StepChannel<W, T> {
    inputs: [reset, tick, integrand, modulus, dir, clear_overrange, mode, step_len, step_space, dir_setup, dir_hold],
    outputs: [out_a, out_b, overrun, overrange, mode_invalid, busy],
});
