//! LinuxCNC's polar coordinates: `@` is the distance and `^` the angle
//! (degrees, counter-clockwise from +X) of the end about the work origin,
//! in the XY plane. Absolute (G90): a word left out keeps the current
//! point's distance or angle. Incremental (G91): the words add to the
//! current point's distance and angle. They give the end of a G0 or G1 and
//! a canned cycle's hole (under G91, added on every repeat, as LinuxCNC's
//! `hole-circle.ngc` uses them); nothing else.

use super::block_words::{Motion, Words};
use super::interpreter::State;

impl State {
    /// Checks where the block's `@` or `^` may stand: with G0, G1 or a
    /// G17 canned cycle, without X or Y, and not under G53.
    pub(super) fn check_polar(
        &self,
        words: &Words,
        motion: Option<Motion>,
        machine: bool,
    ) -> Result<(), String> {
        let Some(word) = words.polar.iter().flatten().next() else {
            return Ok(());
        };
        let w = word.name();
        if let Some(xy) = words.axes[..2].iter().flatten().next() {
            return Err(format!(
                "{w} with {}: give the end in X and Y or in polar coordinates, not both (LinuxCNC: Cannot use X and polar coordinates)",
                xy.name()
            ));
        }
        if machine {
            return Err(format!(
                "{w} with G53: machine coordinates are not polar (LinuxCNC: Cannot use polar coordinates with G53)"
            ));
        }
        match motion {
            Some(Motion::Rapid | Motion::Line) => Ok(()),
            Some(Motion::Cycle(_)) if self.plane == crate::host::toolpath::Plane::Xy => Ok(()),
            _ => Err(format!(
                "{w}: polar coordinates give the end of a G0 or G1, or a canned cycle's hole in the G17 plane"
            )),
        }
    }

    /// X and Y (work, program units) from the block's `@` and `^` about the
    /// origin, from the current `at`; `None` without them.
    pub(super) fn polar_xy(&self, words: &Words, at: [f64; 2]) -> Result<Option<[f64; 2]>, String> {
        let [radius_word, angle_word] = words.polar;
        if radius_word.is_none() && angle_word.is_none() {
            return Ok(None);
        }
        let radius = at[0].hypot(at[1]);
        let angle = at[1].atan2(at[0]).to_degrees();
        let (radius, angle) = if self.incremental {
            if radius == 0.0 {
                return Err(
                    "incremental polar coordinates at the origin have no angle to add to (LinuxCNC: Incremental motion with polar coordinates is indeterminate when at the origin)"
                        .into(),
                );
            }
            (
                radius + radius_word.map_or(0.0, |w| w.value),
                angle + angle_word.map_or(0.0, |w| w.value),
            )
        } else {
            (
                radius_word.map_or(radius, |w| w.value),
                angle_word.map_or(angle, |w| w.value),
            )
        };
        let theta = angle.to_radians();
        Ok(Some([radius * theta.cos(), radius * theta.sin()]))
    }
}
