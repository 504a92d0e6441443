//! Canned cycles with LinuxCNC's motion (its `interp_cycles.cc`): G73,
//! G74, G81, G82, G83, G84, G85, G86, G87, G88 and G89 in the G17, G18 and G19
//! planes, with R, Q, P, L and (G87) I, J, K; G98 and G99; modal repeats
//! on bare axis lines; G91 with L repeats.
//!
//! Along the plane's normal (Z for G17), the cycle works between three
//! levels: the initial level (the normal position before the first cycle
//! of a series; a series ends at any other motion or G80), R, and the
//! bottom Z. The first repeat rapids in the plane at the current level,
//! then down to R (if the tool starts below R it first rapids up to R,
//! which becomes the initial level); later repeats rapid at the clear
//! level, R under G99 (LinuxCNC's default) or the initial level under G98,
//! then down to R. Each cycle ends at the clear level. Under G91, R counts from the initial
//! level, Z from R, and X and Y add on every repeat.

use super::block_words::{Cycle, Words};
use super::interpreter::State;
use super::lexer::Word;
use crate::host::toolpath::Item;

/// G73's and G83's clearance when no D word gives it: LinuxCNC 2.9's, as
/// its G-code documentation states it (0.010 in). LinuxCNC's newer
/// sources default to 1 mm (or 0.050 in).
pub const PECK_CLEARANCE_MM: f64 = 0.254;

/// What a cycle keeps for the next block of the same cycle (LinuxCNC's
/// `cycle_*` settings), in the program's units as written.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct CycleMemory {
    /// The initial level of the series, if one is under way.
    pub(super) initial: Option<f64>,
    r: f64,
    /// The bottom as written (an increment from R under G91).
    z: f64,
    q: f64,
    p: f64,
    ijk: [f64; 3],
}

impl State {
    /// Runs `cycle` for one block: L repeats at the block's point (or,
    /// under G91, stepping by it). `same`: the motion mode before the block
    /// was this cycle, so that R, Z, Q, P, I, J, K may be left out.
    pub(super) fn cycle(
        &mut self,
        cycle: Cycle,
        same: bool,
        words: &Words,
        line: usize,
    ) -> Result<(), String> {
        let name = cycle.name();
        let (first, second, normal) = self.plane.axes();
        let depth_letter = ['X', 'Y', 'Z'][normal];
        self.feed
            .ok_or_else(|| format!("{name} needs a feed rate: no F word so far"))?;
        let memory = self.cycle_memory;
        let r = match (words.radius, same) {
            (Some(r), _) => r.value,
            (None, true) => memory.r,
            (None, false) => {
                return Err(format!(
                    "{name} needs R, the retract level (LinuxCNC: R clearance plane unspecified in cycle)"
                ))
            }
        };
        let z = match (words.axes[normal], same) {
            (Some(z), _) => z.value,
            (None, true) => memory.z,
            (None, false) => {
                return Err(format!(
                    "{name} needs {depth_letter}, the bottom of the hole (LinuxCNC: {depth_letter} value unspecified in {} plane canned cycle)",
                    self.plane.gcode()
                ))
            }
        };
        let repeats = match words.l {
            None => 1,
            Some(l) if l.value >= 1.0 && l.value.fract() == 0.0 && l.value <= 1e6 => l.value as u32,
            Some(l) => {
                return Err(format!(
                    "{} is not a number of repeats: a whole number from 1 (LinuxCNC: Cannot do zero repeats of cycle)",
                    l.name()
                ))
            }
        };
        let sticky = |word: Option<&Word>, kept: f64, letter: char| match (word, same) {
            (Some(w), _) => Ok(w.value),
            (None, true) => Ok(kept),
            (None, false) => Err(format!(
                "{name} needs {letter} (LinuxCNC: {} word missing with {})",
                if letter == 'P' { "Dwell time p" } else { "Q" },
                name.to_lowercase()
            )),
        };
        let q = match cycle {
            Cycle::G73 | Cycle::G83 => sticky(words.q, memory.q, 'Q')?,
            _ => 0.0,
        };
        let p = match cycle {
            Cycle::G82 | Cycle::G86 | Cycle::G88 | Cycle::G89 => sticky(words.p, memory.p, 'P')?,
            // The tapping cycles' dwell at the bottom is optional.
            Cycle::G74 | Cycle::G84 => words
                .p
                .map_or(if same { memory.p } else { 0.0 }, |w| w.value),
            _ => 0.0,
        };
        if p < 0.0 {
            return Err(format!(
                "P{p} is not a dwell time: it must be 0 or more seconds"
            ));
        }
        let mut ijk = memory.ijk;
        if cycle == Cycle::G87 {
            for k in 0..3 {
                match (words.offsets[k], same) {
                    (Some(w), _) => ijk[k] = w.value,
                    (None, true) => {}
                    (None, false) => {
                        let letter = ['I', 'J', 'K'][k];
                        return Err(format!(
                            "{name} needs {letter} (LinuxCNC: {letter} word missing with g87)"
                        ));
                    }
                }
            }
        } else if let Some(w) = words.offsets.iter().flatten().next() {
            return Err(format!("{} has no G2, G3 or G87 to use it", w.name()));
        }
        if matches!(cycle, Cycle::G86 | Cycle::G87 | Cycle::G88) && self.spindle_turning.is_none() {
            return Err(format!(
                "{name} needs the spindle turning: M3 or M4 first (LinuxCNC: Spindle not turning in {})",
                name.to_lowercase()
            ));
        }
        match (cycle, self.spindle_turning) {
            (Cycle::G74 | Cycle::G84, None) => {
                return Err(format!(
                    "{name} needs the spindle turning: {} first (LinuxCNC: Spindle not turning in {})",
                    if cycle == Cycle::G84 { "M3" } else { "M4" },
                    name.to_lowercase()
                ))
            }
            (Cycle::G84, Some(false)) => {
                return Err(
                    "G84 taps right-hand: the spindle must turn clockwise (M3), not M4 (LinuxCNC: Spindle turning counterclockwise in G84)".into(),
                )
            }
            (Cycle::G74, Some(true)) => {
                return Err(
                    "G74 taps left-hand: the spindle must turn counterclockwise (M4), not M3 (LinuxCNC: Spindle turning clockwise in G74)".into(),
                )
            }
            _ => {}
        }
        let scale = self.units.mm_per_unit();
        let clearance = match (cycle, words.d) {
            (Cycle::G73 | Cycle::G83, Some(d)) => d.value,
            _ => PECK_CLEARANCE_MM / scale,
        };

        let current = self.position;
        // LinuxCNC keeps the series' initial level as first found, even when
        // a cycle then starts by rising to R.
        let series_initial = memory.initial.unwrap_or(current[normal]);
        let mut initial = series_initial;
        let (mut a, mut b) = (current[first], current[second]);
        let (step_a, step_b, r_level, bottom) = if self.incremental {
            let step = |k: usize| words.axes[k].map_or(0.0, |w| w.value);
            let r_level = initial + r;
            (step(first), step(second), r_level, r_level + z)
        } else {
            a = words.axes[first].map_or(a, |w| w.value);
            b = words.axes[second].map_or(b, |w| w.value);
            if let Some([x, y]) = self.polar_xy(words, [a, b])? {
                (a, b) = (x, y);
            }
            (0.0, 0.0, r, z)
        };
        if r_level < bottom {
            return Err(format!(
                "R{r} is below the bottom {depth_letter}{z} (LinuxCNC: R less than {} in cycle in {} plane)",
                depth_letter.to_ascii_lowercase(),
                self.plane.gcode()
            ));
        }
        let mut level = current[normal];
        if initial < r_level {
            self.cycle_move(true, [current[first], current[second], r_level], line);
            initial = r_level;
            level = r_level;
        }
        let clear = if self.retract_to_r { r_level } else { initial };
        for repeat in 0..repeats {
            a += step_a;
            b += step_b;
            if self.incremental {
                // Polar increments add on every repeat (LinuxCNC's
                // CYCLE_MACRO).
                if let Some([x, y]) = self.polar_xy(words, [a, b])? {
                    (a, b) = (x, y);
                }
            }
            if repeat == 0 && level > r_level {
                self.cycle_move(true, [a, b, level], line);
                self.cycle_move(true, [a, b, r_level], line);
            } else {
                self.cycle_move(true, [a, b, clear], line);
                if clear > r_level {
                    self.cycle_move(true, [a, b, r_level], line);
                }
            }
            self.cycle_body(
                cycle,
                [a, b],
                [r_level, clear, bottom],
                q,
                p,
                ijk,
                clearance,
                line,
            )?;
        }
        self.cycle_memory = CycleMemory {
            initial: Some(series_initial),
            r,
            z,
            q,
            p,
            ijk,
        };
        Ok(())
    }

    /// One hole at (`at`) from R: `levels` are R, the clear level and the
    /// bottom along the normal, in the program's units.
    #[allow(clippy::too_many_arguments)]
    fn cycle_body(
        &mut self,
        cycle: Cycle,
        at: [f64; 2],
        levels: [f64; 3],
        q: f64,
        p: f64,
        ijk: [f64; 3],
        clearance: f64,
        line: usize,
    ) -> Result<(), String> {
        let [r, clear, bottom] = levels;
        let [a, b] = at;
        match cycle {
            Cycle::G81 => {
                self.cycle_move(false, [a, b, bottom], line);
            }
            Cycle::G82 | Cycle::G86 | Cycle::G88 | Cycle::G89 => {
                self.cycle_move(false, [a, b, bottom], line);
                self.toolpath.items.push(Item::Dwell {
                    seconds: p,
                    laser: self.laser,
                    line,
                });
            }
            Cycle::G73 | Cycle::G83 => {
                if q <= 0.0 {
                    return Err(format!(
                        "Q{q} is not a peck depth: it must be above zero (LinuxCNC: Negative or zero q value used)"
                    ));
                }
                let mut depth = r - q;
                while depth > bottom {
                    self.cycle_move(false, [a, b, depth], line);
                    if cycle == Cycle::G83 {
                        self.cycle_move(true, [a, b, r], line);
                    }
                    self.cycle_move(true, [a, b, depth + clearance], line);
                    depth -= q;
                }
                self.cycle_move(false, [a, b, bottom], line);
            }
            Cycle::G85 => {
                self.cycle_move(false, [a, b, bottom], line);
                self.cycle_move(false, [a, b, r], line);
            }
            Cycle::G74 | Cycle::G84 => {
                // A floating holder takes up the difference between the
                // feed and the spindle: the moves are not geared (LinuxCNC:
                // G84 does not use synchronized motion). At the bottom the
                // spindle reverses, then the tap feeds out to the clear
                // level.
                self.cycle_move(false, [a, b, bottom], line);
                self.toolpath.items.push(Item::Dwell {
                    seconds: p,
                    laser: self.laser,
                    line,
                });
                self.cycle_move(false, [a, b, clear], line);
                return Ok(());
            }
            Cycle::G87 => {
                // Back boring: the tool goes down the hole off-center, then
                // bores upward to K.
                let off = [a + ijk[0], b + ijk[1]];
                let middle = if self.incremental {
                    bottom + ijk[2]
                } else {
                    ijk[2]
                };
                self.cycle_move(true, [off[0], off[1], r], line);
                self.cycle_move(true, [off[0], off[1], bottom], line);
                self.cycle_move(true, [a, b, bottom], line);
                self.cycle_move(false, [a, b, middle], line);
                self.cycle_move(false, [a, b, bottom], line);
                self.cycle_move(true, [off[0], off[1], bottom], line);
                self.cycle_move(true, [off[0], off[1], clear], line);
                self.cycle_move(true, [a, b, clear], line);
                return Ok(());
            }
        }
        // G88 stops there for the operator to retract by hand: a rapid
        // straight out to the clear level stands for that.
        match cycle {
            Cycle::G89 => self.cycle_move(false, [a, b, clear], line),
            _ => self.cycle_move(true, [a, b, clear], line),
        }
        Ok(())
    }

    /// A cycle's move to (`first`, `second`, `normal`) of the plane, in
    /// work coordinates and the program's units.
    fn cycle_move(&mut self, rapid: bool, to: [f64; 3], line: usize) {
        let (first, second, normal) = self.plane.axes();
        let mut end = self.position;
        end[first] = to[0];
        end[second] = to[1];
        end[normal] = to[2];
        let (offset, scale) = (self.offset(), self.units.mm_per_unit());
        let end_mm = [0, 1, 2].map(|k| end[k] * scale + offset[k]);
        self.position = end;
        self.line_to(end_mm, if rapid { None } else { self.feed }, line);
    }
}
