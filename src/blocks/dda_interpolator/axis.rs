//! One axis of the [`super::DdaInterpolator`]: the staged, pending and
//! active step commands, the DDA that spreads the remainder, and the
//! position fraction that produces steps.

use rust_hdl::prelude::*;

use crate::blocks::dda_integrator::DdaIntegrator;

/// Width of the per-tick integer step part q, two's complement. |q| <= 2^16
/// (one step per tick), so 18 bits hold it with its sign.
pub const Q_BITS: usize = 18;

/// Width of the period length P in ticks (and of the remainder r < P).
pub const PERIOD_BITS: usize = 24;

/// One axis of the interpolator (an internal block; its ports are the
/// interpolator's internal interface, not a user contract).
#[derive(Clone, Debug, LogicBlock)]
pub struct InterpolatorAxis {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Latch `delta` as this axis's staged command.
    pub stage: Signal<In, Bit>,
    /// Signed Q16.16 steps for the next period.
    pub delta: Signal<In, Bits<32>>,
    /// |staged delta|, the divider's dividend.
    pub magnitude: Signal<Out, Bits<32>>,
    /// Store the divider's result for the staged delta into the pending slot.
    pub write_result: Signal<In, Bit>,
    /// |delta| / P from the divider, low bits (clamped results are not used).
    pub quotient: Signal<In, Bits<Q_BITS>>,
    /// |delta| % P from the divider (< P, so PERIOD_BITS wide).
    pub remainder: Signal<In, Bits<PERIOD_BITS>>,
    /// The staged period P (for the remainder of a negative delta).
    pub staged_period: Signal<In, Bits<PERIOD_BITS>>,
    /// The result exceeds one step per tick: write the clamped command.
    pub clamp: Signal<In, Bit>,
    /// Move the pending command to the active one.
    pub commit: Signal<In, Bit>,
    /// Process one tick of the active period.
    pub tick: Signal<In, Bit>,
    /// The active period P, the DDA modulus.
    pub active_period: Signal<In, Bits<PERIOD_BITS>>,
    /// One-clock step pulse.
    pub step: Signal<Out, Bit>,
    /// Direction of the last step: 1 = positive.
    pub dir: Signal<Out, Bit>,
    /// |staged delta| and its sign, taken apart when the command is staged
    /// so that the divider's operand comes straight from a register.
    staged_magnitude: DFF<Bits<32>>,
    staged_negative: DFF<Bit>,
    pending_q: DFF<Bits<Q_BITS>>,
    pending_r: DFF<Bits<PERIOD_BITS>>,
    active_q: DFF<Bits<Q_BITS>>,
    active_r: DFF<Bits<PERIOD_BITS>>,
    /// The tick's q, delayed to meet the DDA's 2-clock pulse latency.
    q_stage1: DFF<Bits<Q_BITS>>,
    q_stage2: DFF<Bits<Q_BITS>>,
    /// q + 1, ready beside q: the DDA's extra unit then only selects the
    /// addend, and the fraction update is a single carry chain.
    q_plus_one_stage2: DFF<Bits<Q_BITS>>,
    tick_stage1: DFF<Bit>,
    tick_stage2: DFF<Bit>,
    tick_stage3: DFF<Bit>,
    /// The last position update: fraction + q (+1), 18 bits. Bits 15..0 are
    /// the position fraction in 2^-16 steps; bit 16 set means a step, bit 17
    /// set means it was down. Registering the whole sum keeps the step
    /// decision off the adder's path.
    fraction: DFF<Bits<Q_BITS>>,
    step_reg: DFF<Bit>,
    dir_reg: DFF<Bit>,
    remainder_dda: DdaIntegrator<PERIOD_BITS>,
    negative: Signal<Local, Bit>,
    next_fraction: Signal<Local, Bits<Q_BITS>>,
    addend: Signal<Local, Bits<Q_BITS>>,
    zero: Constant<Bits<32>>,
    zero_r: Constant<Bits<PERIOD_BITS>>,
    sign32: Constant<Bits<32>>,
    zero_q: Constant<Bits<Q_BITS>>,
    one_q: Constant<Bits<Q_BITS>>,
    clamp_q: Constant<Bits<Q_BITS>>,
    clamp_q_negative: Constant<Bits<Q_BITS>>,
    fraction_mask: Constant<Bits<Q_BITS>>,
    bit16: Constant<Bits<Q_BITS>>,
    bit17: Constant<Bits<Q_BITS>>,
}

impl Default for InterpolatorAxis {
    fn default() -> Self {
        let q_mask = (1u64 << Q_BITS) - 1;
        Self {
            clock: Default::default(),
            reset: Default::default(),
            stage: Default::default(),
            delta: Default::default(),
            magnitude: Default::default(),
            write_result: Default::default(),
            quotient: Default::default(),
            remainder: Default::default(),
            staged_period: Default::default(),
            clamp: Default::default(),
            commit: Default::default(),
            tick: Default::default(),
            active_period: Default::default(),
            step: Default::default(),
            dir: Default::default(),
            staged_magnitude: Default::default(),
            staged_negative: Default::default(),
            pending_q: Default::default(),
            pending_r: Default::default(),
            active_q: Default::default(),
            active_r: Default::default(),
            q_stage1: Default::default(),
            q_stage2: Default::default(),
            q_plus_one_stage2: Default::default(),
            tick_stage1: Default::default(),
            tick_stage2: Default::default(),
            tick_stage3: Default::default(),
            fraction: Default::default(),
            step_reg: Default::default(),
            dir_reg: Default::default(),
            remainder_dda: Default::default(),
            negative: Default::default(),
            next_fraction: Default::default(),
            addend: Default::default(),
            zero: Constant::new(0u64.into()),
            zero_r: Constant::new(0u64.into()),
            sign32: Constant::new((1u64 << 31).into()),
            zero_q: Constant::new(0u64.into()),
            one_q: Constant::new(1u64.into()),
            clamp_q: Constant::new((1u64 << 16).into()),
            clamp_q_negative: Constant::new((((1u64 << Q_BITS) - (1u64 << 16)) & q_mask).into()),
            fraction_mask: Constant::new(0xffffu64.into()),
            bit16: Constant::new((1u64 << 16).into()),
            bit17: Constant::new((1u64 << 17).into()),
        }
    }
}

impl Logic for InterpolatorAxis {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            staged_magnitude,
            staged_negative,
            pending_q,
            pending_r,
            active_q,
            active_r,
            q_stage1,
            q_stage2,
            q_plus_one_stage2,
            tick_stage1,
            tick_stage2,
            tick_stage3,
            fraction,
            step_reg,
            dir_reg
        );
        self.remainder_dda.clock.next = self.clock.val();
        self.remainder_dda.reset.next = self.reset.val();
        self.remainder_dda.clear_overrange.next = false;
        self.step.next = self.step_reg.q.val();
        self.dir.next = self.dir_reg.q.val();

        // Staging and the divider's operand.
        if self.stage.val() {
            self.staged_negative.d.next = (self.delta.val() & self.sign32.val()) != self.zero.val();
            self.staged_magnitude.d.next = self.delta.val();
            if (self.delta.val() & self.sign32.val()) != self.zero.val() {
                self.staged_magnitude.d.next = self.zero.val() - self.delta.val();
            }
        }
        self.negative.next = self.staged_negative.q.val();
        self.magnitude.next = self.staged_magnitude.q.val();

        // Result: |d| = q'P + r'. More than one step per tick is clamped.
        if self.write_result.val() {
            if self.clamp.val() {
                self.pending_r.d.next = self.zero_r.val();
                if self.negative.val() {
                    self.pending_q.d.next = self.clamp_q_negative.val();
                } else {
                    self.pending_q.d.next = self.clamp_q.val();
                }
            } else if !self.negative.val() {
                self.pending_q.d.next = self.quotient.val();
                self.pending_r.d.next = self.remainder.val();
            } else if self.remainder.val() == self.zero_r.val() {
                // d = -q'P: q = -q', r = 0.
                self.pending_q.d.next = self.zero_q.val() - self.quotient.val();
                self.pending_r.d.next = self.zero_r.val();
            } else {
                // d = -(q'+1)P + (P - r'): floor division, 0 <= r < P.
                self.pending_q.d.next = !self.quotient.val();
                self.pending_r.d.next = self.staged_period.val() - self.remainder.val();
            }
        }
        if self.commit.val() {
            self.active_q.d.next = self.pending_q.q.val();
            self.active_r.d.next = self.pending_r.q.val();
        }

        // Per tick: the DDA spreads r over the P ticks (one extra 2^-16 step
        // per overflow); q is added on every tick. The DDA answers 2 clocks
        // after its tick, so the tick and its q are delayed to meet it.
        self.remainder_dda.tick.next = self.tick.val();
        self.remainder_dda.integrand.next = self.active_r.q.val();
        self.remainder_dda.modulus.next = self.active_period.val();
        self.tick_stage1.d.next = self.tick.val();
        self.tick_stage2.d.next = self.tick_stage1.q.val();
        self.q_stage1.d.next = self.active_q.q.val();
        self.q_stage2.d.next = self.q_stage1.q.val();
        self.q_plus_one_stage2.d.next = self.q_stage1.q.val() + self.one_q.val();
        self.addend.next = self.q_stage2.q.val();
        if self.remainder_dda.pulse.val() {
            self.addend.next = self.q_plus_one_stage2.q.val();
        }
        // fraction in [0, 2^16), q + extra in [-2^16, 2^16]: the 18-bit sum
        // lies in [-2^16, 2^17), so bit 16 says "step" and bit 17 "down".
        self.next_fraction.next =
            (self.fraction.q.val() & self.fraction_mask.val()) + self.addend.val();
        if self.tick_stage2.q.val() {
            self.fraction.d.next = self.next_fraction.val();
        }
        self.tick_stage3.d.next = self.tick_stage2.q.val();
        self.step_reg.d.next = false;
        if self.tick_stage3.q.val()
            & ((self.fraction.q.val() & self.bit16.val()) != self.zero_q.val())
        {
            self.step_reg.d.next = true;
            self.dir_reg.d.next = (self.fraction.q.val() & self.bit17.val()) == self.zero_q.val();
        }
        if self.reset.val() {
            self.staged_magnitude.d.next = self.zero.val();
            self.staged_negative.d.next = false;
            self.pending_q.d.next = self.zero_q.val();
            self.pending_r.d.next = self.zero_r.val();
            self.active_q.d.next = self.zero_q.val();
            self.active_r.d.next = self.zero_r.val();
            self.tick_stage1.d.next = false;
            self.tick_stage2.d.next = false;
            self.tick_stage3.d.next = false;
            self.fraction.d.next = self.zero_q.val();
            self.step_reg.d.next = false;
            self.dir_reg.d.next = false;
        }
    }
}
