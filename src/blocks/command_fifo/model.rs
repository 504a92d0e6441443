//! Reference model of [`super::CommandFifo`]: a queue, not a copy of the
//! pointer logic.

use std::collections::VecDeque;

/// Inputs of one clock cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CommandFifoInputs {
    /// Synchronous reset (a flush).
    pub reset: bool,
    /// Push `write_data`.
    pub write: bool,
    /// The word pushed.
    pub write_data: u64,
    /// Drop the head.
    pub pop: bool,
    /// `low` threshold.
    pub low_water: u64,
    /// Clears `overflow` and `underflow`.
    pub clear_flags: bool,
}

impl CommandFifoInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.write as u64,
            self.write_data,
            self.pop as u64,
            self.low_water,
            self.clear_flags as u64,
        ]
    }
}

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

impl CommandFifoOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            head: v[0],
            empty: v[1] != 0,
            full: v[2] != 0,
            level: v[3],
            low: v[4] != 0,
            overflow: v[5] != 0,
            underflow: v[6] != 0,
        }
    }
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

impl crate::sim::LockstepModel for CommandFifoModel {
    type Inputs = CommandFifoInputs;
    type Outputs = CommandFifoOutputs;
    fn input_vector(inputs: &CommandFifoInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> CommandFifoOutputs {
        CommandFifoOutputs::from_vector(vector)
    }
    fn expected(&mut self, i: &CommandFifoInputs) -> CommandFifoOutputs {
        self.step(
            i.reset,
            i.write,
            i.write_data,
            i.pop,
            i.low_water,
            i.clear_flags,
        )
    }
    /// `head` is not specified while the FIFO is empty.
    fn agrees(rtl: &CommandFifoOutputs, model: &CommandFifoOutputs) -> bool {
        let head = if rtl.empty { 0 } else { rtl.head };
        CommandFifoOutputs { head, ..*rtl } == *model
    }
}
