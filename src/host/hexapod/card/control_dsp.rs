//! The control-level DSP of the parallel-machine card: it writes each
//! period's point into every slave's command FIFO through the master port,
//! arms the release with SYNC (the bridge's tick mode: the next
//! `period_tick` releases it), and reads the card's fault flags once a
//! period to learn of an underrun.

use std::collections::VecDeque;

use crate::blocks::parallel_card::registers::{master_map, SLAVES};
use crate::regmap::RegisterMap;

use super::super::{CommandError, PeriodPoint};
use super::bus::BusAgent;

/// An underrun the card flagged: every joint stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Underrun {
    /// Bit k: slave k had no released point at the tick.
    pub slaves: u64,
    /// The period whose tick found it (0 is the first release).
    pub period: u64,
}

impl Underrun {
    /// The slaves that underran.
    pub fn slave_list(&self) -> Vec<usize> {
        (0..SLAVES).filter(|k| self.slaves >> k & 1 != 0).collect()
    }
}

/// The control DSP's half of the card's protocol.
pub struct ControlDsp {
    map: RegisterMap,
    /// Its bus to the card.
    pub bus: BusAgent,
    /// A point it leaves out: (period, slave), to show an underrun.
    pub drop_point: Option<(u64, usize)>,
    /// The first underrun read back, if any.
    pub underrun: Option<Underrun>,
    /// The period of each CARD_FAULT read in flight, oldest first.
    fault_reads: VecDeque<u64>,
}

impl Default for ControlDsp {
    fn default() -> Self {
        Self {
            map: master_map().expect("the card's master map is valid"),
            bus: BusAgent::default(),
            drop_point: None,
            underrun: None,
            fault_reads: VecDeque::new(),
        }
    }
}

impl ControlDsp {
    fn address(&self, register: &str, index: u32) -> u64 {
        self.map
            .address_of(register, index)
            .expect("a register of the card's master map") as u64
    }

    fn pack(&self, register: &str, fields: &[(&str, u64)]) -> u64 {
        self.map
            .register(register)
            .and_then(|r| r.pack(fields))
            .expect("fields of the card's master map") as u64
    }

    /// Before the first tick: tick mode, the encoder filter, point 0 for
    /// every slave, SYNC, and the fault flags of power-up cleared.
    pub fn prime(&mut self, first: &PeriodPoint, encoder_filter: u64) -> Result<(), CommandError> {
        let control = self.pack("CONTROL", &[("TICK_MODE", 1)]);
        self.bus.write(self.address("CONTROL", 0), control);
        let filter = self.pack("CARD_CONTROL", &[("ENC_FILTER", encoder_filter)]);
        self.bus.write(self.address("CARD_CONTROL", 0), filter);
        self.send(first, 0)?;
        let clear = self.pack("CARD_FAULT", &[("UNDERRUN", (1 << SLAVES) - 1)]);
        self.bus.write(self.address("CARD_FAULT", 0), clear);
        Ok(())
    }

    /// After tick `period`: the point for the next release, and the fault
    /// flags' read.
    pub fn after_tick(&mut self, period: u64, next: &PeriodPoint) -> Result<(), CommandError> {
        self.send(next, period + 1)?;
        self.bus.read(self.address("CARD_FAULT", 0));
        self.fault_reads.push_back(period);
        Ok(())
    }

    fn send(&mut self, point: &PeriodPoint, period: u64) -> Result<(), CommandError> {
        let words = point.encode()?;
        for k in 0..SLAVES {
            if self.drop_point == Some((period, k)) {
                continue;
            }
            let cmd = self.address("CMD", k as u32);
            for &w in &words {
                self.bus.write(cmd, w as u64);
            }
        }
        self.bus.write(self.address("SYNC", 0), 0);
        Ok(())
    }

    /// After each clock: takes the fault flags read back.
    pub fn clock(&mut self) {
        if self.bus.results_ready() == 0 {
            return;
        }
        let field = self
            .map
            .field("CARD_FAULT", "UNDERRUN")
            .expect("CARD_FAULT.UNDERRUN");
        for word in self.bus.take_results() {
            let Some(period) = self.fault_reads.pop_front() else {
                break;
            };
            let slaves = field.extract(word as u32).unwrap_or(0);
            if slaves != 0 && self.underrun.is_none() {
                self.underrun = Some(Underrun { slaves, period });
            }
        }
    }
}
