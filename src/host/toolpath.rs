//! Toolpaths: the moves a program asks for, in machine units (mm for
//! G-code, steps for a `.path` file in steps), before any planning.
//!
//! A toolpath is a start position and a list of [`Item`]s: straight lines,
//! circular arcs (helical when the axis normal to the arc's plane moves)
//! and dwells. Every position is absolute. The interpreters (the G-code
//! one and the `.path` file) produce it; the planner consumes it.

/// The plane of an arc (G17, G18, G19), with its axes ordered so that a
/// positive angle is counter-clockwise seen from the positive normal axis
/// (G3): XY about Z, ZX about Y, YZ about X.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Plane {
    /// G17: X and Y, normal Z.
    #[default]
    Xy,
    /// G18: Z and X, normal Y.
    Zx,
    /// G19: Y and Z, normal X.
    Yz,
}

impl Plane {
    /// The plane's (first, second, normal) axis indices (X = 0).
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::Xy => (0, 1, 2),
            Plane::Zx => (2, 0, 1),
            Plane::Yz => (1, 2, 0),
        }
    }

    /// The G code that selects it: "G17".
    pub fn gcode(self) -> &'static str {
        match self {
            Plane::Xy => "G17",
            Plane::Zx => "G18",
            Plane::Yz => "G19",
        }
    }
}

/// A circular arc's shape beyond its end point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// The plane of the circle.
    pub plane: Plane,
    /// The center, absolute, in the plane's (first, second) coordinates.
    pub center: [f64; 2],
    /// G2 (clockwise) or G3.
    pub clockwise: bool,
    /// Full turns beyond the first (G-code `P` minus 1): an arc whose end
    /// equals its start in the plane is a full circle, and `turns` more.
    pub turns: u32,
}

/// What kind of move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MoveKind {
    /// A straight line.
    Line,
    /// A circular or helical arc.
    Arc(Arc),
}

/// The laser's power along a move or through a dwell, on a machine with a
/// laser (`laser_s_max` in its settings): M3 or M4 with S, as a fraction
/// of full power. Off on every other machine, on rapids (G0) and after
/// M5.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct LaserPower {
    /// S over the machine's full-power S, 0 to 1 (0: off).
    pub fraction: f64,
    /// M4: scaled in gateware by the path speed over the programmed feed
    /// (grbl's dynamic mode); M3 (false): constant.
    pub dynamic: bool,
}

impl LaserPower {
    /// Off.
    pub const OFF: Self = Self {
        fraction: 0.0,
        dynamic: false,
    };

    /// Whether the laser burns: a power above 0.
    pub fn is_on(&self) -> bool {
        self.fraction > 0.0
    }
}

/// One move from the previous position to `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Move {
    /// Line or arc.
    pub kind: MoveKind,
    /// End position, absolute, machine units.
    pub end: [f64; 3],
    /// The rotary axes A, B, C at the end, absolute, degrees; they move
    /// linearly along the move. Always 0 on a machine without them (a
    /// `.path` file, G-code for the 3-axis controller).
    pub angles: [f64; 3],
    /// Path speed, machine units per second: along X Y Z, or in degrees
    /// per second (the A B C change's length) for a move of the rotary
    /// axes alone (LinuxCNC's rule); `None` for a rapid (G0): as fast as
    /// every axis's maximum velocity allows.
    pub feed: Option<f64>,
    /// The laser's power along it ([`LaserPower::OFF`] for a rapid).
    pub laser: LaserPower,
    /// The 1-based line of the program it came from.
    pub line: usize,
}

/// X Y Z travel below this many machine units with a change of A, B or C
/// is a move of the angles alone (its F is degrees per minute): a sum of
/// incremental moves can leave 1e-17 mm where the program meant none.
pub const ANGLES_ONLY_TRAVEL: f64 = 1e-7;

/// Whether a move from `start` to `end` (X Y Z) moves the angles alone,
/// its travel below [`ANGLES_ONLY_TRAVEL`].
pub fn moves_angles_only(start: [f64; 3], end: [f64; 3]) -> bool {
    let d: f64 = (0..3).map(|k| (end[k] - start[k]).powi(2)).sum();
    d.sqrt() < ANGLES_ONLY_TRAVEL
}

/// A straight move of one axis geared to the spindle (G33, G33.1, each
/// pass of a G76): the controller's electronic gearbox steps the axis
/// `pitch` mm per spindle revolution from the next index on, and the
/// move ends exactly at `end`. The planner does not plan it; the driver
/// arms the gearbox for it (see [`crate::host::driver::GearRun`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SyncedMove {
    /// The one axis that moves (X = 0).
    pub axis: usize,
    /// Start position, absolute, machine mm (the previous item's end).
    pub start: [f64; 3],
    /// End position, absolute, machine mm: where the gearbox stops (for
    /// a rigid tap, the bottom of the hole; the tap then comes back to
    /// `start`).
    pub end: [f64; 3],
    /// Travel along the axis per spindle revolution, mm (above zero).
    pub pitch: f64,
    /// The spindle speed programmed (S), rpm, above zero.
    pub rpm: f64,
    /// M3 (true, clockwise) or M4.
    pub clockwise: bool,
    /// G33.1: at `end` the spindle reverses and the axis follows it back
    /// to where the move started.
    pub rigid_tap: bool,
    /// A G76 pass: its number in the cycle, from 1; `None` for a G33 or
    /// G33.1.
    pub pass: Option<u32>,
    /// The 1-based line of the program it came from.
    pub line: usize,
}

/// One item of a toolpath.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Item {
    /// A move.
    Move(Move),
    /// A move geared to the spindle.
    Synced(SyncedMove),
    /// A pause at rest (G4), seconds.
    Dwell {
        /// How long.
        seconds: f64,
        /// The laser's power meanwhile (M3 pierces; M4 is off at rest).
        laser: LaserPower,
        /// The 1-based line of the program.
        line: usize,
    },
}

/// A start position and the moves from it.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Toolpath {
    /// Start position, machine units.
    pub start: [f64; 3],
    /// The rotary axes A, B, C at the start, degrees.
    pub start_angles: [f64; 3],
    /// The moves and dwells, in order.
    pub items: Vec<Item>,
}

impl Toolpath {
    /// The position after the last move.
    pub fn end(&self) -> [f64; 3] {
        self.items
            .iter()
            .rev()
            .find_map(|item| match item {
                Item::Move(m) => Some(m.end),
                Item::Synced(m) if m.rigid_tap => Some(m.start),
                Item::Synced(m) => Some(m.end),
                Item::Dwell { .. } => None,
            })
            .unwrap_or(self.start)
    }

    /// The rotary axes after the last move, degrees.
    pub fn end_angles(&self) -> [f64; 3] {
        self.items
            .iter()
            .rev()
            .find_map(|item| match item {
                Item::Move(m) => Some(m.angles),
                Item::Synced(_) | Item::Dwell { .. } => None,
            })
            .unwrap_or(self.start_angles)
    }
}
