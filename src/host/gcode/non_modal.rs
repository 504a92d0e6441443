//! The non-modal codes that move or redefine the coordinates (LinuxCNC's
//! group 0 but G4): G10 L2 and L20, G28 and G30 with G28.1 and G30.1, G53's
//! checks, and G92 to G92.3, with LinuxCNC's semantics. Lengths are kept in
//! machine mm: a system's origin, the G92 offset and the stored positions
//! (see [`PersistentParameters`](super::PersistentParameters)).

use super::block_words::{Motion, NonModal, Words};
use super::interpreter::State;
use super::lexer::Word;
use super::parameters::SYSTEMS;

impl State {
    /// Runs `code` (written as `word`) on the block's `words`; `motion` is
    /// the motion the block runs, if any.
    pub(super) fn non_modal(
        &mut self,
        word: &Word,
        code: NonModal,
        words: &Words,
        motion: Option<Motion>,
        line: usize,
    ) -> Result<(), String> {
        let named = words.axes.map(|w| w.is_some());
        let refused = match code {
            NonModal::Home { .. } => Some("Cannot use g28 or g30 with cutter radius comp"),
            NonModal::StoreHome { .. } => {
                Some("Cannot set reference point with cutter compensation in effect")
            }
            NonModal::SetOffset
            | NonModal::ClearOffset
            | NonModal::SuspendOffset
            | NonModal::RestoreOffset => {
                Some("Cannot change axis offsets with cutter radius compensation on")
            }
            NonModal::SetOrigin | NonModal::MachineCoordinates => None,
        };
        if let Some(lcnc) = refused {
            self.refuse_with_comp(&word.name(), lcnc)?;
        }
        match code {
            NonModal::MachineCoordinates => {
                if !matches!(motion, Some(Motion::Rapid | Motion::Line)) {
                    return Err(format!(
                        "{} needs a G0 or G1 move with axis words (LinuxCNC: Must use g0 or g1 with g53)",
                        word.name()
                    ));
                }
                if self.incremental {
                    return Err(format!(
                        "{} with G91: machine coordinates are absolute (LinuxCNC: Cannot use g53 incremental)",
                        word.name()
                    ));
                }
            }
            NonModal::Home { second } => {
                // The axis words are a point on the way, in the current
                // distance mode and offsets; then only the named axes (all
                // of them when none is named) go to the stored position.
                let (_, via) = self.target(words, self.offset())?;
                self.rapid_to_machine(via, line);
                let home = self.parameters.home(second);
                let any = named.iter().any(|&n| n);
                let end = [0, 1, 2].map(|k| {
                    if named[k] || !any {
                        home[k]
                    } else {
                        self.position_mm[k]
                    }
                });
                self.rapid_to_machine(end, line);
            }
            NonModal::StoreHome { second } => {
                self.parameters.set_home(second, self.base_mm());
            }
            NonModal::SetOffset => {
                if !named.iter().any(|&n| n) {
                    return Err(format!(
                        "{} needs an axis word (LinuxCNC: All axes missing with g92)",
                        word.name()
                    ));
                }
                // An axis not named keeps the G92 offset in force
                // (LinuxCNC's source; its documentation says it is zeroed).
                let origin = self.parameters.origin(self.parameters.active_system());
                let mut offset = self.parameters.g92();
                let (scale, base) = (self.units.mm_per_unit(), self.base_mm());
                for (k, w) in words.axes.iter().enumerate() {
                    if let Some(w) = w {
                        offset[k] = base[k] - origin[k] - self.tool_offset[k] - w.value * scale;
                    }
                }
                self.parameters.set_g92(offset, true);
                self.sync_work_position();
            }
            NonModal::ClearOffset => {
                self.parameters.set_g92([0.0; 3], false);
                self.sync_work_position();
            }
            NonModal::SuspendOffset | NonModal::RestoreOffset => {
                let stored = self.parameters.g92_stored();
                self.parameters
                    .set_g92(stored, code == NonModal::RestoreOffset);
                self.sync_work_position();
            }
            NonModal::SetOrigin => self.set_origin(word, words)?,
        }
        Ok(())
    }

    /// G10 L2 (the origin at the words, machine coordinates) or L20 (the
    /// origin where the current position reads the words) of system P
    /// (0: the active one). G91 does not apply; R must be 0.
    fn set_origin(&mut self, word: &Word, words: &Words) -> Result<(), String> {
        let g10 = word.name();
        let l20 = match words.l.map(|l| (l, l.code())) {
            Some((_, Some(20))) => false,
            Some((_, Some(200))) => true,
            other => {
                let what = other.map_or("no L".to_string(), |(l, _)| l.name());
                return Err(format!(
                    "{g10} with {what}: L2 and L20 set a coordinate system; L1, L10 and L11 set the tool table, which is not supported"
                ));
            }
        };
        let p = words.p.ok_or_else(|| {
            format!(
                "{g10} needs P: the coordinate system, 0 (the active one) or 1 (G54) to 9 (G59.3)"
            )
        })?;
        let system = match p.value {
            v if v.fract() == 0.0 && (0.0..=SYSTEMS as f64).contains(&v) => v as usize,
            _ => {
                return Err(format!(
                    "{} is not a coordinate system: 0 (the active one) or 1 (G54) to 9 (G59.3)",
                    p.name()
                ))
            }
        };
        if let Some(r) = words.rotation.filter(|r| r.value != 0.0) {
            return Err(format!(
                "{} on {g10} rotates the coordinate system, which is not supported",
                r.name()
            ));
        }
        let active = self.parameters.active_system();
        let index = system.checked_sub(1).unwrap_or(active);
        if index == active {
            self.refuse_with_comp(
                &format!("{g10} {}", p.name()),
                "Cannot change the active coordinate system with cutter radius compensation on",
            )?;
        }
        let mut origin = self.parameters.origin(index);
        let g92 = self.parameters.g92();
        let (scale, base) = (self.units.mm_per_unit(), self.base_mm());
        for (k, w) in words.axes.iter().enumerate() {
            if let Some(w) = w {
                origin[k] = if l20 {
                    base[k] - g92[k] - self.tool_offset[k] - w.value * scale
                } else {
                    w.value * scale
                };
            }
        }
        self.parameters.set_origin(index, origin);
        if index == active {
            self.sync_work_position();
        }
        Ok(())
    }
}
