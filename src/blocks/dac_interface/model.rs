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
    /// Register word address (`bus_address`).
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
    /// Bit k: stage `load_code` into channel k.
    pub load: u64,
    /// The code of `load` (W bits).
    pub load_code: u64,
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
            self.load,
            self.load_code,
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
    fn from_word(word: u64, d: &Decode) -> Self {
        let [setup, width, hold, ldac] = d
            .timing_fields
            .map(|(lsb, mask)| ((word >> lsb) & mask).max(1));
        Self {
            setup,
            width,
            hold,
            ldac,
        }
    }
}

/// The map's addresses and field masks, looked up by name once.
#[derive(Clone, Copy, Debug)]
struct Decode {
    id: u64,
    config: u64,
    control: u64,
    update: u64,
    status: u64,
    timing: u64,
    config_value: u64,
    timing_reset: u64,
    offset_binary: u64,
    start: u64,
    busy: u64,
    safe: u64,
    force_safe: u64,
    pending: u64,
    deferred: u64,
    refused: u64,
    /// `TIMING`'s SETUP, WIDTH, HOLD and LDAC_WIDTH: (lsb, value mask).
    timing_fields: [(u32, u64); 4],
}

impl Decode {
    fn new(map: &RegisterMap) -> Self {
        let register = |name: &str| map.register(name).expect("a register of the map");
        let address = |name: &str| register(name).address as u64;
        let mask = |r: &str, f: &str| field_of(map, r, f).mask() as u64;
        let timing_field = |f: &str| {
            let field = field_of(map, "TIMING", f);
            (field.lsb, field.max_value())
        };
        Self {
            id: address("ID"),
            config: address("CONFIG"),
            control: address("CONTROL"),
            update: address("UPDATE"),
            status: address("STATUS"),
            timing: address("TIMING"),
            config_value: register("CONFIG").reset_value() as u64,
            timing_reset: register("TIMING").reset_value() as u64,
            offset_binary: mask("CONTROL", "OFFSET_BINARY"),
            start: mask("UPDATE", "START"),
            busy: mask("STATUS", "BUSY"),
            safe: mask("STATUS", "SAFE"),
            force_safe: mask("STATUS", "FORCE_SAFE"),
            pending: mask("STATUS", "PENDING"),
            deferred: mask("STATUS", "DEFERRED"),
            refused: mask("STATUS", "REFUSED"),
            timing_fields: ["SETUP", "WIDTH", "HOLD", "LDAC_WIDTH"].map(timing_field),
        }
    }
}

/// Cycle-exact model of a `channels`-channel, `width`-bit interface.
#[derive(Clone, Debug)]
pub struct DacModel {
    decode: Decode,
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
        let decode = Decode::new(&map);
        let timing_word = decode.timing_reset;
        let timing = Timing::from_word(timing_word, &decode);
        Self {
            decode,
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
            timing,
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

    /// An interface at power-up, before any reset: every flip-flop 0 (so
    /// `TIMING` reads 0 and no safe update is due: the pins stay idle until
    /// a reset).
    pub fn power_up(channels: usize, width: usize) -> Self {
        let mut m = Self::new(channels, width);
        m.timing_word = 0;
        m.timing = Timing::from_word(0, &m.decode);
        m.pending_safe = false;
        m.safe = false;
        m
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

    fn read(&self, address: u64, force_safe: bool) -> u64 {
        let d = &self.decode;
        let bit = |mask: u64, on: bool| if on { mask } else { 0 };
        let k = self.channels as u64;
        match address {
            a if a == d.id => ID_VALUE as u64,
            a if a == d.config => d.config_value,
            a if a == d.control => bit(d.offset_binary, self.offset_binary),
            a if a == d.status => {
                bit(d.busy, self.busy() || self.ldac)
                    | bit(d.safe, self.safe)
                    | bit(d.force_safe, force_safe)
                    | bit(d.pending, self.pending)
                    | bit(d.deferred, self.deferred)
                    | bit(d.refused, self.refused)
            }
            a if a == d.timing => self.timing_word,
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
        let (cs_n, l1_n, ldac, pin_data) = match self.phase {
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

        // Strobes and flags first. The registers an update takes at its
        // start (codes, format, timing) land after the sequencer: an update
        // starting on this edge takes them as they were before it.
        let d = self.decode;
        let (a, data) = (i.bus_address, i.bus_write_data);
        let code_write =
            i.bus_write && (CODE_BASE as u64..CODE_BASE as u64 + k as u64).contains(&a);
        let mut request = i.update || (i.bus_write && a == d.update && data & d.start != 0);
        if i.bus_write && a == d.status {
            if data & d.deferred != 0 {
                self.deferred = false;
            }
            if data & d.refused != 0 {
                self.refused = false;
            }
        }
        let load = i.load & width_mask(k as u32);
        if i.force_safe && (request || code_write || load != 0) {
            self.refused = true;
            request = false;
        }

        // Sequencer.
        let abort_rise = i.force_safe && !self.abort_prev;
        let cut_now = self.cut || (abort_rise && self.busy() && !self.safe_run);
        let (old_phase, old_left) = (self.phase, self.left);
        let safe_run_before = self.safe_run;
        let start = |m: &mut Self, safe: bool| {
            m.shadow = if safe { vec![0; k] } else { m.staged.clone() };
            m.shadow_offset = m.offset_binary;
            m.timing = Timing::from_word(m.timing_word, &d);
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
        if i.bus_write && a == d.control {
            self.offset_binary = data & d.offset_binary != 0;
        }
        if i.bus_write && a == d.timing {
            self.timing_word = data;
        }
        if code_write && !i.force_safe {
            self.staged[(a - CODE_BASE as u64) as usize] = data & code_mask;
        }
        if !i.force_safe {
            for (c, staged) in self.staged.iter_mut().enumerate() {
                if load >> c & 1 == 1 {
                    *staged = i.load_code & code_mask;
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
        (self.cs_n, self.l1_n, self.ldac, self.data) = (cs_n, l1_n, ldac, pin_data);

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

crate::lockstep_model!(DacModel {
    inputs: DacInputs,
    outputs: DacOutputs,
    step: |model, inputs| model.step(*inputs),
});
