//! Spindle-synchronized motion: G33 (one axis geared to the spindle),
//! G33.1 (rigid tapping) and G76 (LinuxCNC's threading cycle, its
//! `convert_threading_cycle`).
//!
//! Each geared move becomes an [`Item::Synced`]: the controller's
//! electronic gearbox steps the axis `pitch` mm per spindle revolution
//! from the next index on, so every pass of a thread starts at the same
//! spindle angle. The gearbox drives one axis, so a geared move moves
//! one axis: a G33 that moves two (a tapered thread) and G76's taper
//! (E, L) are refused, each with its reason.
//!
//! **G76** (LinuxCNC's words and formulas). From the tool's position (the
//! drive line: X, and Z where the thread starts) to Z, with P the pitch,
//! I the crest's offset from the drive line (negative: an outside thread),
//! J the first cut's depth and K the thread's full depth beyond the crest,
//! R the depth degression (pass n cuts to |I| + J n^(1/R)), Q the compound
//! angle in degrees (each pass starts (depth - |I|) tan Q back along Z,
//! and ends K tan Q beyond Z, so the last pass ends at Z) and H the spring
//! passes at full depth. Each pass: a rapid back off the work, a rapid in
//! to its depth, the geared cut, a rapid out. At the end, a rapid to the
//! block's X and Z.
//!
//! Where LinuxCNC silently corrects a value, this interpreter refuses it:
//! R below 1 (LinuxCNC takes 1), E and L (the taper; LinuxCNC clamps a
//! negative E to 0), a Q of 90 degrees or more. LinuxCNC's own checks
//! (I not 0, J above 0, K above J, P given) come with its message.

use super::block_words::{Motion, Words};
use super::interpreter::State;
use super::lexer::Word;
use crate::host::toolpath::{Item, SyncedMove};

/// The most passes one G76 may make (a J far below K with a high R could
/// ask for millions).
pub const MAX_G76_PASSES: u64 = 1000;

/// A geared move's words, taken out of the block before the checks that
/// would otherwise call them unused (K is G33's pitch, not an arc center).
#[derive(Clone, Copy, Default)]
pub(super) struct SyncWords<'a> {
    /// G33's and G33.1's K, G76's K (full depth).
    k: Option<&'a Word>,
    i: Option<&'a Word>,
    j: Option<&'a Word>,
    p: Option<&'a Word>,
    q: Option<&'a Word>,
    r: Option<&'a Word>,
    h: Option<&'a Word>,
    e: Option<&'a Word>,
    l: Option<&'a Word>,
}

impl<'a> SyncWords<'a> {
    /// Takes the words of the block's G33, G33.1 or G76 out of `words`
    /// (nothing when the block has none of them and `modal`, the motion
    /// mode in force, is not G33 or G33.1).
    pub(super) fn take(words: &mut Words<'a>, modal: Option<Motion>) -> Self {
        let mut taken = Self::default();
        match words.motion.map(|(_, m)| m).or(modal) {
            Some(Motion::SpindleSync | Motion::RigidTap) => {
                taken.k = words.offsets[2].take();
            }
            Some(Motion::Threading) => {
                taken.i = words.offsets[0].take();
                taken.j = words.offsets[1].take();
                taken.k = words.offsets[2].take();
                taken.p = words.p.take();
                taken.q = words.q.take();
                taken.r = words.radius.take();
                taken.h = words.h.take();
                taken.e = words.e.take();
                taken.l = words.l.take();
            }
            _ => return taken,
        }
        words.first_center = words
            .offsets
            .iter()
            .flatten()
            .copied()
            .chain(words.radius)
            .next();
        taken
    }
}

impl State {
    /// The spindle speed and direction a geared move runs at: M3 or M4
    /// with an S above zero.
    fn geared_spindle(&self, name: &str) -> Result<(f64, bool), String> {
        match self.spindle_turning {
            Some(clockwise) if self.spindle_speed > 0.0 => Ok((self.spindle_speed, clockwise)),
            Some(_) => Err(format!(
                "{name} with the spindle stopped: S is 0; give S, the speed in rpm"
            )),
            None => Err(format!(
                "{name} with the spindle stopped: M3 or M4 with S first (LinuxCNC: Spindle not turning in {name})"
            )),
        }
    }

    /// G33 (`rigid_tap` false) or G33.1 to the block's axis words.
    pub(super) fn spindle_synced(
        &mut self,
        rigid_tap: bool,
        sync: &SyncWords,
        words: &Words,
        line: usize,
    ) -> Result<(), String> {
        let name = if rigid_tap { "G33.1" } else { "G33" };
        self.refuse_with_comp(
            name,
            "Cannot use G33 or G33.1 with cutter radius compensation on",
        )?;
        if let Some(word) = words.rotary.iter().flatten().next() {
            return Err(format!(
                "{} with {name}: a geared move moves one of X, Y and Z",
                word.name()
            ));
        }
        let k = sync.k.ok_or_else(|| {
            format!("{name} needs K, the distance per spindle revolution (LinuxCNC: K word missing in {name})")
        })?;
        if k.value <= 0.0 {
            return Err(format!(
                "{} is not a pitch: the distance per revolution must be above zero",
                k.name()
            ));
        }
        let (rpm, clockwise) = self.geared_spindle(name)?;
        let start = self.base_mm();
        let (end, end_mm) = self.target(words, self.offset())?;
        let moving: Vec<usize> = (0..3).filter(|&k| end_mm[k] != start[k]).collect();
        let axis = match moving.as_slice() {
            [] => {
                self.position = end;
                return Ok(());
            }
            [axis] => *axis,
            [a, b, ..] => {
                return Err(format!(
                    "{name} moves {} and {} together: the gearbox drives one axis, so a tapered thread is not supported; thread along one axis",
                    ['X', 'Y', 'Z'][*a],
                    ['X', 'Y', 'Z'][*b]
                ))
            }
        };
        self.programmed_mm = None;
        self.toolpath.items.push(Item::Synced(SyncedMove {
            axis,
            start,
            end: end_mm,
            pitch: k.value * self.units.mm_per_unit(),
            rpm,
            clockwise,
            rigid_tap,
            pass: None,
            line,
        }));
        if rigid_tap {
            // The tap comes back out to where it went in.
            self.position_mm = start;
            self.sync_work_position();
        } else {
            self.position = end;
            self.position_mm = end_mm;
        }
        Ok(())
    }

    /// G76 with the block's words; the tool ends at the block's X and Z.
    pub(super) fn threading_cycle(
        &mut self,
        sync: &SyncWords,
        words: &Words,
        line: usize,
    ) -> Result<(), String> {
        self.refuse_with_comp(
            "G76",
            "Cannot use G76 threading cycle with cutter radius compensation on",
        )?;
        if let Some(word) = words
            .rotary
            .iter()
            .flatten()
            .copied()
            .next()
            .or(words.axes[1])
        {
            return Err(format!(
                "{} with G76: the cycle threads along Z and cuts in X; it takes X and Z only",
                word.name()
            ));
        }
        let scale = self.units.mm_per_unit();
        let needed = |word: Option<&Word>, what: &str, lcnc: &str| {
            word.map(|w| w.value)
                .ok_or_else(|| format!("G76 needs {what} (LinuxCNC: {lcnc})"))
        };
        if words.axes[2].is_none() {
            return Err("G76 needs Z, where the thread ends".into());
        }
        let pitch = needed(sync.p, "P, the pitch", "P word missing with G76")?;
        let i = needed(
            sync.i,
            "I, the crest's offset from the drive line",
            "In G76, I must not be 0",
        )?;
        let j = needed(
            sync.j,
            "J, the first cut's depth",
            "In G76, J must be greater than 0",
        )?;
        let k = needed(
            sync.k,
            "K, the thread's full depth",
            "In G76, K must be greater than J",
        )?;
        if pitch <= 0.0 {
            return Err(format!(
                "G76's P{pitch} is not a pitch: it must be above zero"
            ));
        }
        if i == 0.0 {
            return Err("G76's I is 0: the crest must be off the drive line (LinuxCNC: In G76, I must not be 0)".into());
        }
        if j <= 0.0 {
            return Err(format!(
                "G76's J{j} is not a depth: it must be above zero (LinuxCNC: In G76, J must be greater than 0)"
            ));
        }
        if k <= j {
            return Err(format!(
                "G76's K{k} must be deeper than J{j}: K is the full depth, J the first cut (LinuxCNC: In G76, K must be greater than J)"
            ));
        }
        let degression = sync.r.map_or(1.0, |w| w.value);
        if degression < 1.0 {
            return Err(format!(
                "G76's R{degression} is not a depth degression: it must be 1 or more (LinuxCNC silently takes 1)"
            ));
        }
        let angle = sync.q.map_or(0.0, |w| w.value);
        if angle.abs() >= 90.0 {
            return Err(format!(
                "G76's Q{angle} is not a compound angle: it must be within ±90 degrees"
            ));
        }
        let spring = sync.h.map_or(0.0, |w| w.value);
        if !(spring >= 0.0 && spring.fract() == 0.0 && spring <= MAX_G76_PASSES as f64) {
            return Err(format!(
                "G76's H{spring} is not a number of spring passes: a whole number from 0 to {MAX_G76_PASSES}"
            ));
        }
        if let Some(e) = sync.e.filter(|w| w.value != 0.0) {
            return Err(format!(
                "G76's {} asks for a tapered entry or exit: it moves X and Z together, and the gearbox drives one axis; leave out E and L",
                e.name()
            ));
        }
        if let Some(l) = sync
            .l
            .filter(|w| !(0.0..=3.0).contains(&w.value) || w.value.fract() != 0.0)
        {
            return Err(format!(
                "G76's {} is not a taper selection: 0 to 3",
                l.name()
            ));
        }
        // Passes while the depth is short of the full depth: n < (K/J)^R.
        let cuts = ((k / j).powf(degression)).ceil();
        if cuts + spring > MAX_G76_PASSES as f64 {
            return Err(format!(
                "G76 would make about {cuts:.0} passes (K/J to the power R) plus {spring} spring passes: more than {MAX_G76_PASSES}"
            ));
        }
        let (rpm, clockwise) = self.geared_spindle("G76")?;
        let start = self.base_mm();
        let (end, end_mm) = self.target(words, self.offset())?;
        if end_mm[2] == start[2] {
            return Err("G76's Z is where the tool stands: the thread has no length".into());
        }
        let (i, j, k, pitch) = (i * scale, j * scale, k * scale, pitch * scale);
        let boring = i > 0.0;
        let (safe_x, start_z) = (start[0], start[2]);
        let crest = i.abs();
        let full_depth = crest + k;
        let mut compound = angle.to_radians();
        if end_mm[2] > start_z {
            compound = -compound;
        }
        let target_z = end_mm[2] + k * compound.tan();
        // X at `depth` from the drive line, into the work.
        let x_at = |depth: f64| {
            if boring {
                safe_x + depth
            } else {
                safe_x - depth
            }
        };
        self.programmed_mm = None;
        let mut pass = 1u32;
        let mut depth = crest + j;
        let cut = |state: &mut State, depth: f64, pass: u32| {
            let zoff = (depth - crest) * compound.tan();
            // Back off by the depth still to cut, as LinuxCNC does.
            let back = x_at(depth - full_depth);
            let mut at = state.position_mm;
            at[0] = back;
            at[2] = start_z - zoff;
            state.line_to(at, None, line);
            at[0] = x_at(depth);
            state.line_to(at, None, line);
            let cut_start = at;
            at[2] = target_z - zoff;
            state.toolpath.items.push(Item::Synced(SyncedMove {
                axis: 2,
                start: cut_start,
                end: at,
                pitch,
                rpm,
                clockwise,
                rigid_tap: false,
                pass: Some(pass),
                line,
            }));
            state.position_mm = at;
            at[0] = back;
            state.line_to(at, None, line);
        };
        while depth < full_depth {
            cut(self, depth, pass);
            pass += 1;
            depth = crest + j * f64::from(pass).powf(1.0 / degression);
        }
        for _ in 0..=spring as u32 {
            cut(self, full_depth, pass);
            pass += 1;
        }
        self.line_to(end_mm, None, line);
        self.position = end;
        Ok(())
    }
}
