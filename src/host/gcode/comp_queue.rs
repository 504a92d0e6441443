//! The moves that cutter radius compensation holds back until the next
//! move shows where they must end: LinuxCNC's `interp_queue.cc`. A move
//! into a concave corner is shortened to where the tool touches both
//! sides; shortening it past its start (the corner is too tight for the
//! tool) is an error, never a gouge.

use std::f64::consts::TAU;

use crate::host::toolpath::{Item, MoveKind, Plane, Toolpath};

/// A held-back item.
pub(super) struct Queued {
    pub(super) item: Item,
    /// A straight move's direction as LinuxCNC records it, in the plane's
    /// (first, second) coordinates: the programmed direction (zero when
    /// the move has no motion in the plane), or for the entry move the
    /// direction from the programmed end to the tool. Zero for arcs.
    pub(super) direction: [f64; 2],
    /// An arc's programmed sweep, radians, counter-clockwise positive; 0
    /// for the entry arc, whose end is never checked.
    pub(super) sweep: f64,
}

/// The held-back items and where the first of them starts.
#[derive(Default)]
pub(super) struct CompQueue {
    pub(super) items: Vec<Queued>,
    /// Where the held-back moves start, in the plane, when it is known
    /// (LinuxCNC's `endpoint` and `endpoint_valid`).
    pub(super) start: Option<[f64; 2]>,
}

/// LinuxCNC's signed turn of an arc: +P counter-clockwise, -P clockwise.
pub(super) fn signed_turns(kind: &MoveKind) -> i64 {
    match kind {
        MoveKind::Arc(arc) => {
            let turns = i64::from(arc.turns) + 1;
            if arc.clockwise {
                -turns
            } else {
                turns
            }
        }
        MoveKind::Line => 0,
    }
}

/// The angle an arc about `center` with LinuxCNC's signed `turn` sweeps
/// from `from` to `to`, radians, counter-clockwise positive (LinuxCNC's
/// `find_turn`).
pub(super) fn sweep(from: [f64; 2], center: [f64; 2], turn: i64, to: [f64; 2]) -> f64 {
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (from[1] - center[1]).atan2(from[0] - center[0]);
    let mut beta = (to[1] - center[1]).atan2(to[0] - center[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += TAU;
        }
        beta - alpha + (turn - 1) as f64 * TAU
    } else {
        if alpha <= beta {
            alpha += TAU;
        }
        beta - alpha + (turn + 1) as f64 * TAU
    }
}

/// `point`'s coordinates in `plane`: (first, second).
pub(super) fn in_plane(plane: Plane, point: [f64; 3]) -> [f64; 2] {
    let (first, second, _) = plane.axes();
    [point[first], point[second]]
}

/// `point` with its coordinates in `plane` set to `at`.
pub(super) fn with_plane(plane: Plane, mut point: [f64; 3], at: [f64; 2]) -> [f64; 3] {
    let (first, second, _) = plane.axes();
    point[first] = at[0];
    point[second] = at[1];
    point
}

impl CompQueue {
    /// The first held-back item if it is an arc: its center and radius in
    /// `plane` and its signed turn.
    pub(super) fn front_arc(&self, plane: Plane) -> Option<([f64; 2], f64, i64)> {
        match self.items.first().map(|q| &q.item) {
            Some(Item::Move(m)) => match &m.kind {
                MoveKind::Arc(arc) => {
                    let end = in_plane(plane, m.end);
                    let radius = (end[0] - arc.center[0]).hypot(end[1] - arc.center[1]);
                    Some((arc.center, radius, signed_turns(&m.kind)))
                }
                MoveKind::Line => None,
            },
            _ => None,
        }
    }

    /// Holds `item` back.
    pub(super) fn push(&mut self, item: Item, direction: [f64; 2], sweep: f64) {
        self.items.push(Queued {
            item,
            direction,
            sweep,
        });
    }

    /// Releases every held-back item as it is (LinuxCNC's
    /// `dequeue_canons`), but for straight moves of no length (a move with
    /// no motion in the plane, held where the tool is, stays one when its
    /// end moves); where the next ones start is then unknown.
    pub(super) fn flush(&mut self, toolpath: &mut Toolpath) {
        self.start = None;
        for queued in self.items.drain(..) {
            if let Item::Move(m) = &queued.item {
                if m.kind == MoveKind::Line && m.end == toolpath.end() {
                    continue;
                }
            }
            toolpath.items.push(queued.item);
        }
    }

    /// Ends every held-back move at `to` in `plane`, then releases them
    /// (LinuxCNC's `move_endpoint_and_flush`). A straight move that would
    /// then run backwards, or an arc that would sweep further than it was
    /// programmed to (by more than `slack` radians: LinuxCNC's 0.001 in
    /// inch programs and 0.0254 in mm ones), cannot reach the corner
    /// without gouging: an error.
    pub(super) fn end_at_and_flush(
        &mut self,
        plane: Plane,
        to: [f64; 2],
        slack: f64,
        toolpath: &mut Toolpath,
    ) -> Result<(), String> {
        if self.items.is_empty() {
            return Ok(());
        }
        for queued in &mut self.items {
            let Item::Move(m) = &mut queued.item else {
                continue;
            };
            match &m.kind {
                MoveKind::Arc(arc) => {
                    let end = in_plane(plane, m.end);
                    let r1 = (end[0] - arc.center[0]).hypot(end[1] - arc.center[1]);
                    let r2 = (to[0] - arc.center[0]).hypot(to[1] - arc.center[1]);
                    if (r1 - r2).abs() > 1e-3 * r1.max(1.0) {
                        return Err(format!(
                            "cutter compensation moved an arc's end off its circle (radius {r1:.6} mm, then {r2:.6} mm): an interpreter bug"
                        ));
                    }
                    if let Some(start) = self.start.filter(|_| queued.sweep != 0.0) {
                        let new = sweep(start, arc.center, signed_turns(&m.kind), to);
                        if new.abs() > queued.sweep.abs() + slack {
                            return Err("arc move in concave corner cannot be reached by the tool without gouging \
                                 (LinuxCNC: Arc move in concave corner cannot be reached by the tool without gouging)"
                                .into());
                        }
                    }
                }
                MoveKind::Line => {
                    if let Some(start) = self.start {
                        let d = queued.direction;
                        let dot = d[0] * (to[0] - start[0]) + d[1] * (to[1] - start[1]);
                        if dot < 0.0 {
                            let (what, lcnc) = match m.feed {
                                Some(_) => ("feed", "Straight feed"),
                                None => ("traverse", "Straight traverse"),
                            };
                            return Err(format!(
                                "straight {what} in concave corner cannot be reached by the tool without gouging \
                                 (LinuxCNC: {lcnc} in concave corner cannot be reached by the tool without gouging)"
                            ));
                        }
                    }
                }
            }
            m.end = with_plane(plane, m.end, to);
        }
        self.flush(toolpath);
        self.start = Some(to);
        Ok(())
    }
}
