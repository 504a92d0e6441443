//! The merge of an axis's gearbox steps with its interpolator's, in front
//! of the axis's request register (build option `SPINDLE`).
//!
//! Internal to [`super::axis::MotionAxis`]; the behavior is specified in
//! [`super`] ("Spindle encoder and electronic gearbox") and modelled by
//! [`GearMergeModel`].
//!
//! The request register takes one step a clock. The interpolator's step
//! has the clock; a gearbox step that meets one waits in a hold of one and
//! goes in the next clock without an interpolator step (a held step goes
//! before a new gearbox step, which then waits in turn). A gearbox step
//! that finds the hold full and the interpolator stepping, or that comes
//! to an analog axis, is lost and raises `lost` (sticky, the axis's
//! `STEP_OVERRUN`): gearbox steps are at least 31 clocks apart, so that
//! takes an interpolator stepping in every one of 31 clocks (a DDA at one
//! step per tick with `TICK_DIVISOR` 1). An abort empties the hold: the
//! held step never left, as the output stage's flushed ones.

use rust_hdl::prelude::*;

/// The merge. See the [module documentation](self).
#[derive(LogicBlock, Default)]
pub struct GearMerge {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// The interpolator offers a step in this clock.
    pub interp: Signal<In, Bit>,
    /// Its direction: 1 = forward.
    pub interp_forward: Signal<In, Bit>,
    /// A gearbox step for this axis in this clock.
    pub gear: Signal<In, Bit>,
    /// Its direction.
    pub gear_forward: Signal<In, Bit>,
    /// The axis is analog: gearbox steps are lost.
    pub analog: Signal<In, Bit>,
    /// Abort: empty the hold.
    pub abort: Signal<In, Bit>,
    /// Clear `lost`.
    pub clear_lost: Signal<In, Bit>,
    /// The step offered to the request register.
    pub candidate: Signal<Out, Bit>,
    /// Its direction.
    pub candidate_forward: Signal<Out, Bit>,
    /// Sticky: a gearbox step was lost.
    pub lost: Signal<Out, Bit>,

    held: DFF<Bit>,
    held_forward: DFF<Bit>,
    lost_flag: DFF<Bit>,
    gear_in: Signal<Local, Bit>,
    gear_offer: Signal<Local, Bit>,
    gear_offer_forward: Signal<Local, Bit>,
}

impl Logic for GearMerge {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, held, held_forward, lost_flag);
        self.gear_in.next = self.gear.val() & !self.analog.val();
        // The held step first.
        self.gear_offer.next = self.gear_in.val() | self.held.q.val();
        self.gear_offer_forward.next = self.gear_forward.val();
        if self.held.q.val() {
            self.gear_offer_forward.next = self.held_forward.q.val();
        }
        // Without a step the direction is the interpolator's, as in an
        // axis without the merge.
        self.candidate.next = self.interp.val() | self.gear_offer.val();
        self.candidate_forward.next = self.interp_forward.val();
        if !self.interp.val() & self.gear_offer.val() {
            self.candidate_forward.next = self.gear_offer_forward.val();
        }
        // What waits: the new gearbox step when something else went, or
        // the held one when the interpolator went.
        self.held.d.next = (self.gear_in.val() & (self.interp.val() | self.held.q.val()))
            | (self.held.q.val() & self.interp.val());
        if self.gear_in.val() & !(self.interp.val() & self.held.q.val()) {
            self.held_forward.d.next = self.gear_forward.val();
        }
        self.lost.next = self.lost_flag.q.val();
        self.lost_flag.d.next = (self.lost_flag.q.val() & !self.clear_lost.val())
            | (self.gear.val() & self.analog.val())
            | (self.gear_in.val() & self.interp.val() & self.held.q.val());
        if self.abort.val() {
            self.held.d.next = false;
        }
        if self.reset.val() {
            self.held.d.next = false;
            self.held_forward.d.next = false;
            self.lost_flag.d.next = false;
        }
    }
}

/// Cycle-exact model of [`GearMerge`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearMergeModel {
    held: Option<bool>,
    lost: bool,
}

impl GearMergeModel {
    /// The step offered to the request register in this clock and its
    /// direction, for the interpolator's (`interp`: a step, and the
    /// direction it holds with or without one) and a gearbox step `gear`
    /// (`Some(forward)`), on an axis that is `analog` or not. Without a
    /// step the direction is the interpolator's.
    pub fn candidate(
        &self,
        (interp, interp_forward): (bool, bool),
        gear: Option<bool>,
        analog: bool,
    ) -> (bool, bool) {
        let gear = gear.filter(|_| !analog);
        match self.held.or(gear) {
            Some(forward) if !interp => (true, forward),
            _ => (interp, interp_forward),
        }
    }

    /// Sticky: a gearbox step was lost.
    pub fn lost(&self) -> bool {
        self.lost
    }

    /// One rising edge with this clock's inputs.
    pub fn edge(
        &mut self,
        interp: Option<bool>,
        gear: Option<bool>,
        analog: bool,
        abort: bool,
        clear_lost: bool,
        reset: bool,
    ) {
        let taken = gear.filter(|_| !analog);
        let lost = (gear.is_some() && analog)
            || (taken.is_some() && interp.is_some() && self.held.is_some());
        let held = match (interp, self.held, taken) {
            // The interpolator went: the held step stays (a new one is lost).
            (Some(_), Some(h), _) => Some(h),
            // The interpolator went: a new gearbox step waits.
            (Some(_), None, g) => g,
            // The held step went: a new one waits.
            (None, Some(_), g) => g,
            // The new gearbox step went.
            (None, None, _) => None,
        };
        self.lost = (self.lost && !clear_lost) || lost;
        self.held = if abort { None } else { held };
        if reset {
            *self = Self::default();
        }
    }
}
