//! One motor-control DSP's side of the card: its two joints' quadrature
//! decoders and their DAC pair, and the decode of its slave port into the
//! bridge's window (0x00), the joints' registers (0x10) and the DACs'
//! window (0x20).
//!
//! Internal to [`super::ParallelCard`]; its behavior is the card's (see the
//! card's datasheet), modelled by [`super::model`].
//!
//! ## Contract (as the card uses it)
//! * A read or write with `address[5:4]` = 00 goes to the bridge
//!   (`bridge_read`, `bridge_write`, with the low 4 address bits); 01 to
//!   the joints' registers; `address[5]` = 1 to the DAC pair's register bus
//!   with the low 5 bits.
//! * `read_data` is the data of the last read, whichever window it
//!   addressed: the bridge's (`bridge_read_data`), the DAC's or the joints'
//!   read register, each valid the clock after the read and held.
//! * `period_tick` latches both joints' counts (`COUNT`) and requests the
//!   DAC pair's update; `stop` holds the DACs at the safe code.

use rust_hdl::prelude::*;

use super::registers::{fields, slave_map, JOINTS_PER_SLAVE, SLAVE_DAC_BASE, SLAVE_JOINT_BASE};
use crate::blocks::dac_interface::DacInterface;
use crate::blocks::quadrature_decoder::QuadratureDecoder;
use crate::blocks::sync_fifo_bridge::registers::field_of;

// The RTL selects the windows by `address[5:4]`: the map must keep them there.
const _: () = assert!(SLAVE_JOINT_BASE == 0b01_0000 && SLAVE_DAC_BASE == 0b10_0000);
const _: () = assert!(JOINTS_PER_SLAVE == 2);

/// A slave's two joints. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct JointPair {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// The slave's word address.
    pub address: Signal<In, Bits<6>>,
    /// The slave's write data.
    pub write_data: Signal<In, Bits<32>>,
    /// The slave's write strobe.
    pub write: Signal<In, Bit>,
    /// The slave's read strobe.
    pub read: Signal<In, Bit>,
    /// Latch the counts and update the DACs.
    pub period_tick: Signal<In, Bit>,
    /// Encoder channel A of joints 0 and 1.
    pub enc_a: Signal<In, Bits<2>>,
    /// Encoder channel B of joints 0 and 1.
    pub enc_b: Signal<In, Bits<2>>,
    /// The decoders' filter length.
    pub filter: Signal<In, Bits<4>>,
    /// This slave's sticky underrun flag.
    pub underrun: Signal<In, Bit>,
    /// The synchronized estop.
    pub estop: Signal<In, Bit>,
    /// Every DAC held at the safe code.
    pub stop: Signal<In, Bit>,
    /// The bridge's read data for this slave.
    pub bridge_read_data: Signal<In, Bits<32>>,
    /// The bridge's write strobe for this slave.
    pub bridge_write: Signal<Out, Bit>,
    /// The bridge's read strobe for this slave.
    pub bridge_read: Signal<Out, Bit>,
    /// The slave's read data.
    pub read_data: Signal<Out, Bits<32>>,
    /// Joint 0's live count.
    pub live0: Signal<Out, Bits<32>>,
    /// Joint 1's live count.
    pub live1: Signal<Out, Bits<32>>,
    /// The DAC pair's data bus.
    pub dac_data: Signal<Out, Bits<16>>,
    /// The DAC pair's chip selects.
    pub dac_cs_n: Signal<Out, Bits<2>>,
    /// The DAC pair's first-rank load.
    pub dac_l1_n: Signal<Out, Bit>,
    /// The DAC pair's second-rank load.
    pub dac_ldac: Signal<Out, Bit>,

    encoder0: QuadratureDecoder<32, 8, 16>,
    encoder1: QuadratureDecoder<32, 8, 16>,
    dac: DacInterface<2, 16>,
    /// The counts as they stood in the clock of the last period_tick.
    latched0: DFF<Bits<32>>,
    latched1: DFF<Bits<32>>,
    /// The joints' registers' read data.
    read_reg: DFF<Bits<32>>,
    /// The last read addressed the joints' registers / the DAC's.
    joint_sel: DFF<Bit>,
    dac_sel: DFF<Bit>,
    window: Signal<Local, Bits<2>>,
    in_joints: Signal<Local, Bit>,
    in_dac: Signal<Local, Bit>,
    encoder_write: Signal<Local, Bit>,
    joint_word: Signal<Local, Bits<32>>,
    w_bridge: Constant<Bits<2>>,
    w_joints: Constant<Bits<2>>,
    a_count: [Constant<Bits<6>>; 2],
    a_live: [Constant<Bits<6>>; 2],
    a_encoder: Constant<Bits<6>>,
    a_state: Constant<Bits<6>>,
    f_error: [Constant<Bits<32>>; 2],
    f_clear: [Constant<Bits<32>>; 2],
    f_underrun: Constant<Bits<32>>,
    f_estop: Constant<Bits<32>>,
    f_stopped: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    zero8: Constant<Bits<8>>,
    zero16: Constant<Bits<16>>,
    zero2: Constant<Bits<2>>,
}

impl Default for JointPair {
    fn default() -> Self {
        let map = slave_map().expect("the card's slave map validates");
        let a6 = |name: &str, index: u32| {
            Constant::new((map.address_of(name, index).expect("a joint register") as u64).into())
        };
        let mask = |r: &str, f: &str| Constant::new((field_of(&map, r, f).1.mask() as u64).into());
        let bit = |lsb: u32| Constant::new((1u64 << lsb).into());
        let (_, error) = field_of(&map, "ENCODER", "ERROR");
        let (_, clear) = field_of(&map, "ENCODER", "CLEAR");
        assert_eq!(
            (error.lsb, clear.lsb),
            (fields::ENC_ERROR, fields::ENC_CLEAR)
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            address: Default::default(),
            write_data: Default::default(),
            write: Default::default(),
            read: Default::default(),
            period_tick: Default::default(),
            enc_a: Default::default(),
            enc_b: Default::default(),
            filter: Default::default(),
            underrun: Default::default(),
            estop: Default::default(),
            stop: Default::default(),
            bridge_read_data: Default::default(),
            bridge_write: Default::default(),
            bridge_read: Default::default(),
            read_data: Default::default(),
            live0: Default::default(),
            live1: Default::default(),
            dac_data: Default::default(),
            dac_cs_n: Default::default(),
            dac_l1_n: Default::default(),
            dac_ldac: Default::default(),
            encoder0: Default::default(),
            encoder1: Default::default(),
            dac: Default::default(),
            latched0: Default::default(),
            latched1: Default::default(),
            read_reg: Default::default(),
            joint_sel: Default::default(),
            dac_sel: Default::default(),
            window: Default::default(),
            in_joints: Default::default(),
            in_dac: Default::default(),
            encoder_write: Default::default(),
            joint_word: Default::default(),
            w_bridge: Constant::new(0u64.into()),
            w_joints: Constant::new(((SLAVE_JOINT_BASE >> 4) as u64).into()),
            a_count: array_init::array_init(|j| a6("COUNT", j as u32)),
            a_live: array_init::array_init(|j| a6("LIVE", j as u32)),
            a_encoder: a6("ENCODER", 0),
            a_state: a6("CARD_STATE", 0),
            f_error: array_init::array_init(|j| bit(error.lsb + j as u32)),
            f_clear: array_init::array_init(|j| bit(clear.lsb + j as u32)),
            f_underrun: mask("CARD_STATE", "UNDERRUN"),
            f_estop: mask("CARD_STATE", "ESTOP"),
            f_stopped: mask("CARD_STATE", "STOPPED"),
            zero32: Constant::new(0u64.into()),
            zero8: Constant::new(0u64.into()),
            zero16: Constant::new(0u64.into()),
            zero2: Constant::new(0u64.into()),
        }
    }
}

impl Logic for JointPair {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, latched0, latched1, read_reg, joint_sel, dac_sel);

        // Windows: address[5:4].
        self.window.next = self.address.val().get_bits::<2>(4);
        self.bridge_write.next = self.write.val() & (self.window.val() == self.w_bridge.val());
        self.bridge_read.next = self.read.val() & (self.window.val() == self.w_bridge.val());
        self.in_joints.next = self.window.val() == self.w_joints.val();
        self.in_dac.next = self.address.val().get_bit(5);

        // Decoders: 4x quadrature, no index.
        self.encoder_write.next = self.write.val() & (self.address.val() == self.a_encoder.val());
        self.encoder0.clock.next = self.clock.val();
        self.encoder0.reset.next = self.reset.val();
        self.encoder0.a.next = self.enc_a.val().get_bit(0);
        self.encoder0.b.next = self.enc_b.val().get_bit(0);
        self.encoder0.clear.next = self.encoder_write.val()
            & ((self.write_data.val() & self.f_clear[0].val()) != self.zero32.val());
        self.encoder0.clear_error.next = self.encoder_write.val()
            & ((self.write_data.val() & self.f_error[0].val()) != self.zero32.val());
        self.encoder1.clock.next = self.clock.val();
        self.encoder1.reset.next = self.reset.val();
        self.encoder1.a.next = self.enc_a.val().get_bit(1);
        self.encoder1.b.next = self.enc_b.val().get_bit(1);
        self.encoder1.clear.next = self.encoder_write.val()
            & ((self.write_data.val() & self.f_clear[1].val()) != self.zero32.val());
        self.encoder1.clear_error.next = self.encoder_write.val()
            & ((self.write_data.val() & self.f_error[1].val()) != self.zero32.val());
        self.encoder0.filter.next = self.filter.val();
        self.encoder1.filter.next = self.filter.val();
        self.encoder0.index.next = false;
        self.encoder1.index.next = false;
        self.encoder0.sample_rate.next = self.zero8.val();
        self.encoder1.sample_rate.next = self.zero8.val();
        self.encoder0.counter_mode.next = false;
        self.encoder1.counter_mode.next = false;
        self.encoder0.index_invert.next = false;
        self.encoder1.index_invert.next = false;
        self.encoder0.index_clear.next = false;
        self.encoder1.index_clear.next = false;
        self.encoder0.index_latch.next = false;
        self.encoder1.index_latch.next = false;
        self.encoder0.index_once.next = false;
        self.encoder1.index_once.next = false;
        self.encoder0.index_rearm.next = false;
        self.encoder1.index_rearm.next = false;
        self.live0.next = self.encoder0.count.val();
        self.live1.next = self.encoder1.count.val();
        if self.period_tick.val() {
            self.latched0.d.next = self.encoder0.count.val();
            self.latched1.d.next = self.encoder1.count.val();
        }

        // The DAC pair: its window, the period's update, the stop.
        self.dac.clock.next = self.clock.val();
        self.dac.reset.next = self.reset.val();
        self.dac.bus_address.next = self.address.val().get_bits::<5>(0);
        self.dac.bus_write_data.next = self.write_data.val();
        self.dac.bus_write.next = self.write.val() & self.in_dac.val();
        self.dac.bus_read.next = self.read.val() & self.in_dac.val();
        self.dac.update.next = self.period_tick.val();
        self.dac.force_safe.next = self.stop.val();
        self.dac.load.next = self.zero2.val();
        self.dac.load_code.next = self.zero16.val();
        self.dac_data.next = self.dac.dac_data.val();
        self.dac_cs_n.next = self.dac.dac_cs_n.val();
        self.dac_l1_n.next = self.dac.dac_l1_n.val();
        self.dac_ldac.next = self.dac.dac_ldac.val();

        // The joints' registers (unused addresses read 0).
        self.joint_word.next = self.zero32.val();
        if self.address.val() == self.a_count[0].val() {
            self.joint_word.next = self.latched0.q.val();
        }
        if self.address.val() == self.a_count[1].val() {
            self.joint_word.next = self.latched1.q.val();
        }
        if self.address.val() == self.a_live[0].val() {
            self.joint_word.next = self.encoder0.count.val();
        }
        if self.address.val() == self.a_live[1].val() {
            self.joint_word.next = self.encoder1.count.val();
        }
        if self.address.val() == self.a_encoder.val() {
            if self.encoder0.error.val() {
                self.joint_word.next = self.joint_word.val() | self.f_error[0].val();
            }
            if self.encoder1.error.val() {
                self.joint_word.next = self.joint_word.val() | self.f_error[1].val();
            }
        }
        if self.address.val() == self.a_state.val() {
            if self.underrun.val() {
                self.joint_word.next = self.joint_word.val() | self.f_underrun.val();
            }
            if self.estop.val() {
                self.joint_word.next = self.joint_word.val() | self.f_estop.val();
            }
            if self.stop.val() {
                self.joint_word.next = self.joint_word.val() | self.f_stopped.val();
            }
        }
        if self.read.val() {
            self.joint_sel.d.next = self.in_joints.val();
            self.dac_sel.d.next = self.in_dac.val();
            if self.in_joints.val() {
                self.read_reg.d.next = self.joint_word.val();
            }
        }
        self.read_data.next = self.bridge_read_data.val();
        if self.joint_sel.q.val() {
            self.read_data.next = self.read_reg.q.val();
        }
        if self.dac_sel.q.val() {
            self.read_data.next = self.dac.bus_read_data.val();
        }

        if self.reset.val() {
            self.latched0.d.next = self.zero32.val();
            self.latched1.d.next = self.zero32.val();
            self.read_reg.d.next = self.zero32.val();
            self.joint_sel.d.next = false;
            self.dac_sel.d.next = false;
        }
    }
}
