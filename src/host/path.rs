//! Paths: 3-axis line segments with feed, acceleration and contour error,
//! and the path file format.
//!
//! ## Path file format
//! Plain text, one statement per line; `#` starts a comment. Numbers are
//! decimal (`1.5`, `-20`). Settings come before the first `line`:
//!
//! ```text
//! units mm                  # mm (default: steps); mm needs steps_per_mm
//! steps_per_mm 80 80 400    # X Y Z
//! feed 50                   # path speed, units per second
//! accel 500                 # units per second^2
//! contour_error 0.02        # allowed corner deviation, units
//! period_us 250             # interpolation period T (default 1000)
//! start 0 0 0               # start position (default 0 0 0)
//! line 10 0 0               # a straight move to this absolute position
//! line 10 5 0
//! ```
//!
//! Every error names the line and the problem.

use thiserror::Error;

use super::machine::MachineSettings;
use super::planner::MAX_POSITION_STEPS;
use super::statements::statements;
use super::toolpath::{Item, LaserPower, Move, MoveKind, Toolpath};

/// A problem in a path file or a path.
#[derive(Debug, Error, PartialEq)]
pub enum PathError {
    /// A line of the file could not be understood.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A setting is missing or out of range.
    #[error("{0}")]
    Invalid(String),
}

/// A straight move to an absolute position, in steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segment {
    /// End position in steps (X, Y, Z).
    pub end: [i64; 3],
}

/// A path in steps with its limits in its units (steps, or mm with
/// `steps_per_unit`) and seconds.
#[derive(Clone, Debug, PartialEq)]
pub struct Path {
    /// Start position in steps.
    pub start: [i64; 3],
    /// The moves, in order.
    pub segments: Vec<Segment>,
    /// Steps per unit, per axis (1 for a path in steps): the path is
    /// planned in its units, so an axis with more steps per mm is not
    /// driven faster than the others.
    pub steps_per_unit: [f64; 3],
    /// Path feed rate, units per second (along the path).
    pub feed: f64,
    /// Maximum path acceleration, units per second^2.
    pub accel: f64,
    /// Maximum contour error at a corner, units.
    pub contour_error: f64,
    /// Interpolation period T in seconds.
    pub period: f64,
}

impl Path {
    /// A path in steps; checks the limits.
    pub fn new(
        start: [i64; 3],
        ends: &[[i64; 3]],
        feed: f64,
        accel: f64,
        contour_error: f64,
        period: f64,
    ) -> Result<Self, PathError> {
        let path = Self {
            start,
            segments: ends.iter().map(|&end| Segment { end }).collect(),
            steps_per_unit: [1.0; 3],
            feed,
            accel,
            contour_error,
            period,
        };
        path.validate()?;
        Ok(path)
    }

    /// Checks every limit is a finite positive number and the path is not
    /// empty.
    pub fn validate(&self) -> Result<(), PathError> {
        for (name, value) in [
            ("feed", self.feed),
            ("accel", self.accel),
            ("period", self.period),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(PathError::Invalid(format!(
                    "{name} must be a positive number, not {value}"
                )));
            }
        }
        if !(self.contour_error.is_finite() && self.contour_error >= 0.0) {
            return Err(PathError::Invalid(format!(
                "contour_error must be 0 or positive, not {}",
                self.contour_error
            )));
        }
        if self.segments.is_empty() {
            return Err(PathError::Invalid("the path has no `line`".into()));
        }
        Ok(())
    }

    /// The end position of the path.
    pub fn end(&self) -> [i64; 3] {
        self.segments.last().map_or(self.start, |s| s.end)
    }

    /// The path as lines in its units, every one at the path's feed.
    pub fn toolpath(&self) -> Toolpath {
        let units = |p: [i64; 3]| std::array::from_fn(|k| p[k] as f64 / self.steps_per_unit[k]);
        Toolpath {
            start: units(self.start),
            items: self
                .segments
                .iter()
                .map(|s| {
                    Item::Move(Move {
                        kind: MoveKind::Line,
                        end: units(s.end),
                        angles: [0.0; 3],
                        feed: Some(self.feed),
                        laser: LaserPower::OFF,
                        line: 0,
                    })
                })
                .collect(),
            ..Toolpath::default()
        }
    }

    /// The path's limits as a machine: its acceleration along the path, no
    /// per-axis limits.
    pub fn machine(&self) -> MachineSettings {
        MachineSettings {
            steps_per_mm: self.steps_per_unit,
            max_velocity: [f64::INFINITY; 3],
            max_accel: [f64::INFINITY; 3],
            path_accel: self.accel,
            contour_error: self.contour_error,
            period: self.period,
            parameters: Default::default(),
            spindle_counts_per_rev: 0,
            ..MachineSettings::default()
        }
    }

    /// Parses a path file (see the [module documentation](self)).
    pub fn parse(text: &str) -> Result<Self, PathError> {
        let mut steps_per_mm: Option<[f64; 3]> = None;
        let mut mm = false;
        let (mut feed, mut accel, mut contour) = (None, None, 0.0);
        let mut period_us = 1000.0;
        let mut start = [0.0; 3];
        let mut lines: Vec<(usize, [f64; 3])> = Vec::new();
        for statement in statements(text) {
            let (line, keyword) = (statement.line, statement.keyword);
            let settings_before_lines = |lines: &Vec<(usize, [f64; 3])>| {
                if lines.is_empty() {
                    Ok(())
                } else {
                    Err(statement.error(format!("`{keyword}` must come before the first `line`")))
                }
            };
            if keyword == "units" {
                settings_before_lines(&lines)?;
                mm = match statement.words.first().copied().unwrap_or("") {
                    "mm" => true,
                    "steps" => false,
                    other => {
                        return Err(statement.error(format!("unknown unit `{other}` (mm or steps)")))
                    }
                };
                continue;
            }
            let numbers = statement.numbers()?;
            match keyword {
                "steps_per_mm" => {
                    let values = numbers.exactly::<3>()?;
                    settings_before_lines(&lines)?;
                    if values.iter().any(|&v| v <= 0.0) {
                        return Err(statement.error("steps_per_mm must be positive".into()));
                    }
                    steps_per_mm = Some(values);
                }
                "feed" | "accel" | "contour_error" | "period_us" => {
                    let [v] = numbers.exactly()?;
                    settings_before_lines(&lines)?;
                    match keyword {
                        "feed" => feed = Some(v),
                        "accel" => accel = Some(v),
                        "contour_error" => contour = v,
                        _ => period_us = v,
                    }
                }
                "start" => {
                    start = numbers.exactly()?;
                    settings_before_lines(&lines)?;
                }
                "line" => lines.push((line, numbers.exactly()?)),
                other => return Err(statement.error(format!("unknown statement `{other}`"))),
            }
        }
        // Positions rounded to the nearest step; speeds stay in the path's
        // units, planned in them.
        let scale = match (mm, steps_per_mm) {
            (false, _) => [1.0; 3],
            (true, Some(s)) => s,
            (true, None) => return Err(PathError::Invalid("units mm needs steps_per_mm".into())),
        };
        let to_steps = |p: [f64; 3]| -> Result<[i64; 3], PathError> {
            let mut out = [0i64; 3];
            for k in 0..3 {
                let v = (p[k] * scale[k]).round();
                if v.abs() > MAX_POSITION_STEPS {
                    return Err(PathError::Invalid(format!(
                        "position {} is out of range",
                        p[k]
                    )));
                }
                out[k] = v as i64;
            }
            Ok(out)
        };
        let ends = lines
            .iter()
            .map(|&(line, p)| {
                to_steps(p).map_err(|e| PathError::Syntax {
                    line,
                    message: e.to_string(),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let feed = feed.ok_or_else(|| PathError::Invalid("missing `feed`".into()))?;
        let accel = accel.ok_or_else(|| PathError::Invalid("missing `accel`".into()))?;
        let mut path = Self::new(
            to_steps(start)?,
            &ends,
            feed,
            accel,
            contour,
            period_us * 1e-6,
        )?;
        path.steps_per_unit = scale;
        Ok(path)
    }
}
