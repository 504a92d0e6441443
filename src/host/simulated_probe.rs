//! `simulate --probe-plane AXIS=HEIGHT`: a probe that touches a plane
//! across one axis, and the [`Prober`] that runs a G-code program's probe
//! moves (G38.2 to G38.5) on the simulated controller as the interpreter
//! reaches them.
//!
//! The probe touches while the axis is at the plane or beyond it, seen
//! from where the program starts (`z=-1.234` from Z 0: at or below Z
//! -1.234 mm), in whole steps at the pins: the `probe` pin is high from
//! the first step position at or past the plane. A probe move runs the
//! moves queued before it, then arms the probe with `PROBE_CONTROL.STOP`
//! on the edge the code waits for, with `HOLD_CONTROL.RATE` set to stop the
//! move from its feed within every axis's acceleration (the tick is slow
//! enough for a stop from any axis's maximum velocity: see
//! [`hold_window`](super::hold_window)), and streams the move. The trip latches
//! every axis's position in the clock it is acted on and requests the
//! feed hold, which stops the path along itself at the hold's rate; the
//! periods not taken are flushed and the hold released. The trip is
//! `PROBE_CMD_POSITION` (what the program reads in #5061 to #5063), the
//! machine stands where the hold stopped it, and the program goes on from
//! there.

use std::cell::RefCell;
use std::rc::Rc;

use super::driver::{DriverError, ProbeEdge};
use super::gcode::{ProbeCode, ProbeOutcome, ProbeRequest, Prober};
use super::hold_window::{rate_for_stop, stop_within_limits_s};
use super::machine::{axis_index, AXIS_LETTERS};
use super::planner::to_steps;
use super::toolpath::{Item, LaserPower, Move, MoveKind};
use super::{
    interpolate, plan_toolpath, ControllerBus, Driver, Interpolation, MachineSettings,
    ProbeSurface, RtlBus, Toolpath,
};

/// `--probe-plane`: a plane across `axis` at `height_mm` (machine mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbePlane {
    /// 0 to 2: X, Y, Z.
    pub axis: usize,
    /// The plane's position on that axis, mm.
    pub height_mm: f64,
}

impl ProbePlane {
    /// Parses `AXIS=HEIGHT`: `z=-1.234` (x, y or z; mm).
    pub fn parse(text: &str) -> Result<Self, String> {
        let usage = "AXIS=HEIGHT: x, y or z, then = and a position in mm (z=-1.234)";
        let (axis, height) = text
            .split_once('=')
            .ok_or_else(|| format!("--probe-plane `{text}`: expected {usage}"))?;
        let axis = axis_index(axis.trim()).ok_or_else(|| {
            format!(
                "--probe-plane `{text}`: unknown axis `{}` (x, y or z)",
                axis.trim().to_ascii_lowercase()
            )
        })?;
        let height_mm = height
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|h| h.is_finite())
            .ok_or_else(|| format!("--probe-plane `{text}`: `{height}` is not a position in mm"))?;
        Ok(Self { axis, height_mm })
    }

    /// The axis's letter.
    pub fn axis_name(&self) -> char {
        AXIS_LETTERS[self.axis]
    }

    /// The surface on the controller's steps, for a program starting at
    /// `start_mm` (the controller's 0 is that start, `to_steps(start_mm)`):
    /// contact on the side of the plane away from the start.
    pub fn surface(&self, start_mm: [f64; 3], steps_per_mm: [f64; 3]) -> ProbeSurface {
        let k = self.axis;
        let origin = to_steps(start_mm, steps_per_mm)[k];
        let plane = self.height_mm * steps_per_mm[k];
        let contact_below = start_mm[k] > self.height_mm;
        // The first whole step at or past the plane.
        let contact_at = match contact_below {
            true => plane.floor() as i64,
            false => plane.ceil() as i64,
        } - origin;
        ProbeSurface {
            axis: k,
            contact_at,
            contact_below,
        }
    }
}

/// One probe move as it ran.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeResult {
    /// Its line.
    pub line: usize,
    /// G38.2 to G38.5.
    pub code: ProbeCode,
    /// The trip: `PROBE_CMD_POSITION`, machine mm; `None` without one.
    pub trip_mm: Option<[f64; 3]>,
    /// Where the machine stopped, machine mm.
    pub stop_mm: [f64; 3],
}

/// What the probe moves ran: the driver, to run the rest of the program,
/// and the periods, positions and speeds planned so far.
pub struct ProbingRun {
    /// The driver of the simulated controller.
    pub driver: Driver<RtlBus>,
    /// The periods streamed so far (positions: controller steps plus the
    /// program's start).
    pub run: Interpolation,
    /// Underruns while periods were still to come.
    pub underruns: usize,
    /// Each probe move.
    pub probes: Vec<ProbeResult>,
}

/// The shared state of the prober (the interpreter owns the prober; the
/// simulation takes the run back after it).
pub struct ProbingSession {
    machine: MachineSettings,
    clock_hz: f64,
    /// The program's start, steps: the controller's 0.
    origin: [i64; 3],
    inner: Rc<RefCell<Option<ProbingRun>>>,
}

impl ProbingSession {
    /// A session on `driver` (its controller clocked at `clock_hz`) for a
    /// program starting at `start_mm`.
    pub fn new(
        driver: Driver<RtlBus>,
        machine: MachineSettings,
        clock_hz: f64,
        start_mm: [f64; 3],
    ) -> Self {
        Self {
            machine,
            clock_hz,
            origin: to_steps(start_mm, machine.steps_per_mm),
            inner: Rc::new(RefCell::new(Some(ProbingRun {
                driver,
                run: Interpolation::default(),
                underruns: 0,
                probes: Vec::new(),
            }))),
        }
    }

    /// The prober to give the interpreter.
    pub fn prober(&self) -> Box<dyn Prober> {
        Box::new(SessionProber {
            machine: self.machine,
            clock_hz: self.clock_hz,
            origin: self.origin,
            inner: Rc::clone(&self.inner),
        })
    }

    /// The run, once the interpreter is done with the prober.
    pub fn finish(self) -> ProbingRun {
        self.inner
            .borrow_mut()
            .take()
            .expect("the session's run is taken once")
    }
}

struct SessionProber {
    machine: MachineSettings,
    clock_hz: f64,
    origin: [i64; 3],
    inner: Rc<RefCell<Option<ProbingRun>>>,
}

impl SessionProber {
    /// Machine mm of the controller's `steps`.
    fn mm(&self, steps: [i32; 3]) -> [f64; 3] {
        std::array::from_fn(|k| {
            (steps[k] as i64 + self.origin[k]) as f64 / self.machine.steps_per_mm[k]
        })
    }

    /// The plan of `items` from `start_mm`.
    fn plan(&self, start_mm: [f64; 3], items: &[Item]) -> Result<Interpolation, String> {
        let toolpath = Toolpath {
            start: start_mm,
            items: items.to_vec(),
            ..Toolpath::default()
        };
        let segments = plan_toolpath(&toolpath, &self.machine).map_err(|e| e.to_string())?;
        let start = to_steps(start_mm, self.machine.steps_per_mm);
        Ok(interpolate(start, &segments, self.machine.period))
    }
}

/// Appends the first `periods` periods of `plan` to `run`.
fn append(run: &mut Interpolation, plan: &Interpolation, periods: usize) {
    let n = periods.min(plan.counts.len());
    run.counts.extend_from_slice(&plan.counts[..n]);
    run.positions.extend_from_slice(&plan.positions[..n]);
    run.speeds.extend_from_slice(&plan.speeds[..n]);
}

impl Prober for SessionProber {
    fn probe(&mut self, r: &ProbeRequest) -> Result<ProbeOutcome, String> {
        let mut guard = self.inner.borrow_mut();
        let session = guard.as_mut().ok_or("the probing session has ended")?;
        let driver = &mut session.driver;
        let text = |e: DriverError| e.to_string();
        if !r.pending.is_empty() {
            let plan = self.plan(r.pending_start, r.pending)?;
            let report = driver.run(&plan.counts, |_| {}).map_err(text)?;
            session.underruns += report.underruns;
            append(&mut session.run, &plan, plan.counts.len());
        }
        let touching = driver.probe_level().map_err(text)?;
        if touching == r.code.toward_contact() {
            return Err(match touching {
                true => format!("{}: the probe already touches where the move starts (LinuxCNC: Probe is already tripped when starting G38.2 or G38.3 move)", r.code.name()),
                false => format!("{}: the probe does not touch where the move starts (LinuxCNC: Probe is not tripped when starting G38.4 or G38.5 move)", r.code.name()),
            });
        }
        let edge = match r.code.toward_contact() {
            true => ProbeEdge::Contact,
            false => ProbeEdge::Release,
        };
        // The stop from this move's feed within every axis's acceleration.
        let length = (0..3)
            .map(|k| (r.end_mm[k] - r.start_mm[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        let axis_speed =
            std::array::from_fn(|k| r.feed * (r.end_mm[k] - r.start_mm[k]).abs() / length);
        let stop_s = stop_within_limits_s(&self.machine, 0.0, axis_speed);
        let tick_hz = self.clock_hz / driver.tick_divisor() as f64;
        driver
            .set_hold_rate(rate_for_stop(stop_s, tick_hz))
            .map_err(text)?;
        driver.arm_probe_to_stop(edge).map_err(text)?;
        let probe_move = Item::Move(Move {
            kind: MoveKind::Line,
            end: r.end_mm,
            angles: [0.0; 3],
            feed: Some(r.feed),
            laser: LaserPower::OFF,
            line: r.line,
        });
        let plan = self.plan(r.start_mm, &[probe_move])?;
        let before = driver.bus().cycles();
        let stop = match driver.run(&plan.counts, |_| {}) {
            Ok(report) => {
                session.underruns += report.underruns;
                report.commanded
            }
            Err(DriverError::Held { .. }) => driver.abandon_held_path().map_err(text)?,
            Err(e) => return Err(e.to_string()),
        };
        // A trip in the last periods may end the path before the hold
        // stops it: the request stays, and goes.
        if driver.hold_state().map_err(text)?.requested {
            driver.release().map_err(text)?;
        }
        let trip = driver.probe_trip().map_err(text)?;
        driver.disarm_probe().map_err(text)?;
        let periods = (driver.bus().cycles() - before).div_ceil(driver.period_clocks()) as usize;
        append(&mut session.run, &plan, periods);
        let outcome = ProbeOutcome {
            trip_mm: trip.map(|t| self.mm(t.commanded)),
            stop_mm: self.mm(stop),
        };
        session.probes.push(ProbeResult {
            line: r.line,
            code: r.code,
            trip_mm: outcome.trip_mm,
            stop_mm: outcome.stop_mm,
        });
        Ok(outcome)
    }
}
