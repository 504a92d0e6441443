//! G38.2 to G38.5, the straight probe moves, with LinuxCNC's semantics.
//!
//! A probe move is a straight feed move toward the programmed point that
//! stops when the probe changes state, so the program after it depends on
//! where the machine stopped. The interpreter therefore hands the moves
//! so far and the probe move to a [`Prober`] (the machine, or a simulation
//! of it) and goes on from the position it reports, as LinuxCNC's
//! interpreter waits for motion at a probe move.
//!
//! | Code | Waits for | Without a trip by the move's end |
//! |---|---|---|
//! | G38.2 | contact | an error |
//! | G38.3 | contact | #5070 = 0, the program goes on |
//! | G38.4 | loss of contact | an error |
//! | G38.5 | loss of contact | #5070 = 0, the program goes on |
//!
//! After the move: #5061, #5062, #5063 hold the trip position (without a
//! trip, where the move ended) as X, Y, Z in the program's units and the
//! coordinate system in force; #5070 is 1 after a trip, else 0. The
//! machine stands where it stopped: past the trip point by its
//! deceleration, and the program goes on from there.
//!
//! Errors, by line: a probe move with no [`Prober`] (`G38.2: probing needs
//! a probe ...`); with cutter radius compensation on; to the point where
//! it starts (LinuxCNC: Start point too close to probe point); with A, B
//! or C; the prober's refusal (a probe already in the state the move waits
//! for: LinuxCNC's "Probe is already tripped when starting G38.2 or G38.3
//! move"); and G38.2 or G38.4 ending without a trip.

use super::interpreter::State;
use crate::host::toolpath::{Item, LaserPower, Move, MoveKind};

/// The four probe moves.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ProbeCode {
    /// Toward contact; an error without it.
    G38_2,
    /// Toward contact.
    G38_3,
    /// Away from contact; an error without losing it.
    G38_4,
    /// Away from contact.
    G38_5,
}

impl ProbeCode {
    /// "G38.2" to "G38.5".
    pub fn name(self) -> &'static str {
        match self {
            ProbeCode::G38_2 => "G38.2",
            ProbeCode::G38_3 => "G38.3",
            ProbeCode::G38_4 => "G38.4",
            ProbeCode::G38_5 => "G38.5",
        }
    }

    /// The move waits for contact (G38.2, G38.3), else for its loss.
    pub fn toward_contact(self) -> bool {
        matches!(self, ProbeCode::G38_2 | ProbeCode::G38_3)
    }

    /// A move that ends without the probe tripping is an error (G38.2,
    /// G38.4).
    pub fn must_trip(self) -> bool {
        matches!(self, ProbeCode::G38_2 | ProbeCode::G38_4)
    }
}

/// A probe move for the [`Prober`] to run.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeRequest<'a> {
    /// The code.
    pub code: ProbeCode,
    /// Its line.
    pub line: usize,
    /// Where the moves not yet run start, machine mm: the program's start,
    /// or where the last probe move stopped.
    pub pending_start: [f64; 3],
    /// The moves and dwells not yet run, to run before the probe move.
    pub pending: &'a [Item],
    /// The probe move's start, machine mm (the end of `pending`).
    pub start_mm: [f64; 3],
    /// The programmed point, machine mm.
    pub end_mm: [f64; 3],
    /// The feed, mm/s.
    pub feed: f64,
}

/// What a probe move did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeOutcome {
    /// Where the controlled point was when the probe tripped, machine mm;
    /// `None` when the move ended without a trip.
    pub trip_mm: Option<[f64; 3]>,
    /// Where the machine stopped, machine mm: past the trip by its
    /// deceleration, or the programmed point.
    pub stop_mm: [f64; 3],
}

/// What runs probe moves: the pending moves, then the probe move until
/// the probe trips. An `Err` is a sentence the interpreter reports at the
/// probe move's line.
pub trait Prober {
    /// Runs `request`.
    fn probe(&mut self, request: &ProbeRequest) -> Result<ProbeOutcome, String>;
}

/// The parameters of the trip position (X, Y, Z) and of success.
const TRIP_X: u32 = 5061;
const SUCCESS: u32 = 5070;

impl State {
    /// Runs a probe move from the current position to `end_mm`.
    pub(super) fn probe_move(
        &mut self,
        code: ProbeCode,
        end_mm: [f64; 3],
        feed: f64,
        line: usize,
    ) -> Result<(), String> {
        let name = code.name();
        self.refuse_with_comp(name, "Cannot probe with cutter radius compensation on")?;
        let start_mm = self.position_mm;
        if end_mm == start_mm {
            return Err(format!(
                "{name}: the probe point is where the move starts (LinuxCNC: Start point too close to probe point)"
            ));
        }
        let Some(mut prober) = self.prober.take() else {
            return Err(format!(
                "{name}: probing needs a probe, and this run has none (`simulate --probe-plane z=-1.5` simulates one)"
            ));
        };
        let request = ProbeRequest {
            code,
            line,
            pending_start: self.pending_start,
            pending: &self.toolpath.items[self.items_run..],
            start_mm,
            end_mm,
            feed,
        };
        let outcome = prober.probe(&request);
        self.prober = Some(prober);
        let outcome = outcome?;
        if outcome.trip_mm.is_none() && code.must_trip() {
            return Err(format!(
                "{name}: the move reached the probe point without the probe {} (G38.3 and G38.5 go on without it)",
                if code.toward_contact() {
                    "making contact"
                } else {
                    "losing contact"
                }
            ));
        }
        if outcome.stop_mm != start_mm {
            self.toolpath.items.push(Item::Move(Move {
                kind: MoveKind::Line,
                end: outcome.stop_mm,
                angles: self.angles,
                feed: Some(feed),
                laser: LaserPower::OFF,
                line,
            }));
        }
        self.items_run = self.toolpath.items.len();
        self.pending_start = outcome.stop_mm;
        self.programmed_mm = None;
        self.position_mm = outcome.stop_mm;
        self.sync_work_position();
        let (offset, scale) = (self.offset(), self.units.mm_per_unit());
        let trip = outcome.trip_mm.unwrap_or(outcome.stop_mm);
        for k in 0..3 {
            self.params
                .set_numbered(TRIP_X + k as u32, (trip[k] - offset[k]) / scale);
        }
        self.params
            .set_numbered(SUCCESS, outcome.trip_mm.is_some() as u32 as f64);
        Ok(())
    }
}
