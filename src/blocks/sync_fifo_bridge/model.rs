//! Reference model of [`super::SyncFifoBridge`], cycle-exact. Each FIFO is
//! a [`CommandFifoModel`]; addresses and the packing of every register word
//! come from the register maps, by name.

use super::registers::{master_map, slave_map, SLAVE_ADDRESS_BITS};
use crate::blocks::command_fifo::model::{CommandFifoModel, CommandFifoOutputs};
use crate::blocks::width_mask;
use crate::regmap::RegisterMap;

/// One slave port's bus inputs in one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlaveBus {
    /// Word address (4 bits).
    pub address: u64,
    /// Write data.
    pub write_data: u64,
    /// Write strobe.
    pub write: bool,
    /// Read strobe.
    pub read: bool,
}

/// Inputs of one clock cycle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BridgeInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Master word address.
    pub m_address: u64,
    /// Master write data.
    pub m_write_data: u64,
    /// Master write strobe.
    pub m_write: bool,
    /// Master read strobe.
    pub m_read: bool,
    /// Tick-mode release pulse.
    pub period_tick: bool,
    /// Slave k's bus.
    pub slaves: Vec<SlaveBus>,
}

/// Packs 32-bit per-slave words into the vector columns of a 32 K-bit port.
fn pack_words(words: impl Iterator<Item = u64>, slaves: usize) -> Vec<u64> {
    let mut columns = vec![0u64; (slaves * 32).div_ceil(64)];
    for (k, w) in words.enumerate() {
        columns[k / 2] |= (w & width_mask(32)) << (32 * (k % 2));
    }
    columns
}

impl BridgeInputs {
    /// Idle inputs for `slaves` slaves.
    pub fn idle(slaves: usize) -> Self {
        Self {
            slaves: vec![SlaveBus::default(); slaves],
            ..Self::default()
        }
    }

    /// The RTL's input vector, in its port order (`s_write_data` takes
    /// `ceil(32 K / 64)` columns).
    pub fn to_vector(&self) -> Vec<u64> {
        let k = self.slaves.len();
        let bits = |f: fn(&SlaveBus) -> bool| {
            self.slaves
                .iter()
                .enumerate()
                .fold(0, |v, (i, s)| v | (f(s) as u64) << i)
        };
        let mut v = vec![
            self.reset as u64,
            self.m_address,
            self.m_write_data,
            self.m_write as u64,
            self.m_read as u64,
            self.period_tick as u64,
            self.slaves.iter().enumerate().fold(0, |v, (i, s)| {
                v | (s.address & width_mask(SLAVE_ADDRESS_BITS))
                    << (SLAVE_ADDRESS_BITS as usize * i)
            }),
        ];
        v.extend(pack_words(self.slaves.iter().map(|s| s.write_data), k));
        v.push(bits(|s| s.write));
        v.push(bits(|s| s.read));
        v
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BridgeOutputs {
    /// Master read data.
    pub m_read_data: u64,
    /// Some status FIFO holds words.
    pub m_irq: bool,
    /// Slave k's read data.
    pub s_read_data: Vec<u64>,
    /// Slave k's data_ready.
    pub s_data_ready: Vec<bool>,
}

impl BridgeOutputs {
    /// Reads the RTL's output vector of a bridge with `slaves` slaves.
    pub fn from_vector(v: &[u64], slaves: usize) -> Self {
        let words = (slaves * 32).div_ceil(64);
        let wide = &v[2..2 + words];
        let ready = v[2 + words];
        Self {
            m_read_data: v[0],
            m_irq: v[1] != 0,
            s_read_data: (0..slaves)
                .map(|k| wide[k / 2] >> (32 * (k % 2)) & width_mask(32))
                .collect(),
            s_data_ready: (0..slaves).map(|k| ready >> k & 1 != 0).collect(),
        }
    }
}

/// Addresses of one slave's window on the master port.
#[derive(Clone, Copy, Debug)]
struct Window {
    cmd: u64,
    status: u64,
    levels: u64,
    flags: u64,
}

/// One slave's channel.
#[derive(Clone, Debug)]
struct Channel {
    cmd: CommandFifoModel,
    cmd_out: CommandFifoOutputs,
    status: CommandFifoModel,
    status_out: CommandFifoOutputs,
    released: u64,
    synced: u64,
    cmd_underflow: bool,
    status_underflow: bool,
    s_read_data: u64,
}

impl Channel {
    fn new(depth: usize) -> Self {
        let empty = CommandFifoOutputs {
            empty: true,
            low: true,
            ..Default::default()
        };
        Self {
            cmd: CommandFifoModel::new(depth),
            cmd_out: empty,
            status: CommandFifoModel::new(depth),
            status_out: empty,
            released: 0,
            synced: 0,
            cmd_underflow: false,
            status_underflow: false,
            s_read_data: 0,
        }
    }
}

/// What happened in the last clock, for tests' activity counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BridgeEvents {
    /// A release (immediate SYNC or armed tick) took effect.
    pub release: bool,
    /// Slave commands popped.
    pub pops: u32,
    /// Master status words popped.
    pub status_pops: u32,
    /// Writes refused (either FIFO direction).
    pub overflows: u32,
    /// Reads refused (either direction).
    pub underflows: u32,
}

/// Cycle-exact model of a bridge with `slaves` slaves and 2^`fifo_log2`-word FIFOs.
#[derive(Clone, Debug)]
pub struct BridgeModel {
    depth: usize,
    master: RegisterMap,
    slave: RegisterMap,
    a_id: u64,
    a_config: u64,
    a_control: u64,
    a_sync: u64,
    a_state: u64,
    windows: Vec<Window>,
    s_cmd: u64,
    s_status: u64,
    s_levels: u64,
    s_flags: u64,
    channels: Vec<Channel>,
    tick_mode: bool,
    armed: bool,
    m_read_data: u64,
    irq: bool,
    /// What the last clock did.
    pub events: BridgeEvents,
}

fn flag(map: &RegisterMap, register: &str, field: &str) -> u64 {
    map.register(register)
        .and_then(|r| r.field(field))
        .expect("a field of the bridge's map")
        .mask() as u64
}

fn pack(map: &RegisterMap, register: &str, fields: &[(&str, u64)]) -> u64 {
    map.register(register)
        .and_then(|r| r.pack(fields))
        .expect("a field of the bridge's map") as u64
}

impl BridgeModel {
    /// A bridge in its reset state.
    pub fn new(slaves: usize, fifo_log2: u32) -> Self {
        let master = master_map(slaves, fifo_log2).expect("valid bridge configuration");
        let slave = slave_map(fifo_log2).expect("valid bridge configuration");
        let global = |name: &str| master.register(name).expect("a global register").address as u64;
        let at = |name: &str, k: usize| {
            master
                .register(name)
                .and_then(|r| r.address_of(k as u32))
                .expect("a slave window") as u64
        };
        let local = |name: &str| slave.register(name).expect("a slave register").address as u64;
        let windows = (0..slaves)
            .map(|k| Window {
                cmd: at("CMD", k),
                status: at("STATUS", k),
                levels: at("LEVELS", k),
                flags: at("FLAGS", k),
            })
            .collect();
        Self {
            depth: 1 << fifo_log2,
            a_id: global("ID"),
            a_config: global("CONFIG"),
            a_control: global("CONTROL"),
            a_sync: global("SYNC"),
            a_state: global("STATE"),
            windows,
            s_cmd: local("CMD"),
            s_status: local("STATUS"),
            s_levels: local("LEVELS"),
            s_flags: local("FLAGS"),
            channels: vec![Channel::new(1 << fifo_log2); slaves],
            tick_mode: false,
            armed: false,
            m_read_data: 0,
            irq: false,
            events: BridgeEvents::default(),
            master,
            slave,
        }
    }

    /// Slaves.
    pub fn slaves(&self) -> usize {
        self.channels.len()
    }

    /// The master's map.
    pub fn master_map(&self) -> &RegisterMap {
        &self.master
    }

    /// The slave ports' map.
    pub fn slave_map(&self) -> &RegisterMap {
        &self.slave
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: &BridgeInputs) -> BridgeOutputs {
        assert_eq!(
            i.slaves.len(),
            self.channels.len(),
            "one SlaveBus per slave"
        );
        let mut events = BridgeEvents::default();
        let m_data = i.m_write_data & width_mask(32);
        let sync_write = i.m_write && i.m_address == self.a_sync;
        let release = i.period_tick && self.armed;
        let sync_now = sync_write && !self.tick_mode;
        let arm = sync_write && self.tick_mode;
        events.release = release || sync_now;

        // Reads of this clock see the state before the edge.
        let mut m_word = 0;
        if i.m_read {
            let a = i.m_address;
            if a == self.a_id {
                m_word = pack(
                    &self.master,
                    "ID",
                    &[("VALUE", super::registers::ID_VALUE as u64)],
                );
            }
            if a == self.a_config {
                m_word = self
                    .master
                    .register("CONFIG")
                    .expect("CONFIG")
                    .reset_value() as u64;
            }
            if a == self.a_control {
                m_word = pack(
                    &self.master,
                    "CONTROL",
                    &[("TICK_MODE", self.tick_mode as u64)],
                );
            }
            if a == self.a_state {
                let bits = |f: fn(&Channel) -> bool| {
                    self.channels
                        .iter()
                        .enumerate()
                        .fold(0, |v, (k, c)| v | (f(c) as u64) << k)
                };
                m_word = pack(
                    &self.master,
                    "STATE",
                    &[
                        ("ARMED", self.armed as u64),
                        ("DATA_READY", bits(|c| c.released != 0)),
                        ("STATUS_PENDING", bits(|c| !c.status_out.empty)),
                    ],
                );
            }
            for (c, w) in self.channels.iter().zip(&self.windows) {
                if a == w.status && !c.status_out.empty {
                    m_word = c.status_out.head;
                }
                if a == w.levels {
                    m_word = pack(
                        &self.master,
                        "LEVELS",
                        &[
                            ("CMD_LEVEL", c.cmd_out.level),
                            ("CMD_RELEASED", c.released),
                            ("STATUS_LEVEL", c.status_out.level),
                        ],
                    );
                }
                if a == w.flags {
                    m_word = pack(
                        &self.master,
                        "FLAGS",
                        &[
                            ("CMD_OVERFLOW", c.cmd_out.overflow as u64),
                            ("STATUS_UNDERFLOW", c.status_underflow as u64),
                            ("SLAVE_CMD_UNDERFLOW", c.cmd_underflow as u64),
                            ("SLAVE_STATUS_OVERFLOW", c.status_out.overflow as u64),
                        ],
                    );
                }
            }
        }
        let any_pending = self.channels.iter().any(|c| !c.status_out.empty);

        let m_cmd_overflow = flag(&self.master, "FLAGS", "CMD_OVERFLOW");
        let m_status_underflow = flag(&self.master, "FLAGS", "STATUS_UNDERFLOW");
        let s_cmd_underflow = flag(&self.slave, "FLAGS", "CMD_UNDERFLOW");
        let s_status_overflow = flag(&self.slave, "FLAGS", "STATUS_OVERFLOW");
        for (k, (c, s)) in self.channels.iter_mut().zip(&i.slaves).enumerate() {
            let w = self.windows[k];
            let m_at = |a: u64| i.m_address == a;
            let s_at = |a: u64| s.address & width_mask(SLAVE_ADDRESS_BITS) == a;
            let s_data = s.write_data & width_mask(32);
            let any_released = c.released != 0;
            let pop = s.read && s_at(self.s_cmd) && any_released;
            let cmd_write = i.m_write && m_at(w.cmd);
            let cmd_clear = i.m_write && m_at(w.flags) && m_data & m_cmd_overflow != 0;
            let status_write = s.write && s_at(self.s_status);
            let status_pop = i.m_read && m_at(w.status);
            let status_clear = s.write && s_at(self.s_flags) && s_data & s_status_overflow != 0;

            if s.read {
                c.s_read_data = 0;
                if s_at(self.s_cmd) && any_released {
                    c.s_read_data = c.cmd_out.head;
                }
                if s_at(self.s_levels) {
                    c.s_read_data = pack(
                        &self.slave,
                        "LEVELS",
                        &[
                            ("CMD_READY", c.released),
                            ("STATUS_LEVEL", c.status_out.level),
                        ],
                    );
                }
                if s_at(self.s_flags) {
                    c.s_read_data = pack(
                        &self.slave,
                        "FLAGS",
                        &[
                            ("CMD_UNDERFLOW", c.cmd_underflow as u64),
                            ("STATUS_OVERFLOW", c.status_out.overflow as u64),
                        ],
                    );
                }
            }
            if i.m_write && m_at(w.flags) && m_data & m_status_underflow != 0 {
                c.status_underflow = false;
            }
            if status_pop && c.status_out.empty {
                c.status_underflow = true;
                events.underflows += 1;
            }
            if s.write && s_at(self.s_flags) && s_data & s_cmd_underflow != 0 {
                c.cmd_underflow = false;
            }
            if s.read && s_at(self.s_cmd) && !any_released {
                c.cmd_underflow = true;
                events.underflows += 1;
            }

            let mut released = c.released;
            if release {
                released = c.synced;
            }
            if sync_now {
                released = c.cmd_out.level;
            }
            let mut synced = c.synced;
            if sync_now || arm {
                synced = c.cmd_out.level;
            }
            c.released = released - pop as u64;
            c.synced = synced - pop as u64;
            events.pops += pop as u32;
            let status_popped = status_pop && !c.status_out.empty;
            events.status_pops += status_popped as u32;
            events.overflows += (cmd_write && c.cmd_out.full && !pop) as u32;
            events.overflows += (status_write && c.status_out.full && !status_popped) as u32;

            c.cmd_out = c.cmd.step(i.reset, cmd_write, m_data, pop, 0, cmd_clear);
            c.status_out =
                c.status
                    .step(i.reset, status_write, s_data, status_pop, 0, status_clear);
        }

        if i.m_write && i.m_address == self.a_control {
            self.tick_mode = m_data & flag(&self.master, "CONTROL", "TICK_MODE") != 0;
        }
        if release {
            self.armed = false;
        }
        if sync_write {
            self.armed = self.tick_mode;
        }
        if i.m_read {
            self.m_read_data = m_word;
        }
        self.irq = any_pending;
        if i.reset {
            let events = events;
            *self = Self::new(self.channels.len(), self.depth.trailing_zeros());
            self.events = events;
        } else {
            self.events = events;
        }
        self.outputs()
    }

    /// The outputs as they are now.
    pub fn outputs(&self) -> BridgeOutputs {
        BridgeOutputs {
            m_read_data: self.m_read_data,
            m_irq: self.irq,
            s_read_data: self.channels.iter().map(|c| c.s_read_data).collect(),
            s_data_ready: self.channels.iter().map(|c| c.released != 0).collect(),
        }
    }
}

impl crate::sim::LockstepModel for BridgeModel {
    type Inputs = BridgeInputs;
    type Outputs = BridgeOutputs;
    fn input_vector(inputs: &BridgeInputs, vector: &mut Vec<u64>) {
        *vector = inputs.to_vector();
    }
    fn read_outputs(&self, vector: &[u64]) -> BridgeOutputs {
        BridgeOutputs::from_vector(vector, self.channels.len())
    }
    fn expected(&mut self, inputs: &BridgeInputs) -> BridgeOutputs {
        self.step(inputs)
    }
}
