//! The shape of one move in machine units: a point at any distance along
//! it, its tangents at both ends, its length and (for an arc) its radius.
//!
//! An arc whose radius at the end differs from the one at the start (a
//! G-code arc within the interpreter's radius tolerance) is a spiral: the
//! radius changes linearly with the angle, so the move ends exactly at its
//! end point. The axis normal to the plane moves linearly with the angle
//! (a helix).

use super::toolpath::{Arc, Plane};

/// An arc resolved against its start and end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcGeometry {
    /// The plane.
    pub plane: Plane,
    /// Center in the plane's (first, second) coordinates.
    pub center: [f64; 2],
    /// Radius at the start and at the end.
    pub radius: [f64; 2],
    /// Angle of the start, radians.
    pub start_angle: f64,
    /// Signed angle swept (positive: counter-clockwise, G3), radians.
    pub sweep: f64,
    /// Normal-axis position at the start and at the end.
    pub normal: [f64; 2],
}

/// Two plane points closer than this (machine units) are one point: an
/// arc from a point to itself is a full circle.
pub const SAME_POINT: f64 = 1e-9;

impl ArcGeometry {
    /// The arc `arc` from `start` to `end`.
    pub fn new(arc: &Arc, start: [f64; 3], end: [f64; 3]) -> Self {
        let (a, b, n) = arc.plane.axes();
        let [ca, cb] = arc.center;
        let angle = |p: [f64; 3]| (p[b] - cb).atan2(p[a] - ca);
        let radius = |p: [f64; 3]| (p[a] - ca).hypot(p[b] - cb);
        let (start_angle, end_angle) = (angle(start), angle(end));
        let tau = std::f64::consts::TAU;
        let same = (start[a] - end[a]).hypot(start[b] - end[b]) <= SAME_POINT;
        // The sweep in (0, 2 pi] in the arc's direction; a full circle
        // when the end is the start.
        let mut sweep = if same {
            tau
        } else if arc.clockwise {
            (start_angle - end_angle).rem_euclid(tau)
        } else {
            (end_angle - start_angle).rem_euclid(tau)
        };
        if sweep == 0.0 {
            sweep = tau;
        }
        sweep += tau * arc.turns as f64;
        Self {
            plane: arc.plane,
            center: arc.center,
            radius: [radius(start), radius(end)],
            start_angle,
            sweep: if arc.clockwise { -sweep } else { sweep },
            normal: [start[n], end[n]],
        }
    }

    /// The length the planner drives: the fastest rate at which the point
    /// moves with the fraction, |dp/df| at the larger radius. For a circle
    /// or a helix that is its exact length. A spiral's is a little more
    /// than its true length (it is driven a little slower than planned),
    /// so that no point of it, and no axis, moves faster than planned:
    /// with the mean radius, a short spiral whose radius change is most of
    /// its motion would run several times over its limits.
    pub fn length(&self) -> f64 {
        let r = self.radius[0].max(self.radius[1]);
        let dr = self.radius[1] - self.radius[0];
        ((r * self.sweep).hypot(dr)).hypot(self.normal[1] - self.normal[0])
    }

    /// The smaller radius: the tightest curvature (a helix curves less).
    pub fn min_radius(&self) -> f64 {
        self.radius[0].min(self.radius[1])
    }

    /// The point at `fraction` (0 to 1) of the angle.
    pub fn point(&self, fraction: f64) -> [f64; 3] {
        let (a, b, n) = self.plane.axes();
        let theta = self.start_angle + self.sweep * fraction;
        let r = self.radius[0] + (self.radius[1] - self.radius[0]) * fraction;
        let mut p = [0.0; 3];
        p[a] = self.center[0] + r * theta.cos();
        p[b] = self.center[1] + r * theta.sin();
        p[n] = self.normal[0] + (self.normal[1] - self.normal[0]) * fraction;
        p
    }

    /// Unit tangent (direction of travel) at `fraction` of the angle.
    pub fn tangent(&self, fraction: f64) -> [f64; 3] {
        unit(self.derivatives(fraction).0).0
    }

    /// The first and second derivatives of [`ArcGeometry::point`] by the
    /// fraction, at `fraction`.
    pub fn derivatives(&self, fraction: f64) -> ([f64; 3], [f64; 3]) {
        let (a, b, n) = self.plane.axes();
        let theta = self.start_angle + self.sweep * fraction;
        let dr = self.radius[1] - self.radius[0];
        let r = self.radius[0] + dr * fraction;
        let (sin, cos) = theta.sin_cos();
        let w = self.sweep;
        let (mut d1, mut d2) = ([0.0; 3], [0.0; 3]);
        d1[a] = dr * cos - r * w * sin;
        d1[b] = dr * sin + r * w * cos;
        d1[n] = self.normal[1] - self.normal[0];
        d2[a] = -2.0 * dr * w * sin - r * w * w * cos;
        d2[b] = 2.0 * dr * w * cos - r * w * w * sin;
        (d1, d2)
    }

    /// The normal axis's share of the move's speed: its travel over the
    /// length (0 for a flat arc). The plane axes share at most
    /// sqrt(1 - share^2).
    pub fn normal_share(&self) -> f64 {
        let length = self.length();
        if length > 0.0 {
            (self.normal[1] - self.normal[0]).abs() / length
        } else {
            0.0
        }
    }
}

/// `v` scaled to length 1, and its length (a zero vector stays zero).
pub fn unit(v: [f64; 3]) -> ([f64; 3], f64) {
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if length > 0.0 {
        ([v[0] / length, v[1] / length, v[2] / length], length)
    } else {
        ([0.0; 3], 0.0)
    }
}
