//! Model of the analog outputs' walk: the codes it loads into the DAC,
//! clock for clock, and its update requests (see
//! [`super::analog_outputs`]). The DAC itself is the
//! [`DacModel`](crate::blocks::dac_interface::model::DacModel).

use super::analog_outputs::SCALE_STEPS;
use super::hold_ramp::UNITY;

/// The walk's inputs in one clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct WalkInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Every FIFO pops in this clock.
    pub pop: bool,
    /// RUN falls in this clock, not by an abort (and the build is analog).
    pub stop_zero: bool,
    /// The abort level.
    pub abort: bool,
    /// Periods are running.
    pub running: bool,
    /// The feed hold's factor, 0 to [`UNITY`].
    pub factor: u32,
    /// Bit k: axis k is analog in this run.
    pub analog_axes: u64,
    /// The build has the analog outputs.
    pub has_analog: bool,
    /// The DAC's `busy` in this clock.
    pub dac_busy: bool,
    /// The number of axes.
    pub axes: usize,
    /// The code of the axis [`AnalogWalkModel::walked_axis`] names (its
    /// running period's, saturated to 16 bits signed; 0 for none), as the
    /// controller's mux answers the RTL's `walk`.
    pub code: i16,
}

/// What the walk drives into the DAC in one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WalkOutputs {
    /// Bit k: channel k stages `load_code`.
    pub load: u64,
    /// The code loaded, as the DAC's 16-bit word.
    pub load_code: u64,
    /// The update request (registered).
    pub update: bool,
}

/// floor(|code| x factor / 2^16) with the code's sign: the scaled walk's
/// code for a factor below [`UNITY`].
pub fn scaled_code(code: i16, factor: u32) -> i16 {
    let magnitude = code.unsigned_abs() as u64;
    let product = ((magnitude * factor as u64) >> 16) as i32;
    (if code < 0 { -product } else { product }) as i16
}

/// The walk's registers. See the [module documentation](self).
#[derive(Clone, Debug, Default)]
pub struct AnalogWalkModel {
    /// One-hot: the axis walked in this clock (0: none).
    walk: u64,
    update: bool,
    stop_zero_d: bool,
    scaled: bool,
    factor_bits: u32,
    step_count: u32,
    magnitude: u32,
    negative: bool,
    product: u32,
    owed: bool,
    update_wait: bool,
}

impl AnalogWalkModel {
    /// The axis the walk reads in this clock, if any.
    pub fn walked_axis(&self) -> Option<usize> {
        (self.walk != 0).then(|| self.walk.trailing_zeros() as usize)
    }

    /// One clock: the loads and the request of this clock, then the edge.
    pub fn step(&mut self, i: &WalkInputs) -> WalkOutputs {
        let axes = i.axes;
        let mask = crate::blocks::width_mask(axes as u32);
        let last_axis = 1u64 << (axes - 1);
        let any_analog = i.analog_axes != 0;
        let slowed = i.factor < UNITY;
        let walking = self.walk != 0;
        let rewalk = (slowed || self.owed)
            && i.running
            && !i.abort
            && !walking
            && !self.update_wait
            && !self.update
            && !i.dac_busy
            && any_analog
            && i.has_analog;
        let start = i.pop || rewalk;
        let mut next = self.clone();
        let (walk_now, scaled_now, count_now) = (self.walk, self.scaled, self.step_count);
        let code = i.code;
        let mut load = walk_now & i.analog_axes;
        next.walk = (walk_now << 1) & mask;
        next.step_count = 0;
        let mut last_load = false;
        if scaled_now && walk_now != 0 {
            if count_now == SCALE_STEPS + 1 {
                last_load = walk_now & last_axis != 0;
            } else {
                load = 0;
                next.walk = walk_now;
                next.step_count = (count_now + 1) & 0x1f;
                if count_now == 0 {
                    next.magnitude = code.unsigned_abs() as u32;
                    next.negative = code < 0;
                    next.product = 0;
                } else {
                    let addend = if self.factor_bits & 1 == 1 {
                        self.magnitude
                    } else {
                        0
                    };
                    next.product = (self.product + addend) >> 1;
                    next.factor_bits =
                        (self.factor_bits >> 1) | ((self.factor_bits << 15) & 0xffff);
                }
            }
        }
        if start {
            next.walk = 1;
            next.scaled = slowed;
            next.step_count = 0;
            next.factor_bits = i.factor & 0xffff;
            next.owed = slowed;
        }
        let mut load_code = if scaled_now {
            scaled_code_from_product(self.negative, self.product)
        } else {
            code as u16 as u64
        };
        next.update = walk_now & last_axis != 0 && any_analog && !scaled_now;
        if self.update_wait && !start {
            if !i.dac_busy {
                next.update = true;
                next.update_wait = false;
            } else {
                next.update_wait = true;
            }
        } else {
            next.update_wait = false;
        }
        if last_load && any_analog {
            next.update_wait = true;
        }
        next.stop_zero_d = i.stop_zero;
        if self.stop_zero_d {
            load = i.analog_axes;
            load_code = 0;
            next.walk = 0;
            next.update = any_analog;
            next.update_wait = false;
            next.owed = false;
        }
        if i.abort {
            next.walk = 0;
            next.update_wait = false;
            next.owed = false;
        }
        if i.reset {
            next.walk = 0;
            next.update = false;
            next.stop_zero_d = false;
            next.owed = false;
            next.update_wait = false;
        }
        let outputs = WalkOutputs {
            load,
            load_code,
            update: self.update,
        };
        *self = next;
        outputs
    }
}

/// The 16-bit word of a scaled walk's load: the product with the code's sign.
fn scaled_code_from_product(negative: bool, product: u32) -> u64 {
    let signed = if negative {
        -(product as i32)
    } else {
        product as i32
    };
    signed as u16 as u64
}
