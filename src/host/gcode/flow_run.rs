//! Running a program whose O-words jump: the program counter, the call
//! stack and the loop bound (see [`flow`](super::flow) for the rules).

use std::collections::HashMap;

use super::flow::{OKind, OWord, Structure, MAX_CALL_DEPTH, MAX_ITERATIONS};
use super::interpreter::{GcodeError, State};
use super::lexer::Block;

/// A call in progress.
struct Frame {
    /// The block after the call.
    return_to: usize,
    call_line: usize,
    label: String,
    saved: super::param_store::Saved,
}

/// What a run needs besides the state.
struct Run<'a> {
    blocks: &'a [Block],
    structure: &'a Structure,
    frames: Vec<Frame>,
    iterations: u64,
    /// Repeats left, by the `repeat` block's index.
    repeats: HashMap<usize, f64>,
}

impl Run<'_> {
    /// Where `map` sends block `pc` (found by the structure pass).
    fn jump(map: &HashMap<usize, usize>, pc: usize) -> Result<usize, String> {
        map.get(&pc)
            .copied()
            .ok_or_else(|| "an O-word the structure pass did not pair".to_string())
    }

    fn iterate(&mut self, o: &OWord) -> Result<(), String> {
        self.iterations += 1;
        if self.iterations > MAX_ITERATIONS {
            return Err(format!(
                "O{}: the program's loops jumped back {MAX_ITERATIONS} times: a loop that does not end (this interpreter's bound; LinuxCNC has none)",
                o.label
            ));
        }
        Ok(())
    }
}

impl State {
    /// Runs `blocks` from the first; returns the index after the last
    /// block run (the end of the file, or the block after M2 or M30).
    pub(super) fn run_blocks(
        &mut self,
        blocks: &[Block],
        structure: &Structure,
    ) -> Result<usize, GcodeError> {
        let mut run = Run {
            blocks,
            structure,
            frames: Vec::new(),
            iterations: 0,
            repeats: HashMap::new(),
        };
        let mut pc = 0;
        while let Some(block) = blocks.get(pc) {
            if self.end.is_some() {
                break;
            }
            let located = |message: String, frames: &[Frame]| GcodeError {
                line: block.line,
                message: match frames.last() {
                    Some(f) => {
                        format!("{message} (in O{} called on line {})", f.label, f.call_line)
                    }
                    None => message,
                },
            };
            if block.deleted {
                pc += 1;
                continue;
            }
            pc = match &block.o_word {
                None => {
                    self.run_block(block).map_err(|m| located(m, &run.frames))?;
                    pc + 1
                }
                Some(o) => self
                    .o_word(o, pc, &mut run)
                    .map_err(|m| located(m, &run.frames))?,
            };
        }
        Ok(pc)
    }

    fn truth(&self, expr: &super::expr::Expr) -> Result<bool, String> {
        Ok(expr.evaluate(self)? != 0.0)
    }

    /// Runs the O-word at `pc`; returns the next block's index.
    fn o_word(&mut self, o: &OWord, pc: usize, run: &mut Run) -> Result<usize, String> {
        let s = run.structure;
        Ok(match &o.kind {
            OKind::Sub => Run::jump(&s.target, pc)? + 1,
            OKind::EndSub(value) | OKind::Return(value) => {
                let value = value.as_ref().map(|v| v.evaluate(self)).transpose()?;
                let frame = run
                    .frames
                    .pop()
                    .ok_or_else(|| format!("O{} return outside a subroutine", o.label))?;
                self.params.leave(frame.saved, value);
                frame.return_to
            }
            OKind::Call(arguments) => {
                let &(start, _) = s.subs.get(&o.label).ok_or_else(|| {
                    format!(
                        "O{} call: this file has no O{} sub (LinuxCNC would look for a file {}.ngc; subroutine files are not read)",
                        o.label,
                        o.label,
                        o.label.trim_matches(['<', '>'])
                    )
                })?;
                if run.frames.len() >= MAX_CALL_DEPTH {
                    return Err(format!(
                        "O{} call: more than {MAX_CALL_DEPTH} calls deep (LinuxCNC: Too many subroutine levels)",
                        o.label
                    ));
                }
                let values = arguments
                    .iter()
                    .map(|a| a.evaluate(self))
                    .collect::<Result<Vec<f64>, String>>()?;
                let saved = self.params.enter(&values);
                run.frames.push(Frame {
                    return_to: pc + 1,
                    call_line: run.blocks.get(pc).map_or(0, |b| b.line),
                    label: o.label.clone(),
                    saved,
                });
                start + 1
            }
            OKind::If(condition) => {
                if self.truth(condition)? {
                    pc + 1
                } else {
                    self.next_branch(pc, run)?
                }
            }
            OKind::ElseIf(_) | OKind::Else => Run::jump(&s.endif, pc)? + 1,
            OKind::EndIf | OKind::Do => pc + 1,
            OKind::While(condition) if s.do_while.contains(&pc) => {
                if self.truth(condition)? {
                    run.iterate(o)?;
                    Run::jump(&s.target, pc)? + 1
                } else {
                    pc + 1
                }
            }
            OKind::While(condition) => {
                if self.truth(condition)? {
                    pc + 1
                } else {
                    Run::jump(&s.target, pc)? + 1
                }
            }
            OKind::EndWhile | OKind::EndRepeat => {
                run.iterate(o)?;
                Run::jump(&s.target, pc)?
            }
            OKind::Repeat(count) => {
                let left = match run.repeats.get(&pc) {
                    Some(&left) => left,
                    None => count.evaluate(self)?.floor(),
                };
                if left >= 1.0 {
                    run.repeats.insert(pc, left - 1.0);
                    pc + 1
                } else {
                    run.repeats.remove(&pc);
                    Run::jump(&s.target, pc)? + 1
                }
            }
            OKind::Break => {
                let (head, end) = *s.loop_of.get(&pc).ok_or("break outside a loop")?;
                run.repeats.remove(&head);
                end + 1
            }
            OKind::Continue => {
                let (head, _) = *s.loop_of.get(&pc).ok_or("continue outside a loop")?;
                run.iterate(o)?;
                head
            }
        })
    }

    /// After a false `if` or `elseif` at `pc`: the first branch whose
    /// condition holds, the `else`, or the block after the `endif`.
    fn next_branch(&mut self, pc: usize, run: &Run) -> Result<usize, String> {
        let mut branch = Run::jump(&run.structure.target, pc)?;
        loop {
            match run
                .blocks
                .get(branch)
                .and_then(|b| b.o_word.as_ref())
                .map(|o| &o.kind)
            {
                Some(OKind::ElseIf(condition)) => {
                    if self.truth(condition)? {
                        return Ok(branch + 1);
                    }
                    branch = Run::jump(&run.structure.target, branch)?;
                }
                _ => return Ok(branch + 1),
            }
        }
    }
}
