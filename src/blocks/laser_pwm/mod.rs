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
//! One shift-right multiplier (a 21-bit adder; the product's high part
//! adds the multiplicand and shifts right into the low part) squares
//! a and b, forms v x f and ratio x power; a product starts from the
//! high part's initial value, which carries a^2's low bits into b^2,
//! and the rounding half into ratio x power. The digit-by-digit square root
//! shifts the radicand out of the product two bits a step into a 23-bit
//! remainder (a 24-bit subtractor), the root building up in the
//! multiplicand. A [`SequentialDivider`] (40 by 24 bits) forms the ratio.
//! The ratio's clamp at 2^16 is an OR of the quotient's high bits. The
//! PWM keeps its counter one ahead, so that the wrap and the pulse's end
//! are each one compare, not an increment, a mux and a compare in a
//! row. No carry chain is longer than the divider's 25 bits; area and
//! Fmax are in the synthesis report.

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
/// The multiplicand and the product's high part.
const H: usize = 20;
/// The product's low part: a multiplier of 17 bits, 17 steps.
const L: usize = 17;
/// The root's remainder (below 2^23; the width of its trial).
const REM: usize = 24;
/// The divider's dividend.
const DIVIDEND: usize = 40;
// `update` writes these at literal positions (rust-hdl prints a named
// constant by name): the low part's top two bits at 16 and 15, the
// product's high part at 17, the radicand's bits 31 and 30 at the high
// part's 14 and 13.
const _: () = assert!(L == 17 && H == 20 && REM == 24);

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

    /// The PWM counter plus one (0 .. `pwm_period` - 1, plus one), its
    /// bit 0 inverted: 0 at power-up is the counter at 0.
    count_ahead_stored: DFF<Bits<17>>,
    duty_now: DFF<Bits<R>>,
    ended: DFF<Bit>,
    committed: DFF<Bits<R>>,
    pwm_out: DFF<Bit>,
    result: DFF<Bits<R>>,
    speed_out: DFF<Bits<16>>,
    phase: DFF<Bits<3>>,
    seq: DFF<Bits<5>>,
    /// The product's high part (the radicand's top during the root).
    product_hi: DFF<Bits<H>>,
    /// The product's low part.
    product_lo: DFF<Bits<L>>,
    /// The root's remainder; a^2's high part while b is squared.
    remainder: DFF<Bits<REM>>,
    /// The multiplicand; the root as it builds up.
    multiplicand: DFF<Bits<H>>,
    mplier: DFF<Bits<L>>,
    magnitude_b: DFF<Bits<17>>,
    power_taken: DFF<Bits<R>>,
    feed_taken: DFF<Bits<F>>,
    factor_taken: DFF<Bits<17>>,
    divide_start: DFF<Bit>,
    /// The next clock is b^2's last step.
    b_last: DFF<Bit>,
    divider: SequentialDivider<DIVIDEND, F>,
    /// What the multiplier's step adds to the product's high part.
    addend: Signal<Local, Bits<H>>,
    /// The remainder's low bits: a^2's high part, while b is squared.
    a_square_high: Signal<Local, Bits<H>>,
    /// product_hi + addend.
    sum: Signal<Local, Bits<21>>,
    /// The product after the step, shifted right.
    product_hi_next: Signal<Local, Bits<H>>,
    product_lo_next: Signal<Local, Bits<L>>,
    /// 4 remainder + the radicand's next two bits.
    widened: Signal<Local, Bits<24>>,
    /// 4 root + 1.
    subtrahend: Signal<Local, Bits<24>>,
    /// widened - subtrahend: the root's trial (bit 23: it failed).
    trial: Signal<Local, Bits<24>>,
    root_next: Signal<Local, Bits<H>>,
    /// The radicand's top after the root's step (shifted left by 2).
    radicand_hi: Signal<Local, Bits<H>>,
    /// v x f for the divider.
    product: Signal<Local, Bits<DIVIDEND>>,
    /// The product's high part after the last step, low bits.
    duty_high: Signal<Local, Bits<R>>,
    duty_word: Signal<Local, Bits<R>>,
    magnitude_a: Signal<Local, Bits<17>>,
    magnitude_b_in: Signal<Local, Bits<17>>,
    /// The PWM counter plus one.
    count_ahead: Signal<Local, Bits<17>>,
    count_ahead_next: Signal<Local, Bits<17>>,
    duty_next: Signal<Local, Bits<R>>,
    wrap: Signal<Local, Bit>,
    ended_next: Signal<Local, Bit>,
    running: Signal<Local, Bit>,
    last_step: Signal<Local, Bit>,
    target_duty: Signal<Local, Bits<R>>,
    /// The quotient's bits 39..16.
    quotient_high: Signal<Local, Bits<24>>,
    /// min(quotient, 2^16), 0 on a division by zero.
    ratio: Signal<Local, Bits<H>>,
    multiplying: Signal<Local, Bit>,
    code_idle: Constant<Bits<3>>,
    code_square_a: Constant<Bits<3>>,
    code_square_b: Constant<Bits<3>>,
    code_root: Constant<Bits<3>>,
    code_times_factor: Constant<Bits<3>>,
    code_divide: Constant<Bits<3>>,
    code_times_power: Constant<Bits<3>>,
    zero_h: Constant<Bits<H>>,
    one_h: Constant<Bits<H>>,
    zero_remainder: Constant<Bits<REM>>,
    one_24: Constant<Bits<24>>,
    two_24: Constant<Bits<24>>,
    two_h: Constant<Bits<H>>,
    lo_top: Constant<Bits<L>>,
    zero_24: Constant<Bits<24>>,
    ratio_one_h: Constant<Bits<H>>,
    /// 1/2 in the ratio x power product's 2^-16 units.
    half_clock: Constant<Bits<H>>,
    factor_one: Constant<Bits<17>>,
    sign_17: Constant<Bits<17>>,
    one_17: Constant<Bits<17>>,
    zero_17: Constant<Bits<17>>,
    zero_seq: Constant<Bits<5>>,
    one_seq: Constant<Bits<5>>,
    last_multiply: Constant<Bits<5>>,
    before_last_multiply: Constant<Bits<5>>,
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
            count_ahead_stored: Default::default(),
            duty_now: Default::default(),
            ended: Default::default(),
            committed: Default::default(),
            pwm_out: Default::default(),
            result: Default::default(),
            speed_out: Default::default(),
            phase: Default::default(),
            seq: Default::default(),
            product_hi: Default::default(),
            product_lo: Default::default(),
            remainder: Default::default(),
            multiplicand: Default::default(),
            mplier: Default::default(),
            magnitude_b: Default::default(),
            power_taken: Default::default(),
            feed_taken: Default::default(),
            factor_taken: Default::default(),
            divide_start: Default::default(),
            b_last: Default::default(),
            divider: Default::default(),
            addend: Default::default(),
            a_square_high: Default::default(),
            sum: Default::default(),
            product_hi_next: Default::default(),
            product_lo_next: Default::default(),
            widened: Default::default(),
            subtrahend: Default::default(),
            trial: Default::default(),
            root_next: Default::default(),
            radicand_hi: Default::default(),
            product: Default::default(),
            duty_high: Default::default(),
            duty_word: Default::default(),
            magnitude_a: Default::default(),
            magnitude_b_in: Default::default(),
            count_ahead: Default::default(),
            count_ahead_next: Default::default(),
            duty_next: Default::default(),
            wrap: Default::default(),
            ended_next: Default::default(),
            running: Default::default(),
            last_step: Default::default(),
            target_duty: Default::default(),
            quotient_high: Default::default(),
            ratio: Default::default(),
            multiplying: Default::default(),
            code_idle: konst(P_IDLE),
            code_square_a: konst(P_SQUARE_A),
            code_square_b: konst(P_SQUARE_B),
            code_root: konst(P_ROOT),
            code_times_factor: konst(P_TIMES_FACTOR),
            code_divide: konst(P_DIVIDE),
            code_times_power: konst(P_TIMES_POWER),
            zero_h: konst(0),
            one_h: konst(1),
            zero_remainder: konst(0),
            one_24: konst(1),
            two_24: konst(2),
            two_h: konst(2),
            lo_top: konst(1 << (L - 1)),
            zero_24: konst(0),
            ratio_one_h: konst(1 << 16),
            half_clock: konst(1 << 15),
            factor_one: konst(1 << 16),
            sign_17: konst(1 << 16),
            one_17: konst(1),
            zero_17: konst(0),
            zero_seq: konst(0),
            one_seq: konst(1),
            last_multiply: konst(16),
            before_last_multiply: konst(15),
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
            count_ahead_stored,
            duty_now,
            ended,
            committed,
            pwm_out,
            result,
            speed_out,
            phase,
            seq,
            product_hi,
            product_lo,
            remainder,
            multiplicand,
            mplier,
            magnitude_b,
            power_taken,
            feed_taken,
            factor_taken,
            divide_start,
            b_last
        );
        clock!(self, clock, divider);
        self.pwm.next = self.pwm_out.q.val();
        self.duty.next = self.duty_now.q.val();
        self.speed.next = self.speed_out.q.val();
        self.busy.next = self.phase.q.val() != self.code_idle.val();

        // The engine.
        // The multiplier's step: product_hi + addend, shifted right into
        // product_lo.
        self.a_square_high.next = self.remainder.q.val().get_bits::<H>(0);
        self.addend.next = self.zero_h.val();
        if self.mplier.q.val().get_bit(0) {
            self.addend.next = self.multiplicand.q.val();
        }
        self.last_step.next = self.seq.q.val() == self.last_multiply.val();
        // Registered, so that the adder's operand waits on no decode.
        self.b_last.d.next = (self.phase.q.val() == self.code_square_b.val())
            & (self.seq.q.val() == self.before_last_multiply.val());
        if self.b_last.q.val() {
            // b's bit 16 is 0 (|b| <= 2^15): the idle last step adds a^2's
            // high part at its weight, 2^17 = 2 x 2^16.
            self.addend.next = self.a_square_high.val() << 1;
        }
        self.sum.next =
            bit_cast::<21, H>(self.product_hi.q.val()) + bit_cast::<21, H>(self.addend.val());
        self.product_hi_next.next = self.sum.val().get_bits::<H>(1);
        self.product_lo_next.next = self.product_lo.q.val() >> 1;
        if self.sum.val().get_bit(0) {
            self.product_lo_next.next = (self.product_lo.q.val() >> 1) | self.lo_top.val();
        }
        // The root's step: two radicand bits (the product's bits 31, 30)
        // into the remainder, then 4 remainder + pair - (4 root + 1).
        self.widened.next = self.remainder.q.val() << 2;
        if self.product_hi.q.val().get_bit(14) {
            self.widened.next = (self.remainder.q.val() << 2) | self.two_24.val();
        }
        if self.product_hi.q.val().get_bit(13) {
            self.widened.next = self.widened.val() | self.one_24.val();
        }
        self.subtrahend.next =
            (bit_cast::<24, H>(self.multiplicand.q.val()) << 2) | self.one_24.val();
        self.trial.next = self.widened.val() - self.subtrahend.val();
        self.root_next.next = self.multiplicand.q.val() << 1;
        if !self.trial.val().get_bit(23) {
            self.root_next.next = (self.multiplicand.q.val() << 1) | self.one_h.val();
        }
        self.radicand_hi.next = self.product_hi.q.val() << 2;
        if self.product_lo.q.val().get_bit(16) {
            self.radicand_hi.next = (self.product_hi.q.val() << 2) | self.two_h.val();
        }
        if self.product_lo.q.val().get_bit(15) {
            self.radicand_hi.next = self.radicand_hi.val() | self.one_h.val();
        }
        self.product.next = (bit_cast::<DIVIDEND, H>(self.product_hi.q.val()) << 17)
            | bit_cast::<DIVIDEND, L>(self.product_lo.q.val());
        // (ratio x power + 2^15) >> 16 from the last step's product.
        // The duty is below 2^16, so hi_next's bit 15 is 0.
        self.duty_high.next = self.product_hi_next.val().get_bits::<R>(0);
        self.duty_word.next = self.duty_high.val() << 1;
        if self.sum.val().get_bit(0) {
            self.duty_word.next = (self.duty_high.val() << 1) | self.one_r.val();
        }
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
        self.ratio.next = self.divider.quotient.val().get_bits::<H>(0);
        // At or above 2^16: any of the quotient's high bits (a wide OR, not
        // a 40-bit compare).
        self.quotient_high.next = self.divider.quotient.val().get_bits::<24>(16);
        if self.quotient_high.val() != self.zero_24.val() {
            self.ratio.next = self.ratio_one_h.val();
        }
        if self.divider.divide_by_zero.val() {
            self.ratio.next = self.zero_h.val();
        }
        self.divider.start.next = self.divide_start.q.val();
        self.divider.dividend.next = self.product.val();
        self.divider.divisor.next = self.feed_taken.q.val();
        self.divide_start.d.next = false;

        self.multiplying.next = (self.phase.q.val() == self.code_square_a.val())
            | (self.phase.q.val() == self.code_square_b.val())
            | (self.phase.q.val() == self.code_times_factor.val())
            | (self.phase.q.val() == self.code_times_power.val());
        if self.multiplying.val() {
            self.product_hi.d.next = self.product_hi_next.val();
            self.product_lo.d.next = self.product_lo_next.val();
            self.mplier.d.next = self.mplier.q.val() >> 1;
            self.seq.d.next = self.seq.q.val() + self.one_seq.val();
        }
        if self.phase.q.val() == self.code_root.val() {
            self.product_hi.d.next = self.radicand_hi.val();
            self.product_lo.d.next = self.product_lo.q.val() << 2;
            self.remainder.d.next = self.widened.val();
            if !self.trial.val().get_bit(23) {
                self.remainder.d.next = self.trial.val();
            }
            self.multiplicand.d.next = self.root_next.val();
            self.seq.d.next = self.seq.q.val() + self.one_seq.val();
        }
        if (self.phase.q.val() == self.code_square_a.val()) & self.last_step.val() {
            // b^2 starts from a^2's low part; its high part waits in the remainder.
            self.phase.d.next = self.code_square_b.val();
            self.seq.d.next = self.zero_seq.val();
            self.product_hi.d.next = bit_cast::<H, L>(self.product_lo_next.val());
            self.remainder.d.next = bit_cast::<REM, H>(self.product_hi_next.val());
            self.multiplicand.d.next = bit_cast::<H, 17>(self.magnitude_b.q.val());
            self.mplier.d.next = self.magnitude_b.q.val();
        }
        if (self.phase.q.val() == self.code_square_b.val()) & self.last_step.val() {
            // The root of 256 (a^2 + b^2), the speed in 1/16 step: the sum's
            // 32 bits, then 8 zero bits.
            self.phase.d.next = self.code_root.val();
            self.seq.d.next = self.zero_seq.val();
            self.multiplicand.d.next = self.zero_h.val();
            self.remainder.d.next = self.zero_remainder.val();
        }
        if (self.phase.q.val() == self.code_root.val()) & (self.seq.q.val() == self.last_root.val())
        {
            self.phase.d.next = self.code_times_factor.val();
            self.seq.d.next = self.zero_seq.val();
            self.product_hi.d.next = self.zero_h.val();
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
            self.product_hi.d.next = self.half_clock.val();
            self.multiplicand.d.next = self.ratio.val();
            self.mplier.d.next = bit_cast::<L, R>(self.power_taken.q.val());
        }
        if (self.phase.q.val() == self.code_times_power.val()) & self.last_step.val() {
            self.phase.d.next = self.code_idle.val();
            self.result.d.next = self.duty_word.val();
        }
        if (self.phase.q.val() == self.code_idle.val()) & self.load.val() {
            self.phase.d.next = self.code_square_a.val();
            self.seq.d.next = self.zero_seq.val();
            self.product_hi.d.next = self.zero_h.val();
            self.multiplicand.d.next = bit_cast::<H, 17>(self.magnitude_a.val());
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
        // The counter is kept one ahead (count_ahead = counter + 1), so
        // that the wrap and the pulse's end each take one compare of
        // registers and inputs, side by side, not an increment, a mux and
        // a compare in a row.
        self.count_ahead.next = self.count_ahead_stored.q.val() ^ self.one_17.val();
        self.wrap.next = !self.running.val()
            | (self.count_ahead.val() >= bit_cast::<17, R>(self.pwm_period.val()));
        self.count_ahead_next.next = self.count_ahead.val() + self.one_17.val();
        if self.wrap.val() {
            self.count_ahead_next.next = self.one_17.val();
        }
        self.duty_next.next = self.target_duty.val();
        if self.kill.val() {
            self.duty_next.next = self.zero_r.val();
        }
        // The counter's next value is 0 at a wrap (at or past a duty of 0
        // only), count_ahead otherwise.
        self.ended_next.next = self.ended.q.val()
            | (self.count_ahead.val() >= bit_cast::<17, R>(self.duty_next.val()));
        if self.wrap.val() {
            self.ended_next.next = self.duty_next.val() == self.zero_r.val();
        }
        self.count_ahead_stored.d.next = self.count_ahead_next.val() ^ self.one_17.val();
        self.duty_now.d.next = self.duty_next.val();
        self.ended.d.next = self.ended_next.val();
        self.pwm_out.d.next =
            self.enable.val() & !self.kill.val() & self.running.val() & !self.ended_next.val();

        self.divider.reset.next = self.reset.val();
        if self.reset.val() {
            self.count_ahead_stored.d.next = self.zero_17.val();
            self.duty_now.d.next = self.zero_r.val();
            self.ended.d.next = false;
            self.committed.d.next = self.zero_r.val();
            self.pwm_out.d.next = false;
            self.result.d.next = self.zero_r.val();
            self.speed_out.d.next = self.zero_16.val();
            self.phase.d.next = self.code_idle.val();
            self.seq.d.next = self.zero_seq.val();
            self.product_hi.d.next = self.zero_h.val();
            self.product_lo.d.next = self.zero_17.val();
            self.remainder.d.next = self.zero_remainder.val();
            self.multiplicand.d.next = self.zero_h.val();
            self.mplier.d.next = self.zero_17.val();
            self.magnitude_b.d.next = self.zero_17.val();
            self.power_taken.d.next = self.zero_r.val();
            self.feed_taken.d.next = self.zero_f.val();
            self.factor_taken.d.next = self.zero_17.val();
            self.divide_start.d.next = false;
            self.b_last.d.next = false;
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
