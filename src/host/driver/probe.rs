//! The probe through the driver: arm it, then read the positions it
//! latched on its trip (`PROBE_CONTROL`, `PROBE_CMD_POSITION`,
//! `PROBE_ACT_POSITION`; see the controller's "Probe").

use super::{ControllerBus, Driver, DriverError};

/// The probe edge that trips, in G38's words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProbeEdge {
    /// Contact made: the rising edge of `probe` (G38.2, G38.3).
    Contact,
    /// Contact lost: the falling edge (G38.4, G38.5).
    Release,
}

/// The positions every axis had in the clock the probe tripped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProbeTrip {
    /// Each axis's `CMD_POSITION` then: the steps that had left its pins.
    pub commanded: [i32; 3],
    /// Each axis's `ACT_POSITION` then: its encoder count.
    pub actual: [i32; 3],
}

impl<B: ControllerBus> Driver<B> {
    /// Whether the controller has the probe latch (`CONFIG.PROBE`).
    pub fn has_probe(&self) -> bool {
        self.map.register("PROBE_CONTROL").is_ok()
    }

    fn require_probe(&self) -> Result<(), DriverError> {
        match self.has_probe() {
            true => Ok(()),
            false => Err(DriverError::Config(
                "this controller has no probe latch (CONFIG.PROBE reads 0)".into(),
            )),
        }
    }

    /// Arms the probe on `edge`; clears an earlier trip. The first such
    /// edge from the next clock on latches every axis's positions.
    pub fn arm_probe(&mut self, edge: ProbeEdge) -> Result<(), DriverError> {
        self.require_probe()?;
        let falling = (edge == ProbeEdge::Release) as u64;
        let word = self.pack("PROBE_CONTROL", &[("ARM", 1), ("EDGE", falling)])?;
        self.write("PROBE_CONTROL", 0, word)
    }

    /// Arms the probe on `edge` with `PROBE_CONTROL.STOP`: its trip also
    /// requests the feed hold, a controlled stop along the path (a run
    /// then fails with [`DriverError::Held`]; see
    /// [`Driver::abandon_held_path`]).
    pub fn arm_probe_to_stop(&mut self, edge: ProbeEdge) -> Result<(), DriverError> {
        self.require_probe()?;
        let falling = (edge == ProbeEdge::Release) as u64;
        let word = self.pack(
            "PROBE_CONTROL",
            &[("ARM", 1), ("EDGE", falling), ("STOP", 1)],
        )?;
        self.write("PROBE_CONTROL", 0, word)
    }

    /// The filtered `probe` input (`PROBE_CONTROL.LEVEL`): 1 = contact.
    pub fn probe_level(&mut self) -> Result<bool, DriverError> {
        self.require_probe()?;
        let control = self.read("PROBE_CONTROL", 0)?;
        Ok(self.field("PROBE_CONTROL", "LEVEL", control)? == 1)
    }

    /// Disarms the probe; a trip already latched stays readable.
    pub fn disarm_probe(&mut self) -> Result<(), DriverError> {
        self.require_probe()?;
        let control = self.read("PROBE_CONTROL", 0)?;
        let edge = self.field("PROBE_CONTROL", "EDGE", control)?;
        let word = self.pack("PROBE_CONTROL", &[("ARM", 0), ("EDGE", edge)])?;
        self.write("PROBE_CONTROL", 0, word)
    }

    /// The positions latched by the trip since the last arming, or `None`
    /// if the probe has not tripped.
    pub fn probe_trip(&mut self) -> Result<Option<ProbeTrip>, DriverError> {
        self.require_probe()?;
        let control = self.read("PROBE_CONTROL", 0)?;
        if self.field("PROBE_CONTROL", "TRIPPED", control)? == 0 {
            return Ok(None);
        }
        let mut trip = ProbeTrip::default();
        for k in 0..3 {
            trip.commanded[k] = self.read("PROBE_CMD_POSITION", k as u32)? as i32;
            trip.actual[k] = self.read("PROBE_ACT_POSITION", k as u32)? as i32;
        }
        Ok(Some(trip))
    }
}
