//! The feed hold: the `feed_hold` input's conditioner, `HOLD_CONTROL`, the
//! hold request, and the [`HoldRamp`] whose gated tick paces the periods
//! and the axes.
//!
//! Internal to [`super::MotionController`]; the behavior is specified in
//! [`super`] ("Feed hold") and modelled by
//! [`super::io_model::FeedHoldModel`].
//!
//! The request is sticky: the filtered `feed_hold` input (while active),
//! a `HOLD_CONTROL` write with `HOLD` = 1, a probe trip with
//! `PROBE_CONTROL.STOP`, or a soft-limit verdict (while beyond) set it; only a write with `RELEASE` = 1 (and
//! `HOLD` = 0) clears it, and not while one of the others sets it in the
//! same clock. The ramp follows the registered request and rate (what
//! `HOLD_CONTROL.REQUESTED` and `RATE` read), so a hold requested in
//! clock c lowers the factor at the first base tick from c + 1 on, at the
//! rate written with it. The register between them keeps the bus decode
//! and the pin's conditioner out of the ramp's adders (on the iCE40 this
//! path, unregistered, set the controller's Fmax).

use rust_hdl::prelude::*;

use super::hold_ramp::HoldRamp;
use super::registers::{fields, global};
use crate::blocks::input_conditioner::InputConditioner;

// HOLD_CONTROL's single-bit fields are taken by literal index, its rate
// by a slice at this position.
const _: () = assert!(
    fields::HOLD_HOLD == 0
        && fields::HOLD_RELEASE == 1
        && fields::HOLD_INVERT == 2
        && fields::HOLD_RATE == 16
        && fields::HOLD_RATE_WIDTH == 16
);

/// The feed hold. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct FeedHold {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Pin: the feed hold request, asynchronous.
    pub feed_hold: Signal<In, Bit>,
    /// The machine I/O's filter sample strobe.
    pub sample: Signal<In, Bit>,
    /// `INPUT_FILTER.LENGTH`.
    pub length: Signal<In, Bits<4>>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data.
    pub write_data: Signal<In, Bits<32>>,
    /// A probe trip with `PROBE_CONTROL.STOP`: request the hold.
    pub probe_stop: Signal<In, Bit>,
    /// A soft-limit verdict is beyond: request the hold (a level: a
    /// release is refused while it lasts).
    pub soft_stop: Signal<In, Bit>,
    /// The base tick.
    pub tick: Signal<In, Bit>,
    /// The gated tick (combinational from `tick`).
    pub tick_out: Signal<Out, Bit>,
    /// `STATE.HOLDING`: the factor is below 1.
    pub holding: Signal<Out, Bit>,
    /// `STATE.HELD`: the factor is 0.
    pub held: Signal<Out, Bit>,
    /// The velocity factor's 16 fraction bits (the factor itself while
    /// `holding`; 0 at 1.0).
    pub factor_fraction: Signal<Out, Bits<16>>,
    /// The velocity factor, 0 to 2^16 (1.0).
    pub factor: Signal<Out, Bits<17>>,
    /// `HOLD_CONTROL` when addressed, else 0.
    pub read_data: Signal<Out, Bits<32>>,
    /// `HOLD_CONTROL.RATE` as the ramp uses it (registered).
    pub rate_out: Signal<Out, Bits<16>>,

    conditioner: InputConditioner<1>,
    ramp: HoldRamp,
    requested: DFF<Bit>,
    invert: DFF<Bit>,
    rate: DFF<Bits<16>>,

    control_write: Signal<Local, Bit>,
    input_active: Signal<Local, Bit>,
    set: Signal<Local, Bit>,
    request_now: Signal<Local, Bit>,

    a_control: Constant<Bits<8>>,
    m_requested: Constant<Bits<32>>,
    m_invert: Constant<Bits<32>>,
    m_input: Constant<Bits<32>>,
    zero1: Constant<Bits<1>>,
    zero16: Constant<Bits<16>>,
    zero32: Constant<Bits<32>>,
}

impl Default for FeedHold {
    fn default() -> Self {
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            feed_hold: Default::default(),
            sample: Default::default(),
            length: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            probe_stop: Default::default(),
            soft_stop: Default::default(),
            tick: Default::default(),
            tick_out: Default::default(),
            holding: Default::default(),
            held: Default::default(),
            factor_fraction: Default::default(),
            factor: Default::default(),
            read_data: Default::default(),
            rate_out: Default::default(),
            conditioner: Default::default(),
            ramp: Default::default(),
            requested: Default::default(),
            invert: Default::default(),
            rate: Default::default(),
            control_write: Default::default(),
            input_active: Default::default(),
            set: Default::default(),
            request_now: Default::default(),
            a_control: Constant::new((global::HOLD_CONTROL as u64).into()),
            m_requested: m32(fields::HOLD_REQUESTED),
            m_invert: m32(fields::HOLD_INVERT),
            m_input: m32(fields::HOLD_INPUT),
            zero1: Constant::new(0u64.into()),
            zero16: Constant::new(0u64.into()),
            zero32: Constant::new(0u64.into()),
        }
    }
}

impl Logic for FeedHold {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, requested, invert, rate);
        clock!(self, clock, conditioner, ramp);

        self.conditioner.reset.next = self.reset.val();
        self.conditioner.raw.next = self.zero1.val();
        if self.feed_hold.val() {
            self.conditioner.raw.next = !self.zero1.val();
        }
        self.conditioner.invert.next = self.zero1.val();
        if self.invert.q.val() {
            self.conditioner.invert.next = !self.zero1.val();
        }
        self.conditioner.sample.next = self.sample.val();
        self.conditioner.length.next = self.length.val();
        self.input_active.next = self.conditioner.active.val() != self.zero1.val();

        self.control_write.next = self.write.val() & (self.address.val() == self.a_control.val());
        if self.control_write.val() {
            self.invert.d.next = self.write_data.val().get_bit(2);
            self.rate.d.next = self.write_data.val().get_bits::<16>(16);
        }
        // The request of this clock: set by the input, HOLD or a probe
        // stop; cleared by RELEASE unless one of them sets it.
        self.set.next = self.input_active.val()
            | self.probe_stop.val()
            | self.soft_stop.val()
            | (self.control_write.val() & self.write_data.val().get_bit(0));
        self.request_now.next = self.requested.q.val();
        if self.control_write.val() & self.write_data.val().get_bit(1) {
            self.request_now.next = false;
        }
        if self.set.val() {
            self.request_now.next = true;
        }
        self.requested.d.next = self.request_now.val();
        if self.reset.val() {
            self.requested.d.next = false;
            self.invert.d.next = false;
            self.rate.d.next = self.zero16.val();
        }

        self.ramp.reset.next = self.reset.val();
        self.ramp.tick.next = self.tick.val();
        self.ramp.hold.next = self.requested.q.val();
        self.ramp.rate.next = self.rate.q.val();
        self.rate_out.next = self.rate.q.val();
        self.tick_out.next = self.ramp.tick_out.val();
        self.holding.next = self.ramp.slowed.val();
        self.held.next = self.ramp.stopped.val();
        self.factor_fraction.next = self.ramp.factor.val().get_bits::<16>(0);
        self.factor.next = self.ramp.factor.val();

        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_control.val() {
            self.read_data.next = bit_cast::<32, 16>(self.rate.q.val()) << 16;
            if self.requested.q.val() {
                self.read_data.next = self.read_data.val() | self.m_requested.val();
            }
            if self.invert.q.val() {
                self.read_data.next = self.read_data.val() | self.m_invert.val();
            }
            if self.input_active.val() {
                self.read_data.next = self.read_data.val() | self.m_input.val();
            }
        }
    }
}
