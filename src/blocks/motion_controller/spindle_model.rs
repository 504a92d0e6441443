//! Cycle-exact model of the spindle unit ([`super::spindle::SpindleUnit`]):
//! the spindle encoder, its registers, and the electronic gearbox's model
//! ([`GearboxModel`]) with the register layer around it.

use super::model::{bit_set, field_value, flag, position_word};
use super::registers::{fields, spindle};
use crate::blocks::electronic_gearbox::model::{
    GearboxInputs, GearboxModel, GearboxOutputs, GearboxWidths, Phase,
};
use crate::blocks::quadrature_decoder::model::{
    QuadratureDecoderInputs, QuadratureDecoderModel, QuadratureDecoderOutputs,
};
use crate::blocks::width_mask;

/// The spindle unit's inputs in one clock (the bus and the abort are the
/// controller's).
#[derive(Clone, Copy, Debug, Default)]
pub struct SpindleInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Pins A, B and index.
    pub pins: (bool, bool, bool),
    /// Bus word address.
    pub address: u32,
    /// Bus write strobe.
    pub write: bool,
    /// Bus write data.
    pub write_data: u32,
    /// The controller aborts.
    pub abort: bool,
}

/// Model of the spindle unit of a `axes`-axis controller.
#[derive(Clone, Debug)]
pub struct SpindleModel {
    axes: u32,
    decoder: QuadratureDecoderModel,
    decoder_out: QuadratureDecoderOutputs,
    gearbox: GearboxModel,
    gear_out: GearboxOutputs,
    filter: u32,
    counter_mode: bool,
    index_invert: bool,
    window: u32,
    spindle_reverse: bool,
    axis_reverse: bool,
    axis: u32,
    numerator: u64,
    denominator: u64,
    ramp: u64,
    length: u64,
    count_low: u64,
    clocks: u32,
    window_bit: bool,
    window_start: u64,
    speed: u64,
    axis_invalid: bool,
    flags_prev: u32,
}

impl SpindleModel {
    /// The unit at power-up (registers 0 until the first reset).
    pub fn new(axes: usize) -> Self {
        let decoder = QuadratureDecoderModel::new(super::POSITION_BITS as u32, 1, 1);
        let decoder_out = decoder.outputs();
        Self {
            axes: axes as u32,
            decoder,
            decoder_out,
            gearbox: GearboxModel::new(GearboxWidths::EXPORTED),
            gear_out: GearboxOutputs::default(),
            filter: 0,
            counter_mode: false,
            index_invert: false,
            window: 0,
            spindle_reverse: false,
            axis_reverse: false,
            axis: 0,
            numerator: 0,
            denominator: 0,
            ramp: 0,
            length: 0,
            count_low: 0,
            clocks: 0,
            window_bit: false,
            window_start: 0,
            speed: 0,
            axis_invalid: false,
            flags_prev: 0,
        }
    }

    /// The gearbox's step in this clock: `Some((axis, forward))`.
    pub fn step_out(&self) -> Option<(usize, bool)> {
        (self.gear_out.step_up || self.gear_out.step_down)
            .then_some((self.axis as usize, self.gear_out.step_up))
    }

    fn invalid(&self) -> bool {
        self.gear_out.invalid || self.axis_invalid
    }

    fn flags(&self) -> u32 {
        flag(self.gear_out.done, 0)
            | flag(self.invalid(), 1)
            | flag(self.gear_out.overrun, 2)
            | flag(self.decoder_out.error, 3)
    }

    /// A `STATUS.SPINDLE` cause rose in this clock.
    pub fn event(&self) -> bool {
        self.flags() & !self.flags_prev != 0
    }

    /// The gearbox's outputs in this clock.
    pub fn gearbox(&self) -> GearboxOutputs {
        self.gear_out
    }

    /// The spindle encoder's count in this clock.
    pub fn count(&self) -> u64 {
        self.decoder_out.count
    }

    /// The word the window reads at `address` (0 outside it).
    pub fn read(&self, address: u32) -> u32 {
        let gear = |v: u64| v as u32;
        match address {
            spindle::SPINDLE_POSITION => position_word(self.decoder_out.count),
            spindle::SPINDLE_INDEX_POSITION => position_word(self.decoder_out.index_count),
            spindle::SPINDLE_SPEED => position_word(self.speed),
            spindle::SPINDLE_CONFIG => {
                self.filter << fields::SPINDLE_FILTER
                    | flag(self.counter_mode, fields::SPINDLE_COUNTER_MODE)
                    | flag(self.index_invert, fields::SPINDLE_INDEX_INVERT)
                    | self.window << fields::SPINDLE_SPEED_WINDOW
            }
            spindle::GEAR_CONTROL => {
                flag(self.spindle_reverse, fields::GEAR_SPINDLE_REVERSE)
                    | flag(self.axis_reverse, fields::GEAR_AXIS_REVERSE)
                    | self.axis << fields::GEAR_AXIS
            }
            spindle::GEAR_STATUS => {
                let o = self.gear_out;
                (o.phase as u32) << fields::GEAR_PHASE
                    | flag(o.locked, fields::GEAR_LOCKED)
                    | flag(o.done, fields::GEAR_DONE)
                    | flag(self.invalid(), fields::GEAR_INVALID)
                    | flag(o.overrun, fields::GEAR_OVERRUN)
                    | flag(self.decoder_out.error, fields::GEAR_ENCODER_ERROR)
            }
            spindle::GEAR_NUMERATOR => gear(self.numerator),
            spindle::GEAR_DENOMINATOR => gear(self.denominator),
            spindle::GEAR_RAMP => gear(self.ramp),
            spindle::GEAR_LENGTH => gear(self.length),
            spindle::GEAR_POSITION => position_word(self.gear_out.position),
            _ => 0,
        }
    }

    /// One rising clock edge.
    pub fn edge(&mut self, i: SpindleInputs) {
        self.flags_prev = self.flags();
        let written = |address: u32| (i.write && i.address == address).then_some(i.write_data);
        let gear_value = |w: u32| field_value(w, fields::VALUE, super::registers::GEAR_BITS) as u64;
        let control = written(spindle::GEAR_CONTROL);
        let strobe = |n: u32| control.is_some_and(|w| bit_set(w, n));
        // The directions and the axis are written while idle.
        let idle = self.gear_out.phase == Phase::Idle;
        if let Some(w) = control.filter(|_| idle) {
            self.axis = field_value(w, fields::GEAR_AXIS, fields::GEAR_AXIS_WIDTH);
            self.spindle_reverse = bit_set(w, fields::GEAR_SPINDLE_REVERSE);
            self.axis_reverse = bit_set(w, fields::GEAR_AXIS_REVERSE);
        }
        let arm_request = strobe(fields::GEAR_ARM);
        let axis_ok = self.axis < self.axes;
        if arm_request && idle {
            self.axis_invalid = !axis_ok;
        }
        // A count moves the decoder's count by one: its low bits tell the
        // direction.
        let low = self.decoder_out.count & 3;
        let counted = (low ^ self.count_low) & 1 != 0;
        let forward = (low >> 1) == ((self.count_low >> 1) ^ (self.count_low & 1));
        let gear_in = GearboxInputs {
            reset: i.reset,
            count_up: counted && forward,
            count_down: counted && !forward,
            index: self.decoder_out.index_seen,
            arm: arm_request && axis_ok,
            stop: strobe(fields::GEAR_STOP),
            halt: strobe(fields::GEAR_HALT) || i.abort,
            spindle_reverse: self.spindle_reverse,
            axis_reverse: self.axis_reverse,
            numerator: self.numerator,
            denominator: self.denominator,
            ramp: self.ramp,
            length: self.length,
        };
        self.count_low = low;
        // Speed: the count's change over each window.
        let window_bit = self.clocks.checked_shr(self.window).unwrap_or(0) & 1 != 0;
        if window_bit != self.window_bit {
            self.speed = self.decoder_out.count.wrapping_sub(self.window_start)
                & width_mask(super::POSITION_BITS as u32);
            self.window_start = self.decoder_out.count;
        }
        self.window_bit = window_bit;
        self.clocks = self.clocks.wrapping_add(1);
        for (address, register) in [
            (spindle::GEAR_NUMERATOR, &mut self.numerator),
            (spindle::GEAR_DENOMINATOR, &mut self.denominator),
            (spindle::GEAR_RAMP, &mut self.ramp),
            (spindle::GEAR_LENGTH, &mut self.length),
        ] {
            if let Some(w) = written(address) {
                *register = gear_value(w);
            }
        }
        let decoder_in = QuadratureDecoderInputs {
            reset: i.reset,
            a: i.pins.0,
            b: i.pins.1,
            index: i.pins.2,
            filter: self.filter as u8,
            clear: false,
            clear_error: strobe(fields::GEAR_CLEAR_ENCODER_ERROR),
            sample_rate: 0,
            counter_mode: self.counter_mode,
            index_invert: self.index_invert,
            index_clear: false,
            index_latch: true,
            index_once: false,
            index_rearm: self.decoder_out.index_seen,
        };
        // The gearbox takes this clock's registers (the directions as
        // written by an arm of this clock).
        self.gear_out = self.gearbox.step(gear_in);
        self.decoder_out = self.decoder.step(decoder_in);
        // The encoder's options and the window apply from the next clock.
        if let Some(w) = written(spindle::SPINDLE_CONFIG) {
            self.filter = field_value(w, fields::SPINDLE_FILTER, fields::SPINDLE_FILTER_WIDTH);
            self.counter_mode = bit_set(w, fields::SPINDLE_COUNTER_MODE);
            self.index_invert = bit_set(w, fields::SPINDLE_INDEX_INVERT);
            self.window = field_value(
                w,
                fields::SPINDLE_SPEED_WINDOW,
                fields::SPINDLE_SPEED_WINDOW_WIDTH,
            );
        }
        if i.reset {
            let (decoder, decoder_out, gearbox, gear_out) = (
                self.decoder.clone(),
                self.decoder_out,
                self.gearbox.clone(),
                self.gear_out,
            );
            *self = Self {
                decoder,
                decoder_out,
                gearbox,
                gear_out,
                window: fields::SPINDLE_SPEED_WINDOW_RESET as u32,
                ..Self::new(self.axes as usize)
            };
        }
    }
}
