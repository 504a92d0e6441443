//! Reference model of [`super::DacInterface`], cycle-exact, written from the
//! datasheet; it owns the packing of the RTL's port vectors.

use super::registers::{field_of, register_map, APPLIED_BASE, CODE_BASE, ID_VALUE};
use crate::blocks::width_mask;
use crate::regmap::RegisterMap;

/// Inputs of one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DacInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Register word address (4 bits).
    pub bus_address: u64,
    /// Register write data.
    pub bus_write_data: u64,
    /// Write strobe.
    pub bus_write: bool,
    /// Read strobe.
    pub bus_read: bool,
    /// Update request (the period boundary).
    pub update: bool,
    /// Forces the safe code (the abort level).
    pub force_safe: bool,
}

impl DacInputs {
    /// The RTL's input vector, in its port order.
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.bus_address,
            self.bus_write_data,
            self.bus_write as u64,
            self.bus_read as u64,
            self.update as u64,
            self.force_safe as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DacOutputs {
    /// Register read data.
    pub bus_read_data: u64,
    /// DAC data bus.
    pub dac_data: u64,
    /// Chip selects, active low, bit k for channel k.
    pub dac_cs_n: u64,
    /// First-rank load, active low.
    pub dac_l1_n: bool,
    /// Second-rank load, active high.
    pub dac_ldac: bool,
    /// An update is running (until LDAC falls).
    pub busy: bool,
    /// The safe code is applied, pending or being written.
    pub safe: bool,
}

impl DacOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            bus_read_data: v[0],
            dac_data: v[1],
            dac_cs_n: v[2],
            dac_l1_n: v[3] != 0,
            dac_ldac: v[4] != 0,
            busy: v[5] != 0,
            safe: v[6] != 0,
        }
    }
}

/// The sequencer's phase; the channel phases carry the channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Idle,
    Setup(usize),
    Width(usize),
    Hold(usize),
    Ldac,
}

/// Pin timing of one update, in clocks (each at least 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Timing {
    setup: u64,
    width: u64,
    hold: u64,
    ldac: u64,
}

impl Timing {
    fn from_word(word: u64) -> Self {
        let at = |lsb: u32| ((word >> lsb) & 0xff).max(1);
        Self {
            setup: at(0),
            width: at(8),
            hold: at(16),
            ldac: at(24),
        }
    }
}

/// Cycle-exact model of a `channels`-channel, `width`-bit interface.
#[derive(Clone, Debug)]
pub struct DacModel {
    map: RegisterMap,
    channels: usize,
    width: u32,
    // Register layer.
    staged: Vec<u64>,
    offset_binary: bool,
    timing_word: u64,
    deferred: bool,
    refused: bool,
    read_data: u64,
    abort_prev: bool,
    // Sequencer.
    phase: Phase,
    left: u64,
    shadow: Vec<u64>,
    shadow_offset: bool,
    timing: Timing,
    safe_run: bool,
    cut: bool,
    pending: bool,
    pending_safe: bool,
    applied: Vec<u64>,
    safe: bool,
    // Pins (registered from the phase of the clock before).
    data: u64,
    cs_n: u64,
    l1_n: bool,
    ldac: bool,
}

impl DacModel {
    /// An interface just out of reset.
    pub fn new(channels: usize, width: usize) -> Self {
        let map = register_map(channels, width).expect("a valid dac_interface geometry");
        let timing_word = map.register("TIMING").expect("TIMING").reset_value() as u64;
        Self {
            map,
            channels,
            width: width as u32,
            staged: vec![0; channels],
            offset_binary: false,
            timing_word,
            deferred: false,
            refused: false,
            read_data: 0,
            abort_prev: false,
            phase: Phase::Idle,
            left: 0,
            shadow: vec![0; channels],
            shadow_offset: false,
            timing: Timing::from_word(timing_word),
            safe_run: false,
            cut: false,
            pending: false,
            pending_safe: true,
            applied: vec![0; channels],
            safe: true,
            data: 0,
            cs_n: width_mask(channels as u32),
            l1_n: true,
            ldac: false,
        }
    }

    /// The register map the model decodes.
    pub fn map(&self) -> &RegisterMap {
        &self.map
    }

    /// The pins' code for signed code `value` in the chosen format.
    fn pin_code(&self, value: u64, offset_binary: bool) -> u64 {
        value
            ^ if offset_binary {
                1 << (self.width - 1)
            } else {
                0
            }
    }

    fn address(&self, name: &str) -> u64 {
        self.map
            .register(name)
            .expect("a register of the map")
            .address as u64
    }

    fn field_mask(&self, register: &str, field: &str) -> u64 {
        field_of(&self.map, register, field).mask() as u64
    }

    fn read(&self, address: u64, abort: bool) -> u64 {
        let status_bit = |field: &str, on: bool| {
            if on {
                self.field_mask("STATUS", field)
            } else {
                0
            }
        };
        let k = self.channels as u64;
        match address {
            a if a == self.address("ID") => ID_VALUE as u64,
            a if a == self.address("CONFIG") => {
                self.map.register("CONFIG").expect("CONFIG").reset_value() as u64
            }
            a if a == self.address("CONTROL") => {
                if self.offset_binary {
                    self.field_mask("CONTROL", "OFFSET_BINARY")
                } else {
                    0
                }
            }
            a if a == self.address("STATUS") => {
                status_bit("BUSY", self.busy() || self.ldac)
                    | status_bit("SAFE", self.safe)
                    | status_bit("FORCE_SAFE", abort)
                    | status_bit("PENDING", self.pending)
                    | status_bit("DEFERRED", self.deferred)
                    | status_bit("REFUSED", self.refused)
            }
            a if a == self.address("TIMING") => self.timing_word,
            a if (CODE_BASE as u64..CODE_BASE as u64 + k).contains(&a) => {
                self.staged[(a - CODE_BASE as u64) as usize]
            }
            a if (APPLIED_BASE as u64..APPLIED_BASE as u64 + k).contains(&a) => {
                self.applied[(a - APPLIED_BASE as u64) as usize]
            }
            _ => 0,
        }
    }

    fn busy(&self) -> bool {
        self.phase != Phase::Idle
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: DacInputs) -> DacOutputs {
        let code_mask = width_mask(self.width);
        let k = self.channels;

        // Pins: from the phase before this edge.
        let (cs_n, l1_n, ldac, data) = match self.phase {
            Phase::Idle => (width_mask(k as u32), true, false, self.data),
            Phase::Setup(c) | Phase::Hold(c) | Phase::Width(c) => (
                width_mask(k as u32) & !(1 << c),
                !matches!(self.phase, Phase::Width(_)),
                false,
                self.pin_code(self.shadow[c], self.shadow_offset),
            ),
            Phase::Ldac => (width_mask(k as u32), true, true, self.data),
        };

        // Reads see the registers before this edge.
        if i.bus_read {
            self.read_data = self.read(i.bus_address, i.force_safe);
        }

        // An update that starts on this edge takes the registers as they
        // were before it (a write on the same clock goes to the next one).
        let before = (self.staged.clone(), self.offset_binary, self.timing_word);

        // Register writes.
        let mut request = i.update;
        if i.bus_write {
            let a = i.bus_address;
            let d = i.bus_write_data;
            if a == self.address("CONTROL") {
                self.offset_binary = d & self.field_mask("CONTROL", "OFFSET_BINARY") != 0;
            } else if a == self.address("UPDATE") {
                request |= d & self.field_mask("UPDATE", "START") != 0;
            } else if a == self.address("STATUS") {
                if d & self.field_mask("STATUS", "DEFERRED") != 0 {
                    self.deferred = false;
                }
                if d & self.field_mask("STATUS", "REFUSED") != 0 {
                    self.refused = false;
                }
            } else if a == self.address("TIMING") {
                self.timing_word = d;
            } else if (CODE_BASE as u64..CODE_BASE as u64 + k as u64).contains(&a) {
                if i.force_safe {
                    self.refused = true;
                } else {
                    self.staged[(a - CODE_BASE as u64) as usize] = d & code_mask;
                }
            }
        }
        if request && i.force_safe {
            self.refused = true;
            request = false;
        }

        // Sequencer.
        let abort_rise = i.force_safe && !self.abort_prev;
        let cut_now = self.cut || (abort_rise && self.busy() && !self.safe_run);
        let (old_phase, old_left) = (self.phase, self.left);
        let safe_run_before = self.safe_run;
        let start = |m: &mut Self, safe: bool| {
            m.shadow = if safe { vec![0; k] } else { before.0.clone() };
            m.shadow_offset = before.1;
            m.timing = Timing::from_word(before.2);
            m.safe_run = safe;
            m.cut = false;
            m.phase = Phase::Setup(0);
            m.left = m.timing.setup;
        };
        match old_phase {
            Phase::Idle => {
                if self.pending_safe {
                    // A request waits behind the safe update, as behind
                    // any running one.
                    if request {
                        self.pending = true;
                        self.deferred = true;
                    }
                    self.pending_safe = false;
                    start(self, true);
                } else if (self.pending || request) && !i.force_safe {
                    self.pending = false;
                    start(self, false);
                }
            }
            running => {
                if request {
                    self.pending = true;
                    self.deferred = true;
                }
                self.cut = cut_now;
                if old_left > 1 {
                    self.left = old_left - 1;
                } else {
                    match running {
                        Phase::Setup(c) => {
                            self.phase = Phase::Width(c);
                            self.left = self.timing.width;
                        }
                        Phase::Width(c) => {
                            self.phase = Phase::Hold(c);
                            self.left = self.timing.hold;
                        }
                        Phase::Hold(_) if cut_now => {
                            self.phase = Phase::Idle;
                            self.cut = false;
                        }
                        Phase::Hold(c) if c + 1 < k => {
                            self.phase = Phase::Setup(c + 1);
                            self.left = self.timing.setup;
                        }
                        Phase::Hold(_) => {
                            self.phase = Phase::Ldac;
                            self.left = self.timing.ldac;
                        }
                        Phase::Ldac => {
                            self.phase = Phase::Idle;
                            self.applied = self.shadow.clone();
                            self.safe = self.safe_run || self.pending_safe;
                            self.cut = false;
                        }
                        Phase::Idle => unreachable!(),
                    }
                }
            }
        }
        if abort_rise {
            self.staged = vec![0; k];
            self.pending = false;
            self.pending_safe = !(old_phase != Phase::Idle && safe_run_before);
            // (A running safe update already writes 0 everywhere.)
            self.safe = true;
        }
        self.abort_prev = i.force_safe;
        (self.cs_n, self.l1_n, self.ldac, self.data) = (cs_n, l1_n, ldac, data);

        if i.reset {
            *self = Self::new(k, self.width as usize);
        }
        self.outputs()
    }

    /// The outputs as they stand.
    pub fn outputs(&self) -> DacOutputs {
        DacOutputs {
            bus_read_data: self.read_data,
            dac_data: self.data,
            dac_cs_n: self.cs_n,
            dac_l1_n: self.l1_n,
            dac_ldac: self.ldac,
            busy: self.busy() || self.ldac,
            safe: self.safe,
        }
    }
}
