//! One block's words, read and sorted by their role, with the tables of
//! the G and M codes this interpreter runs, accepts, ignores or refuses.
//! Errors come back as messages without the line.

use std::collections::HashSet;

use super::interpreter::Units;
use super::lexer::{Block, Word};
use super::probing::ProbeCode;
use crate::host::toolpath::Plane;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Motion {
    Rapid,
    Line,
    Clockwise,
    CounterClockwise,
    Cycle(Cycle),
    /// G38.2 to G38.5.
    Probe(ProbeCode),
    /// G33: one axis geared to the spindle.
    SpindleSync,
    /// G33.1: rigid tapping, geared to the spindle there and back.
    RigidTap,
    /// G76: LinuxCNC's threading cycle.
    Threading,
}

/// The canned cycles that run here.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Cycle {
    /// Peck drilling, chip breaking: back off by the clearance.
    G73,
    /// Drilling.
    G81,
    /// Drilling with a dwell.
    G82,
    /// Peck drilling: back out to R after each peck.
    G83,
    /// Boring, feed out.
    G85,
    /// Boring, spindle stop, rapid out.
    G86,
    /// Back boring.
    G87,
    /// Boring, spindle stop, manual out.
    G88,
    /// Boring, dwell, feed out.
    G89,
    /// Left-hand tapping with a floating holder: feed in, the spindle
    /// reverses, dwell, feed out.
    G74,
    /// Right-hand tapping with a floating holder.
    G84,
}

impl Cycle {
    pub(super) fn name(self) -> &'static str {
        match self {
            Cycle::G73 => "G73",
            Cycle::G81 => "G81",
            Cycle::G82 => "G82",
            Cycle::G83 => "G83",
            Cycle::G85 => "G85",
            Cycle::G86 => "G86",
            Cycle::G87 => "G87",
            Cycle::G88 => "G88",
            Cycle::G89 => "G89",
            Cycle::G74 => "G74",
            Cycle::G84 => "G84",
        }
    }
}

impl Motion {
    pub(super) fn name(self) -> &'static str {
        match self {
            Motion::Rapid => "G0",
            Motion::Line => "G1",
            Motion::Clockwise => "G2",
            Motion::CounterClockwise => "G3",
            Motion::Cycle(c) => c.name(),
            Motion::Probe(p) => p.name(),
            Motion::SpindleSync => "G33",
            Motion::RigidTap => "G33.1",
            Motion::Threading => "G76",
        }
    }

    pub(super) fn is_arc(self) -> bool {
        matches!(self, Motion::Clockwise | Motion::CounterClockwise)
    }

    pub(super) fn is_cycle(self) -> bool {
        matches!(self, Motion::Cycle(_))
    }
}

/// The non-modal G codes other than G4 (LinuxCNC's group 0): each acts
/// on its own block only.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum NonModal {
    /// G10 (L2, L20): set a coordinate system's origin.
    SetOrigin,
    /// G28 (`second` false) or G30: rapid to the stored position.
    Home { second: bool },
    /// G28.1 or G30.1: store the current position.
    StoreHome { second: bool },
    /// G53: the block's G0 or G1 in machine coordinates.
    MachineCoordinates,
    /// G92: offset the coordinates so that the position reads the words.
    SetOffset,
    /// G92.1: clear the G92 offset and its parameters.
    ClearOffset,
    /// G92.2: stop applying the G92 offset, keeping its parameters.
    SuspendOffset,
    /// G92.3: apply the G92 offset kept in its parameters.
    RestoreOffset,
}

impl NonModal {
    /// Whether the code takes the block's axis words (then no motion runs).
    pub(super) fn takes_axes(self) -> bool {
        matches!(
            self,
            NonModal::SetOrigin | NonModal::Home { .. } | NonModal::SetOffset
        )
    }

    /// Whether the code reads axis words at all.
    pub(super) fn reads_axes(self) -> bool {
        self.takes_axes() || self == NonModal::MachineCoordinates
    }
}

/// G43, G43.1, G43.2, G49: the tool length offset (LinuxCNC's group 8).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum ToolLength {
    /// G43 [H]: the offset of tool H, or of the loaded tool.
    FromTable,
    /// G43.1: the offset given by the axis words.
    Dynamic,
    /// G43.2: tool H's offset or the axis words added to the one in force.
    Add,
    /// G49: no offset.
    Cancel,
}

impl ToolLength {
    /// Whether the code takes the block's axis words (G43.1, G43.2).
    pub(super) fn takes_axes(self) -> bool {
        matches!(self, ToolLength::Dynamic | ToolLength::Add)
    }
}

/// G40, G41, G42, G41.1, G42.1: cutter radius compensation (LinuxCNC's
/// group 7).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum CutterComp {
    /// G40.
    Off,
    /// G41 (`left`) or G42: the radius of tool D from the tool table, or
    /// of the loaded tool without D.
    FromTable { left: bool },
    /// G41.1 (`left`) or G42.1: D is the diameter.
    Dynamic { left: bool },
}

/// The group message of LinuxCNC's group 0: one code of it per block.
const GROUP_0: &str = "one non-modal code (G4, G10, G28, G30, G53, G92) per block";

const CUTTER_COMP: &str = "both set cutter radius compensation";

/// What a supported or accepted G code does.
#[derive(Clone, Copy)]
enum GEffect {
    Motion(Motion),
    /// G80: no motion mode (LinuxCNC's motion group 1).
    CancelMotion,
    Dwell,
    NonModal(NonModal),
    ToolLength(ToolLength),
    CutterComp(CutterComp),
    /// G54 to G59.3: 0 to 8.
    System(usize),
    /// G98 (false: back to the initial level), G99 (true: to R).
    RetractToR(bool),
    Plane(Plane),
    Units(Units),
    Incremental(bool),
    ArcIncremental(bool),
    /// G64, G61, G61.1: reported; G64 may carry P and Q.
    PathControl,
    /// Accepted, no effect, not reported: the default or a cancel.
    Nothing,
    /// Accepted, no effect on the motion, reported.
    Ignored(&'static str),
}

/// A G code's effect and its modal group, named by what two codes of the
/// group in one block would both do (the end of the error message).
fn g_effect(code: u32) -> Option<(GEffect, &'static str)> {
    use GEffect::*;
    Some(match code {
        0 => (Motion(self::Motion::Rapid), "one motion per block"),
        10 => (Motion(self::Motion::Line), "one motion per block"),
        20 => (Motion(self::Motion::Clockwise), "one motion per block"),
        30 => (
            Motion(self::Motion::CounterClockwise),
            "one motion per block",
        ),
        800 => (CancelMotion, "one motion per block"),
        382 => (
            Motion(self::Motion::Probe(ProbeCode::G38_2)),
            "one motion per block",
        ),
        383 => (
            Motion(self::Motion::Probe(ProbeCode::G38_3)),
            "one motion per block",
        ),
        384 => (
            Motion(self::Motion::Probe(ProbeCode::G38_4)),
            "one motion per block",
        ),
        385 => (
            Motion(self::Motion::Probe(ProbeCode::G38_5)),
            "one motion per block",
        ),
        730 => (
            Motion(self::Motion::Cycle(self::Cycle::G73)),
            "one motion per block",
        ),
        810 => (
            Motion(self::Motion::Cycle(self::Cycle::G81)),
            "one motion per block",
        ),
        820 => (
            Motion(self::Motion::Cycle(self::Cycle::G82)),
            "one motion per block",
        ),
        830 => (
            Motion(self::Motion::Cycle(self::Cycle::G83)),
            "one motion per block",
        ),
        850 => (
            Motion(self::Motion::Cycle(self::Cycle::G85)),
            "one motion per block",
        ),
        860 => (
            Motion(self::Motion::Cycle(self::Cycle::G86)),
            "one motion per block",
        ),
        870 => (
            Motion(self::Motion::Cycle(self::Cycle::G87)),
            "one motion per block",
        ),
        880 => (
            Motion(self::Motion::Cycle(self::Cycle::G88)),
            "one motion per block",
        ),
        890 => (
            Motion(self::Motion::Cycle(self::Cycle::G89)),
            "one motion per block",
        ),
        740 => (
            Motion(self::Motion::Cycle(self::Cycle::G74)),
            "one motion per block",
        ),
        840 => (
            Motion(self::Motion::Cycle(self::Cycle::G84)),
            "one motion per block",
        ),
        330 => (Motion(self::Motion::SpindleSync), "one motion per block"),
        331 => (Motion(self::Motion::RigidTap), "one motion per block"),
        760 => (Motion(self::Motion::Threading), "one motion per block"),
        980 => (
            RetractToR(false),
            "both select the canned cycle return level",
        ),
        990 => (
            RetractToR(true),
            "both select the canned cycle return level",
        ),
        40 => (Dwell, GROUP_0),
        100 => (NonModal(self::NonModal::SetOrigin), GROUP_0),
        280 => (NonModal(self::NonModal::Home { second: false }), GROUP_0),
        300 => (NonModal(self::NonModal::Home { second: true }), GROUP_0),
        281 => (
            NonModal(self::NonModal::StoreHome { second: false }),
            GROUP_0,
        ),
        301 => (
            NonModal(self::NonModal::StoreHome { second: true }),
            GROUP_0,
        ),
        530 => (NonModal(self::NonModal::MachineCoordinates), GROUP_0),
        920 => (NonModal(self::NonModal::SetOffset), GROUP_0),
        921 => (NonModal(self::NonModal::ClearOffset), GROUP_0),
        922 => (NonModal(self::NonModal::SuspendOffset), GROUP_0),
        923 => (NonModal(self::NonModal::RestoreOffset), GROUP_0),
        540 | 550 | 560 | 570 | 580 | 590 => (
            System((code / 10 - 54) as usize),
            "both select the coordinate system",
        ),
        591..=593 => (
            System((code - 585) as usize),
            "both select the coordinate system",
        ),
        170 => (Plane(self::Plane::Xy), "both select the plane"),
        180 => (Plane(self::Plane::Zx), "both select the plane"),
        190 => (Plane(self::Plane::Yz), "both select the plane"),
        200 => (Units(self::Units::Inch), "both select the units"),
        210 => (Units(self::Units::Millimetre), "both select the units"),
        900 => (Incremental(false), "both select the distance mode"),
        910 => (Incremental(true), "both select the distance mode"),
        901 => (ArcIncremental(false), "both select the arc center mode"),
        911 => (ArcIncremental(true), "both select the arc center mode"),
        610 | 611 | 640 => (PathControl, "both select path control"),
        940 => (Nothing, "both select the feed mode"),
        400 => (CutterComp(self::CutterComp::Off), CUTTER_COMP),
        410 => (
            CutterComp(self::CutterComp::FromTable { left: true }),
            CUTTER_COMP,
        ),
        420 => (
            CutterComp(self::CutterComp::FromTable { left: false }),
            CUTTER_COMP,
        ),
        411 => (
            CutterComp(self::CutterComp::Dynamic { left: true }),
            CUTTER_COMP,
        ),
        421 => (
            CutterComp(self::CutterComp::Dynamic { left: false }),
            CUTTER_COMP,
        ),
        430 => (
            ToolLength(self::ToolLength::FromTable),
            "both set the tool length offset",
        ),
        431 => (
            ToolLength(self::ToolLength::Dynamic),
            "both set the tool length offset",
        ),
        432 => (
            ToolLength(self::ToolLength::Add),
            "both set the tool length offset",
        ),
        490 => (
            ToolLength(self::ToolLength::Cancel),
            "both set the tool length offset",
        ),
        960 | 970 => (Ignored("spindle"), "both select the spindle speed mode"),
        _ => return None,
    })
}

/// The G codes refused because they would change the motion, with what
/// they do.
fn g_refused(code: u32) -> Option<&'static str> {
    Some(match code {
        50..=53 => "spline",
        70 => "lathe diameter mode",
        80 => "lathe radius mode",
        520 => "local coordinate offset",
        930 => "inverse-time feed",
        950 => "feed per revolution",
        _ => return None,
    })
}

/// What an M code does (`None`: the end of the program), and the group
/// within which two in one block are an error.
fn m_effect(code: u32) -> (Option<&'static str>, Option<&'static str>) {
    const STOP: Option<&str> = Some("both stop the program");
    match code {
        20 | 300 => (None, STOP),
        0 | 10 | 600 => (Some("program pause"), STOP),
        30 | 40 | 50 => (Some("spindle"), Some("both set the spindle")),
        60 => (Some("tool change"), None),
        610 => (Some("tool"), None),
        70 | 80 | 90 => (Some("coolant"), None),
        480..=530 => (Some("override"), None),
        620..=680 => (Some("digital and analog I/O"), None),
        _ => (Some("unknown M code"), None),
    }
}

/// One block's words, sorted by their role.
#[derive(Default)]
pub(super) struct Words<'a> {
    pub(super) motion: Option<(&'a Word, Motion)>,
    /// G80.
    pub(super) cancel_motion: Option<&'a Word>,
    /// G10, G28, G30, G53, G92 and their variants.
    pub(super) non_modal: Option<(&'a Word, NonModal)>,
    /// G54 to G59.3: 0 to 8.
    pub(super) system: Option<usize>,
    /// G43, G43.1, G43.2, G49 as written.
    pub(super) tool_length: Option<(&'a Word, ToolLength)>,
    /// G40, G41, G42, G41.1, G42.1 as written.
    pub(super) cutter_comp: Option<(&'a Word, CutterComp)>,
    /// T: the tool to select.
    pub(super) tool: Option<&'a Word>,
    /// H: the tool whose offset G43 or G43.2 takes.
    pub(super) h: Option<&'a Word>,
    /// D: G41's and G42's tool, G41.1's and G42.1's diameter, G73's and
    /// G83's clearance (else reported).
    pub(super) d: Option<&'a Word>,
    /// G98 (false), G99 (true).
    pub(super) retract_to_r: Option<bool>,
    /// M3 (Some(true)), M4 (Some(false)): the spindle turns; M5: stops.
    pub(super) spindle: Option<Option<bool>>,
    /// M6: load the selected tool.
    pub(super) tool_change: Option<&'a Word>,
    /// M61: set the loaded tool to Q.
    pub(super) set_tool: Option<&'a Word>,
    pub(super) dwell: Option<&'a Word>,
    pub(super) plane: Option<Plane>,
    pub(super) units: Option<Units>,
    pub(super) incremental: Option<bool>,
    pub(super) arc_incremental: Option<bool>,
    /// G61, G61.1 or G64 as written.
    pub(super) path_control: Option<&'a Word>,
    pub(super) end: bool,
    /// M0, M1 or M60: a pause, which ends a compensated path's look-ahead.
    pub(super) pause: Option<&'a Word>,
    pub(super) axes: [Option<&'a Word>; 3],
    /// A, B, C: the rotary axes, degrees (accepted by the interpreter only
    /// on a machine that has them, [`super::Setup::rotary_axes`]).
    pub(super) rotary: [Option<&'a Word>; 3],
    /// `@` (distance) and `^` (angle, degrees): X and Y in polar
    /// coordinates about the work origin.
    pub(super) polar: [Option<&'a Word>; 2],
    pub(super) offsets: [Option<&'a Word>; 3],
    pub(super) radius: Option<&'a Word>,
    /// R on a G10 block: the coordinate system's rotation.
    pub(super) rotation: Option<&'a Word>,
    pub(super) l: Option<&'a Word>,
    /// The first X, Y, Z, A, B or C and the first I, J, K or R as written, for the
    /// messages.
    pub(super) first_axis: Option<&'a Word>,
    pub(super) first_center: Option<&'a Word>,
    pub(super) feed: Option<&'a Word>,
    pub(super) p: Option<&'a Word>,
    pub(super) q: Option<&'a Word>,
    /// S: the spindle speed, rpm.
    pub(super) s: Option<&'a Word>,
    /// E: G76's taper length (else an extruder, refused).
    pub(super) e: Option<&'a Word>,
    /// (the word, what it controls, the key it is reported once under).
    pub(super) ignored: Vec<(&'a Word, &'static str, String)>,
    /// `O<number>` alone on its block: a post's program number.
    pub(super) program_number: Option<&'a Word>,
}

impl<'a> Words<'a> {
    /// The block's words on a machine with X, Y, Z and, with
    /// `rotary_axes`, A, B, C.
    pub(super) fn read(block: &'a Block, rotary_axes: bool) -> Result<Self, String> {
        let mut words = Words::default();
        let mut groups: Vec<(&'static str, &Word)> = Vec::new();
        let mut letters = HashSet::new();

        for word in &block.words {
            let name = word.name();
            if !word.value.is_finite() {
                return Err(format!("{name} is not a finite number"));
            }
            let mut group = |group: &'static str| match groups.iter().find(|(g, _)| *g == group) {
                Some((_, first)) => {
                    Err(format!("{} and {name} in one block: {group}", first.name()))
                }
                None => {
                    groups.push((group, word));
                    Ok(())
                }
            };
            match word.letter {
                'G' => {
                    let code = word
                        .code()
                        .ok_or_else(|| format!("{name} is not a G code"))?;
                    if let Some(what) = g_refused(code) {
                        return Err(format!(
                            "{name} ({what}) changes the motion and is not supported"
                        ));
                    }
                    let (effect, g) = g_effect(code)
                        .ok_or_else(|| format!("{name} is not a supported G code"))?;
                    // LinuxCNC lets G80 share a block with another motion
                    // code, which wins (its read_g).
                    if !matches!(effect, GEffect::CancelMotion) {
                        group(g)?;
                    }
                    match effect {
                        GEffect::Motion(m) => words.motion = Some((word, m)),
                        GEffect::CancelMotion => words.cancel_motion = Some(word),
                        GEffect::NonModal(n) => words.non_modal = Some((word, n)),
                        GEffect::System(index) => words.system = Some(index),
                        GEffect::ToolLength(t) => words.tool_length = Some((word, t)),
                        GEffect::CutterComp(c) => words.cutter_comp = Some((word, c)),
                        GEffect::RetractToR(r) => words.retract_to_r = Some(r),
                        GEffect::Dwell => words.dwell = Some(word),
                        GEffect::Plane(p) => words.plane = Some(p),
                        GEffect::Units(u) => words.units = Some(u),
                        GEffect::Incremental(i) => words.incremental = Some(i),
                        GEffect::ArcIncremental(i) => words.arc_incremental = Some(i),
                        GEffect::PathControl => {
                            words.path_control = Some(word);
                            words.ignored.push((word, "path control", g_name(code)));
                        }
                        GEffect::Nothing => {}
                        GEffect::Ignored(what) => words.ignored.push((word, what, g_name(code))),
                    }
                }
                'M' => {
                    let code = word
                        .code()
                        .filter(|c| c % 10 == 0)
                        .ok_or_else(|| format!("{name} is not an M code"))?;
                    match code {
                        30 => words.spindle = Some(Some(true)),
                        40 => words.spindle = Some(Some(false)),
                        50 => words.spindle = Some(None),
                        60 => words.tool_change = Some(word),
                        610 => words.set_tool = Some(word),
                        0 | 10 | 600 => words.pause = Some(word),
                        _ => {}
                    }
                    let (effect, m) = m_effect(code);
                    if let Some(m) = m {
                        group(m)?;
                    }
                    match effect {
                        None => words.end = true,
                        Some(what) => words.ignored.push((word, what, format!("M{}", code / 10))),
                    }
                }
                letter => {
                    if !letters.insert(letter) {
                        return Err(format!("{letter} appears twice"));
                    }
                    match letter {
                        'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | '@' | '^' => {
                            words.first_axis = words.first_axis.or(Some(word))
                        }
                        'I' | 'J' | 'K' | 'R' => {
                            words.first_center = words.first_center.or(Some(word))
                        }
                        _ => {}
                    }
                    let slot = match letter {
                        'X' | 'Y' | 'Z' => &mut words.axes[axis_index(letter, 'X')],
                        'A' | 'B' | 'C' if rotary_axes => {
                            &mut words.rotary[axis_index(letter, 'A')]
                        }
                        '@' => &mut words.polar[0],
                        '^' => &mut words.polar[1],
                        'I' | 'J' | 'K' => &mut words.offsets[axis_index(letter, 'I')],
                        'R' => &mut words.radius,
                        'F' => &mut words.feed,
                        'P' => &mut words.p,
                        'Q' => &mut words.q,
                        'T' => {
                            words.ignored.push((word, "tool", "T".to_string()));
                            &mut words.tool
                        }
                        'H' => &mut words.h,
                        'D' => &mut words.d,
                        'S' => {
                            words.ignored.push((
                                word,
                                "spindle speed (G33, G33.1 and G76 use it)",
                                "S".to_string(),
                            ));
                            &mut words.s
                        }
                        'A' | 'B' | 'C' | 'U' | 'V' | 'W' => {
                            let have = if rotary_axes {
                                "X, Y, Z, A, B and C only"
                            } else {
                                "X, Y and Z only"
                            };
                            return Err(format!(
                                "{name} moves an axis this machine does not have ({have})"
                            ));
                        }
                        'E' => &mut words.e,
                        'O' if block.words.len() == 1
                            && word.value >= 0.0
                            && word.value.fract() == 0.0 =>
                        {
                            words.program_number = Some(word);
                            words
                                .ignored
                                .push((word, "program number", "O".to_string()));
                            continue;
                        }
                        'O' => {
                            return Err(format!(
                                "{name}: subroutines and flow control (O words) are not supported"
                            ))
                        }
                        'L' => &mut words.l,
                        _ => return Err(format!("{name} is not a word this interpreter knows")),
                    };
                    *slot = Some(word);
                }
            }
        }
        if words.motion.is_some() {
            words.cancel_motion = None;
        }
        if let Some(e) = words
            .e
            .filter(|_| !matches!(words.motion, Some((_, Motion::Threading))))
        {
            return Err(format!(
                "{} drives an extruder (RepRap), an axis this machine does not have",
                e.name()
            ));
        }
        if let Some((_, NonModal::SetOrigin)) = words.non_modal {
            // G10's R is the system's rotation, not an arc's radius.
            words.rotation = words.radius.take();
            words.first_center = block
                .words
                .iter()
                .find(|w| matches!(w.letter, 'I' | 'J' | 'K'));
        }
        Ok(words)
    }
}

fn axis_index(letter: char, first: char) -> usize {
    (letter as u8 - first as u8) as usize
}

/// G64.0 as "G64", G61.1 as "G61.1".
fn g_name(code: u32) -> String {
    match code % 10 {
        0 => format!("G{}", code / 10),
        minor => format!("G{}.{minor}", code / 10),
    }
}
