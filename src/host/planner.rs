//! Velocity planning with look-ahead over lines, arcs and dwells: a
//! trapezoidal speed profile per move, junction speeds limited by
//! acceleration and contour error, every limit per axis.
//!
//! All in machine units (mm; steps for a `.path` file in steps) and
//! seconds.
//!
//! * **Speed limit of a move** (`v_limit`): its feed (a rapid has none),
//!   and each axis's maximum velocity over the share of the move it
//!   carries. A line with unit direction u: v <= vmax_k / |u_k|. An arc's
//!   plane axes each carry at most the plane share p of the speed, its
//!   normal axis the share h (a helix): v <= vmax_k / p, vmax_n / h.
//! * **Acceleration of a move** (`accel`, along the path): a line's is
//!   min(path accel, amax_k / |u_k|). An arc's plane axes also carry the
//!   centripetal acceleration; with A the smaller plane-axis limit, an arc
//!   gives half of A to the tangential acceleration and sqrt(3)/2 of A to
//!   the centripetal one (LinuxCNC's split), so that on any plane axis
//!   sqrt(a_t^2 + a_n^2) <= A. Its speed is limited by v^2 p^2 / r <=
//!   sqrt(3)/2 A (r the smaller radius).
//! * **Chord error of an arc**: the controller moves in a straight line
//!   within a period, so an arc is followed by chords of one period each.
//!   A chord of angle phi on radius r deviates r (1 - cos(phi / 2)) from
//!   the arc; the speed is limited so that this stays within the contour
//!   error e: v p T / r <= 2 acos(1 - e / r). An arc needs e > 0.
//! * **Corner speed** (the junction-deviation rule): a corner between the
//!   unit tangents u1 (end of one move) and u2 (start of the next) is
//!   passed at most at v = sqrt(a e s / (1 - s)), s = sin(theta / 2),
//!   theta the angle between -u1 and u2, a the smaller of the two moves'
//!   accelerations: the speed at which a circular arc of deviation e from
//!   the corner is driven at acceleration a. A reversal gives 0; a tangent
//!   junction (a line into an arc along its tangent) only the moves' own
//!   limits. A dwell stops the path on both sides.
//! * **Look-ahead**: a backward pass caps each entry speed so that the
//!   move can still decelerate to its exit speed (v0^2 <= v1^2 + 2aL), a
//!   forward pass caps each exit speed by what the move can reach
//!   (v1^2 <= v0^2 + 2aL). The path starts and ends at rest.
//! * Each move then accelerates to min(v_limit, the triangle peak
//!   sqrt((2aL + v0^2 + v1^2) / 2)), cruises, and decelerates.
//!
//! What a corner does to the axes is the contour-error rule's business: a
//! corner's speed changes direction within a period, which the per-axis
//! acceleration limits do not cover (as in Grbl and Marlin).

use super::geometry::{unit, ArcGeometry};
use super::machine::MachineSettings;
use super::path::{Path, PathError};
use super::toolpath::{Item, LaserPower, MoveKind, Toolpath};

/// The shape of a planned move, in machine units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A straight line between two points.
    Line {
        /// Start point.
        from: [f64; 3],
        /// End point.
        to: [f64; 3],
    },
    /// A circular, spiral or helical arc.
    Arc(ArcGeometry),
    /// A pause at rest.
    Dwell {
        /// How long, seconds.
        seconds: f64,
        /// Where, machine units.
        at: [f64; 3],
    },
}

/// One move with its speed profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlannedSegment {
    /// Start position, steps.
    pub start: [i64; 3],
    /// End position, steps.
    pub end: [i64; 3],
    /// The move's shape, machine units.
    pub shape: Shape,
    /// Steps per machine unit, per axis (to place an arc's points).
    pub steps_per_unit: [f64; 3],
    /// Length, machine units.
    pub length: f64,
    /// The move's own speed limit (feed, axes, and for an arc the
    /// centripetal and chord limits).
    pub v_limit: f64,
    /// Entry speed.
    pub v_entry: f64,
    /// Cruise (peak) speed.
    pub v_cruise: f64,
    /// Exit speed.
    pub v_exit: f64,
    /// Acceleration along the path.
    pub accel: f64,
    /// The programmed feed, machine units per second (`None`: a rapid or
    /// a dwell).
    pub feed: Option<f64>,
    /// The laser's power along it.
    pub laser: LaserPower,
    /// The 1-based program line it came from (0 for a `.path` file's
    /// moves made in code).
    pub line: usize,
}

impl PlannedSegment {
    fn accel_distance(&self) -> f64 {
        (self.v_cruise.powi(2) - self.v_entry.powi(2)).max(0.0) / (2.0 * self.accel)
    }

    fn decel_distance(&self) -> f64 {
        (self.v_cruise.powi(2) - self.v_exit.powi(2)).max(0.0) / (2.0 * self.accel)
    }

    fn cruise_distance(&self) -> f64 {
        (self.length - self.accel_distance() - self.decel_distance()).max(0.0)
    }

    fn phase_times(&self) -> (f64, f64, f64) {
        if let Shape::Dwell { seconds, .. } = self.shape {
            return (0.0, seconds, 0.0);
        }
        let ta = (self.v_cruise - self.v_entry).max(0.0) / self.accel;
        let td = (self.v_cruise - self.v_exit).max(0.0) / self.accel;
        let tc = if self.v_cruise > 0.0 {
            self.cruise_distance() / self.v_cruise
        } else {
            0.0
        };
        (ta, tc, td)
    }

    /// Time to drive the move (or to dwell), seconds.
    pub fn duration(&self) -> f64 {
        let (ta, tc, td) = self.phase_times();
        ta + tc + td
    }

    /// (distance along the move, speed) at time `t` after its start,
    /// clamped to the move.
    pub fn state_at(&self, t: f64) -> (f64, f64) {
        if let Shape::Dwell { .. } = self.shape {
            return (0.0, 0.0);
        }
        let (ta, tc, td) = self.phase_times();
        let a = self.accel;
        let t = t.clamp(0.0, ta + tc + td);
        if t <= ta {
            (self.v_entry * t + 0.5 * a * t * t, self.v_entry + a * t)
        } else if t <= ta + tc {
            (
                self.accel_distance() + self.v_cruise * (t - ta),
                self.v_cruise,
            )
        } else {
            let u = t - ta - tc;
            let d = self.accel_distance() + self.cruise_distance() + self.v_cruise * u
                - 0.5 * a * u * u;
            (d.min(self.length), (self.v_cruise - a * u).max(self.v_exit))
        }
    }

    /// The point `distance` along the move, machine units.
    pub fn point_at(&self, distance: f64) -> [f64; 3] {
        let fraction = if self.length > 0.0 {
            (distance / self.length).clamp(0.0, 1.0)
        } else {
            1.0
        };
        match self.shape {
            Shape::Line { from, to } => {
                std::array::from_fn(|k| from[k] + (to[k] - from[k]) * fraction)
            }
            Shape::Arc(arc) => arc.point(fraction),
            Shape::Dwell { at, .. } => at,
        }
    }

    /// Unit tangents at the start and at the end (zero for a dwell).
    pub fn tangents(&self) -> ([f64; 3], [f64; 3]) {
        match self.shape {
            Shape::Line { from, to } => {
                let u = unit(std::array::from_fn(|k| to[k] - from[k])).0;
                (u, u)
            }
            Shape::Arc(arc) => (arc.tangent(0.0), arc.tangent(1.0)),
            Shape::Dwell { .. } => ([0.0; 3], [0.0; 3]),
        }
    }
}

/// The corner speed limit between two directions (see the module docs).
pub fn junction_speed(
    u1: [f64; 3],
    u2: [f64; 3],
    accel: f64,
    contour_error: f64,
    feed: f64,
) -> f64 {
    let cos_theta = -(u1[0] * u2[0] + u1[1] * u2[1] + u1[2] * u2[2]);
    let sin_half = (0.5 * (1.0 - cos_theta)).max(0.0).sqrt();
    if sin_half >= 1.0 - 1e-12 {
        return feed;
    }
    (accel * contour_error * sin_half / (1.0 - sin_half))
        .sqrt()
        .min(feed)
}

/// The most steps a position may be from zero (2^40: exact in f64, and
/// far beyond any machine).
pub const MAX_POSITION_STEPS: f64 = (1u64 << 40) as f64;

/// The most steps a move may take in one period on one axis (2^30: a
/// period's count is an `i32`).
pub const MAX_STEPS_PER_PERIOD: f64 = (1u64 << 30) as f64;

/// Refuses a position that is not finite or is beyond
/// [`MAX_POSITION_STEPS`] in steps.
fn check_position(what: &str, p: [f64; 3], spu: [f64; 3], line: usize) -> Result<(), PathError> {
    for k in 0..3 {
        let steps = p[k] * spu[k];
        if steps.is_nan() || steps.abs() > MAX_POSITION_STEPS {
            let message = format!("{what} {:?} is {steps} steps on axis {k}, beyond +-2^40", p);
            return Err(if line == 0 {
                PathError::Invalid(message)
            } else {
                PathError::Syntax { line, message }
            });
        }
    }
    Ok(())
}

/// A position in machine units to the nearest step.
pub fn to_steps(p: [f64; 3], steps_per_unit: [f64; 3]) -> [i64; 3] {
    std::array::from_fn(|k| (p[k] * steps_per_unit[k]).round() as i64)
}

/// The fraction of `u`'s length along each axis, as a speed or
/// acceleration limit: the smallest limit_k / |u_k|.
fn axis_limit(u: [f64; 3], limits: [f64; 3]) -> f64 {
    (0..3)
        .filter(|&k| u[k] != 0.0)
        .map(|k| limits[k] / u[k].abs())
        .fold(f64::INFINITY, f64::min)
}

/// A line's or an arc's speed limit and acceleration (see the module
/// docs), or why it has none.
fn limits_of(shape: &Shape, feed: f64, machine: &MachineSettings) -> Result<(f64, f64), String> {
    match shape {
        Shape::Line { from, to } => {
            let u = unit(std::array::from_fn(|k| to[k] - from[k])).0;
            let v = feed.min(axis_limit(u, machine.max_velocity));
            let a = machine.path_accel.min(axis_limit(u, machine.max_accel));
            Ok((v, a))
        }
        Shape::Arc(arc) => {
            let (a_axis, b_axis, n_axis) = arc.plane.axes();
            let h = arc.normal_share();
            let p = (1.0 - h * h).max(0.0).sqrt();
            let plane_accel = machine.max_accel[a_axis].min(machine.max_accel[b_axis]);
            let plane_velocity = machine.max_velocity[a_axis].min(machine.max_velocity[b_axis]);
            let share = |limit: f64, s: f64| if s > 0.0 { limit / s } else { f64::INFINITY };
            let r = arc.min_radius();
            let e = machine.contour_error;
            if e <= 0.0 {
                return Err(
                    "an arc needs a contour error above 0 (its chords would have to be points)"
                        .into(),
                );
            }
            // The largest angle per period whose chord stays within e.
            let chord_angle = if e < r {
                2.0 * (1.0 - e / r).acos()
            } else {
                std::f64::consts::PI
            };
            let centripetal = 0.75f64.sqrt() * plane_accel;
            let v = feed
                .min(share(plane_velocity, p))
                .min(share(machine.max_velocity[n_axis], h))
                .min(share((centripetal * r).sqrt(), p))
                .min(share(chord_angle * r / machine.period, p));
            let a = machine
                .path_accel
                .min(share(0.5 * plane_accel, p))
                .min(share(machine.max_accel[n_axis], h));
            Ok((v, a))
        }
        // At rest: speed 0; the acceleration only keeps the profile's
        // arithmetic finite.
        Shape::Dwell { .. } => Ok((0.0, 1.0)),
    }
}

/// Plans `toolpath` on `machine`: zero-length moves are dropped; the path
/// starts and ends at rest, and stops for every dwell. A position that is
/// not finite or beyond [`MAX_POSITION_STEPS`], a feed that is not a
/// positive speed, an arc with no contour error, or a move that could take
/// more than [`MAX_STEPS_PER_PERIOD`] steps in a period is an error naming
/// its line.
pub fn plan_toolpath(
    toolpath: &Toolpath,
    machine: &MachineSettings,
) -> Result<Vec<PlannedSegment>, PathError> {
    machine.validate()?;
    let spu = machine.steps_per_mm;
    check_position("the start", toolpath.start, spu, 0)?;
    let finest = spu.iter().fold(0.0, |m: f64, &s| m.max(s));
    let mut segments: Vec<PlannedSegment> = Vec::new();
    let mut at = toolpath.start;
    let mut at_steps = to_steps(at, spu);
    // A segment from `start` (steps); the look-ahead below sets its speeds.
    let segment = |start, shape, end, length, v_limit, accel, (feed, laser, line)| PlannedSegment {
        start,
        end,
        shape,
        steps_per_unit: spu,
        length,
        v_limit,
        v_entry: 0.0,
        v_cruise: 0.0,
        v_exit: 0.0,
        accel,
        feed,
        laser,
        line,
    };
    for item in &toolpath.items {
        let m = match item {
            Item::Dwell {
                seconds,
                laser,
                line,
            } => {
                if !(seconds.is_finite() && *seconds >= 0.0) {
                    return Err(PathError::Syntax {
                        line: *line,
                        message: format!("dwell of {seconds} s"),
                    });
                }
                let shape = Shape::Dwell {
                    seconds: *seconds,
                    at,
                };
                let (v_limit, accel) =
                    limits_of(&shape, 0.0, machine).map_err(|message| PathError::Syntax {
                        line: *line,
                        message,
                    })?;
                segments.push(segment(
                    at_steps,
                    shape,
                    at_steps,
                    0.0,
                    v_limit,
                    accel,
                    (None, *laser, *line),
                ));
                continue;
            }
            Item::Move(m) => m,
            // The gearbox runs it, between planned runs (the caller splits
            // the toolpath there).
            Item::Synced(m) => {
                return Err(PathError::Syntax {
                    line: m.line,
                    message: "a spindle-synchronized move (G33, G33.1, G76) runs on the gearbox, not through the planner".into(),
                })
            }
        };
        let line = m.line;
        let error = |message: String| PathError::Syntax { line, message };
        check_position("the end", m.end, spu, line)?;
        if let MoveKind::Arc(arc) = m.kind {
            if !arc.center.iter().all(|c| c.is_finite()) {
                return Err(error(format!(
                    "the arc's center {:?} is not a position",
                    arc.center
                )));
            }
        }
        if let Some(feed) = m.feed.filter(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(error(format!("feed {feed} is not a speed")));
        }
        let (shape, length) = match m.kind {
            MoveKind::Line => (
                Shape::Line {
                    from: at,
                    to: m.end,
                },
                unit(std::array::from_fn(|k| m.end[k] - at[k])).1,
            ),
            MoveKind::Arc(arc) => {
                let geometry = ArcGeometry::new(&arc, at, m.end);
                (Shape::Arc(geometry), geometry.length())
            }
        };
        let end_steps = to_steps(m.end, spu);
        // A move too short to leave a step behind is dropped with its
        // length: the next one starts where this one would have ended.
        if length == 0.0 || (end_steps == at_steps && length * finest < 0.5) {
            at = m.end;
            continue;
        }
        let (v_limit, accel) =
            limits_of(&shape, m.feed.unwrap_or(f64::INFINITY), machine).map_err(error)?;
        if !(v_limit > 0.0 && accel > 0.0 && v_limit.is_finite()) {
            return Err(error(format!(
                "the move has no usable speed limit (speed {v_limit}, acceleration {accel})"
            )));
        }
        let steps_per_period = v_limit * machine.period * finest;
        if steps_per_period > MAX_STEPS_PER_PERIOD {
            return Err(error(format!(
                "the move may take {steps_per_period:.0} steps a period, beyond the {MAX_STEPS_PER_PERIOD} an axis's count holds"
            )));
        }
        segments.push(segment(
            at_steps,
            shape,
            end_steps,
            length,
            v_limit,
            accel,
            (m.feed, m.laser, line),
        ));
        at = m.end;
        at_steps = end_steps;
    }
    let n = segments.len();
    // Junction limits: v[i] is the speed between move i-1 and move i.
    let mut v = vec![0.0; n + 1];
    for i in 1..n {
        let (before, after) = (&segments[i - 1], &segments[i]);
        if matches!(before.shape, Shape::Dwell { .. }) || matches!(after.shape, Shape::Dwell { .. })
        {
            continue;
        }
        let corner = junction_speed(
            before.tangents().1,
            after.tangents().0,
            before.accel.min(after.accel),
            machine.contour_error,
            f64::INFINITY,
        );
        v[i] = corner.min(before.v_limit).min(after.v_limit);
    }
    let reach = |v0: f64, s: &PlannedSegment| (v0 * v0 + 2.0 * s.accel * s.length).sqrt();
    for i in (0..n).rev() {
        v[i] = v[i].min(reach(v[i + 1], &segments[i]));
    }
    for i in 0..n {
        v[i + 1] = v[i + 1].min(reach(v[i], &segments[i]));
    }
    for (i, s) in segments.iter_mut().enumerate() {
        s.v_entry = v[i];
        s.v_exit = v[i + 1];
        if matches!(s.shape, Shape::Dwell { .. }) {
            continue;
        }
        let peak = ((2.0 * s.accel * s.length + v[i] * v[i] + v[i + 1] * v[i + 1]) / 2.0).sqrt();
        s.v_cruise = s.v_limit.min(peak).max(v[i]).max(v[i + 1]);
    }
    Ok(segments)
}

/// Plans a `.path` file's path: its lines at its feed, its acceleration
/// along the path, in its units.
pub fn plan(path: &Path) -> Result<Vec<PlannedSegment>, PathError> {
    plan_toolpath(&path.toolpath(), &path.machine())
}
