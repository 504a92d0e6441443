//! Cutter radius compensation, G40, G41, G42, G41.1 and G42.1, as LinuxCNC
//! 2.9 does it (`interp_convert.cc`: `convert_cutter_compensation_on`,
//! `convert_straight_comp1/2`, `convert_arc_comp1/2`), in the G17 or G18
//! plane. The tool's center runs one tool radius to the left (G41) or right
//! (G42) of the programmed path:
//!
//! - the first move after G41 or G42 (the entry) ends one radius to the
//!   side of its programmed end, square to the entry line, or on the
//!   radius through its end for an entry arc;
//! - a convex corner becomes an arc about the programmed corner (a rapid
//!   straight to the next offset line for G0);
//! - a move into a concave corner is shortened to where the tool touches
//!   both sides: each move is held back (see `CompQueue`) until the next
//!   one shows where it must end; a corner the tool cannot reach without
//!   gouging is an error;
//! - G40 ends the last move where it was going, and the next move, which
//!   must be straight, runs from there to its programmed end.
//!
//! Geometry is computed in machine mm in the plane's (first, second)
//! coordinates, which is LinuxCNC's work-coordinate geometry moved by the
//! offsets: the offsets cannot change while compensation is on.

use std::f64::consts::{FRAC_PI_2, PI};

use super::block_words::{CutterComp, Motion, Words};
use super::comp_queue::{in_plane, signed_turns, sweep, with_plane, CompQueue};
use super::interpreter::{State, Units};
use crate::host::toolpath::{Arc, Item, Move, MoveKind, Plane};

/// Corners within this angle, radians, of straight on are not corners
/// (LinuxCNC's TOLERANCE_CONCAVE_CORNER).
const CORNER_TOLERANCE: f64 = 0.05;

/// Compensation in force.
pub(super) struct Compensation {
    /// Left of the path (G41, or G42 with a negative diameter).
    pub(super) left: bool,
    /// The tool's radius, mm, 0 or more: 0 compensates nothing.
    pub(super) radius: f64,
    /// The plane it was turned on in: G17 or G18.
    pub(super) plane: Plane,
    /// The word that turned it on, "G41", and its line, for messages.
    pub(super) word: String,
    pub(super) line: usize,
    /// No move has run since it was turned on.
    pub(super) first_move: bool,
    pub(super) queue: CompQueue,
}

/// Whether the tool runs inside an arc of LinuxCNC's signed `turn`
/// (LinuxCNC's TOOL_INSIDE_ARC).
fn inside(left: bool, turn: i64) -> bool {
    (left && turn > 0) || (!left && turn < 0)
}

/// The unit vector at `angle`.
fn unit(angle: f64) -> [f64; 2] {
    [angle.cos(), angle.sin()]
}

/// `p` plus `length` along `angle`.
fn along(p: [f64; 2], length: f64, angle: f64) -> [f64; 2] {
    [p[0] + length * angle.cos(), p[1] + length * angle.sin()]
}

fn angle_to(from: [f64; 2], to: [f64; 2]) -> f64 {
    (to[1] - from[1]).atan2(to[0] - from[0])
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// The slack, radians, that a shortened arc may sweep beyond its
/// programmed sweep: LinuxCNC compares it with 0.001 in inch programs and
/// 0.0254 in mm ones.
fn sweep_slack(units: Units) -> f64 {
    match units {
        Units::Inch => 0.001,
        Units::Millimetre => 0.0254,
    }
}

/// What a compensated move reads before it changes anything.
struct Frame {
    /// See [`sweep_slack`].
    slack: f64,
    units: Units,
    /// The programmed point and the tool's, machine mm.
    base: [f64; 3],
    current: [f64; 3],
    plane: Plane,
    /// The tool's radius, mm, and its side.
    r: f64,
    left: bool,
    /// The axis normal to the plane.
    normal: usize,
}

impl State {
    fn comp_frame(&self) -> Frame {
        let comp = self.comp.as_ref().expect("compensation is on");
        Frame {
            slack: sweep_slack(self.units),
            units: self.units,
            base: self.base_mm(),
            current: self.position_mm,
            plane: comp.plane,
            r: comp.radius,
            left: comp.left,
            normal: comp.plane.axes().2,
        }
    }

    /// Where the program is, machine mm: the programmed point, which
    /// differs from the tool's while compensation offsets it and after G40
    /// until the next move.
    pub(super) fn base_mm(&self) -> [f64; 3] {
        self.programmed_mm.unwrap_or(self.position_mm)
    }

    /// Adds `item` to the toolpath, behind any moves compensation holds
    /// back.
    pub(super) fn emit(&mut self, item: Item) {
        match self.comp.as_mut().filter(|c| !c.queue.items.is_empty()) {
            Some(comp) => comp.queue.push(item, [0.0; 2], 0.0),
            None => self.toolpath.items.push(item),
        }
    }

    /// An error when compensation is on: `word` cannot run with it
    /// (LinuxCNC's message `lcnc`).
    pub(super) fn refuse_with_comp(&self, word: &str, lcnc: &str) -> Result<(), String> {
        match &self.comp {
            Some(comp) => Err(format!(
                "{word} with cutter radius compensation on ({} on line {}): turn it off with G40 first (LinuxCNC: {lcnc})",
                comp.word, comp.line
            )),
            None => Ok(()),
        }
    }

    /// G40, G41, G42, G41.1, G42.1 (LinuxCNC's step 13).
    pub(super) fn cutter_comp_words(&mut self, words: &Words, line: usize) -> Result<(), String> {
        let Some((word, code)) = words.cutter_comp else {
            return Ok(());
        };
        let (left, dynamic) = match code {
            CutterComp::Off => return self.cutter_comp_off(),
            CutterComp::FromTable { left } => (left, false),
            CutterComp::Dynamic { left } => (left, true),
        };
        let name = word.name();
        if self.plane == Plane::Yz {
            return Err(format!(
                "{name} in G19: cutter radius compensation works in G17 and G18 only \
                 (LinuxCNC: Cutter radius compensation allowed only in XY, XZ planes)"
            ));
        }
        if let Some(comp) = &self.comp {
            return Err(format!(
                "{name}: cutter radius compensation is already on ({} on line {}) \
                 (LinuxCNC: Cannot turn cutter radius comp on when on)",
                comp.word, comp.line
            ));
        }
        if let Some(l) = words.l {
            return Err(format!(
                "{} with {name}: lathe tool orientations are not supported",
                l.name()
            ));
        }
        let diameter = if dynamic {
            let d = words.d.ok_or_else(|| {
                format!("{name} needs D: the tool's diameter (LinuxCNC: {name} with no D word)")
            })?;
            d.value * self.units.mm_per_unit()
        } else {
            let (tool_word, number) = match words.d {
                Some(d) => {
                    let v = d.value;
                    if v.fract() != 0.0 || !(0.0..=f64::from(u32::MAX)).contains(&v) {
                        return Err(format!(
                            "{} is not a tool number: a whole number, 0 (no tool) or more \
                             (LinuxCNC: {name} requires D word to be a whole number)",
                            d.name()
                        ));
                    }
                    (d.name(), v as u32)
                }
                None => (format!("T{}", self.loaded), self.loaded),
            };
            // D0 is LinuxCNC's table slot 0, the tool in the spindle.
            let number = if number == 0 { self.loaded } else { number };
            if self.tools.is_none() && number != 0 {
                self.report(
                    "no tool table for compensation",
                    line,
                    format!("{name} {tool_word}"),
                    "cutter radius 0: no tool table given (--tools)",
                );
            }
            self.table_tool(&tool_word, number)?
                .map_or(0.0, |t| t.diameter)
        };
        // A negative diameter (a tool smaller than the one the path was
        // drawn for) puts the tool on the other side.
        self.comp = Some(Compensation {
            left: left == (diameter >= 0.0),
            radius: diameter.abs() / 2.0,
            plane: self.plane,
            word: name,
            line,
            first_move: true,
            queue: CompQueue::default(),
        });
        Ok(())
    }

    /// G40: the held-back move ends where it was going; the next move,
    /// which must be straight, starts there.
    fn cutter_comp_off(&mut self) -> Result<(), String> {
        if self
            .comp
            .as_ref()
            .is_some_and(|c| c.radius > 0.0 && !c.first_move)
        {
            self.comp_stop()?;
            self.arc_not_allowed = true;
        }
        self.comp = None;
        Ok(())
    }

    /// At M0, M1, M60, M2, M30 and the end of the file: the held-back
    /// moves run as they are (LinuxCNC's `convert_stop`).
    pub(super) fn comp_stop(&mut self) -> Result<(), String> {
        let slack = sweep_slack(self.units);
        if let Some(comp) = self.comp.as_mut() {
            let here = in_plane(comp.plane, self.position_mm);
            comp.queue
                .end_at_and_flush(comp.plane, here, slack, &mut self.toolpath)?;
            comp.queue.flush(&mut self.toolpath);
        }
        Ok(())
    }

    /// The move's program end is `end` (work, program units) and
    /// `end_mm` (machine).
    fn set_programmed(&mut self, end: [f64; 3], end_mm: [f64; 3], tool_mm: [f64; 3]) {
        self.position = end;
        self.programmed_mm = Some(end_mm);
        self.position_mm = tool_mm;
    }

    /// A compensated G0 or G1 to the programmed `end`/`end_mm`; `feed`
    /// `None` for G0.
    pub(super) fn compensated_straight(
        &mut self,
        end: [f64; 3],
        end_mm: [f64; 3],
        feed: Option<f64>,
        line: usize,
    ) -> Result<(), String> {
        let name = if feed.is_some() { "G1" } else { "G0" };
        let f = self.comp_frame();
        let (slack, units, base, current) = (f.slack, f.units, f.base, f.current);
        let (plane, r, left, normal) = (f.plane, f.r, f.left, f.normal);
        let angles = self.angles;
        let laser = self.laser_along(feed);
        let comp = self.comp.as_mut().expect("compensation is on");
        let p = in_plane(plane, end_mm);
        let line_to = |at: [f64; 2], z: f64| {
            let mut end = with_plane(plane, end_mm, at);
            end[normal] = z;
            Item::Move(Move {
                kind: MoveKind::Line,
                end,
                angles,
                feed,
                laser,
                line,
            })
        };
        if comp.first_move {
            // The entry: square to the entry line at its end.
            let c = in_plane(plane, base);
            if distance(c, p) <= r {
                return Err(format!(
                    "{name}: the cutter compensation entry move, {}, is not longer than the tool radius, {} \
                     (LinuxCNC: Length of cutter compensation entry move is not greater than the tool radius)",
                    units.show(distance(c, p)),
                    units.show(r)
                ));
            }
            let alpha = angle_to(c, p) + if left { FRAC_PI_2 } else { -FRAC_PI_2 };
            let e = along(p, r, alpha);
            comp.queue.start = Some(c);
            comp.queue
                .push(line_to(e, end_mm[normal]), unit(alpha), 0.0);
            comp.first_move = false;
            let tool = with_plane(plane, end_mm, e);
            self.set_programmed(end, end_mm, tool);
            return Ok(());
        }
        let c = in_plane(plane, current);
        let op = in_plane(plane, base);
        if p == op {
            // No motion in the plane: the tool stays where it is in it.
            comp.queue.push(line_to(c, end_mm[normal]), [0.0; 2], 0.0);
            let tool = with_plane(plane, end_mm, c);
            self.set_programmed(end, end_mm, tool);
            return Ok(());
        }
        let mut theta = angle_to(op, c);
        let mut alpha = angle_to(op, p);
        let (beta, gamma) = if left {
            if theta < alpha {
                theta += 2.0 * PI;
            }
            (theta - alpha - FRAC_PI_2, FRAC_PI_2)
        } else {
            if alpha < theta {
                alpha += 2.0 * PI;
            }
            (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
        };
        let e = along(p, r, alpha + gamma);
        let mid = along(op, r, alpha + gamma);
        let front = comp.queue.front_arc(plane).map(|(_, _, turn)| turn);
        let concave = !(-CORNER_TOLERANCE..=PI + CORNER_TOLERANCE).contains(&beta)
            // An "h": over the arc's top, then down beside the stem; the
            // tool stays above and right rather than looping around.
            || (beta > PI - CORNER_TOLERANCE
                && front.is_some_and(|turn| (!left && turn > 0) || (left && turn < 0)));
        let cz = current[normal];
        if !concave && beta > CORNER_TOLERANCE {
            // Convex: around the corner on an arc about it (G1), or
            // straight to the next offset line (G0: rapids have no arcs).
            comp.queue
                .end_at_and_flush(plane, c, slack, &mut self.toolpath)?;
            let mut corner_end = with_plane(plane, current, mid);
            corner_end[normal] = cz;
            let kind = match feed {
                Some(_) => MoveKind::Arc(Arc {
                    plane,
                    center: op,
                    clockwise: left,
                    turns: 0,
                }),
                None => MoveKind::Line,
            };
            comp.queue.push(
                Item::Move(Move {
                    kind,
                    end: corner_end,
                    angles: self.angles,
                    feed,
                    laser,
                    line,
                }),
                [0.0; 2],
                0.0,
            );
            comp.queue.flush(&mut self.toolpath);
            comp.queue.start = Some(mid);
        } else if concave {
            let to = match comp.queue.front_arc(plane) {
                None => {
                    // Line into line: back along the last move until the
                    // tool touches the new line too.
                    let half_corner = (beta + PI) / 2.0;
                    if half_corner == 0.0 {
                        return Err(format!(
                            "{name}: a zero degree inside corner cannot be compensated \
                             (LinuxCNC: Zero degree inside corner is invalid for cutter compensation)"
                        ));
                    }
                    along(c, r / half_corner.tan(), theta + gamma)
                }
                Some((pc, old_radius, prev_turn)) => {
                    // Arc into line: along the arc to where the tool
                    // touches the line.
                    let base_dir = angle_to(op, p);
                    let theta = if prev_turn > 0 {
                        base_dir + FRAC_PI_2
                    } else {
                        base_dir - FRAC_PI_2
                    };
                    let phi = angle_to(op, pc);
                    let tool_inside = inside(left, prev_turn);
                    let uncompensated = if tool_inside {
                        old_radius + r
                    } else {
                        old_radius - r
                    };
                    let d = uncompensated * (theta - phi).cos();
                    let l = (if tool_inside { d - r } else { d + r }) / old_radius;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(format!(
                            "{name}: arc to straight motion makes a corner the compensated tool can't fit in without gouging \
                             (LinuxCNC: Arc to straight motion makes a corner the compensated tool can't fit in without gouging)"
                        ));
                    }
                    let angle = if tool_inside == (prev_turn > 0) {
                        -l.acos() + theta + PI
                    } else {
                        l.acos() + theta + PI
                    };
                    along(pc, old_radius, angle)
                }
            };
            comp.queue
                .end_at_and_flush(plane, to, slack, &mut self.toolpath)?;
        } else {
            // Straight on, or tangent from an arc.
            comp.queue.flush(&mut self.toolpath);
            comp.queue.start = Some(c);
        }
        comp.queue.push(
            line_to(e, end_mm[normal]),
            [p[0] - op[0], p[1] - op[1]],
            0.0,
        );
        let tool = with_plane(plane, end_mm, e);
        self.set_programmed(end, end_mm, tool);
        Ok(())
    }

    /// A compensated G2 or G3 whose programmed shape is `arc` (its center
    /// from the programmed start), to the programmed `end`/`end_mm`.
    pub(super) fn compensated_arc(
        &mut self,
        motion: Motion,
        arc: Arc,
        end: [f64; 3],
        end_mm: [f64; 3],
        feed: f64,
        line: usize,
    ) -> Result<(), String> {
        let name = motion.name();
        let f = self.comp_frame();
        let (slack, units, base, current) = (f.slack, f.units, f.base, f.current);
        let (plane, r, left, normal) = (f.plane, f.r, f.left, f.normal);
        let laser = self.laser_along(Some(feed));
        let comp = self.comp.as_mut().expect("compensation is on");
        let turn = signed_turns(&MoveKind::Arc(arc));
        let tool_inside = inside(left, turn);
        let p = in_plane(plane, end_mm);
        let center = arc.center;
        let arc_radius = distance(center, p);
        if tool_inside && arc_radius <= r {
            return Err(format!(
                "{name}: the arc's radius, {}, is not more than the tool's, {}, and the tool is inside it \
                 (LinuxCNC: Tool radius not less than arc radius with comp)",
                units.show(arc_radius),
                units.show(r)
            ));
        }
        // The tool ends one radius from the programmed end, toward the
        // center or away from it.
        let gamma = if tool_inside {
            angle_to(p, center)
        } else {
            angle_to(center, p)
        };
        let e = along(p, r, gamma);
        let angles = self.angles;
        let arc_item = |from: [f64; 2], center: [f64; 2], to: [f64; 2]| {
            let mut to = to;
            // A full circle stays one: its end is its start exactly.
            if distance(from, to) <= crate::host::geometry::SAME_POINT {
                to = from;
            }
            Item::Move(Move {
                kind: MoveKind::Arc(Arc { center, ..arc }),
                end: with_plane(plane, end_mm, to),
                angles,
                feed: Some(feed),
                laser,
                line,
            })
        };
        if comp.first_move {
            // The entry arc: from the tool to the offset end, on a circle
            // through both whose center lies on the programmed radius
            // through the end.
            let c = in_plane(plane, base);
            if distance(c, p) <= r {
                return Err(format!(
                    "{name}: the cutter compensation entry arc ends {} from its start, not more than the tool radius, {} \
                     (LinuxCNC: Radius of cutter compensation entry arc is not greater than the tool radius)",
                    units.show(distance(c, p)),
                    units.show(r)
                ));
            }
            let half_chord = distance(c, e) / 2.0;
            let ab = angle_to(e, center);
            let a = angle_to(e, c) - ab;
            if a.cos().abs() < 1e-6 {
                return Err(format!(
                    "{name}: the entry arc cannot be compensated: the tool cannot reach its end on a circle through its start \
                     (LinuxCNC: Tool radius not less than arc radius with comp)"
                ));
            }
            let new_center = along(e, half_chord / a.cos(), ab);
            comp.queue.push(arc_item(c, new_center, e), [0.0; 2], 0.0);
            comp.first_move = false;
            let tool = with_plane(plane, end_mm, e);
            self.set_programmed(end, end_mm, tool);
            return Ok(());
        }
        let c = in_plane(plane, current);
        let op = in_plane(plane, base);
        let theta = angle_to(op, c) + if left { -FRAC_PI_2 } else { FRAC_PI_2 };
        let mut delta = angle_to(op, center);
        let alpha = if turn > 0 {
            delta - FRAC_PI_2
        } else {
            delta + FRAC_PI_2
        };
        let mut beta = if left { theta - alpha } else { alpha - theta };
        if beta > 1.5 * PI {
            beta -= 2.0 * PI;
        } else if beta < -FRAC_PI_2 {
            beta += 2.0 * PI;
        }
        if !tool_inside {
            delta += PI;
        }
        let programmed_sweep = sweep(op, center, turn, p);
        let cz = current[normal];
        let start;
        if !(-CORNER_TOLERANCE..=PI + CORNER_TOLERANCE).contains(&beta)
            // Over the top of an "m" or an "h": convex though tangent.
            || ((beta - PI).abs() < CORNER_TOLERANCE && !tool_inside)
        {
            let to = match comp.queue.front_arc(plane) {
                None => {
                    // Line into arc: back along the line until the tool
                    // touches the arc's offset circle.
                    let cy = arc_radius * (beta - FRAC_PI_2).sin();
                    let (from_center, toward) = if tool_inside {
                        (arc_radius - r, cy + r)
                    } else {
                        (arc_radius + r, cy - r)
                    };
                    let l = toward / from_center;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(format!(
                            "{name}: arc move in concave corner cannot be reached by the tool without gouging \
                             (LinuxCNC: Arc move in concave corner cannot be reached by the tool without gouging)"
                        ));
                    }
                    let angle = match (tool_inside, turn > 0) {
                        (true, true) => theta + l.asin(),
                        (true, false) => theta - l.asin(),
                        (false, true) => theta + PI - l.asin(),
                        (false, false) => theta + PI + l.asin(),
                    };
                    along(center, from_center, angle)
                }
                Some((pc, old_radius, prev_turn)) => {
                    // Arc into arc: where the two offset circles meet.
                    let new_radius = if tool_inside {
                        arc_radius - r
                    } else {
                        arc_radius + r
                    };
                    let centers = distance(pc, center);
                    if old_radius == 0.0 || centers == 0.0 {
                        return Err(format!(
                            "{name}: arc to arc motion is invalid because the arcs have the same center \
                             (LinuxCNC: Arc to arc motion is invalid because the arcs have the same center)"
                        ));
                    }
                    let a = (old_radius * old_radius + centers * centers - new_radius * new_radius)
                        / (2.0 * old_radius * centers);
                    if !(-1.0..=1.0).contains(&a) {
                        return Err(format!(
                            "{name}: arc to arc motion makes a corner the compensated tool can't fit in without gouging \
                             (LinuxCNC: Arc to arc motion makes a corner the compensated tool can't fit in without gouging)"
                        ));
                    }
                    let pullback = a.acos();
                    let cc_dir = angle_to(pc, center);
                    let dir = if inside(left, prev_turn) == (turn > 0) {
                        cc_dir + pullback
                    } else {
                        cc_dir - pullback
                    };
                    along(pc, old_radius, dir)
                }
            };
            comp.queue
                .end_at_and_flush(plane, to, slack, &mut self.toolpath)?;
            start = to;
        } else if beta > CORNER_TOLERANCE {
            // Convex: around the corner on an arc about it first.
            let mid = along(op, r, delta);
            comp.queue.flush(&mut self.toolpath);
            let mut corner_end = with_plane(plane, current, mid);
            corner_end[normal] = cz;
            self.toolpath.items.push(Item::Move(Move {
                kind: MoveKind::Arc(Arc {
                    plane,
                    center: op,
                    clockwise: left,
                    turns: 0,
                }),
                end: corner_end,
                angles: self.angles,
                feed: Some(feed),
                laser,
                line,
            }));
            comp.queue.start = Some(mid);
            start = mid;
        } else {
            comp.queue.flush(&mut self.toolpath);
            comp.queue.start = Some(c);
            start = c;
        }
        comp.queue
            .push(arc_item(start, center, e), [0.0; 2], programmed_sweep);
        let tool = with_plane(plane, end_mm, e);
        self.set_programmed(end, end_mm, tool);
        Ok(())
    }
}
