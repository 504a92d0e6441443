//! Reference model of [`super::LaserPwm`], cycle-exact, from the
//! datasheet's equations in plain integers.

use crate::blocks::{signed_value, width_mask};

/// Clocks from a taken `load` to the new dynamic duty in `target`: the
/// engine's squares, square root, two products and division.
pub const ENGINE_CLOCKS: u32 = 130;

/// Clocks from a taken `load` to its vector speed in `speed` (the squares
/// and the root).
pub const SPEED_CLOCKS: u32 = 54;

/// The hold factor's full scale: 1.0 (`factor` above it is taken as it).
pub const FACTOR_ONE: u64 = 1 << 16;

/// Floor of the square root.
pub fn isqrt(s: u64) -> u64 {
    let mut root = (s as f64).sqrt() as u64;
    while root * root > s {
        root -= 1;
    }
    while (root + 1) * (root + 1) <= s {
        root += 1;
    }
    root
}

/// The speed of a period's counts: floor(sqrt(a^2 + b^2)) steps.
pub fn vector_steps(a: i64, b: i64) -> u64 {
    isqrt((a * a + b * b) as u64)
}

/// The vector speed in 1/16 step: floor(sqrt(256 (a^2 + b^2))).
pub fn vector_sixteenths(a: i64, b: i64) -> u64 {
    isqrt(((a * a + b * b) as u64) << 8)
}

/// The dynamic duty of a period with counts `a`, `b`: `power` x min(1,
/// v x factor / (feed x 2^16)) in whole clocks, v the vector speed and
/// `feed` both in 1/16 step (v16): ratio = min(floor(v16 x f / feed),
/// 2^16), duty = floor((ratio x power + 2^15) / 2^16) (rounded to the
/// nearest clock, never above `power`). 0 when `feed` is 0.
pub fn dynamic_duty(a: i64, b: i64, power: u64, feed: u64, factor: u64) -> u64 {
    if feed == 0 {
        return 0;
    }
    let f = factor.min(FACTOR_ONE);
    let ratio = (vector_sixteenths(a, b) * f / feed).min(FACTOR_ONE);
    (ratio * power + (1 << 15)) >> 16
}

/// Inputs of one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaserInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The PWM period, clocks (R bits).
    pub pwm_period: u64,
    /// The programmed duty, clocks high per PWM period (R bits).
    pub power: u64,
    /// Scale the duty with the path speed.
    pub dynamic: bool,
    /// Strobe: the next interpolation period's counts.
    pub load: bool,
    /// Strobe: the next interpolation period starts; its computed duty
    /// becomes the target.
    pub commit: bool,
    /// The period's steps of the plane's first axis (C-bit two's complement).
    pub count_a: u64,
    /// The period's steps of the second axis.
    pub count_b: u64,
    /// The programmed feed, 1/16 step per interpolation period (F bits).
    pub feed: u64,
    /// The feed hold's factor, 1/65536 (17 bits).
    pub factor: u64,
    /// The laser may fire.
    pub enable: bool,
    /// Off at once, and the duty in force cleared (an abort, the hold's stop).
    pub kill: bool,
}

impl LaserInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.pwm_period,
            self.power,
            self.dynamic as u64,
            self.load as u64,
            self.commit as u64,
            self.count_a,
            self.count_b,
            self.feed,
            self.factor,
            self.enable as u64,
            self.kill as u64,
        ]
    }
}

/// Outputs after a clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaserOutputs {
    /// The laser's PWM.
    pub pwm: bool,
    /// The duty in force, clocks per PWM period.
    pub duty: u64,
    /// The duty the next PWM period takes.
    pub target: u64,
    /// The vector speed of the last period computed, steps per period.
    pub speed: u64,
    /// The engine is computing; a `load` now is ignored.
    pub busy: bool,
}

impl LaserOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            pwm: v[0] != 0,
            duty: v[1],
            target: v[2],
            speed: v[3],
            busy: v[4] != 0,
        }
    }
}

/// The model, with the RTL's widths: `R`-bit PWM, `C`-bit counts, `F`-bit
/// feed.
#[derive(Clone, Debug)]
pub struct LaserPwmModel {
    r: u32,
    c: u32,
    f: u32,
    counter: u64,
    duty: u64,
    /// The pulse of this PWM period has ended.
    ended: bool,
    result: u64,
    committed: u64,
    speed: u64,
    pwm: bool,
    /// Clocks the engine has worked, with the result and speed it will give.
    engine: Option<(u32, u64, u64)>,
}

impl LaserPwmModel {
    /// A model of the block with these widths, in its reset state.
    pub fn new(r: u32, c: u32, f: u32) -> Self {
        Self {
            r,
            c,
            f,
            counter: 0,
            duty: 0,
            ended: false,
            result: 0,
            committed: 0,
            speed: 0,
            pwm: false,
            engine: None,
        }
    }

    /// The outputs now.
    pub fn outputs(&self, inputs: &LaserInputs) -> LaserOutputs {
        LaserOutputs {
            pwm: self.pwm,
            duty: self.duty,
            target: self.target(inputs),
            speed: self.speed,
            busy: self.engine.is_some(),
        }
    }

    fn target(&self, inputs: &LaserInputs) -> u64 {
        match inputs.dynamic {
            true => self.committed,
            false => inputs.power & width_mask(self.r),
        }
    }

    /// One clock edge.
    pub fn step(&mut self, inputs: &LaserInputs) -> LaserOutputs {
        if inputs.reset {
            *self = Self::new(self.r, self.c, self.f);
            return self.outputs(inputs);
        }
        let r_mask = width_mask(self.r);
        let target = self.target(inputs);
        let committed = match inputs.commit {
            true => self.result,
            false => self.committed,
        };
        // The engine: a load while idle is taken; its result shows
        // ENGINE_CLOCKS edges later.
        match self.engine {
            Some((worked, result, speed)) => {
                let worked = worked + 1;
                if worked == SPEED_CLOCKS {
                    self.speed = speed;
                }
                self.engine = Some((worked, result, speed));
                if worked == ENGINE_CLOCKS {
                    self.result = result;
                    self.engine = None;
                }
            }
            None if inputs.load => {
                let a = signed_value(inputs.count_a, self.c);
                let b = signed_value(inputs.count_b, self.c);
                let power = inputs.power & r_mask;
                let feed = inputs.feed & width_mask(self.f);
                let factor = inputs.factor & width_mask(17);
                self.engine = Some((
                    0,
                    dynamic_duty(a, b, power, feed, factor),
                    vector_steps(a, b),
                ));
            }
            None => {}
        }
        let period = inputs.pwm_period & r_mask;
        let running = period >= 2;
        let wrap = !running || self.counter + 1 >= period;
        self.counter = if wrap { 0 } else { self.counter + 1 };
        self.duty = if inputs.kill { 0 } else { target };
        // Once the pulse of a PWM period has ended it does not start
        // again in that period, whatever the duty does.
        self.ended = (!wrap && self.ended) || self.counter >= self.duty;
        self.pwm = inputs.enable && !inputs.kill && running && !self.ended;
        self.committed = committed;
        self.outputs(inputs)
    }
}

crate::lockstep_model!(LaserPwmModel {
    inputs: LaserInputs,
    outputs: LaserOutputs,
    step: |model, inputs| model.step(inputs),
});
