//! The center of a G2/G3 arc, from its radius (`R`) or checked when given
//! (`I`, `J`, `K`), in the plane's (first, second) coordinates, millimetres.
//! Errors come back as messages (without the line), with lengths in the
//! program's units.

use super::interpreter::Units;

/// A half chord longer than |R| by less than this is taken as a half
/// circle: `R` written with a few decimals rarely reaches the end exactly.
/// LinuxCNC's tolerance in mm programs (`TOLERANCE_MM`).
pub(super) const HALF_CIRCLE_SNAP_MM: f64 = 0.005;

/// A radius below this is no radius at all.
const ZERO_RADIUS_MM: f64 = 1e-9;

/// The center of the arc from `start` to `end` with radius `radius` (mm,
/// signed as written): LinuxCNC's rule, the center on the perpendicular
/// bisector of the chord, on the side that makes the arc at most half a
/// circle for a positive R and at least half a circle for a negative one.
/// `start` and `end` differ (the caller refuses a full circle with R).
pub(super) fn center_from_radius(
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    clockwise: bool,
    word: &str,
    units: Units,
) -> Result<[f64; 2], String> {
    let chord = [end[0] - start[0], end[1] - start[1]];
    let length = chord[0].hypot(chord[1]);
    let half = length / 2.0;
    let r = radius.abs();
    if half - r > HALF_CIRCLE_SNAP_MM {
        return Err(format!(
            "{word} cannot reach the end: |R| must be at least half the chord, {}",
            units.show(half)
        ));
    }
    // (r - half)(r + half) rather than r² - half²: the difference of two
    // near-equal squares loses the digits a near half circle depends on.
    let offset = ((r - half).max(0.0) * (r + half)).sqrt();
    // The short arc turning clockwise has its center on the chord's right;
    // the long one, or counter-clockwise, on its left (G3 turns positive
    // in (first, second)).
    let right = clockwise == (radius > 0.0);
    let normal = if right {
        [chord[1] / length, -chord[0] / length]
    } else {
        [-chord[1] / length, chord[0] / length]
    };
    let mid = [(start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0];
    Ok([mid[0] + offset * normal[0], mid[1] + offset * normal[1]])
}

/// Checks a center given by I, J, K: the radius at the start and at the
/// end must agree within max(0.002 mm, 0.1 % of the start radius), close
/// to LinuxCNC's tolerance for the rounding of a program's decimals.
pub(super) fn check_center(
    start: [f64; 2],
    end: [f64; 2],
    center: [f64; 2],
    units: Units,
) -> Result<(), String> {
    let r0 = (start[0] - center[0]).hypot(start[1] - center[1]);
    let r1 = (end[0] - center[0]).hypot(end[1] - center[1]);
    if r0 < ZERO_RADIUS_MM {
        return Err("the arc's center is its start (zero radius)".into());
    }
    if r1 < ZERO_RADIUS_MM {
        return Err("the arc's center is its end (zero radius)".into());
    }
    if (r1 - r0).abs() > (0.001 * r0).max(0.002) {
        return Err(format!(
            "the arc's radius is {} at its start and {} at its end",
            units.show(r0),
            units.show(r1)
        ));
    }
    Ok(())
}
