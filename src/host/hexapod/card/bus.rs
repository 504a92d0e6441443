//! One DSP's bus to `parallel_card`: the accesses its program asks for,
//! played onto the card's pins one at a time.
//!
//! Timing, as the card's datasheet gives it for both ports: a write is one
//! clock with the strobe high; a read is the strobe in one clock and the
//! data in the outputs after the next, a clock in which this bus is idle.

use std::collections::VecDeque;

/// One access.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Write `data` at `address`.
    Write {
        /// Word address.
        address: u64,
        /// The word.
        data: u64,
    },
    /// Read the word at `address`.
    Read {
        /// Word address.
        address: u64,
    },
}

/// A bus's pins for one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BusPins {
    /// Word address.
    pub address: u64,
    /// Write data.
    pub write_data: u64,
    /// Write strobe.
    pub write: bool,
    /// Read strobe.
    pub read: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ReadPhase {
    Strobed,
    Waiting,
}

/// The accesses a DSP has queued, and the words its reads returned.
#[derive(Clone, Debug, Default)]
pub struct BusAgent {
    queue: VecDeque<Access>,
    read: Option<ReadPhase>,
    /// The address held on the pins (a bus keeps its last address).
    address: u64,
    results: Vec<u64>,
}

impl BusAgent {
    /// Queues a write.
    pub fn write(&mut self, address: u64, data: u64) {
        self.queue.push_back(Access::Write { address, data });
    }

    /// Queues a read; its word is returned in order by
    /// [`BusAgent::take_results`].
    pub fn read(&mut self, address: u64) {
        self.queue.push_back(Access::Read { address });
    }

    /// Nothing queued and no read waiting for its data.
    pub fn idle(&self) -> bool {
        self.queue.is_empty() && self.read.is_none()
    }

    /// The pins for the next clock.
    pub fn drive(&mut self) -> BusPins {
        let mut pins = BusPins {
            address: self.address,
            ..BusPins::default()
        };
        if self.read.is_some() {
            return pins;
        }
        match self.queue.pop_front() {
            Some(Access::Write { address, data }) => {
                pins = BusPins {
                    address,
                    write_data: data,
                    write: true,
                    read: false,
                };
            }
            Some(Access::Read { address }) => {
                pins.address = address;
                pins.read = true;
                self.read = Some(ReadPhase::Strobed);
            }
            None => {}
        }
        self.address = pins.address;
        pins
    }

    /// After the clock: the port's read data output.
    pub fn sample(&mut self, read_data: u64) {
        self.read = match self.read {
            Some(ReadPhase::Strobed) => Some(ReadPhase::Waiting),
            Some(ReadPhase::Waiting) => {
                self.results.push(read_data);
                None
            }
            None => None,
        };
    }

    /// The words read so far, oldest first; taking them empties the list.
    pub fn take_results(&mut self) -> Vec<u64> {
        std::mem::take(&mut self.results)
    }

    /// Words read and not yet taken.
    pub fn results_ready(&self) -> usize {
        self.results.len()
    }
}
