//! The probe trigger: the `probe` input's conditioner, `PROBE_CONTROL`, and
//! the one-clock strobe that makes every axis latch its positions.
//!
//! Internal to [`super::MotionController`]; the behavior is specified in
//! [`super`] ("Probe") and modelled by [`super::io_model::ProbeModel`].
//!
//! The input passes an [`InputConditioner`] with the machine I/O's filter
//! sample and length (`INPUT_FILTER`), so it is acted on
//! [`super::latency::switch`] clocks after the pin, like a home switch. The
//! trip is decided against the armed state *after* a `PROBE_CONTROL` write
//! of the same clock: a write that arms in the clock of an edge trips at
//! once, and one that disarms misses it.

use rust_hdl::prelude::*;

use super::registers::{fields, global};
use crate::blocks::input_conditioner::InputConditioner;

// PROBE_CONTROL's writable bits are the written word's low three, taken
// by literal index.
const _: () = assert!(fields::PROBE_ARM == 0 && fields::PROBE_EDGE == 1 && fields::PROBE_STOP == 2);

/// The probe trigger. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct ProbeTrigger {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Pin: the probe, asynchronous.
    pub probe: Signal<In, Bit>,
    /// The machine I/O's filter sample strobe.
    pub sample: Signal<In, Bit>,
    /// `INPUT_FILTER.LENGTH`.
    pub length: Signal<In, Bits<4>>,
    /// Bus word address.
    pub address: Signal<In, Bits<8>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data, bits 2..0: `PROBE_CONTROL.STOP`, `EDGE` and `ARM`.
    pub write_data: Signal<In, Bits<3>>,
    /// The probe trips in this clock: every axis latches its positions.
    pub latch: Signal<Out, Bit>,
    /// The trip requests the feed hold (`PROBE_CONTROL.STOP`).
    pub stop: Signal<Out, Bit>,
    /// `PROBE_CONTROL` when addressed, else 0.
    pub read_data: Signal<Out, Bits<32>>,

    conditioner: InputConditioner<1>,
    armed: DFF<Bit>,
    falling: DFF<Bit>,
    stop_on_trip: DFF<Bit>,
    tripped: DFF<Bit>,

    control_write: Signal<Local, Bit>,
    armed_now: Signal<Local, Bit>,
    falling_now: Signal<Local, Bit>,
    stop_now: Signal<Local, Bit>,
    hit: Signal<Local, Bit>,
    trip: Signal<Local, Bit>,

    a_control: Constant<Bits<8>>,
    m_arm: Constant<Bits<32>>,
    m_edge: Constant<Bits<32>>,
    m_stop: Constant<Bits<32>>,
    m_tripped: Constant<Bits<32>>,
    m_level: Constant<Bits<32>>,
    zero1: Constant<Bits<1>>,
    zero32: Constant<Bits<32>>,
}

impl Default for ProbeTrigger {
    fn default() -> Self {
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            probe: Default::default(),
            sample: Default::default(),
            length: Default::default(),
            address: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            latch: Default::default(),
            stop: Default::default(),
            read_data: Default::default(),
            conditioner: Default::default(),
            armed: Default::default(),
            falling: Default::default(),
            stop_on_trip: Default::default(),
            tripped: Default::default(),
            control_write: Default::default(),
            armed_now: Default::default(),
            falling_now: Default::default(),
            stop_now: Default::default(),
            hit: Default::default(),
            trip: Default::default(),
            a_control: Constant::new((global::PROBE_CONTROL as u64).into()),
            m_arm: m32(fields::PROBE_ARM),
            m_edge: m32(fields::PROBE_EDGE),
            m_stop: m32(fields::PROBE_STOP),
            m_tripped: m32(fields::PROBE_TRIPPED),
            m_level: m32(fields::PROBE_LEVEL),
            zero1: Constant::new(0u64.into()),
            zero32: Constant::new(0u64.into()),
        }
    }
}

impl Logic for ProbeTrigger {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, armed, falling, stop_on_trip, tripped);
        clock!(self, clock, conditioner);

        self.conditioner.reset.next = self.reset.val();
        self.conditioner.raw.next = self.zero1.val();
        if self.probe.val() {
            self.conditioner.raw.next = !self.zero1.val();
        }
        self.conditioner.invert.next = self.zero1.val();
        self.conditioner.sample.next = self.sample.val();
        self.conditioner.length.next = self.length.val();

        // A write of this clock decides the armed state and the edge.
        self.control_write.next = self.write.val() & (self.address.val() == self.a_control.val());
        self.armed_now.next = self.armed.q.val();
        self.falling_now.next = self.falling.q.val();
        self.stop_now.next = self.stop_on_trip.q.val();
        if self.control_write.val() {
            self.armed_now.next = self.write_data.val().get_bit(0);
            self.falling_now.next = self.write_data.val().get_bit(1);
            self.stop_now.next = self.write_data.val().get_bit(2);
        }
        self.hit.next = self.conditioner.rise.val() != self.zero1.val();
        if self.falling_now.val() {
            self.hit.next = self.conditioner.fall.val() != self.zero1.val();
        }
        // The first edge after arming trips, and the trip disarms.
        self.trip.next = self.armed_now.val() & self.hit.val();
        self.latch.next = self.trip.val();
        self.stop.next = self.trip.val() & self.stop_now.val();
        self.armed.d.next = self.armed_now.val() & !self.trip.val();
        self.falling.d.next = self.falling_now.val();
        self.stop_on_trip.d.next = self.stop_now.val();
        if self.control_write.val() & self.write_data.val().get_bit(0) {
            self.tripped.d.next = false;
        }
        if self.trip.val() {
            self.tripped.d.next = true;
        }
        if self.reset.val() {
            self.armed.d.next = false;
            self.falling.d.next = false;
            self.stop_on_trip.d.next = false;
            self.tripped.d.next = false;
        }

        self.read_data.next = self.zero32.val();
        if self.address.val() == self.a_control.val() {
            if self.armed.q.val() {
                self.read_data.next = self.read_data.val() | self.m_arm.val();
            }
            if self.falling.q.val() {
                self.read_data.next = self.read_data.val() | self.m_edge.val();
            }
            if self.stop_on_trip.q.val() {
                self.read_data.next = self.read_data.val() | self.m_stop.val();
            }
            if self.tripped.q.val() {
                self.read_data.next = self.read_data.val() | self.m_tripped.val();
            }
            if self.conditioner.active.val() != self.zero1.val() {
                self.read_data.next = self.read_data.val() | self.m_level.val();
            }
        }
    }
}
