//! STOP_CAUSE: why RUN last fell, taken in the clock it falls.
//!
//! Internal to [`super::MotionController`]; the register's behavior is the
//! controller's, modelled by [`super::model`].
//!
//! ## Contract (as the controller uses it)
//! * When RUN falls (`running` and `underrun` or `halt`), the register
//!   takes the cause of that clock, from the next clock on. Of
//!   simultaneous causes the highest code wins (E-stop, drive alarm, limit,
//!   home, watchdog, underrun, stop), and for an axis's cause the lowest
//!   axis that holds it is named in STOP_CAUSE.AXIS.
//! * A held switch cause counts only once the registered abort
//!   (`abort_hold`) is up, as the axes see it.
//! * Reset clears it (CAUSE = none).

use rust_hdl::prelude::*;

use super::registers::{fields, StopCause};

/// STOP_CAUSE of `K` axes. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct StopCauseRegister<const K: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: CAUSE = none.
    pub reset: Signal<In, Bit>,
    /// Per axis: a limit stop is held.
    pub limit_held: Signal<In, Bits<K>>,
    /// Per axis: a drive alarm stop is held.
    pub alarm_held: Signal<In, Bits<K>>,
    /// Per axis: a home stop is held.
    pub home_held: Signal<In, Bits<K>>,
    /// The E-stop is latched.
    pub estop_latched: Signal<In, Bit>,
    /// A stop cause is held (the registered OR of every latch).
    pub abort_hold: Signal<In, Bit>,
    /// The watchdog has expired.
    pub watchdog_expired: Signal<In, Bit>,
    /// RUN is set.
    pub running: Signal<In, Bit>,
    /// A boundary found an empty FIFO.
    pub underrun: Signal<In, Bit>,
    /// RUN is cleared or the run aborted.
    pub halt: Signal<In, Bit>,
    /// STOP_CAUSE.
    pub stop_cause: Signal<Out, Bits<32>>,

    cause: DFF<Bits<32>>,
    cause_now: Signal<Local, Bits<32>>,
    /// STOP_CAUSE.AXIS of the lowest axis holding each cause, in place.
    limit_axis: Signal<Local, Bits<32>>,
    alarm_axis: Signal<Local, Bits<32>>,
    home_axis: Signal<Local, Bits<32>>,
    limit_found: Signal<Local, Bit>,
    alarm_found: Signal<Local, Bit>,
    home_found: Signal<Local, Bit>,
    /// STOP_CAUSE.CAUSE values, in place.
    cause_stop: Constant<Bits<32>>,
    cause_underrun: Constant<Bits<32>>,
    cause_watchdog: Constant<Bits<32>>,
    cause_home: Constant<Bits<32>>,
    cause_limit: Constant<Bits<32>>,
    cause_alarm: Constant<Bits<32>>,
    cause_estop: Constant<Bits<32>>,
    /// STOP_CAUSE.AXIS = k, in place.
    cause_axis: [Constant<Bits<32>>; K],
    zero32: Constant<Bits<32>>,
    zero_k: Constant<Bits<K>>,
    /// Bit k of a K-bit vector.
    axis_bit: [Constant<Bits<K>>; K],
}

impl<const K: usize> Default for StopCauseRegister<K> {
    fn default() -> Self {
        let cause = |c: StopCause| Constant::new(((c as u64) << fields::STOP_CAUSE_CAUSE).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            limit_held: Default::default(),
            alarm_held: Default::default(),
            home_held: Default::default(),
            estop_latched: Default::default(),
            abort_hold: Default::default(),
            watchdog_expired: Default::default(),
            running: Default::default(),
            underrun: Default::default(),
            halt: Default::default(),
            stop_cause: Default::default(),
            cause: Default::default(),
            cause_now: Default::default(),
            limit_axis: Default::default(),
            alarm_axis: Default::default(),
            home_axis: Default::default(),
            limit_found: Default::default(),
            alarm_found: Default::default(),
            home_found: Default::default(),
            cause_stop: cause(StopCause::Stop),
            cause_underrun: cause(StopCause::Underrun),
            cause_watchdog: cause(StopCause::Watchdog),
            cause_home: cause(StopCause::Home),
            cause_limit: cause(StopCause::Limit),
            cause_alarm: cause(StopCause::DriveAlarm),
            cause_estop: cause(StopCause::Estop),
            cause_axis: array_init::array_init(|k| {
                Constant::new(((k as u64) << fields::STOP_CAUSE_AXIS).into())
            }),
            zero32: Constant::new(0u64.into()),
            zero_k: Constant::new(0u64.into()),
            axis_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
        }
    }
}

impl<const K: usize> Logic for StopCauseRegister<K> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, cause);
        self.stop_cause.next = self.cause.q.val();
        self.limit_axis.next = self.zero32.val();
        self.alarm_axis.next = self.zero32.val();
        self.home_axis.next = self.zero32.val();
        self.limit_found.next = false;
        self.alarm_found.next = false;
        self.home_found.next = false;
        // Bits of the K-bit ports by mask, not bit select: at K = 1
        // rust-hdl declares them without a range.
        for i in 0..K {
            if ((self.limit_held.val() & self.axis_bit[i].val()) != self.zero_k.val())
                & !self.limit_found.val()
            {
                self.limit_axis.next = self.cause_axis[i].val();
                self.limit_found.next = true;
            }
            if ((self.alarm_held.val() & self.axis_bit[i].val()) != self.zero_k.val())
                & !self.alarm_found.val()
            {
                self.alarm_axis.next = self.cause_axis[i].val();
                self.alarm_found.next = true;
            }
            if ((self.home_held.val() & self.axis_bit[i].val()) != self.zero_k.val())
                & !self.home_found.val()
            {
                self.home_axis.next = self.cause_axis[i].val();
                self.home_found.next = true;
            }
        }
        self.cause_now.next = self.cause_stop.val();
        if self.underrun.val() {
            self.cause_now.next = self.cause_underrun.val();
        }
        if self.watchdog_expired.val() {
            self.cause_now.next = self.cause_watchdog.val();
        }
        if self.abort_hold.val() & self.home_found.val() {
            self.cause_now.next = self.cause_home.val() | self.home_axis.val();
        }
        if self.abort_hold.val() & self.limit_found.val() {
            self.cause_now.next = self.cause_limit.val() | self.limit_axis.val();
        }
        if self.abort_hold.val() & self.alarm_found.val() {
            self.cause_now.next = self.cause_alarm.val() | self.alarm_axis.val();
        }
        if self.abort_hold.val() & self.estop_latched.val() {
            self.cause_now.next = self.cause_estop.val();
        }
        if self.running.val() & (self.underrun.val() | self.halt.val()) {
            self.cause.d.next = self.cause_now.val();
        }
        if self.reset.val() {
            self.cause.d.next = self.zero32.val();
        }
    }
}
