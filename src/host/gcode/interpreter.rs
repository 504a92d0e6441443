//! The modal interpreter: blocks of words into a [`Toolpath`] in mm.
//! What it supports and refuses is listed in the [module doc](super).

use std::collections::HashSet;

use thiserror::Error;

use super::arc_center::{center_from_radius, check_center};
use super::block_words::{CutterComp, Motion, NonModal, Words};
use super::cutter_comp::Compensation;
use super::cycles::CycleMemory;
use super::flow::structure;
use super::lexer::{lex_program, Block, LexError};
use super::messages::Message;
use super::param_store::ParamStore;
use super::parameters::{system_name, PersistentParameters};
use super::probing::Prober;
use super::threading::SyncWords;
use crate::host::tool_table::ToolTable;
// An arc whose end is within SAME_POINT of its start, in its plane, is a
// full circle (and its end is set to the start exactly).
use crate::host::geometry::SAME_POINT;
use crate::host::toolpath::{
    moves_angles_only, Arc, Item, LaserPower, Move, MoveKind, Plane, Toolpath,
};

/// Positions (ends and arc centers) beyond this many mm from zero are
/// refused: far outside any machine, and where f64 mm keep too few
/// fractional digits for the 1e-9 mm full-circle test.
pub const POSITION_LIMIT_MM: f64 = 1e6;

/// A program that cannot be interpreted.
#[derive(Debug, Error, PartialEq, Eq, Clone)]
#[error("line {line}: {message}")]
pub struct GcodeError {
    /// The 1-based line of the file.
    pub line: usize,
    /// What is wrong, naming the word at fault.
    pub message: String,
}

impl From<LexError> for GcodeError {
    fn from(e: LexError) -> Self {
        GcodeError {
            line: e.line,
            message: e.message,
        }
    }
}

/// The length unit of a program's numbers (G20, G21).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Units {
    /// G21, the default.
    #[default]
    Millimetre,
    /// G20.
    Inch,
}

impl Units {
    /// "mm" or "in".
    pub fn name(self) -> &'static str {
        match self {
            Units::Millimetre => "mm",
            Units::Inch => "in",
        }
    }

    /// Millimetres in one unit: 1 or 25.4.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            Units::Millimetre => 1.0,
            Units::Inch => 25.4,
        }
    }

    /// A length in mm shown in these units with 4 decimals: "0.3937 in".
    pub(super) fn show(self, mm: f64) -> String {
        format!("{:.4} {}", mm / self.mm_per_unit(), self.name())
    }
}

/// A word read and accepted with no effect on the motion.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ignored {
    /// The 1-based line of its first occurrence.
    pub line: usize,
    /// The word as first written: "M3", "S12000", "G64".
    pub word: String,
    /// What it controls: "spindle", "coolant", "tool", "path control"...
    pub what: &'static str,
}

/// An interpreted program.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// The moves and dwells, absolute, in mm, feeds in mm/s.
    pub toolpath: Toolpath,
    /// The units mode in force at the end.
    pub units: Units,
    /// Where the program ends, in `units`, in the work coordinates of the
    /// coordinate system in force at its end (`coordinate_system`, with the
    /// G92 offset if one applies).
    pub final_position: [f64; 3],
    /// Where the program ends in machine coordinates, mm: the toolpath's end.
    pub final_machine: [f64; 3],
    /// The rotary axes A, B, C at the end, degrees (0 on a machine
    /// without them).
    pub final_angles: [f64; 3],
    /// The coordinate system in force at the end: "G54" to "G59.3".
    pub coordinate_system: &'static str,
    /// The persistent parameters (#5161 to #5390) as the program left them.
    pub parameters: PersistentParameters,
    /// The active comments (MSG, DEBUG, PRINT) in the order they ran.
    pub messages: Vec<Message>,
    /// The words that do nothing here, each once, at its first line:
    /// once per M code, per ignored G code, and per letter S, T, H and D.
    pub ignored: Vec<Ignored>,
    /// The line of the M2 or M30 that ended the program, if one did; `None`
    /// when the file ended without one (the program ends there, as #40 asks;
    /// LinuxCNC 2.9 refuses such a file: "File ended with no percent sign (%)
    /// or program end (M2)").
    pub end: Option<usize>,
    /// Blocks after the M2 or M30, not run (block-deleted ones not counted).
    pub blocks_after_end: usize,
    /// The line of the `%` that closed the program (its first line being
    /// `%` too): the end of the program, as in LinuxCNC, when no M2 or M30
    /// came before it. Nothing after it is read.
    pub closing_percent: Option<usize>,
    /// The items of `toolpath` a [`Prober`] has run (every one up to the
    /// last probe move, which ends where the machine stopped); 0 without
    /// probe moves.
    pub items_run: usize,
    /// Where the items not yet run start, machine mm: the toolpath's
    /// start, or where the last probe move stopped.
    pub pending_start: [f64; 3],
}

/// Interprets `program` from the machine's origin with the default
/// parameters (every offset 0, G54). See the [module doc](super).
pub fn interpret(program: &str) -> Result<Program, GcodeError> {
    interpret_from(program, [0.0; 3])
}

/// Interprets `program` from `start` (machine mm) with the default
/// parameters: a program's first incremental moves and arc centers count
/// from there.
pub fn interpret_from(program: &str, start: [f64; 3]) -> Result<Program, GcodeError> {
    interpret_with(
        program,
        &Setup {
            start,
            ..Setup::default()
        },
    )
}

/// What a program starts from besides its text.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Setup {
    /// The machine position, mm.
    pub start: [f64; 3],
    /// The machine settings' #5161 to #5390: coordinate systems, G92, G28
    /// and G30.
    pub parameters: PersistentParameters,
    /// The tool table; `None` when none is given: every tool number is
    /// then accepted, with no offsets and no diameter (reported once when
    /// G43 or G43.2 takes a tool's offset).
    pub tools: Option<ToolTable>,
    /// The machine has the rotary axes A, B and C (the hexapod): G0 to G3
    /// move them, in degrees. Without them (the default) an A, B or C word
    /// is an error.
    pub rotary_axes: bool,
    /// The rotary axes at the start, degrees.
    pub start_angles: [f64; 3],
    /// A laser machine: the S of full laser power (the machine setting
    /// `laser_s_max`). M3 and M4 then turn the laser on at S over this,
    /// constant (M3) or scaled by the path speed (M4), on every feed move
    /// and dwell; rapids run with it off; M5 turns it off; an S above it
    /// is an error. `None` (the default): S is a spindle speed.
    pub laser_s_max: Option<f64>,
}

/// Interprets `program` from `setup`.
pub fn interpret_with(program: &str, setup: &Setup) -> Result<Program, GcodeError> {
    interpret_inner(program, setup, None)
}

/// Interprets `program` from `setup`, its probe moves (G38.2 to G38.5)
/// run by `prober` as they come (see [`probing`](super::probing)).
pub fn interpret_probing(
    program: &str,
    setup: &Setup,
    prober: Box<dyn Prober>,
) -> Result<Program, GcodeError> {
    interpret_inner(program, setup, Some(prober))
}

fn interpret_inner(
    program: &str,
    setup: &Setup,
    prober: Option<Box<dyn Prober>>,
) -> Result<Program, GcodeError> {
    let mut state = State::new(setup.start, setup.parameters, setup.tools.clone());
    state.prober = prober;
    state.rotary_axes = setup.rotary_axes;
    state.laser_s_max = setup.laser_s_max;
    state.angles = setup.start_angles;
    state.toolpath.start_angles = setup.start_angles;
    let lexed = lex_program(program)?;
    let structure =
        structure(&lexed.blocks).map_err(|(line, message)| GcodeError { line, message })?;
    let next = state.run_blocks(&lexed.blocks, &structure)?;
    // The file's end stops the program as M2 would: compensation's
    // held-back moves run.
    if state.end.is_none() {
        let line = lexed.blocks.last().map_or(1, |b| b.line);
        state
            .comp_stop()
            .map_err(|message| GcodeError { line, message })?;
    }
    let after_end = match state.end {
        Some(_) => lexed
            .blocks
            .iter()
            .skip(next)
            .filter(|b| !b.deleted)
            .count(),
        None => 0,
    };
    Ok(state.finish(after_end, lexed.closing_percent))
}

const AXES: [char; 3] = ['X', 'Y', 'Z'];

/// The modal state and what the program has produced so far.
pub(super) struct State {
    pub(super) units: Units,
    pub(super) plane: Plane,
    pub(super) incremental: bool,
    pub(super) arc_incremental: bool,
    pub(super) motion: Option<Motion>,
    /// mm/s.
    pub(super) feed: Option<f64>,
    /// The same F for a move of the rotary axes alone, degrees/s (F is
    /// then degrees per minute in either unit mode).
    pub(super) feed_degrees: Option<f64>,
    /// The machine has A, B and C ([`Setup::rotary_axes`]).
    pub(super) rotary_axes: bool,
    /// A, B, C, degrees: no offsets apply, so work and machine agree.
    pub(super) angles: [f64; 3],
    /// The work position in the program's current units: kept apart from
    /// the machine one so that a program's own sums (G91 in inches) come
    /// out as it computes them, not through a round trip by 25.4.
    pub(super) position: [f64; 3],
    /// The machine position, mm: the toolpath's coordinates, where the
    /// tool is.
    pub(super) position_mm: [f64; 3],
    /// The programmed position, machine mm, where it is not the tool's:
    /// while cutter compensation offsets the tool, and after G40 until the
    /// next move (see [`State::base_mm`]).
    pub(super) programmed_mm: Option<[f64; 3]>,
    /// Cutter radius compensation, while it is on.
    pub(super) comp: Option<Compensation>,
    /// G40 has just ended compensation: the next move must be straight.
    pub(super) arc_not_allowed: bool,
    /// Coordinate systems, G92, G28 and G30 positions.
    pub(super) parameters: PersistentParameters,
    pub(super) tools: Option<ToolTable>,
    /// The tool T selected, if any (0: none).
    pub(super) selected: Option<u32>,
    /// The tool in the spindle (0: none).
    pub(super) loaded: u32,
    /// The tool length offset in force, mm (G43, G43.1, G43.2).
    pub(super) tool_offset: [f64; 3],
    /// G99 (true, LinuxCNC's default: cycles retract to R) or G98 (false).
    pub(super) retract_to_r: bool,
    /// M3 (Some(true)), M4 (Some(false)), M5 or none yet (None).
    pub(super) spindle_turning: Option<bool>,
    /// The last S, rpm (0 before any).
    pub(super) spindle_speed: f64,
    /// A laser machine's full-power S ([`Setup::laser_s_max`]).
    pub(super) laser_s_max: Option<f64>,
    /// The laser's power on a feed move or a dwell now.
    pub(super) laser: LaserPower,
    /// What the last canned cycle keeps for the next.
    pub(super) cycle_memory: CycleMemory,
    /// Numbered and named parameters (the persistent ones aside).
    pub(super) params: ParamStore,
    pub(super) messages: Vec<Message>,
    pub(super) toolpath: Toolpath,
    pub(super) ignored: Vec<Ignored>,
    pub(super) reported: HashSet<String>,
    pub(super) end: Option<usize>,
    /// Runs the probe moves, if the run has a probe.
    pub(super) prober: Option<Box<dyn Prober>>,
    /// The toolpath's items the prober has run.
    pub(super) items_run: usize,
    /// Where the items not yet run start, machine mm.
    pub(super) pending_start: [f64; 3],
}

impl State {
    fn new(start: [f64; 3], parameters: PersistentParameters, tools: Option<ToolTable>) -> Self {
        let mut state = State {
            units: Units::Millimetre,
            plane: Plane::Xy,
            incremental: false,
            arc_incremental: true,
            motion: None,
            feed: None,
            feed_degrees: None,
            rotary_axes: false,
            angles: [0.0; 3],
            position: start,
            position_mm: start,
            programmed_mm: None,
            comp: None,
            arc_not_allowed: false,
            parameters,
            tools,
            selected: None,
            loaded: 0,
            tool_offset: [0.0; 3],
            retract_to_r: true,
            spindle_turning: None,
            spindle_speed: 0.0,
            laser_s_max: None,
            laser: LaserPower::OFF,
            cycle_memory: CycleMemory::default(),
            params: ParamStore::default(),
            messages: Vec::new(),
            toolpath: Toolpath {
                start,
                ..Toolpath::default()
            },
            ignored: Vec::new(),
            reported: HashSet::new(),
            end: None,
            prober: None,
            items_run: 0,
            pending_start: start,
        };
        state.sync_work_position();
        state
    }

    /// Machine = work + this, mm: the active system's origin, the G92
    /// offset and the tool length offset in force.
    pub(super) fn offset(&self) -> [f64; 3] {
        let origin = self.parameters.origin(self.parameters.active_system());
        let g92 = self.parameters.g92();
        [0, 1, 2].map(|k| origin[k] + g92[k] + self.tool_offset[k])
    }

    /// The laser's power along a move at `feed`: off on a rapid (`None`).
    pub(super) fn laser_along(&self, feed: Option<f64>) -> LaserPower {
        match feed {
            Some(_) => self.laser,
            None => LaserPower::OFF,
        }
    }

    /// The work position from the machine one, after the units or an
    /// offset changed.
    pub(super) fn sync_work_position(&mut self) {
        let (offset, scale, base) = (self.offset(), self.units.mm_per_unit(), self.base_mm());
        self.position = [0, 1, 2].map(|k| (base[k] - offset[k]) / scale);
    }

    fn finish(self, blocks_after_end: usize, closing_percent: Option<usize>) -> Program {
        Program {
            toolpath: self.toolpath,
            units: self.units,
            final_position: self.position,
            final_machine: self.position_mm,
            final_angles: self.angles,
            coordinate_system: system_name(self.parameters.active_system()),
            parameters: self.parameters,
            messages: self.messages,
            ignored: self.ignored,
            end: self.end,
            blocks_after_end,
            closing_percent,
            items_run: self.items_run,
            pending_start: self.pending_start,
        }
    }

    /// Lists `word` in [`Program::ignored`] unless something was already
    /// reported under `key`.
    pub(super) fn report(&mut self, key: &str, line: usize, word: String, what: &'static str) {
        if self.reported.insert(key.to_string()) {
            self.ignored.push(Ignored { line, word, what });
        }
    }

    /// One block as written: its values evaluated, run, then its
    /// parameter assignments made.
    pub(super) fn run_block(&mut self, block: &Block) -> Result<(), String> {
        let evaluated = self.evaluate(block)?;
        self.messages(&evaluated);
        self.apply(&evaluated)?;
        self.assign(&block.assignments)
    }

    /// One block, in RS-274's order of execution.
    fn apply(&mut self, block: &Block) -> Result<(), String> {
        let mut words = Words::read(block, self.rotary_axes)?;
        let sync = SyncWords::take(&mut words, self.motion);
        if let Some(number) = words.program_number {
            // A Fanuc- or Haas-style post's program number: accepted only
            // before the program has moved, where it can name nothing else.
            if !self.toolpath.items.is_empty() {
                return Err(format!(
                    "{}: a program number stands before any motion; subroutines and flow control (O words) are not supported",
                    number.name()
                ));
            }
        }
        let motion = self.motion_to_run(&words)?;
        self.check_rotary_motion(&words, motion)?;
        let g10 = matches!(words.non_modal, Some((_, NonModal::SetOrigin)));
        // The cycle mode in force or set by the block, whether it runs here
        // or not: its words (R, Q, P, L) may stand on a block without
        // axis words.
        let cycle = words
            .motion
            .map(|(_, m)| m)
            .or(self.motion)
            .filter(|m| m.is_cycle());
        if let Some(p) = words.p {
            let used = words.dwell.is_some()
                || words.path_control.is_some()
                || g10
                || cycle.is_some()
                || motion.is_some_and(Motion::is_arc);
            if !used {
                return Err(format!(
                    "{} has no G2, G3, G4, G10, G64 or canned cycle to use it",
                    p.name()
                ));
            }
        }
        let q_used = words.path_control.is_some() || words.set_tool.is_some() || cycle.is_some();
        if let Some(q) = words.q.filter(|_| !q_used) {
            return Err(format!(
                "{} has no G64, M61 or canned cycle to use it",
                q.name()
            ));
        }
        // G41 to G42.1 take D (their tool or diameter), and refuse L.
        let comp_on = matches!(
            words.cutter_comp,
            Some((_, CutterComp::FromTable { .. } | CutterComp::Dynamic { .. }))
        );
        if let Some(l) = words.l.filter(|_| !g10 && cycle.is_none() && !comp_on) {
            return Err(format!("{} has no G10 or canned cycle to use it", l.name()));
        }
        if let Some(d) = words.d.filter(|_| cycle.is_none() && !comp_on) {
            self.report("D", block.line, d.name(), "tool offset");
        }
        if let Some(turning) = words.spindle {
            self.spindle_turning = turning;
        }
        if let Some(s) = words.s {
            if s.value < 0.0 {
                return Err(format!(
                    "{} is not a spindle speed: it must be 0 or more rpm",
                    s.name()
                ));
            }
            if let Some(s_max) = self.laser_s_max.filter(|&m| s.value > m) {
                return Err(format!(
                    "{} is beyond the laser's full power, S{s_max} (laser_s_max in the machine settings)",
                    s.name()
                ));
            }
            self.spindle_speed = s.value;
        }
        if let Some(s_max) = self.laser_s_max {
            self.laser = match self.spindle_turning {
                Some(clockwise) => LaserPower {
                    fraction: self.spindle_speed / s_max,
                    dynamic: !clockwise,
                },
                None => LaserPower::OFF,
            };
        }
        if let Some(r) = words.retract_to_r {
            let code = if r { "G99" } else { "G98" };
            self.refuse_with_comp(
                code,
                "Cannot change retract mode with cutter radius compensation on",
            )?;
            self.retract_to_r = r;
        }

        if let Some(word) = words.path_control {
            self.refuse_with_comp(
                &word.name(),
                "Cannot change control mode with cutter radius compensation on",
            )?;
        }
        for (word, what, key) in &words.ignored {
            // On a laser machine M3, M4, M5 and S set the laser.
            let laser_word = matches!(key.as_str(), "S" | "M3" | "M4" | "M5");
            if !(laser_word && self.laser_s_max.is_some()) {
                self.report(key, block.line, word.name(), what);
            }
        }
        // RS-274/NGC's order of execution sets F (step 3) before the units
        // (step 12): an F beside a G20 is in the units in force before it.
        if let Some(f) = words.feed {
            if f.value <= 0.0 {
                return Err(format!(
                    "{} is not a feed rate: it must be above zero",
                    f.name()
                ));
            }
            let (mm_per_s, degrees_per_s) =
                (f.value * self.units.mm_per_unit() / 60.0, f.value / 60.0);
            if !(mm_per_s > 0.0 && degrees_per_s > 0.0) {
                return Err(format!(
                    "{} is not a feed rate: it must be above zero",
                    f.name()
                ));
            }
            self.feed = Some(mm_per_s);
            self.feed_degrees = Some(degrees_per_s);
        }
        if let Some(units) = words.units.filter(|u| *u != self.units) {
            self.units = units;
            self.sync_work_position();
        }
        // T (step 5) and M6 (6) before everything that moves; the tool
        // length offset (14) after the units (12).
        self.tool_words(&words)?;
        if let (Some(plane), Some(comp)) = (words.plane, &self.comp) {
            if plane != comp.plane {
                self.refuse_with_comp(
                    plane.gcode(),
                    "Cannot change planes with cutter radius compensation on",
                )?;
            }
        }
        self.plane = words.plane.unwrap_or(self.plane);
        self.incremental = words.incremental.unwrap_or(self.incremental);
        self.arc_incremental = words.arc_incremental.unwrap_or(self.arc_incremental);
        if words.dwell.is_some() {
            let p = words.p.ok_or("G4 needs a dwell time: P, in seconds")?;
            if p.value < 0.0 {
                return Err(format!(
                    "{} is not a dwell time: it must be 0 or more seconds",
                    p.name()
                ));
            }
            self.emit(Item::Dwell {
                seconds: p.value,
                laser: self.laser,
                line: block.line,
            });
        }
        self.cutter_comp_words(&words, block.line)?;
        self.tool_length(&words, block.line)?;
        // LinuxCNC's order: the coordinate system (step 15), the distance
        // mode (17, above), then G10, G28, G30, G92 (19) and the motion (20).
        if let Some(index) = words.system {
            self.refuse_with_comp(
                system_name(index),
                "Cannot change coordinate systems with cutter radius compensation on",
            )?;
            self.parameters.select_system(index);
            self.sync_work_position();
        }
        let previous_motion = self.motion;
        if let Some((_, m)) = words.motion {
            self.motion = Some(m);
        }
        if words.cancel_motion.is_some() {
            self.motion = None;
        }
        // A series of cycles ends at any other motion or G80 (LinuxCNC's
        // cycle_il_flag).
        if words.cancel_motion.is_some() || motion.is_some_and(|m| !m.is_cycle()) {
            self.cycle_memory.initial = None;
        }
        let machine = matches!(words.non_modal, Some((_, NonModal::MachineCoordinates)));
        self.check_polar(&words, motion, machine)?;
        if let Some((word, code)) = words.non_modal {
            self.non_modal(word, code, &words, motion, block.line)?;
        }
        if let Some(motion) = motion.filter(|m| m.is_arc()) {
            // grbl ignores an out-of-plane offset, and FreeCAD's grbl post
            // writes K0 on every G17 arc: exactly zero changes nothing, so
            // it is dropped and reported once. Any other value stays an
            // error (LinuxCNC refuses every out-of-plane offset).
            let normal = self.plane.axes().2;
            if let Some(offset) = words.offsets[normal].filter(|w| w.value == 0.0) {
                words.offsets[normal] = None;
                self.report(
                    &format!("zero out-of-plane offset {}", self.plane.gcode()),
                    block.line,
                    format!("{} on {}", offset.name(), motion.name()),
                    "out-of-plane arc offset of zero (grbl-style posts)",
                );
            }
        }
        match motion {
            Some(Motion::Cycle(c)) => {
                self.refuse_with_comp(
                    c.name(),
                    "Cannot use canned cycles with cutter compensation on",
                )?;
                let same = previous_motion == Some(Motion::Cycle(c));
                self.cycle(c, same, &words, block.line)?
            }
            Some(Motion::SpindleSync) => self.spindle_synced(false, &sync, &words, block.line)?,
            Some(Motion::RigidTap) => self.spindle_synced(true, &sync, &words, block.line)?,
            Some(Motion::Threading) => {
                self.threading_cycle(&sync, &words, block.line)?;
                // G76 runs on its own block only: a later axis word needs
                // a motion mode again.
                self.motion = None;
            }
            Some(motion) => self.run(motion, &words, block.line, machine)?,
            None if matches!(words.motion, Some((_, Motion::Threading))) => {
                return Err("G76 needs Z, where the thread ends".into())
            }
            None => {}
        }
        if words.end || words.pause.is_some() {
            self.comp_stop()?;
        }
        if words.end {
            self.end = Some(block.line);
        }
        Ok(())
    }

    /// The motion the block runs, if it runs one: its own G0 to G3 or the
    /// modal one, when it has axis words (or, for an arc, center words).
    /// A G4 beside it dwells first (LinuxCNC's order of execution).
    fn motion_to_run(&self, words: &Words) -> Result<Option<Motion>, String> {
        let (axis, center) = (words.first_axis, words.first_center);
        // The codes other than G0 to G3 that take the axis words: then no
        // motion runs.
        let mut takers = Vec::new();
        if let Some((word, _)) = words.non_modal.filter(|(_, c)| c.takes_axes()) {
            takers.push(word);
        }
        if let Some((word, _)) = words.tool_length.filter(|(_, t)| t.takes_axes()) {
            takers.push(word);
        }
        if let Some((written, _)) = words.motion {
            takers.push(written);
        }
        if let (Some(_), [first, second, ..]) = (axis, takers.as_slice()) {
            return Err(format!(
                "{} and {} in one block: both use the axis words \
                 (LinuxCNC: Cannot use two g codes that both use axis values)",
                first.name(),
                second.name()
            ));
        }
        let motion_takes = words.motion.is_some() || takers.is_empty();
        if !motion_takes {
            if let Some(center) = center {
                return Err(format!("{} has no G2 or G3 to use it", center.name()));
            }
            return Ok(None);
        }
        if let Some((code_word, code)) = words.non_modal {
            if let Some(word) = axis.or(center).filter(|_| !code.reads_axes()) {
                return Err(format!(
                    "{} with {}: it takes no axis words",
                    word.name(),
                    code_word.name()
                ));
            }
        }
        if let (Some(g80), Some(word)) = (words.cancel_motion, axis.or(center)) {
            return Err(format!(
                "{} with {}: G80 cancels the motion mode and takes no axis or arc words \
                 (LinuxCNC: Cannot use axis values with g80)",
                word.name(),
                g80.name()
            ));
        }
        let motion = match words.motion {
            Some((_, m)) => Some(m),
            None if axis.or(center).is_some() => self.motion,
            None => None,
        };
        if let (None, Some(axis)) = (motion, axis) {
            return Err(format!(
                "{} needs a motion mode (G0, G1, G2 or G3) first",
                axis.name()
            ));
        }
        if let Some(motion) = motion.filter(|m| m.is_cycle()) {
            // A cycle runs on axis words only; its R, Q, P, L, I, J, K
            // alone set its values for later.
            return Ok(Some(motion).filter(|_| axis.is_some()));
        }
        if let Some(center) = center.filter(|_| !motion.is_some_and(Motion::is_arc)) {
            return Err(format!("{} has no G2 or G3 to use it", center.name()));
        }
        // G0 or G1 with no axis word sets the mode and moves nothing; so
        // does a bare G2 or G3.
        Ok(motion.filter(|_| axis.or(center).is_some()))
    }

    /// Runs `motion` to the block's axis words: work coordinates, or with
    /// `machine` (G53) machine coordinates.
    fn run(
        &mut self,
        motion: Motion,
        words: &Words,
        line: usize,
        machine: bool,
    ) -> Result<(), String> {
        let feed =
            match motion {
                Motion::Rapid => None,
                _ => Some(self.feed.ok_or_else(|| {
                    format!("{} needs a feed rate: no F word so far", motion.name())
                })?),
            };
        if motion.is_arc() && self.arc_not_allowed {
            return Err(format!(
                "{}: the move just after G40 must be straight: it starts where compensation left the tool \
                 (LinuxCNC: The move just after exiting cutter compensation mode must be straight, not an arc)",
                motion.name()
            ));
        }
        self.arc_not_allowed = false;
        let compensating = self.comp.as_ref().is_some_and(|c| c.radius > 0.0);
        if compensating && machine {
            self.refuse_with_comp("G53", "Cannot use g53 with cutter radius comp")?;
        }
        let start_mm = self.position_mm;
        let offset = if machine { [0.0; 3] } else { self.offset() };
        let (mut end, mut end_mm) = self.target(words, offset)?;
        let angles = self.target_angles(words)?;
        if let (Motion::Probe(code), Some(feed)) = (motion, feed) {
            self.position = end;
            return self.probe_move(code, end_mm, feed, line);
        }
        if compensating {
            return match motion {
                Motion::Rapid | Motion::Line => self.compensated_straight(end, end_mm, feed, line),
                _ => {
                    let arc = self.arc(motion, words, &mut end, &mut end_mm)?;
                    let feed = feed.expect("arcs have a feed");
                    self.compensated_arc(motion, arc, end, end_mm, feed, line)
                }
            };
        }
        self.programmed_mm = None;
        let mut feed = feed;
        let kind = if motion.is_arc() {
            let arc = self.arc(motion, words, &mut end, &mut end_mm)?;
            MoveKind::Arc(arc)
        } else if end_mm == start_mm && angles == self.angles {
            self.position = end;
            return Ok(());
        } else {
            if moves_angles_only(start_mm, end_mm) && angles != self.angles {
                // A and B and C alone: F is degrees per minute.
                feed = feed.and(self.feed_degrees);
            }
            MoveKind::Line
        };
        self.position = end;
        self.position_mm = end_mm;
        self.angles = angles;
        if machine {
            self.sync_work_position();
        }
        self.toolpath.items.push(Item::Move(Move {
            kind,
            end: end_mm,
            angles,
            feed,
            laser: self.laser_along(feed),
            line,
        }));
        Ok(())
    }

    /// The block's axis words as an end: in the program's units (absolute
    /// or added to the work position, as G90 or G91 says) and in machine
    /// mm (`offset` added); an axis not written keeps its position.
    pub(super) fn target(
        &self,
        words: &Words,
        offset: [f64; 3],
    ) -> Result<([f64; 3], [f64; 3]), String> {
        let scale = self.units.mm_per_unit();
        let mut end = self.position;
        let mut end_mm = self.base_mm();
        for (axis, word) in words.axes.iter().enumerate() {
            if let Some(word) = word {
                end[axis] = if self.incremental {
                    end[axis] + word.value
                } else {
                    word.value
                };
                end_mm[axis] = end[axis] * scale + offset[axis];
                check_range(&format!("the {} axis", AXES[axis]), end_mm[axis])?;
            }
        }
        if let Some(xy) = self.polar_xy(words, [end[0], end[1]])? {
            for axis in 0..2 {
                end[axis] = xy[axis];
                end_mm[axis] = end[axis] * scale + offset[axis];
                check_range(&format!("the {} axis", AXES[axis]), end_mm[axis])?;
            }
        }
        Ok((end, end_mm))
    }

    /// The block's A, B, C as an end, degrees: absolute or added to the
    /// current angles, as G90 or G91 says; an axis not written keeps its
    /// angle.
    fn target_angles(&self, words: &Words) -> Result<[f64; 3], String> {
        let mut angles = self.angles;
        for (k, word) in words.rotary.iter().enumerate() {
            if let Some(w) = word {
                angles[k] = if self.incremental {
                    angles[k] + w.value
                } else {
                    w.value
                };
                if angles[k].abs() > POSITION_LIMIT_MM {
                    return Err(format!(
                        "the {} axis would be at {:.4} degrees, beyond ±{POSITION_LIMIT_MM} degrees",
                        ['A', 'B', 'C'][k],
                        angles[k]
                    ));
                }
            }
        }
        Ok(angles)
    }

    /// A, B and C move with G0 to G3 only, and not while cutter
    /// compensation is on.
    fn check_rotary_motion(&self, words: &Words, motion: Option<Motion>) -> Result<(), String> {
        let Some(word) = words.rotary.iter().flatten().next() else {
            return Ok(());
        };
        // Compensation is on for the block's motion when G41 or G42 turns
        // it on, or it was on and no G40 turns it off.
        let comp_after_block = match words.cutter_comp {
            Some((_, CutterComp::Off)) => false,
            Some(_) => true,
            None => self.comp.is_some(),
        };
        let taker = words
            .non_modal
            .filter(|(_, c)| c.takes_axes())
            .map(|(w, _)| w.name())
            .or(words
                .tool_length
                .filter(|(_, t)| t.takes_axes())
                .map(|(w, _)| w.name()));
        match motion {
            Some(Motion::Cycle(c)) => Err(format!(
                "{} with {}: the rotary axes move with G0, G1, G2 and G3 only, not in canned cycles",
                word.name(),
                c.name()
            )),
            Some(Motion::Probe(p)) => Err(format!(
                "{} with {}: the rotary axes move with G0, G1, G2 and G3 only, not in probe moves",
                word.name(),
                p.name()
            )),
            Some(_) if comp_after_block => Err(format!(
                "{}: the rotary axes cannot move while cutter radius compensation is on (G40 first)",
                word.name()
            )),
            Some(_) => Ok(()),
            None => Err(format!(
                "{} with {}: the rotary axes move with G0, G1, G2 and G3 only; their offsets and stored positions are not supported",
                word.name(),
                taker.unwrap_or_else(|| "no motion".to_string())
            )),
        }
    }

    /// A rapid to `end_mm` (machine), if it moves at all; the work
    /// position follows.
    pub(super) fn rapid_to_machine(&mut self, end_mm: [f64; 3], line: usize) {
        self.line_to(end_mm, None, line);
        self.sync_work_position();
    }

    /// A line to `end_mm` (machine) at `feed` (`None`: rapid), if it moves
    /// at all. The work position is the caller's to set.
    pub(super) fn line_to(&mut self, end_mm: [f64; 3], feed: Option<f64>, line: usize) {
        self.programmed_mm = None;
        if end_mm != self.position_mm {
            self.position_mm = end_mm;
            self.toolpath.items.push(Item::Move(Move {
                kind: MoveKind::Line,
                end: end_mm,
                angles: self.angles,
                feed,
                laser: self.laser_along(feed),
                line,
            }));
        }
    }

    /// The arc's shape; a full circle's end (`end` in program units and
    /// `end_mm`) is set to its start exactly, so that the planner sees the
    /// full circle the program meant rather than a sliver.
    fn arc(
        &self,
        motion: Motion,
        words: &Words,
        end: &mut [f64; 3],
        end_mm: &mut [f64; 3],
    ) -> Result<Arc, String> {
        let (first, second, normal) = self.plane.axes();
        let start = self.base_mm();
        let (mut a, mut b) = (AXES[first], AXES[second]);
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        let name = motion.name();
        // R needs an end in the plane; I, J, K alone make a full circle
        // (LinuxCNC's rule).
        let in_plane = words.axes[first].is_some()
            || words.axes[second].is_some()
            || (self.plane == Plane::Xy && words.polar.iter().any(Option::is_some));
        if words.radius.is_some() && !in_plane {
            return Err(format!(
                "{name} with R needs {a} or {b} (its end in the {} plane): R cannot make a full circle",
                self.plane.gcode()
            ));
        }
        if let Some(k) = words.offsets[normal] {
            let (i, j) = (a as u8 - b'X' + b'I', b as u8 - b'X' + b'I');
            return Err(format!(
                "{} is not in the {} plane's offsets ({} and {})",
                k.name(),
                self.plane.gcode(),
                i as char,
                j as char
            ));
        }
        let has_offset = words.offsets.iter().any(Option::is_some);
        if let (true, Some(r)) = (has_offset, words.radius) {
            return Err(format!(
                "{} with I, J or K: give the center or the radius, not both",
                r.name()
            ));
        }
        let turns = match words.p {
            None => 0,
            Some(p)
                if p.value >= 1.0 && p.value.fract() == 0.0 && p.value <= f64::from(u32::MAX) =>
            {
                p.value as u32 - 1
            }
            Some(p) => {
                return Err(format!(
                    "{} is not a number of turns: a whole number, 1 or more",
                    p.name()
                ))
            }
        };
        let clockwise = motion == Motion::Clockwise;
        let from = [start[first], start[second]];
        let to = [end_mm[first], end_mm[second]];
        let full = (to[0] - from[0]).hypot(to[1] - from[1]) <= SAME_POINT;
        let scale = self.units.mm_per_unit();
        let center = if let Some(r) = words.radius {
            if full {
                return Err(
                    "R cannot make a full circle (the end is the start); give the center with I, J or K".into(),
                );
            }
            center_from_radius(from, to, r.value * scale, clockwise, &r.name(), self.units)?
        } else if has_offset {
            let frame = self.offset();
            if !self.arc_incremental {
                if let Some(missing) = [first, second]
                    .into_iter()
                    .find(|&k| words.offsets[k].is_none())
                {
                    return Err(format!(
                        "{name} needs {} with G90.1: absolute arc centers need both of the {} plane's offsets \
                         (LinuxCNC: {} word missing in absolute center arc)",
                        offset_letter(missing),
                        self.plane.gcode(),
                        offset_letter(missing)
                    ));
                }
            }
            let center = [first, second].map(|axis| {
                let offset = words.offsets[axis].map_or(0.0, |w| w.value);
                let base = if self.arc_incremental {
                    self.position[axis]
                } else {
                    0.0
                };
                (base + offset) * scale + frame[axis]
            });
            if full {
                for axis in [first, second] {
                    end[axis] = self.position[axis];
                    end_mm[axis] = start[axis];
                }
            }
            check_center(from, if full { from } else { to }, center, self.units)?;
            center
        } else {
            return Err(format!("{name} needs a center (I, J or K) or a radius (R)"));
        };
        check_range("the arc's center", center[0])?;
        check_range("the arc's center", center[1])?;
        Ok(Arc {
            plane: self.plane,
            center,
            clockwise,
            turns,
        })
    }
}

/// I, J or K: the arc center offset along axis `k` (X, Y or Z).
fn offset_letter(k: usize) -> char {
    ['I', 'J', 'K'][k]
}

fn check_range(what: &str, mm: f64) -> Result<(), String> {
    if mm.abs() > POSITION_LIMIT_MM {
        return Err(format!(
            "{what} would be at {mm:.4} mm, beyond ±{POSITION_LIMIT_MM} mm"
        ));
    }
    Ok(())
}
