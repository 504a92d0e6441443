//! Reference model of [`super::CommandFifo`]: a queue, not a copy of the
//! pointer logic.

use std::collections::VecDeque;

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CommandFifoOutputs {
    /// The oldest entry (0 when empty: the model does not know the RAM's
    /// stale word, so compare it only while `empty` is low).
    pub head: u64,
    /// No entry.
    pub empty: bool,
    /// No free slot.
    pub full: bool,
    /// Entries held.
    pub level: u64,
    /// `level <= low_water`.
    pub low: bool,
    /// Sticky overflow.
    pub overflow: bool,
    /// Sticky underflow.
    pub underflow: bool,
}

/// Queue model of a FIFO of `capacity` entries.
#[derive(Clone, Debug)]
pub struct CommandFifoModel {
    capacity: usize,
    queue: VecDeque<u64>,
    overflow: bool,
    underflow: bool,
}

impl CommandFifoModel {
    /// An empty FIFO of `capacity` entries.
    pub fn new(capacity: usize) -> Self {
        Self {
            capacity,
            queue: VecDeque::with_capacity(capacity),
            overflow: false,
            underflow: false,
        }
    }

    /// One edge; returns the outputs after it (`low` with this clock's
    /// `low_water` still applied).
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        reset: bool,
        write: bool,
        write_data: u64,
        pop: bool,
        low_water: u64,
        clear_flags: bool,
    ) -> CommandFifoOutputs {
        if clear_flags {
            self.overflow = false;
            self.underflow = false;
        }
        let pop_taken = pop && !self.queue.is_empty();
        let write_taken = write && (self.queue.len() < self.capacity || pop_taken);
        self.overflow |= write && !write_taken;
        self.underflow |= pop && !pop_taken;
        if pop_taken {
            self.queue.pop_front();
        }
        if write_taken {
            self.queue.push_back(write_data & 0xffff_ffff);
        }
        if reset {
            *self = Self::new(self.capacity);
        }
        CommandFifoOutputs {
            head: self.queue.front().copied().unwrap_or(0),
            empty: self.queue.is_empty(),
            full: self.queue.len() == self.capacity,
            level: self.queue.len() as u64,
            low: self.queue.len() as u64 <= low_water,
            overflow: self.overflow,
            underflow: self.underflow,
        }
    }
}
