//! The feed hold's velocity factor and the tick gate it drives.
//!
//! A controlled stop along the path scales time, not steps: every axis's
//! interpolator, the period counter and so the FIFOs' consumption run on
//! the *gated* base tick, which passes a fraction `factor / UNITY` of the
//! base ticks. Each interpolator emits exactly its steps per period
//! whatever the spacing of its ticks, so a hold changes when steps leave,
//! never how many, on every axis alike: the path slows along itself and
//! ends where it would have ended without the hold, and no axis steps
//! faster than it did before (a gated tick is at most one per base tick).
//!
//! ## Ports
//!
//! | port | dir | width | meaning |
//! |---|---|---|---|
//! | `clock` | in | 1 | rising-edge clock |
//! | `reset` | in | 1 | synchronous: `factor` = [`UNITY`], `phase` 0 (also the power-up state) |
//! | `tick` | in | 1 | the base tick (one clock in `TICK_DIVISOR`) |
//! | `hold` | in | 1 | a hold is requested: ramp the factor down to 0; else up to [`UNITY`] |
//! | `rate` | in | 16 | factor change per base tick, in 1/[`UNITY`]; 0 acts as [`UNITY`] (no ramp: the factor goes to 0 or [`UNITY`] at the next tick) |
//! | `tick_out` | out | 1 | the gated tick, combinational: `tick` and `phase` + `factor` >= [`UNITY`] |
//! | `factor` | out | 17 | the factor, 0 to [`UNITY`] (registered) |
//! | `phase` | out | 16 | the carried fraction of a gated tick, in 1/[`UNITY`] (registered) |
//! | `slowed` | out | 1 | `factor` < [`UNITY`]: decelerating, held or ramping back |
//! | `stopped` | out | 1 | `factor` = 0 |
//!
//! ## Timing
//! In a clock with `tick` high, with the factor f and the phase p of that
//! clock: `tick_out` = 1 iff p + f >= [`UNITY`]; the phase becomes
//! (p + f) mod [`UNITY`] (the fraction is carried: after any ticks since
//! reset, [`UNITY`] x the gated ticks + `phase` = the sum of f over those
//! ticks, exactly); then the factor moves one step of `rate` toward 0
//! (`hold`) or [`UNITY`], clamped. So `hold` raised in clock c first
//! lowers the factor at the first tick from c on, and that tick's gate
//! still uses the old factor: the first reduced tick is the one after.
//! Between ticks nothing changes. At [`UNITY`] every tick passes in its
//! own clock, so an unheld controller runs clock for clock as without the
//! gate.
//!
//! The factor changes by at most `rate` per base tick: a deceleration of
//! `rate` / [`UNITY`] of the programmed speed per tick; from full speed
//! the stop takes ceil([`UNITY`] / `rate`) ticks, and so does the return.
//!
//! ## Formal proof
//! `formal/motion_controller_hold_ramp.sv` (`motion-hdl prove --proof
//! motion_controller_hold_ramp`), with every input free: `tick_out` only
//! with `tick`, so the gate never creates a tick, and so never a step;
//! none at f = 0, every tick at f = [`UNITY`]; the carried fraction
//! p' + [`UNITY`] x `tick_out` = p + f at every tick; the factor's exact
//! step of `rate` per tick, clamped, and nothing between ticks. The
//! mutations of a gate that creates a tick, a lost fraction and a ramp
//! twice too steep each fail it (`tests/formal/motion_controller.rs`).
//!
//! Inside, the register is the deficit d = [`UNITY`] - f, so that the
//! power-up state (all zero) is full speed: the tick passes iff p >= d,
//! and the phase becomes p - d modulo 2^16.

use rust_hdl::prelude::*;

/// Width of the factor's fraction: the factor is a 17-bit number, 0 to
/// [`UNITY`] = 2^16.
pub const FACTOR_FRACTION_BITS: usize = 16;

/// The factor 1: every tick passes.
pub const UNITY: u32 = 1 << FACTOR_FRACTION_BITS;

// The RTL takes the sum's bit 16 as "reached UNITY", and RATE is 16 bits.
const _: () = assert!(FACTOR_FRACTION_BITS == 16);

/// The hold ramp. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct HoldRamp {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// The base tick.
    pub tick: Signal<In, Bit>,
    /// Ramp down (1) or up (0).
    pub hold: Signal<In, Bit>,
    /// Factor change per tick; 0 acts as `UNITY`.
    pub rate: Signal<In, Bits<16>>,
    /// The gated tick.
    pub tick_out: Signal<Out, Bit>,
    /// The factor, 0 to `UNITY`.
    pub factor: Signal<Out, Bits<17>>,
    /// The carried fraction.
    pub phase: Signal<Out, Bits<16>>,
    /// The factor is below `UNITY`.
    pub slowed: Signal<Out, Bit>,
    /// The factor is 0.
    pub stopped: Signal<Out, Bit>,

    deficit: DFF<Bits<17>>,
    fraction: DFF<Bits<16>>,
    rate_is_zero: Signal<Local, Bit>,
    rate17: Signal<Local, Bits<17>>,
    sum: Signal<Local, Bits<17>>,
    unity: Constant<Bits<17>>,
    zero16: Constant<Bits<16>>,
    zero17: Constant<Bits<17>>,
}

impl Default for HoldRamp {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            tick: Default::default(),
            hold: Default::default(),
            rate: Default::default(),
            tick_out: Default::default(),
            factor: Default::default(),
            phase: Default::default(),
            slowed: Default::default(),
            stopped: Default::default(),
            deficit: Default::default(),
            fraction: Default::default(),
            rate_is_zero: Default::default(),
            rate17: Default::default(),
            sum: Default::default(),
            unity: Constant::new((UNITY as u64).into()),
            zero16: Constant::new(0u64.into()),
            zero17: Constant::new(0u64.into()),
        }
    }
}

impl Logic for HoldRamp {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, deficit, fraction);

        // RATE 0 (a full step) is decided beside the adders, not by muxing
        // 65536 into them: the deficit goes to its bound whatever the sums.
        self.rate_is_zero.next = self.rate.val() == self.zero16.val();
        self.rate17.next = bit_cast::<17, 16>(self.rate.val());
        // deficit <= 65536 and rate < 65536: the sum fits 17 bits, and it
        // reaches 65536 (the full deficit) exactly when its bit 16 is set.
        self.sum.next = self.deficit.q.val() + self.rate17.val();
        self.tick_out.next =
            self.tick.val() & (bit_cast::<17, 16>(self.fraction.q.val()) >= self.deficit.q.val());
        if self.tick.val() {
            self.fraction.d.next = self.fraction.q.val() - self.deficit.q.val().get_bits::<16>(0);
            if self.hold.val() {
                if self.sum.val().get_bit(16) | self.rate_is_zero.val() {
                    self.deficit.d.next = self.unity.val();
                } else {
                    self.deficit.d.next = self.sum.val();
                }
            } else if (self.deficit.q.val() > self.rate17.val()) & !self.rate_is_zero.val() {
                self.deficit.d.next = self.deficit.q.val() - self.rate17.val();
            } else {
                self.deficit.d.next = self.zero17.val();
            }
        }
        if self.reset.val() {
            self.deficit.d.next = self.zero17.val();
            self.fraction.d.next = self.zero16.val();
        }
        self.factor.next = self.unity.val() - self.deficit.q.val();
        self.phase.next = self.fraction.q.val();
        self.slowed.next = self.deficit.q.val() != self.zero17.val();
        self.stopped.next = self.deficit.q.val() == self.unity.val();
    }
}

/// The inputs of one clock of [`HoldRampModel`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HoldRampInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// The base tick.
    pub tick: bool,
    /// Ramp down.
    pub hold: bool,
    /// Factor change per tick (16 bits; 0 acts as [`UNITY`]).
    pub rate: u16,
}

/// The outputs of one clock of [`HoldRampModel`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HoldRampOutputs {
    /// The gated tick.
    pub tick_out: bool,
    /// The factor, 0 to [`UNITY`].
    pub factor: u32,
    /// The carried fraction, 0 to [`UNITY`] - 1.
    pub phase: u32,
    /// The factor is below [`UNITY`].
    pub slowed: bool,
    /// The factor is 0.
    pub stopped: bool,
}

/// Reference model of [`HoldRamp`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HoldRampModel {
    factor: u32,
    phase: u32,
}

impl Default for HoldRampModel {
    fn default() -> Self {
        Self {
            factor: UNITY,
            phase: 0,
        }
    }
}

impl HoldRampModel {
    /// A ramp at `factor` (clamped to [`UNITY`]) with no fraction carried.
    pub fn with_factor(factor: u32) -> Self {
        Self {
            factor: factor.min(UNITY),
            phase: 0,
        }
    }

    /// The factor now, 0 to [`UNITY`].
    pub fn factor(&self) -> u32 {
        self.factor
    }

    /// The carried fraction of a gated tick now, 0 to [`UNITY`] - 1.
    pub fn phase(&self) -> u32 {
        self.phase
    }

    /// Whether a base tick passes the gate now (`tick_out` in this clock,
    /// before its edge).
    pub fn gate(&self, tick: bool) -> bool {
        tick && self.phase + self.factor >= UNITY
    }

    /// One clock; returns the outputs after its edge (`tick_out` of the
    /// new state with the same inputs).
    pub fn step(&mut self, i: HoldRampInputs) -> HoldRampOutputs {
        let step = if i.rate == 0 { UNITY } else { i.rate as u32 };
        if i.tick {
            self.phase = (self.phase + self.factor) % UNITY;
            self.factor = if i.hold {
                self.factor.saturating_sub(step)
            } else {
                (self.factor + step).min(UNITY)
            };
        }
        if i.reset {
            *self = Self::default();
        }
        HoldRampOutputs {
            tick_out: self.gate(i.tick),
            factor: self.factor,
            phase: self.phase,
            slowed: self.factor != UNITY,
            stopped: self.factor == 0,
        }
    }
}

crate::vector_ports!(impl[] HoldRamp {
    inputs: [reset, tick, hold, rate],
    outputs: [tick_out, factor, phase, slowed, stopped],
});

impl HoldRampInputs {
    /// The input vector, in `HoldRamp`'s input order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.tick as u64,
            self.hold as u64,
            self.rate as u64,
        ]
    }
}

impl HoldRampOutputs {
    /// The outputs from `HoldRamp`'s output vector.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            tick_out: v[0] != 0,
            factor: v[1] as u32,
            phase: v[2] as u32,
            slowed: v[3] != 0,
            stopped: v[4] != 0,
        }
    }
}

impl crate::sim::LockstepModel for HoldRampModel {
    type Inputs = HoldRampInputs;
    type Outputs = HoldRampOutputs;
    fn input_vector(inputs: &HoldRampInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> HoldRampOutputs {
        HoldRampOutputs::from_vector(vector)
    }
    fn expected(&mut self, inputs: &HoldRampInputs) -> HoldRampOutputs {
        self.step(*inputs)
    }
}
