//! Tools with LinuxCNC's semantics: T selects, M6 loads the selected tool,
//! M61 Q sets the loaded tool without a change; G43 [H], G43.1, G43.2 and
//! G49 set the tool length offset, which moves nothing by itself: it
//! shifts the work coordinates (machine = work + origin + G92 + this).

use super::block_words::{ToolLength, Words};
use super::interpreter::State;
use super::lexer::Word;
use crate::host::tool_table::Tool;

/// A tool number word (T, H, Q): a whole number, 0 (no tool) or more.
fn tool_number(word: &Word) -> Result<u32, String> {
    let v = word.value;
    if v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v) {
        Ok(v as u32)
    } else {
        Err(format!(
            "{} is not a tool number: a whole number, 0 (no tool) or more",
            word.name()
        ))
    }
}

impl State {
    /// Tool `number` from the table, checking that the table has it:
    /// `None` for tool 0 (no tool) or without a table. `name` is the word
    /// that asked for it, for the message.
    pub(super) fn table_tool(&self, name: &str, number: u32) -> Result<Option<&Tool>, String> {
        match (&self.tools, number) {
            (_, 0) | (None, _) => Ok(None),
            (Some(table), n) => table.get(n).map(Some).ok_or_else(|| {
                format!(
                    "{name}: tool {n} is not in the tool table (LinuxCNC: Requested tool {n} not found in the tool table)"
                )
            }),
        }
    }

    /// `number`'s offset, mm (tool 0 and no table: none).
    fn tool_offset_of(&self, name: &str, number: u32) -> Result<[f64; 3], String> {
        Ok(self
            .table_tool(name, number)?
            .map_or([0.0; 3], |t| t.offset))
    }

    /// LinuxCNC reads the position back after M6 and M61: a programmed
    /// point that G40 left apart from the tool's is dropped.
    fn read_position_back(&mut self) {
        self.programmed_mm = None;
        self.sync_work_position();
    }

    /// T, then M6 or M61 (LinuxCNC's steps 5 and 6).
    pub(super) fn tool_words(&mut self, words: &Words) -> Result<(), String> {
        if let Some(t) = words.tool {
            let number = tool_number(t)?;
            self.tool_offset_of(&t.name(), number)?;
            self.selected = Some(number);
        }
        if let Some(m6) = words.tool_change {
            let selected = self.selected.ok_or_else(|| {
                format!(
                    "{} needs a tool selected first with T (LinuxCNC: Need tool prepared -Txx- for toolchange)",
                    m6.name()
                )
            })?;
            self.refuse_with_comp(
                &m6.name(),
                "Cannot change tools with cutter radius compensation on",
            )?;
            self.loaded = selected;
            self.read_position_back();
        }
        if let Some(m61) = words.set_tool {
            let q = words
                .q
                .ok_or_else(|| format!("{} needs Q: the tool now in the spindle", m61.name()))?;
            let number = tool_number(q)?;
            self.tool_offset_of(&q.name(), number)?;
            self.loaded = number;
            self.read_position_back();
        }
        Ok(())
    }

    /// G43, G43.1, G43.2, G49 (LinuxCNC's step 14); H unused is reported.
    pub(super) fn tool_length(&mut self, words: &Words, line: usize) -> Result<(), String> {
        let code = words.tool_length;
        let uses_h = matches!(code, Some((_, ToolLength::FromTable | ToolLength::Add)));
        if let Some(h) = words.h.filter(|_| !uses_h) {
            self.report("H", line, h.name(), "tool offset");
        }
        let Some((g43, code)) = code else {
            return Ok(());
        };
        self.refuse_with_comp(
            &g43.name(),
            "Cannot change tool offset with cutter radius compensation on",
        )?;
        let scale = self.units.mm_per_unit();
        // Tool `number`'s offset, asked for by the word `name` (H1, or T1
        // for the loaded tool).
        let offset_of = |state: &mut Self, name: String, number: u32| -> Result<[f64; 3], String> {
            if state.tools.is_none() && number != 0 {
                state.report(
                    "no tool table",
                    line,
                    format!("{} {name}", g43.name()),
                    "tool length offset 0: no tool table given (--tools)",
                );
            }
            state.tool_offset_of(&name, number)
        };
        match code {
            ToolLength::FromTable => {
                let (name, number) = match words.h {
                    Some(h) => (h.name(), tool_number(h)?),
                    None => (format!("T{}", self.loaded), self.loaded),
                };
                self.tool_offset = offset_of(self, name, number)?;
            }
            ToolLength::Dynamic => {
                self.tool_offset = words.axes.map(|w| w.map_or(0.0, |w| w.value * scale));
            }
            ToolLength::Add => {
                let added = match words.h {
                    Some(h) => offset_of(self, h.name(), tool_number(h)?)?,
                    None if words.first_axis.is_some() => {
                        words.axes.map(|w| w.map_or(0.0, |w| w.value * scale))
                    }
                    None => {
                        return Err(format!(
                            "{} needs H (a tool) or axis words (the offset to add)",
                            g43.name()
                        ))
                    }
                };
                self.tool_offset = [0, 1, 2].map(|k| self.tool_offset[k] + added[k]);
            }
            ToolLength::Cancel => self.tool_offset = [0.0; 3],
        }
        self.sync_work_position();
        Ok(())
    }
}
