//! Reference model of [`super::InputConditioner`], cycle-exact: the
//! synchronizer as two words, the filters as
//! [`GlitchFilterModel`]s.

use crate::blocks::glitch_filter::model::GlitchFilterModel;

/// Inputs of one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InputConditionerInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The pins, bit i for input i.
    pub raw: u32,
    /// Per bit: active low.
    pub invert: u32,
    /// This edge is a filter sample.
    pub sample: bool,
    /// Samples a new level must hold (4 bits).
    pub length: u8,
}

impl InputConditionerInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.raw as u64,
            self.invert as u64,
            self.sample as u64,
            self.length as u64,
        ]
    }
}

/// Outputs after one edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InputConditionerOutputs {
    /// Accepted levels, polarity applied (0 while priming).
    pub active: u32,
    /// Rose at the last edge.
    pub rise: u32,
    /// Fell at the last edge.
    pub fall: u32,
    /// Primed.
    pub ready: bool,
}

impl InputConditionerOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            active: v[0] as u32,
            rise: v[1] as u32,
            fall: v[2] as u32,
            ready: v[3] != 0,
        }
    }
}

/// Plain-Rust model of a `width`-input conditioner.
#[derive(Clone, Debug)]
pub struct InputConditionerModel {
    mask: u32,
    sync_1: u32,
    sync_2: u32,
    primed: u8,
    width: usize,
    /// The first `width` are used; an array, so that a clone of the model
    /// (the controller model clones itself every clock) allocates nothing.
    filters: [GlitchFilterModel; 32],
}

impl InputConditionerModel {
    /// A conditioner of `width` inputs (1 to 32) in its power-up state.
    pub fn new(width: u32) -> Self {
        assert!((1..=32).contains(&width), "1 to 32 inputs");
        Self {
            mask: crate::blocks::width_mask(width) as u32,
            sync_1: 0,
            sync_2: 0,
            primed: 0,
            width: width as usize,
            filters: Default::default(),
        }
    }

    fn filtered(&self) -> u32 {
        self.filters[..self.width]
            .iter()
            .enumerate()
            .fold(0, |w, (i, f)| w | (f.filtered() as u32) << i)
    }

    fn changed(&self) -> u32 {
        self.filters[..self.width]
            .iter()
            .enumerate()
            .fold(0, |w, (i, f)| w | (f.changed() as u32) << i)
    }

    /// The outputs of the present state with `invert` applied.
    pub fn outputs(&self, invert: u32) -> InputConditionerOutputs {
        let ready = self.primed == 3;
        let level = (self.filtered() ^ invert) & self.mask;
        InputConditionerOutputs {
            active: if ready { level } else { 0 },
            rise: self.changed() & level,
            fall: self.changed() & !level & self.mask,
            ready,
        }
    }

    /// One rising edge; returns the outputs after it.
    pub fn step(&mut self, i: InputConditionerInputs) -> InputConditionerOutputs {
        let priming = self.primed != 3;
        for (bit, filter) in self.filters[..self.width].iter_mut().enumerate() {
            filter.step(
                i.reset,
                self.sync_2 >> bit & 1 != 0,
                i.sample,
                i.length,
                priming,
            );
        }
        self.sync_2 = self.sync_1;
        self.sync_1 = i.raw & self.mask;
        if priming {
            self.primed += 1;
        }
        if i.reset {
            self.primed = 0;
        }
        self.outputs(i.invert)
    }
}

crate::lockstep_model!(InputConditionerModel {
    inputs: InputConditionerInputs,
    outputs: InputConditionerOutputs,
    step: |model, inputs| model.step(*inputs),
});
