//! The feed hold through the driver: request and release it, set its
//! deceleration, read its state (`HOLD_CONTROL`, `STATE.HOLDING`,
//! `STATE.HELD`; see the controller's "Feed hold"), and the hold and
//! release a run makes at given clocks ([`Driver::run_with_holds`]).

use super::{ControllerBus, Driver, DriverError};

/// What the driver does to the feed hold at a [`HoldEvent`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoldAction {
    /// Write `HOLD_CONTROL.HOLD`: the path slows along itself to a stop.
    Hold,
    /// Write `HOLD_CONTROL.RELEASE`: the path ramps back to speed and runs
    /// on (refused by the controller while the `feed_hold` input is
    /// active).
    Release,
}

/// A hold or a release at a clock of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HoldEvent {
    /// The clock (the bus's [`ControllerBus::cycles`]) of the register
    /// write; an event due while the driver is writing or reading comes
    /// in the first clock after.
    pub clock: u64,
    /// What is written.
    pub action: HoldAction,
}

/// The feed hold's state as the registers read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HoldState {
    /// `HOLD_CONTROL.REQUESTED`: the sticky request (input, `HOLD`, or a
    /// probe trip with `PROBE_CONTROL.STOP`).
    pub requested: bool,
    /// `HOLD_CONTROL.INPUT`: the filtered `feed_hold` input is active.
    pub input: bool,
    /// `STATE.HOLDING`: the velocity factor is below 1.
    pub holding: bool,
    /// `STATE.HELD`: the factor is 0, the path stands.
    pub held: bool,
}

impl<B: ControllerBus> Driver<B> {
    /// The `HOLD_CONTROL` word that keeps `INVERT` and `RATE` as they read
    /// and writes the given action bits.
    fn hold_word(&mut self, hold: u64, release: u64) -> Result<u32, DriverError> {
        let control = self.read("HOLD_CONTROL", 0)?;
        let invert = self.field("HOLD_CONTROL", "INVERT", control)?;
        let rate = self.field("HOLD_CONTROL", "RATE", control)?;
        self.pack(
            "HOLD_CONTROL",
            &[
                ("HOLD", hold),
                ("RELEASE", release),
                ("INVERT", invert),
                ("RATE", rate),
            ],
        )
    }

    /// Sets the deceleration: the velocity factor moves by `rate`/65536
    /// per base tick, so a stop from full speed takes ceil(65536 / rate)
    /// base ticks (`HOLD_CONTROL.RATE`; 0 stops at the next tick). Fails
    /// on a rate beyond 16 bits.
    pub fn set_hold_rate(&mut self, rate: u32) -> Result<(), DriverError> {
        if rate > 0xffff {
            return Err(DriverError::Config(format!(
                "hold rate {rate} does not fit HOLD_CONTROL.RATE (16 bits, 0 to 65535)"
            )));
        }
        let control = self.read("HOLD_CONTROL", 0)?;
        let invert = self.field("HOLD_CONTROL", "INVERT", control)?;
        let word = self.pack("HOLD_CONTROL", &[("INVERT", invert), ("RATE", rate as u64)])?;
        self.write("HOLD_CONTROL", 0, word)
    }

    /// Requests the feed hold; the path decelerates from the next base
    /// tick on (see `latency::HOLD_REQUEST_TO_RAMP`).
    pub fn hold(&mut self) -> Result<(), DriverError> {
        let word = self.hold_word(1, 0)?;
        self.write("HOLD_CONTROL", 0, word)
    }

    /// Releases the feed hold: the path ramps back to speed. The
    /// controller ignores it while the `feed_hold` input is active; see
    /// [`HoldState::requested`].
    pub fn release(&mut self) -> Result<(), DriverError> {
        let word = self.hold_word(0, 1)?;
        self.write("HOLD_CONTROL", 0, word)
    }

    /// Ends a path the feed hold has stopped, where it stands: `RUN` 0 and
    /// `FLUSH` (the periods not taken are dropped), then the hold
    /// released; waits for the output stages and returns each axis's
    /// `CMD_POSITION`. What follows a probe move that tripped.
    pub fn abandon_held_path(&mut self) -> Result<[i32; 3], DriverError> {
        let stop = self.pack("CONTROL", &[("RUN", 0), ("FLUSH", 1)])?;
        self.write("CONTROL", 0, stop)?;
        self.release()?;
        self.settle()?;
        self.commanded_positions()
    }

    /// The feed hold's state.
    pub fn hold_state(&mut self) -> Result<HoldState, DriverError> {
        let control = self.read("HOLD_CONTROL", 0)?;
        let state = self.read("STATE", 0)?;
        Ok(HoldState {
            requested: self.field("HOLD_CONTROL", "REQUESTED", control)? == 1,
            input: self.field("HOLD_CONTROL", "INPUT", control)? == 1,
            holding: self.field("STATE", "HOLDING", state)? == 1,
            held: self.field("STATE", "HELD", state)? == 1,
        })
    }

    /// Refuses hold events out of clock order.
    pub(super) fn check_hold_order(holds: &[HoldEvent]) -> Result<(), DriverError> {
        if holds.windows(2).any(|w| w[1].clock < w[0].clock) {
            return Err(DriverError::Config(
                "the hold events are not in clock order".into(),
            ));
        }
        Ok(())
    }

    /// For a path that stands held: [`DriverError::Held`] with its
    /// position when no release is left in `holds[next..]`, else `Ok`.
    pub(super) fn fail_if_held_for_good(
        &mut self,
        holds: &[HoldEvent],
        next: usize,
        periods_queued: usize,
        periods: usize,
    ) -> Result<(), DriverError> {
        if holds[next..]
            .iter()
            .any(|e| e.action == HoldAction::Release)
        {
            return Ok(());
        }
        let hold = self.hold_state()?;
        let commanded = self.commanded_positions()?;
        Err(DriverError::Held {
            input: hold.input,
            commanded,
            periods_queued,
            periods,
        })
    }

    /// Applies every event of `events` due by now (the bus's clock), from
    /// `*next` on; returns the clocks between now and the next one.
    pub(super) fn apply_due_holds(
        &mut self,
        events: &[HoldEvent],
        next: &mut usize,
    ) -> Result<Option<u64>, DriverError> {
        while let Some(event) = events.get(*next) {
            let now = self.bus.cycles();
            if event.clock > now {
                return Ok(Some(event.clock - now));
            }
            match event.action {
                HoldAction::Hold => self.hold()?,
                HoldAction::Release => self.release()?,
            }
            *next += 1;
        }
        Ok(None)
    }
}
