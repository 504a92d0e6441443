//! # `laser_pwm`: laser power tied to the path: a glitch-free PWM whose duty follows the path speed
//!
//! A laser cuts or marks with an energy per millimetre of power / speed.
//! A power set per move burns the corners, where the path slows down.
//! This block scales the duty **in gateware** by the ratio of the path's
//! speed to the programmed feed, for every interpolation period, so that
//! the energy per millimetre stays constant through accelerations,
//! corners and a feed hold; or holds a constant duty (grbl's M3, and M4's
//! dynamic mode).
//!
//! ## Ports (`R` = 16-bit PWM, `C` = 16-bit counts, `F` = 24-bit feed)
//!
#![doc = include_str!("ports.md")]
//!
//! ## The PWM
//! A counter runs 0 .. `pwm_period` - 1 and wraps: the PWM's frequency
//! is clock / `pwm_period`. `pwm` is high from the wrap until the counter
//! reaches the duty in force, once per PWM period. The duty in force
//! follows the target at once (registered: `duty`), so a new duty acts
//! in the PWM period under way, without a glitch: a pulse under way is
//! lengthened or ended early, and a pulse that has ended does not start
//! again before the next wrap. A duty of 0 gives no pulse at all, a duty
//! of `pwm_period` or more a steady high with no low clock across the
//! wraps. `pwm` is registered: high in the clock after the edge where the
//! counter's new value is below the duty and the period's pulse has not
//! ended. `pwm_period` below 2 holds the counter at 0 and `pwm` low.
//!
//! ## The duty
//! * **Constant** (`dynamic` low): the duty the next PWM period takes
//!   (`target`) is `power`.
//! * **Dynamic** (`dynamic` high): at each `load` (one per interpolation
//!   period, ahead of it, with the period's step counts a and b of the
//!   two axes in the laser's plane) the engine computes the period's path
//!   speed in 1/16 step, v16 = floor(sqrt(256 (a^2 + b^2))), the vector
//!   sum, and ratio = min(floor(v16 x f / `feed`), 2^16), `feed` in 1/16
//!   step per period (a feed of a few steps a period stays exact to a
//!   few per cent), with
//!   f = min(`factor`, 2^16) the feed hold's factor (the hold stretches
//!   the period by 1/f). The duty is ratio x `power` / 2^16 rounded to the nearest clock:
//!   `power` at the programmed feed, proportional below it, never above
//!   it, 0 when the axes stand (v = 0), when the hold has stopped them
//!   (f = 0), or when `feed` is 0. It becomes the target at the next
//!   `commit`, the period's start. The speed window is the interpolation
//!   period: its steps are known before it starts (the DDA's pending
//!   slot), so the duty changes with the speed, in the period's first
//!   clock, with no measuring lag.
//! * Both axes need the same steps per millimetre (the vector sum is in
//!   steps).
//!
//! ## Off
//! * `kill` (an abort, the feed hold's stop): `pwm` is low in the clock
//!   after the edge that samples it, and the duty in force becomes 0; the
//!   next PWM period after `kill` falls takes the target again.
//! * `enable` low: `pwm` low from the next clock; the counter runs on.
//!
//! ## Timing
//! * A `load` taken at edge L (taken only while `busy` is low) shows its
//!   speed in `speed` after edge L + [`model::SPEED_CLOCKS`] (54) and its
//!   duty in `target` after edge L + [`model::ENGINE_CLOCKS`] (130); the
//!   first PWM period starting after that takes it. `busy` is high from L to then; a `load` while busy is
//!   ignored (the interpolation period must be longer than the engine).
//!
//! ## Bad input
//! * `count_a`, `count_b` are two's complement; -2^15 is allowed.
//! * `factor` above 2^16 counts as 2^16; `power` above `pwm_period` fires
//!   continuously.
//!
//! ## Structure
//! One shift-add multiplier (a 34-bit adder) squares a and b, forms
//! v x f and ratio x power; a bit-by-bit square root shares its registers
//! (a 34-bit subtractor); a [`SequentialDivider`] (32 by 24 bits) forms
//! the ratio. Area and Fmax are in the synthesis report.

pub mod model;

use rust_hdl::prelude::*;

use crate::blocks::konst;
use crate::blocks::port_doc::{port, PortDoc};
use crate::blocks::sequential_divider::SequentialDivider;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "laser PWM with its duty scaled by path speed / feed each interpolation period: constant energy per mm, glitch-free";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: counter, duties, engine and outputs 0"),
    port("pwm_period", "R", "PWM period, clocks (frequency = clock / pwm_period); below 2: `pwm` low"),
    port("power", "R", "the programmed duty, clocks high per PWM period; at or above `pwm_period`: steady on"),
    port("dynamic", "1", "1: the duty is `power` scaled by path speed / `feed` (M4); 0: `power` (M3)"),
    port("load", "1", "strobe, one per interpolation period, ahead of it: take the next period's `count_a`, `count_b`, `power`, `feed`, `factor` (ignored while `busy`)"),
    port("commit", "1", "strobe: the next interpolation period starts; the duty computed for it becomes the dynamic target"),
    port("count_a", "C", "the period's steps of the plane's first axis, two's complement"),
    port("count_b", "C", "the period's steps of the plane's second axis, two's complement"),
    port("feed", "F", "the programmed feed, 1/16 step per interpolation period (vector length); 0: dynamic duty 0"),
    port("factor", "17", "the feed hold's factor, 1/65536 (65536 = full speed; above counts as 65536)"),
    port("enable", "1", "the laser may fire; low: `pwm` low from the next clock"),
    port("kill", "1", "abort or the hold's stop: `pwm` low from the next clock, the duty in force 0"),
    port("pwm", "1", "the laser's PWM, registered"),
    port("duty", "R", "the duty in force, clocks per PWM period"),
    port("target", "R", "the duty the next PWM period takes"),
    port("speed", "16", "the last computed period's vector speed, steps per period"),
    port("busy", "1", "the engine is computing a `load`"),
];

/// The PWM counter and duty width.
pub const R: usize = 16;
/// The step counts' width.
pub const C: usize = 16;
/// The feed's width.
pub const F: usize = 24;
const ACC: usize = 40;

const P_IDLE: u64 = 0;
const P_SQUARE_A: u64 = 1;
const P_SQUARE_B: u64 = 2;
const P_ROOT: u64 = 3;
const P_TIMES_FACTOR: u64 = 4;
const P_DIVIDE: u64 = 5;
const P_TIMES_POWER: u64 = 6;

/// The laser PWM (see the module documentation).
#[derive(LogicBlock)]
pub struct LaserPwm {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// PWM period, clocks.
    pub pwm_period: Signal<In, Bits<R>>,
    /// Programmed duty, clocks.
    pub power: Signal<In, Bits<R>>,
    /// Scale with the speed.
    pub dynamic: Signal<In, Bit>,
    /// The next period's counts.
    pub load: Signal<In, Bit>,
    /// The next period starts.
    pub commit: Signal<In, Bit>,
    /// First axis's steps.
    pub count_a: Signal<In, Bits<C>>,
    /// Second axis's steps.
    pub count_b: Signal<In, Bits<C>>,
    /// Programmed feed, 1/16 step per period.
    pub feed: Signal<In, Bits<F>>,
    /// Hold factor, 1/65536.
    pub factor: Signal<In, Bits<17>>,
    /// May fire.
    pub enable: Signal<In, Bit>,
    /// Off at once.
    pub kill: Signal<In, Bit>,
    /// The PWM.
    pub pwm: Signal<Out, Bit>,
    /// The duty in force.
    pub duty: Signal<Out, Bits<R>>,
    /// The next PWM period's duty.
    pub target: Signal<Out, Bits<R>>,
    /// The last period's vector speed.
    pub speed: Signal<Out, Bits<16>>,
    /// Computing.
    pub busy: Signal<Out, Bit>,

    counter: DFF<Bits<R>>,
    duty_now: DFF<Bits<R>>,
    ended: DFF<Bit>,
    committed: DFF<Bits<R>>,
    pwm_out: DFF<Bit>,
    result: DFF<Bits<R>>,
    speed_out: DFF<Bits<16>>,
    phase: DFF<Bits<3>>,
    seq: DFF<Bits<5>>,
    acc: DFF<Bits<ACC>>,
    mcand: DFF<Bits<ACC>>,
    mplier: DFF<Bits<17>>,
    root_bit: DFF<Bits<ACC>>,
    magnitude_b: DFF<Bits<17>>,
    power_taken: DFF<Bits<R>>,
    feed_taken: DFF<Bits<F>>,
    factor_taken: DFF<Bits<17>>,
    divide_start: DFF<Bit>,
    divider: SequentialDivider<40, F>,
    /// acc + mcand.
    sum: Signal<Local, Bits<ACC>>,
    /// acc - (mcand | root_bit): the root's trial.
    trial: Signal<Local, Bits<ACC>>,
    root_next: Signal<Local, Bits<ACC>>,
    acc_next: Signal<Local, Bits<ACC>>,
    magnitude_a: Signal<Local, Bits<17>>,
    magnitude_b_in: Signal<Local, Bits<17>>,
    counter_next: Signal<Local, Bits<R>>,
    duty_next: Signal<Local, Bits<R>>,
    wrap: Signal<Local, Bit>,
    ended_next: Signal<Local, Bit>,
    running: Signal<Local, Bit>,
    last_step: Signal<Local, Bit>,
    target_duty: Signal<Local, Bits<R>>,
    ratio: Signal<Local, Bits<ACC>>,
    multiplying: Signal<Local, Bit>,
    code_idle: Constant<Bits<3>>,
    code_square_a: Constant<Bits<3>>,
    code_square_b: Constant<Bits<3>>,
    code_root: Constant<Bits<3>>,
    code_times_factor: Constant<Bits<3>>,
    code_divide: Constant<Bits<3>>,
    code_times_power: Constant<Bits<3>>,
    zero_acc: Constant<Bits<ACC>>,
    root_start: Constant<Bits<ACC>>,
    ratio_one: Constant<Bits<ACC>>,
    /// 1/2 in the ratio x power product's 2^-16 units.
    half_clock: Constant<Bits<ACC>>,
    factor_one: Constant<Bits<17>>,
    sign_17: Constant<Bits<17>>,
    one_17: Constant<Bits<17>>,
    zero_17: Constant<Bits<17>>,
    zero_seq: Constant<Bits<5>>,
    one_seq: Constant<Bits<5>>,
    last_multiply: Constant<Bits<5>>,
    last_root: Constant<Bits<5>>,
    zero_r: Constant<Bits<R>>,
    one_r: Constant<Bits<R>>,
    two_r: Constant<Bits<R>>,
    zero_16: Constant<Bits<16>>,
    zero_f: Constant<Bits<F>>,
}

impl Default for LaserPwm {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            pwm_period: Default::default(),
            power: Default::default(),
            dynamic: Default::default(),
            load: Default::default(),
            commit: Default::default(),
            count_a: Default::default(),
            count_b: Default::default(),
            feed: Default::default(),
            factor: Default::default(),
            enable: Default::default(),
            kill: Default::default(),
            pwm: Default::default(),
            duty: Default::default(),
            target: Default::default(),
            speed: Default::default(),
            busy: Default::default(),
            counter: Default::default(),
            duty_now: Default::default(),
            ended: Default::default(),
            committed: Default::default(),
            pwm_out: Default::default(),
            result: Default::default(),
            speed_out: Default::default(),
            phase: Default::default(),
            seq: Default::default(),
            acc: Default::default(),
            mcand: Default::default(),
            mplier: Default::default(),
            root_bit: Default::default(),
            magnitude_b: Default::default(),
            power_taken: Default::default(),
            feed_taken: Default::default(),
            factor_taken: Default::default(),
            divide_start: Default::default(),
            divider: Default::default(),
            sum: Default::default(),
            trial: Default::default(),
            root_next: Default::default(),
            acc_next: Default::default(),
            magnitude_a: Default::default(),
            magnitude_b_in: Default::default(),
            counter_next: Default::default(),
            duty_next: Default::default(),
            wrap: Default::default(),
            ended_next: Default::default(),
            running: Default::default(),
            last_step: Default::default(),
            target_duty: Default::default(),
            ratio: Default::default(),
            multiplying: Default::default(),
            code_idle: konst(P_IDLE),
            code_square_a: konst(P_SQUARE_A),
            code_square_b: konst(P_SQUARE_B),
            code_root: konst(P_ROOT),
            code_times_factor: konst(P_TIMES_FACTOR),
            code_divide: konst(P_DIVIDE),
            code_times_power: konst(P_TIMES_POWER),
            zero_acc: konst(0),
            root_start: konst(1 << 38),
            ratio_one: konst(1 << 16),
            half_clock: konst(1 << 15),
            factor_one: konst(1 << 16),
            sign_17: konst(1 << 16),
            one_17: konst(1),
            zero_17: konst(0),
            zero_seq: konst(0),
            one_seq: konst(1),
            last_multiply: konst(16),
            last_root: konst(19),
            zero_r: konst(0),
            one_r: konst(1),
            two_r: konst(2),
            zero_16: konst(0),
            zero_f: konst(0),
        }
    }
}

impl Logic for LaserPwm {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            counter,
            duty_now,
            ended,
            committed,
            pwm_out,
            result,
            speed_out,
            phase,
            seq,
            acc,
            mcand,
            mplier,
            root_bit,
            magnitude_b,
            power_taken,
            feed_taken,
            factor_taken,
            divide_start
        );
        clock!(self, clock, divider);
        self.pwm.next = self.pwm_out.q.val();
        self.duty.next = self.duty_now.q.val();
        self.speed.next = self.speed_out.q.val();
        self.busy.next = self.phase.q.val() != self.code_idle.val();

        // The engine.
        self.sum.next = self.acc.q.val() + self.mcand.q.val();
        self.trial.next = self.acc.q.val() - (self.mcand.q.val() | self.root_bit.q.val());
        self.root_next.next = self.mcand.q.val() >> 1;
        if !self.trial.val().get_bit(39) {
            self.root_next.next = (self.mcand.q.val() >> 1) | self.root_bit.q.val();
        }
        self.acc_next.next = self.acc.q.val();
        if self.mplier.q.val().get_bit(0) {
            self.acc_next.next = self.sum.val();
        }
        self.last_step.next = self.seq.q.val() == self.last_multiply.val();
        self.magnitude_a.next = bit_cast::<17, C>(self.count_a.val());
        if self.count_a.val().get_bit(15) {
            self.magnitude_a.next =
                !(bit_cast::<17, C>(self.count_a.val()) | self.sign_17.val()) + self.one_17.val();
        }
        self.magnitude_b_in.next = bit_cast::<17, C>(self.count_b.val());
        if self.count_b.val().get_bit(15) {
            self.magnitude_b_in.next =
                !(bit_cast::<17, C>(self.count_b.val()) | self.sign_17.val()) + self.one_17.val();
        }
        self.ratio.next = self.divider.quotient.val();
        if self.divider.quotient.val() >= self.ratio_one.val() {
            self.ratio.next = self.ratio_one.val();
        }
        if self.divider.divide_by_zero.val() {
            self.ratio.next = self.zero_acc.val();
        }
        self.divider.start.next = self.divide_start.q.val();
        self.divider.dividend.next = self.acc.q.val();
        self.divider.divisor.next = self.feed_taken.q.val();
        self.divide_start.d.next = false;

        self.multiplying.next = (self.phase.q.val() == self.code_square_a.val())
            | (self.phase.q.val() == self.code_square_b.val())
            | (self.phase.q.val() == self.code_times_factor.val())
            | (self.phase.q.val() == self.code_times_power.val());
        if self.multiplying.val() {
            self.acc.d.next = self.acc_next.val();
            self.mcand.d.next = self.mcand.q.val() << 1;
            self.mplier.d.next = self.mplier.q.val() >> 1;
            self.seq.d.next = self.seq.q.val() + self.one_seq.val();
        }
        if self.phase.q.val() == self.code_root.val() {
            if !self.trial.val().get_bit(39) {
                self.acc.d.next = self.trial.val();
            }
            self.mcand.d.next = self.root_next.val();
            self.root_bit.d.next = self.root_bit.q.val() >> 2;
            self.seq.d.next = self.seq.q.val() + self.one_seq.val();
        }
        if (self.phase.q.val() == self.code_square_a.val()) & self.last_step.val() {
            self.phase.d.next = self.code_square_b.val();
            self.seq.d.next = self.zero_seq.val();
            self.mcand.d.next = bit_cast::<ACC, 17>(self.magnitude_b.q.val());
            self.mplier.d.next = self.magnitude_b.q.val();
        }
        if (self.phase.q.val() == self.code_square_b.val()) & self.last_step.val() {
            // The root of 256 (a^2 + b^2): the speed in 1/16 step.
            self.acc.d.next = self.acc_next.val() << 8;
            self.phase.d.next = self.code_root.val();
            self.seq.d.next = self.zero_seq.val();
            self.mcand.d.next = self.zero_acc.val();
            self.root_bit.d.next = self.root_start.val();
        }
        if (self.phase.q.val() == self.code_root.val()) & (self.seq.q.val() == self.last_root.val())
        {
            self.phase.d.next = self.code_times_factor.val();
            self.seq.d.next = self.zero_seq.val();
            self.acc.d.next = self.zero_acc.val();
            self.mplier.d.next = self.factor_taken.q.val();
            self.speed_out.d.next = self.root_next.val().get_bits::<16>(4);
        }
        if (self.phase.q.val() == self.code_times_factor.val()) & self.last_step.val() {
            self.phase.d.next = self.code_divide.val();
            self.divide_start.d.next = true;
        }
        if (self.phase.q.val() == self.code_divide.val()) & self.divider.done.val() {
            self.phase.d.next = self.code_times_power.val();
            self.seq.d.next = self.zero_seq.val();
            // Rounded to the nearest clock: a floor would bias every duty
            // low by up to a clock, 3 % of a duty of 30 clocks.
            self.acc.d.next = self.half_clock.val();
            self.mcand.d.next = self.ratio.val();
            self.mplier.d.next = bit_cast::<17, R>(self.power_taken.q.val());
        }
        if (self.phase.q.val() == self.code_times_power.val()) & self.last_step.val() {
            self.phase.d.next = self.code_idle.val();
            self.result.d.next = self.acc_next.val().get_bits::<R>(16);
        }
        if (self.phase.q.val() == self.code_idle.val()) & self.load.val() {
            self.phase.d.next = self.code_square_a.val();
            self.seq.d.next = self.zero_seq.val();
            self.acc.d.next = self.zero_acc.val();
            self.mcand.d.next = bit_cast::<ACC, 17>(self.magnitude_a.val());
            self.mplier.d.next = self.magnitude_a.val();
            self.magnitude_b.d.next = self.magnitude_b_in.val();
            self.power_taken.d.next = self.power.val();
            self.feed_taken.d.next = self.feed.val();
            self.factor_taken.d.next = self.factor.val();
            if self.factor.val() > self.factor_one.val() {
                self.factor_taken.d.next = self.factor_one.val();
            }
        }

        // The PWM.
        self.target_duty.next = self.power.val();
        if self.dynamic.val() {
            self.target_duty.next = self.committed.q.val();
        }
        if self.commit.val() {
            self.committed.d.next = self.result.q.val();
        }
        self.target.next = self.power.val();
        if self.dynamic.val() {
            self.target.next = self.committed.q.val();
        }
        self.running.next = self.pwm_period.val() >= self.two_r.val();
        self.wrap.next = !self.running.val()
            | ((bit_cast::<17, R>(self.counter.q.val()) + self.one_17.val())
                >= bit_cast::<17, R>(self.pwm_period.val()));
        self.counter_next.next = self.counter.q.val() + self.one_r.val();
        if self.wrap.val() {
            self.counter_next.next = self.zero_r.val();
        }
        self.duty_next.next = self.target_duty.val();
        if self.kill.val() {
            self.duty_next.next = self.zero_r.val();
        }
        self.ended_next.next = (!self.wrap.val() & self.ended.q.val())
            | (self.counter_next.val() >= self.duty_next.val());
        self.counter.d.next = self.counter_next.val();
        self.duty_now.d.next = self.duty_next.val();
        self.ended.d.next = self.ended_next.val();
        self.pwm_out.d.next =
            self.enable.val() & !self.kill.val() & self.running.val() & !self.ended_next.val();

        self.divider.reset.next = self.reset.val();
        if self.reset.val() {
            self.counter.d.next = self.zero_r.val();
            self.duty_now.d.next = self.zero_r.val();
            self.ended.d.next = false;
            self.committed.d.next = self.zero_r.val();
            self.pwm_out.d.next = false;
            self.result.d.next = self.zero_r.val();
            self.speed_out.d.next = self.zero_16.val();
            self.phase.d.next = self.code_idle.val();
            self.seq.d.next = self.zero_seq.val();
            self.acc.d.next = self.zero_acc.val();
            self.mcand.d.next = self.zero_acc.val();
            self.mplier.d.next = self.zero_17.val();
            self.root_bit.d.next = self.zero_acc.val();
            self.magnitude_b.d.next = self.zero_17.val();
            self.power_taken.d.next = self.zero_r.val();
            self.feed_taken.d.next = self.zero_f.val();
            self.factor_taken.d.next = self.zero_17.val();
            self.divide_start.d.next = false;
        }
    }
}

crate::vector_ports!(impl[] LaserPwm {
    inputs: [
        reset, pwm_period, power, dynamic, load, commit, count_a, count_b, feed, factor, enable,
        kill
    ],
    outputs: [pwm, duty, target, speed, busy],
});
