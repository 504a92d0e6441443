//! Reference model of [`super::ParallelCard`], cycle-exact, composed of
//! the models of its blocks (the bridge's, the decoders', the DACs') and
//! the card's own registers, written from the datasheet. Addresses and
//! fields come from the card's register maps, by name. It owns the
//! packing of the card's port vectors.

use super::registers::{
    fields, master_map, slave_map, DAC_BITS, ID_VALUE, JOINTS_PER_SLAVE, RESET_ENC_FILTER, SLAVES,
};
use crate::blocks::dac_interface::model::{DacInputs, DacModel, DacOutputs};
use crate::blocks::quadrature_decoder::model::{
    QuadratureDecoderInputs, QuadratureDecoderModel, QuadratureDecoderOutputs,
};
use crate::blocks::sync_fifo_bridge::model::{BridgeInputs, BridgeModel, BridgeOutputs, SlaveBus};
use crate::blocks::width_mask;

/// Inputs of one clock.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CardInputs {
    /// Synchronous reset.
    pub reset: bool,
    /// Master word address (9 bits).
    pub m_address: u64,
    /// Master write data.
    pub m_write_data: u64,
    /// Master write strobe.
    pub m_write: bool,
    /// Master read strobe.
    pub m_read: bool,
    /// The period's edge.
    pub period_tick: bool,
    /// Slave k's bus (6-bit addresses).
    pub slaves: [SlaveBus; SLAVES],
    /// Bit j: joint j's channel A.
    pub enc_a: u64,
    /// Bit j: joint j's channel B.
    pub enc_b: u64,
    /// Emergency stop.
    pub estop: bool,
}

impl Default for CardInputs {
    fn default() -> Self {
        Self {
            reset: false,
            m_address: 0,
            m_write_data: 0,
            m_write: false,
            m_read: false,
            period_tick: false,
            slaves: [SlaveBus::default(); SLAVES],
            enc_a: 0,
            enc_b: 0,
            estop: false,
        }
    }
}

impl CardInputs {
    /// The RTL's input vector, in its port order (`s_write_data` takes two
    /// columns).
    pub fn to_vector(&self) -> Vec<u64> {
        let bits = |f: fn(&SlaveBus) -> bool| {
            self.slaves
                .iter()
                .enumerate()
                .fold(0, |v, (k, s)| v | (f(s) as u64) << k)
        };
        let address = self
            .slaves
            .iter()
            .enumerate()
            .fold(0, |v, (k, s)| v | (s.address & width_mask(6)) << (6 * k));
        let data: Vec<u64> = self
            .slaves
            .iter()
            .map(|s| s.write_data & width_mask(32))
            .collect();
        vec![
            self.reset as u64,
            self.m_address & width_mask(9),
            self.m_write_data & width_mask(32),
            self.m_write as u64,
            self.m_read as u64,
            self.period_tick as u64,
            address,
            data[0] | data[1] << 32,
            data[2],
            bits(|s| s.write),
            bits(|s| s.read),
            self.enc_a & width_mask(6),
            self.enc_b & width_mask(6),
            self.estop as u64,
        ]
    }
}

/// Outputs after one clock edge.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CardOutputs {
    /// Master read data.
    pub m_read_data: u64,
    /// Some status FIFO holds words.
    pub m_irq: bool,
    /// Slave k's read data.
    pub s_read_data: [u64; SLAVES],
    /// Bit k: slave k's data_ready.
    pub s_data_ready: u64,
    /// Slave k's DAC data in bits [16k, 16k+16).
    pub dac_data: u64,
    /// Bit j: joint j's DAC chip select, active low.
    pub dac_cs_n: u64,
    /// Bit k: slave k's first-rank load, active low.
    pub dac_l1_n: u64,
    /// Bit k: slave k's LDAC.
    pub dac_ldac: u64,
    /// Every DAC held at 0 V.
    pub stopped: bool,
}

impl CardOutputs {
    /// Reads the RTL's output vector, in its port order.
    pub fn from_vector(v: &[u64]) -> Self {
        Self {
            m_read_data: v[0],
            m_irq: v[1] != 0,
            s_read_data: [v[2] & width_mask(32), v[2] >> 32, v[3] & width_mask(32)],
            s_data_ready: v[4],
            dac_data: v[5],
            dac_cs_n: v[6],
            dac_l1_n: v[7],
            dac_ldac: v[8],
            stopped: v[9] != 0,
        }
    }
}

/// Addresses of a slave port's joint registers.
#[derive(Clone, Copy, Debug)]
struct SlaveAddresses {
    count: [u64; JOINTS_PER_SLAVE],
    live: [u64; JOINTS_PER_SLAVE],
    encoder: u64,
    state: u64,
}

/// One slave's joints: two decoders, the DAC pair and the joints' registers.
#[derive(Clone, Debug)]
struct JointPairModel {
    encoders: [QuadratureDecoderModel; JOINTS_PER_SLAVE],
    encoder_out: [QuadratureDecoderOutputs; JOINTS_PER_SLAVE],
    dac: DacModel,
    dac_out: DacOutputs,
    latched: [u64; JOINTS_PER_SLAVE],
    read_reg: u64,
    joint_sel: bool,
    dac_sel: bool,
}

/// What a joint pair takes from the card in one clock.
struct PairInputs<'a> {
    reset: bool,
    bus: &'a SlaveBus,
    period_tick: bool,
    /// Bits 0 and 1: the pair's channel A and B pins.
    a: u64,
    b: u64,
    filter: u8,
    underrun: bool,
    estop: bool,
    stop: bool,
}

impl JointPairModel {
    fn power_up() -> Self {
        Self {
            encoders: std::array::from_fn(|_| QuadratureDecoderModel::new(32, 8, 16)),
            encoder_out: Default::default(),
            dac: DacModel::power_up(JOINTS_PER_SLAVE, DAC_BITS),
            dac_out: DacModel::power_up(JOINTS_PER_SLAVE, DAC_BITS).outputs(),
            latched: [0; JOINTS_PER_SLAVE],
            read_reg: 0,
            joint_sel: false,
            dac_sel: false,
        }
    }

    /// One edge; returns the bridge's (write, read) strobes of this clock.
    fn step(&mut self, i: &PairInputs, at: &SlaveAddresses) -> (bool, bool) {
        let address = i.bus.address & width_mask(6);
        let window = address >> 4;
        let in_joints = window == 1;
        let in_dac = window >= 2;
        let encoder_write = i.bus.write && address == at.encoder;
        let data = i.bus.write_data & width_mask(32);

        let mut word = 0;
        for j in 0..JOINTS_PER_SLAVE {
            if address == at.count[j] {
                word = self.latched[j];
            }
            if address == at.live[j] {
                word = self.encoder_out[j].count;
            }
            if address == at.encoder && self.encoder_out[j].error {
                word |= 1 << (fields::ENC_ERROR + j as u32);
            }
        }
        if address == at.state {
            word |= (i.underrun as u64) << fields::UNDERRUN
                | (i.estop as u64) << fields::ESTOP
                | (i.stop as u64) << fields::STOPPED;
        }
        if i.period_tick {
            for j in 0..JOINTS_PER_SLAVE {
                self.latched[j] = self.encoder_out[j].count;
            }
        }
        if i.bus.read {
            self.joint_sel = in_joints;
            self.dac_sel = in_dac;
            if in_joints {
                self.read_reg = word;
            }
        }
        if i.reset {
            self.latched = [0; JOINTS_PER_SLAVE];
            self.read_reg = 0;
            self.joint_sel = false;
            self.dac_sel = false;
        }
        for j in 0..JOINTS_PER_SLAVE {
            let bit = |lsb: u32| data >> (lsb + j as u32) & 1 != 0;
            self.encoder_out[j] = self.encoders[j].step(QuadratureDecoderInputs {
                reset: i.reset,
                a: i.a >> j & 1 != 0,
                b: i.b >> j & 1 != 0,
                filter: i.filter,
                clear: encoder_write && bit(fields::ENC_CLEAR),
                clear_error: encoder_write && bit(fields::ENC_ERROR),
                ..Default::default()
            });
        }
        self.dac_out = self.dac.step(DacInputs {
            reset: i.reset,
            bus_address: address & width_mask(5),
            bus_write_data: data,
            bus_write: i.bus.write && in_dac,
            bus_read: i.bus.read && in_dac,
            update: i.period_tick,
            force_safe: i.stop,
            load: 0,
            load_code: 0,
        });
        (i.bus.write && window == 0, i.bus.read && window == 0)
    }

    /// The slave's read data after the edge, given the bridge's.
    fn read_data(&self, bridge: u64) -> u64 {
        if self.dac_sel {
            self.dac_out.bus_read_data
        } else if self.joint_sel {
            self.read_reg
        } else {
            bridge
        }
    }
}

/// Cycle-exact model of the card.
#[derive(Clone, Debug)]
pub struct ParallelCardModel {
    bridge: BridgeModel,
    bridge_out: BridgeOutputs,
    pairs: [JointPairModel; SLAVES],
    slave_at: SlaveAddresses,
    a_id: u64,
    a_control: u64,
    a_fault: u64,
    a_count: Vec<u64>,
    estop_meta: bool,
    estop_sync: bool,
    filter: u8,
    underrun: u64,
    tick_d: bool,
    card_read: u64,
    card_sel: bool,
}

impl Default for ParallelCardModel {
    fn default() -> Self {
        Self::power_up()
    }
}

impl ParallelCardModel {
    /// The card at power-up, before any reset (every flip-flop 0; the DACs
    /// idle until a reset starts their safe update).
    pub fn power_up() -> Self {
        let master = master_map().expect("the card's master map");
        let slave = slave_map().expect("the card's slave map");
        let m = |name: &str, index: u32| {
            master.address_of(name, index).expect("a card register") as u64
        };
        let s = |name: &str, index: u32| {
            slave.address_of(name, index).expect("a slave register") as u64
        };
        let bridge = BridgeModel::new(SLAVES, super::registers::FIFO_LOG2);
        Self {
            bridge_out: bridge.outputs(),
            bridge,
            pairs: std::array::from_fn(|_| JointPairModel::power_up()),
            slave_at: SlaveAddresses {
                count: [s("COUNT", 0), s("COUNT", 1)],
                live: [s("LIVE", 0), s("LIVE", 1)],
                encoder: s("ENCODER", 0),
                state: s("CARD_STATE", 0),
            },
            a_id: m("CARD_ID", 0),
            a_control: m("CARD_CONTROL", 0),
            a_fault: m("CARD_FAULT", 0),
            a_count: (0..super::registers::JOINTS as u32)
                .map(|j| m("COUNT", j))
                .collect(),
            estop_meta: false,
            estop_sync: false,
            filter: 0,
            underrun: 0,
            tick_d: false,
            card_read: 0,
            card_sel: false,
        }
    }

    /// Every DAC is held at 0 V (the `stopped` pin).
    fn stop(&self) -> bool {
        self.underrun != 0 || self.estop_sync
    }

    /// Joint j's count now.
    pub fn count(&self, joint: usize) -> u64 {
        self.pairs[joint / JOINTS_PER_SLAVE].encoder_out[joint % JOINTS_PER_SLAVE].count
    }

    /// One rising clock edge; returns the outputs after it.
    pub fn step(&mut self, i: &CardInputs) -> CardOutputs {
        let stop = self.stop();
        let address = i.m_address & width_mask(9);
        let in_card = address >> 8 & 1 != 0;
        let data = i.m_write_data & width_mask(32);

        // The card's registers read before the edge.
        let mut word = 0;
        if address == self.a_id {
            word = ID_VALUE as u64;
        }
        if address == self.a_control {
            word = self.filter as u64;
        }
        if address == self.a_fault {
            word = self.underrun << fields::UNDERRUN
                | (self.estop_sync as u64) << fields::ESTOP
                | (stop as u64) << fields::STOPPED;
        }
        for (j, &a) in self.a_count.iter().enumerate() {
            if address == a {
                word = self.count(j);
            }
        }

        // The joint pairs, then the bridge with their strobes.
        let mut slaves = [SlaveBus::default(); SLAVES];
        for k in 0..SLAVES {
            let pair = PairInputs {
                reset: i.reset,
                bus: &i.slaves[k],
                period_tick: i.period_tick,
                a: i.enc_a >> (2 * k) & 3,
                b: i.enc_b >> (2 * k) & 3,
                filter: self.filter,
                underrun: self.underrun >> k & 1 != 0,
                estop: self.estop_sync,
                stop,
            };
            let (write, read) = self.pairs[k].step(&pair, &self.slave_at);
            slaves[k] = SlaveBus {
                address: i.slaves[k].address & 0xf,
                write_data: i.slaves[k].write_data & width_mask(32),
                write,
                read,
            };
        }
        let ready_before = self
            .bridge_out
            .s_data_ready
            .iter()
            .enumerate()
            .fold(0, |v, (k, &r)| v | (r as u64) << k);
        self.bridge_out = self.bridge.step(&BridgeInputs {
            reset: i.reset,
            m_address: address & 0xff,
            m_write_data: data,
            m_write: i.m_write && !in_card,
            m_read: i.m_read && !in_card,
            period_tick: i.period_tick,
            slaves: slaves.to_vec(),
        });

        // The card's flip-flops.
        let mut underrun = self.underrun;
        if i.m_write && address == self.a_fault {
            underrun &= !(data >> fields::UNDERRUN);
        }
        if self.tick_d {
            underrun |= !ready_before;
        }
        self.underrun = underrun & width_mask(SLAVES as u32);
        if i.m_write && address == self.a_control {
            self.filter = (data >> fields::ENC_FILTER & width_mask(fields::ENC_FILTER_BITS)) as u8;
        }
        if i.m_read {
            self.card_sel = in_card;
            if in_card {
                self.card_read = word;
            }
        }
        self.tick_d = i.period_tick;
        self.estop_sync = self.estop_meta;
        self.estop_meta = i.estop;
        if i.reset {
            self.filter = RESET_ENC_FILTER as u8;
            self.underrun = 0;
            self.tick_d = false;
            self.card_read = 0;
            self.card_sel = false;
        }
        self.outputs()
    }

    /// The outputs as they are now.
    pub fn outputs(&self) -> CardOutputs {
        let mut o = CardOutputs {
            m_read_data: if self.card_sel {
                self.card_read
            } else {
                self.bridge_out.m_read_data
            },
            m_irq: self.bridge_out.m_irq,
            stopped: self.stop(),
            ..Default::default()
        };
        for (k, pair) in self.pairs.iter().enumerate() {
            o.s_read_data[k] = pair.read_data(self.bridge_out.s_read_data[k]);
            o.s_data_ready |= (self.bridge_out.s_data_ready[k] as u64) << k;
            o.dac_data |= pair.dac_out.dac_data << (16 * k);
            o.dac_cs_n |= pair.dac_out.dac_cs_n << (2 * k);
            o.dac_l1_n |= (pair.dac_out.dac_l1_n as u64) << k;
            o.dac_ldac |= (pair.dac_out.dac_ldac as u64) << k;
        }
        o
    }
}

crate::lockstep_model!(ParallelCardModel {
    inputs: CardInputs,
    outputs: CardOutputs,
    step: |model, inputs| model.step(inputs),
});
