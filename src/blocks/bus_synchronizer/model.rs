//! Reference model of [`super::BusSynchronizer`], cycle-exact.

use crate::blocks::width_mask;

/// Inputs of one clock cycle: the pins and the slave's answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BusPinInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Chip select, active low.
    pub cs_n: bool,
    /// Write strobe, active low.
    pub we_n: bool,
    /// Read strobe, active low.
    pub rd_n: bool,
    /// Word address.
    pub address: u64,
    /// Write data at the pins.
    pub data_in: u64,
    /// The slave's read data.
    pub bus_read_data: u64,
}

impl Default for BusPinInputs {
    /// An idle bus: every strobe high.
    fn default() -> Self {
        Self {
            reset: false,
            cs_n: true,
            we_n: true,
            rd_n: true,
            address: 0,
            data_in: 0,
            bus_read_data: 0,
        }
    }
}

impl BusPinInputs {
    /// The RTL's input vector, in its port order (the same for every
    /// adapter built on the synchronizer).
    pub fn to_vector(&self) -> Vec<u64> {
        vec![
            self.reset as u64,
            self.cs_n as u64,
            self.we_n as u64,
            self.rd_n as u64,
            self.address,
            self.data_in,
            self.bus_read_data,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BusSynchronizerOutputs {
    /// Read data to the pins.
    pub data_out: u64,
    /// Drive the data pins.
    pub data_oe: bool,
    /// The access at the pins may end.
    pub ready: bool,
    /// Address of the bus strobe.
    pub bus_address: u64,
    /// Data of the write strobe.
    pub bus_write_data: u64,
    /// Write strobe.
    pub bus_write: bool,
    /// Read strobe.
    pub bus_read: bool,
}

impl BusSynchronizerOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            data_out: v[0],
            data_oe: v[1] != 0,
            ready: v[2] != 0,
            bus_address: v[3],
            bus_write_data: v[4],
            bus_write: v[5] != 0,
            bus_read: v[6] != 0,
        }
    }
}

/// One sample of the pins as the synchronizer stages hold it.
#[derive(Clone, Copy, Debug, Default)]
struct Sample {
    write: bool,
    read: bool,
    address: u64,
    data: u64,
}

/// Cycle-exact model of the synchronizer.
#[derive(Clone, Debug)]
pub struct BusSynchronizerModel {
    address_bits: u32,
    data_bits: u32,
    /// Pin samples, newest first: [meta, sync, prev, older].
    stages: [Sample; 4],
    read_served: bool,
    read_pending: bool,
    read_answer: bool,
    read_done: bool,
    out: BusSynchronizerOutputs,
}

impl BusSynchronizerModel {
    /// A synchronizer with `address_bits` of address and `data_bits` of
    /// data, in its power-up state.
    pub fn new(address_bits: u32, data_bits: u32) -> Self {
        Self {
            address_bits,
            data_bits,
            stages: Default::default(),
            read_served: false,
            read_pending: false,
            read_answer: false,
            read_done: false,
            out: BusSynchronizerOutputs::default(),
        }
    }

    /// One rising clock edge; returns the outputs after it (`data_oe` and
    /// `ready` with this clock's pins still applied).
    pub fn step(&mut self, i: BusPinInputs) -> BusSynchronizerOutputs {
        let data_mask = width_mask(self.data_bits);
        let [_, sync, prev, older] = self.stages;
        let mut out = self.out;
        out.bus_write = false;
        out.bus_read = false;
        // Two active samples make an access; a write ends on the first
        // inactive one and uses the sample before the last active one.
        let write_ends = older.write && prev.write && !sync.write;
        let read_wanted = (prev.read && sync.read && !self.read_served) || self.read_pending;
        if write_ends {
            out.bus_write = true;
            out.bus_address = older.address;
            out.bus_write_data = older.data;
            if read_wanted {
                self.read_pending = true;
                self.read_served = true;
            }
        } else if read_wanted {
            out.bus_read = true;
            out.bus_address = if self.read_pending {
                prev.address
            } else {
                sync.address
            };
            self.read_served = true;
            self.read_pending = false;
        }
        if !sync.read {
            self.read_served = false;
        }
        if self.read_answer {
            out.data_out = i.bus_read_data & data_mask;
        }
        self.read_done = (self.read_done || self.read_answer) && sync.read;
        self.read_answer = self.out.bus_read;
        self.stages = [
            Sample {
                write: !i.cs_n && !i.we_n,
                read: !i.cs_n && !i.rd_n,
                address: i.address & width_mask(self.address_bits),
                data: i.data_in & data_mask,
            },
            self.stages[0],
            self.stages[1],
            self.stages[2],
        ];
        self.out = out;
        if i.reset {
            *self = Self::new(self.address_bits, self.data_bits);
        }
        let [_, sync, prev, _] = self.stages;
        let write_seen = sync.write && prev.write;
        let write_open = !i.cs_n && !i.we_n && !write_seen;
        let read_open = !i.cs_n && !i.rd_n && !self.read_done;
        self.out.data_oe = !i.cs_n && !i.rd_n && i.we_n;
        self.out.ready = !write_open && !read_open;
        self.out
    }
}
