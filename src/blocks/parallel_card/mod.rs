//! # `parallel_card`: the FPGA of the two-level card for parallel machines: a control DSP, three motor DSPs, six servo joints
//!
//! The second seed system (`BACKGROUND.md` section 5): a control-level DSP
//! (the master) cuts a Cartesian path into interpolation periods and
//! writes each period's point to every motor-control DSP (slave k) through
//! a [`sync_fifo_bridge`](crate::blocks::sync_fifo_bridge); the card
//! releases the period to every slave on one clock edge. Each slave runs
//! the mechanism's inverse kinematics and the position loop of **two
//! joints**: it reads their encoder counts (4x quadrature, latched on the
//! period's edge) and writes their velocity commands to its own pair of
//! parallel DACs, which all change on the next period's edge. For a
//! six-leg Stewart-Gough platform that is three slaves; the host side of
//! the whole machine is [`crate::host::hexapod`].
//!
//! **Why 3 slaves x 2 joints.** The seed gives one or two joints per motor
//! DSP. The exported bridge has K = 3; 3 x 2 uses 12 of the HX8K's 32
//! block RAMs (6 x 1 would use 24), three DSPs instead of six, and one DAC
//! pair per DSP, as on the seed card (one DAC chip beside each DSP).
//!
//! **Why the card drives the DACs.** The joints' outputs must change on one
//! edge for coordinated motion; a DAC on each DSP's own bus cannot promise
//! that. Each slave's pair is a [`dac_interface`](crate::blocks::dac_interface)
//! (K = 2, 16 bits, AD669 timing) on that slave's port, and every pair's
//! update is requested by `period_tick`: all six outputs change on the
//! same edge when the three pairs keep the same `DAC_TIMING` (the reset
//! value), at the edge ending the 17th clock after the tick.
//!
//! ## Ports (3 slaves, 6 joints: joint j belongs to slave j / 2)
//!
#![doc = include_str!("ports.md")]
//!
//! ## One period (tick mode: the master writes `CONTROL.TICK_MODE` = 1)
//! | clock | what happens |
//! |---|---|
//! | before t | the master writes each slave's commands (`CMD[k]`) and `SYNC`, which arms |
//! | t | `period_tick`: the armed commands are released, every joint's `COUNT` is latched (the count as it stood in clock t), every DAC pair's update is requested with the codes written before t |
//! | t + 1 | `s_data_ready` is high for every slave with released commands; a slave whose bit is low has **underrun** |
//! | t + 1 on | each slave reads its commands and its joints' `COUNT`, and writes `DAC_CODE[0..1]` for the next tick |
//! | t + 17 | at the edge ending this clock every `dac_ldac` rises and every DAC output changes (`DAC_TIMING` at its reset values: 1 + 2 (S + Wd + H), the `dac_interface` timing with K = 2) |
//!
//! So a slave's velocity command goes out one period after the counts it
//! was computed from, on one edge for all six joints.
//!
//! ## Stop: underrun and estop (nothing moves without a command)
//! * In the clock after a `period_tick`, a slave whose `s_data_ready` is
//!   low (no released command it has not read) sets its sticky
//!   `CARD_FAULT.UNDERRUN[k]`. It is the bridge's rule made a stop: a
//!   slave without a command for this period has no target.
//! * While any `UNDERRUN` flag is set or `estop` (synchronized, 2 clocks)
//!   is high, **every** DAC pair is forced to the safe code (0 V, the
//!   drives' zero velocity) and refuses codes and updates (`STOPPED`; see
//!   `dac_interface`'s abort: the safe `LDAC` rises at most 27 clocks after
//!   `stopped` at the reset `DAC_TIMING`, its `safe_latency` for K = 2). The
//!   master clears the flags (write 1); the outputs stay at 0 V until the
//!   slaves write codes and the next tick updates them.
//! * After reset no commands are released, so the first tick sets every
//!   `UNDERRUN`: the master primes the FIFOs, clears `CARD_FAULT`, then
//!   runs. A slave that still holds released commands at a tick (it has
//!   not drained the last period) is not an underrun; the master sees it
//!   in `STATE.DATA_READY`.
//! * In immediate mode (`SYNC` releases at once) tie `period_tick` low: the
//!   check then never runs, and the DACs update on a slave's
//!   `DAC_UPDATE` write.
//!
//! ## Registers
//! The master's map (`rtl-out/parallel_card_master_regs.h`, `.md`) is the
//! bridge's master map at 0x000 and the card's registers at 0x100:
//! `CARD_ID`, `CARD_CONTROL.ENC_FILTER` (the decoders' glitch filter,
//! reset 3), `CARD_FAULT` (`UNDERRUN`, W1C; `ESTOP`, `STOPPED`) and every
//! joint's live count (`COUNT[0..5]`, for the forward kinematics).
//! Every slave's map (`rtl-out/parallel_card_slave_regs.h`, `.md`) is the
//! bridge's slave map at 0x00 (`CMD`, `STATUS`, `LEVELS`, `FLAGS`), its
//! joints' registers at 0x10 (`COUNT[0..1]` latched at the last tick,
//! `LIVE[0..1]`, `ENCODER.ERROR` W1C and `ENCODER.CLEAR`, `CARD_STATE`),
//! and its DAC pair's map at 0x20 (`DAC_CODE[0..1]`, `DAC_STATUS`, ...).
//! Unused addresses read 0 and ignore writes.
//!
//! ## Latency (clock c is the clock of the strobe)
//! | event | visible |
//! |---|---|
//! | any read in c | `m_read_data` / `s_read_data` in c + 1, held until the next read on that port |
//! | an encoder edge at the pins | in `LIVE` 5 clocks later with `ENC_FILTER` <= 1 (the decoder's `PIN_TO_COUNT_EDGES`), k - 1 more with a filter of k |
//! | `period_tick` in t | `COUNT` (slave) from t + 1; `UNDERRUN` and `stopped` from t + 2; `dac_ldac` rises at the edge ending t + 17, high from t + 18 (reset `DAC_TIMING`) |
//! | `estop` high in c | `stopped` and `ESTOP` from c + 2 (the 2 synchronizer flip-flops) |
//! | `CARD_FAULT` write clearing the last flag in c | `STOPPED` low from c + 1 (a flag set in c stays set) |
//!
//! The bridge's and the DAC's own latencies are in their datasheets.
//!
//! ## Resources (iCE40 HX8K)
//! The three 64-word FIFO pairs take 12 block RAMs. The exported top has
//! more port bits than the package's pins, so
//! `rtl-out/synthesis-report.md` measures it inside the pin wrapper.

pub mod joint_pair;
pub mod model;
pub mod registers;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};
use crate::blocks::sync_fifo_bridge::registers::field_of;
use crate::blocks::sync_fifo_bridge::SyncFifoBridge3;

use joint_pair::JointPair;
use registers::{fields, master_map, ID_VALUE, JOINTS, MASTER_CARD_BASE, RESET_ENC_FILTER, SLAVES};

// The RTL slices these at literal positions.
const _: () = assert!(MASTER_CARD_BASE == 0x100);
const _: () = assert!(fields::ENC_FILTER == 0 && fields::ENC_FILTER_BITS == 4);
const _: () = assert!(fields::UNDERRUN == 0 && SLAVES == 3 && JOINTS == 6);

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "the two-level card for parallel machines: a master, 3 slaves x 2 joints, the command FIFOs released on one edge, 6 quadrature decoders, 3 DAC pairs updated on one edge, underrun and estop stop every joint";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: FIFOs empty, flags and counts 0, registers to their reset values; every DAC pair writes 0 V"),
    port("m_address", "9", "master bus word address: 0x000-0x0FF the bridge's registers, 0x100-0x1FF the card's"),
    port("m_write_data", "32", "master bus write data"),
    port("m_write", "1", "master one-clock write strobe"),
    port("m_read", "1", "master one-clock read strobe (a `STATUS` read pops, once per strobe)"),
    port("period_tick", "1", "the period's edge: releases an armed SYNC, latches every joint's COUNT, requests every DAC pair's update; the clock after it checks for underruns; one clock per pulse; tie low in immediate mode"),
    port("s_address", "18", "slave k's word address in bits [6k, 6k+6): 0x00 the bridge, 0x10 its joints, 0x20 its DAC pair"),
    port("s_write_data", "96", "slave k's write data in bits [32k, 32k+32)"),
    port("s_write", "3", "bit k: slave k's one-clock write strobe"),
    port("s_read", "3", "bit k: slave k's one-clock read strobe (a `CMD` read pops, once per strobe)"),
    port("enc_a", "6", "bit j: joint j's encoder channel A, asynchronous to `clock`"),
    port("enc_b", "6", "bit j: joint j's encoder channel B, asynchronous to `clock`"),
    port("estop", "1", "active high, asynchronous: while high (after 2 synchronizer clocks) every DAC is held at 0 V"),
    port("m_read_data", "32", "master read data, registered: valid in the clock after `m_read`, held until the next read"),
    port("m_irq", "1", "level: some status FIFO holds words; registered"),
    port("s_read_data", "96", "slave k's read data in bits [32k, 32k+32), registered: valid in the clock after its read, held"),
    port("s_data_ready", "3", "bit k: slave k has released commands it has not read (rises on the release edge for every slave); registered"),
    port("dac_data", "48", "slave k's DAC pair's data bus in bits [16k, 16k+16)"),
    port("dac_cs_n", "6", "bit j: joint j's DAC chip select, active low"),
    port("dac_l1_n", "3", "bit k: slave k's DAC pair's first-rank load, active low"),
    port("dac_ldac", "3", "bit k: slave k's DAC pair's second-rank load, active high"),
    port("stopped", "1", "every DAC is held at 0 V: an UNDERRUN flag is set or estop is high; from registers"),
];

/// The card. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct ParallelCard {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Master word address.
    pub m_address: Signal<In, Bits<9>>,
    /// Master write data.
    pub m_write_data: Signal<In, Bits<32>>,
    /// Master write strobe.
    pub m_write: Signal<In, Bit>,
    /// Master read strobe.
    pub m_read: Signal<In, Bit>,
    /// The period's edge.
    pub period_tick: Signal<In, Bit>,
    /// Slave k's address in bits [6k, 6k+6).
    pub s_address: Signal<In, Bits<18>>,
    /// Slave k's write data in bits [32k, 32k+32).
    pub s_write_data: Signal<In, Bits<96>>,
    /// Bit k: slave k's write strobe.
    pub s_write: Signal<In, Bits<3>>,
    /// Bit k: slave k's read strobe.
    pub s_read: Signal<In, Bits<3>>,
    /// Bit j: joint j's channel A.
    pub enc_a: Signal<In, Bits<6>>,
    /// Bit j: joint j's channel B.
    pub enc_b: Signal<In, Bits<6>>,
    /// Emergency stop, active high.
    pub estop: Signal<In, Bit>,
    /// Master read data.
    pub m_read_data: Signal<Out, Bits<32>>,
    /// Some status FIFO holds words.
    pub m_irq: Signal<Out, Bit>,
    /// Slave k's read data in bits [32k, 32k+32).
    pub s_read_data: Signal<Out, Bits<96>>,
    /// Bit k: slave k's data_ready.
    pub s_data_ready: Signal<Out, Bits<3>>,
    /// Slave k's DAC data in bits [16k, 16k+16).
    pub dac_data: Signal<Out, Bits<48>>,
    /// Bit j: joint j's DAC chip select.
    pub dac_cs_n: Signal<Out, Bits<6>>,
    /// Bit k: slave k's first-rank load.
    pub dac_l1_n: Signal<Out, Bits<3>>,
    /// Bit k: slave k's second-rank load.
    pub dac_ldac: Signal<Out, Bits<3>>,
    /// Every DAC held at 0 V.
    pub stopped: Signal<Out, Bit>,

    bridge: SyncFifoBridge3,
    joints: [JointPair; 3],
    estop_meta: DFF<Bit>,
    estop_sync: DFF<Bit>,
    filter: DFF<Bits<4>>,
    underrun: DFF<Bits<3>>,
    tick_d: DFF<Bit>,
    card_read: DFF<Bits<32>>,
    card_sel: DFF<Bit>,
    stop: Signal<Local, Bit>,
    in_card: Signal<Local, Bit>,
    underrun_next: Signal<Local, Bits<3>>,
    card_word: Signal<Local, Bits<32>>,
    bridge_address: Signal<Local, Bits<12>>,
    bridge_write: Signal<Local, Bits<3>>,
    bridge_read: Signal<Local, Bits<3>>,
    packed_read: Signal<Local, Bits<96>>,
    packed_dac: Signal<Local, Bits<48>>,
    packed_cs: Signal<Local, Bits<6>>,
    packed_l1: Signal<Local, Bits<3>>,
    packed_ldac: Signal<Local, Bits<3>>,
    a_id: Constant<Bits<9>>,
    a_control: Constant<Bits<9>>,
    a_fault: Constant<Bits<9>>,
    a_count: [Constant<Bits<9>>; 6],
    id_value: Constant<Bits<32>>,
    f_estop: Constant<Bits<32>>,
    f_stopped: Constant<Bits<32>>,
    filter_reset: Constant<Bits<4>>,
    slave_bit: [Constant<Bits<3>>; 3],
    bit12: [Constant<Bits<12>>; 12],
    bit96: [Constant<Bits<96>>; 96],
    bit48: [Constant<Bits<48>>; 48],
    bit6: [Constant<Bits<6>>; 6],
    /// Bit i of a word: `ENC_FILTER` and `UNDERRUN` start at bit 0.
    bit32: [Constant<Bits<32>>; 4],
    zero3: Constant<Bits<3>>,
    zero6: Constant<Bits<6>>,
    zero12: Constant<Bits<12>>,
    zero32: Constant<Bits<32>>,
    zero48: Constant<Bits<48>>,
    zero96: Constant<Bits<96>>,
}

impl Default for ParallelCard {
    fn default() -> Self {
        let map = master_map().expect("the card's master map validates");
        let a9 = |name: &str, index: u32| {
            Constant::new((map.address_of(name, index).expect("a card register") as u64).into())
        };
        let mask = |r: &str, f: &str| Constant::new((field_of(&map, r, f).1.mask() as u64).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            m_address: Default::default(),
            m_write_data: Default::default(),
            m_write: Default::default(),
            m_read: Default::default(),
            period_tick: Default::default(),
            s_address: Default::default(),
            s_write_data: Default::default(),
            s_write: Default::default(),
            s_read: Default::default(),
            enc_a: Default::default(),
            enc_b: Default::default(),
            estop: Default::default(),
            m_read_data: Default::default(),
            m_irq: Default::default(),
            s_read_data: Default::default(),
            s_data_ready: Default::default(),
            dac_data: Default::default(),
            dac_cs_n: Default::default(),
            dac_l1_n: Default::default(),
            dac_ldac: Default::default(),
            stopped: Default::default(),
            bridge: Default::default(),
            joints: Default::default(),
            estop_meta: Default::default(),
            estop_sync: Default::default(),
            filter: Default::default(),
            underrun: Default::default(),
            tick_d: Default::default(),
            card_read: Default::default(),
            card_sel: Default::default(),
            stop: Default::default(),
            in_card: Default::default(),
            underrun_next: Default::default(),
            card_word: Default::default(),
            bridge_address: Default::default(),
            bridge_write: Default::default(),
            bridge_read: Default::default(),
            packed_read: Default::default(),
            packed_dac: Default::default(),
            packed_cs: Default::default(),
            packed_l1: Default::default(),
            packed_ldac: Default::default(),
            a_id: a9("CARD_ID", 0),
            a_control: a9("CARD_CONTROL", 0),
            a_fault: a9("CARD_FAULT", 0),
            a_count: array_init::array_init(|j| a9("COUNT", j as u32)),
            id_value: Constant::new((ID_VALUE as u64).into()),
            f_estop: mask("CARD_FAULT", "ESTOP"),
            f_stopped: mask("CARD_FAULT", "STOPPED"),
            filter_reset: Constant::new(RESET_ENC_FILTER.into()),
            slave_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
            bit12: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            bit96: array_init::array_init(|i| {
                Constant::new(Bits::<96>::default().replace_bit(i, true))
            }),
            bit48: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            bit6: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            bit32: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            zero3: Constant::new(0u64.into()),
            zero6: Constant::new(0u64.into()),
            zero12: Constant::new(0u64.into()),
            zero32: Constant::new(0u64.into()),
            zero48: Constant::new(0u64.into()),
            zero96: Constant::new(Bits::<96>::default()),
        }
    }
}

impl Logic for ParallelCard {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, estop_meta, estop_sync, filter, underrun, tick_d, card_read, card_sel
        );

        // The stop: any underrun flag, or estop after its synchronizer.
        self.estop_meta.d.next = self.estop.val();
        self.estop_sync.d.next = self.estop_meta.q.val();
        self.stop.next = (self.underrun.q.val() != self.zero3.val()) | self.estop_sync.q.val();
        self.stopped.next = self.stop.val();

        // Master: the bridge below 0x100, the card's registers above.
        self.in_card.next = self.m_address.val().get_bit(8);
        self.bridge.clock.next = self.clock.val();
        self.bridge.reset.next = self.reset.val();
        self.bridge.m_address.next = self.m_address.val().get_bits::<8>(0);
        self.bridge.m_write_data.next = self.m_write_data.val();
        self.bridge.m_write.next = self.m_write.val() & !self.in_card.val();
        self.bridge.m_read.next = self.m_read.val() & !self.in_card.val();
        self.bridge.period_tick.next = self.period_tick.val();
        self.bridge.s_write_data.next = self.s_write_data.val();
        self.m_irq.next = self.bridge.m_irq.val();
        self.s_data_ready.next = self.bridge.s_data_ready.val();

        // Slaves: each port's joints and DACs, and its bridge window.
        self.bridge_address.next = self.zero12.val();
        self.bridge_write.next = self.zero3.val();
        self.bridge_read.next = self.zero3.val();
        self.packed_read.next = self.zero96.val();
        self.packed_dac.next = self.zero48.val();
        self.packed_cs.next = self.zero6.val();
        self.packed_l1.next = self.zero3.val();
        self.packed_ldac.next = self.zero3.val();
        for k in 0..3 {
            self.joints[k].clock.next = self.clock.val();
            self.joints[k].reset.next = self.reset.val();
            self.joints[k].address.next = self.s_address.val().get_bits::<6>(k * 6);
            self.joints[k].write_data.next = self.s_write_data.val().get_bits::<32>(k * 32);
            self.joints[k].write.next = self.s_write.val().get_bit(k);
            self.joints[k].read.next = self.s_read.val().get_bit(k);
            self.joints[k].period_tick.next = self.period_tick.val();
            self.joints[k].enc_a.next = self.enc_a.val().get_bits::<2>(k * 2);
            self.joints[k].enc_b.next = self.enc_b.val().get_bits::<2>(k * 2);
            self.joints[k].filter.next = self.filter.q.val();
            self.joints[k].underrun.next = self.underrun.q.val().get_bit(k);
            self.joints[k].estop.next = self.estop_sync.q.val();
            self.joints[k].stop.next = self.stop.val();
            self.joints[k].bridge_read_data.next =
                self.bridge.s_read_data.val().get_bits::<32>(k * 32);
            if self.joints[k].bridge_write.val() {
                self.bridge_write.next = self.bridge_write.val() | self.slave_bit[k].val();
            }
            if self.joints[k].bridge_read.val() {
                self.bridge_read.next = self.bridge_read.val() | self.slave_bit[k].val();
            }
            for b in 0..4 {
                if self.s_address.val().get_bit(k * 6 + b) {
                    self.bridge_address.next =
                        self.bridge_address.val() | self.bit12[k * 4 + b].val();
                }
            }
            for b in 0..32 {
                if self.joints[k].read_data.val().get_bit(b) {
                    self.packed_read.next = self.packed_read.val() | self.bit96[k * 32 + b].val();
                }
            }
            for b in 0..16 {
                if self.joints[k].dac_data.val().get_bit(b) {
                    self.packed_dac.next = self.packed_dac.val() | self.bit48[k * 16 + b].val();
                }
            }
            for b in 0..2 {
                if self.joints[k].dac_cs_n.val().get_bit(b) {
                    self.packed_cs.next = self.packed_cs.val() | self.bit6[k * 2 + b].val();
                }
            }
            if self.joints[k].dac_l1_n.val() {
                self.packed_l1.next = self.packed_l1.val() | self.slave_bit[k].val();
            }
            if self.joints[k].dac_ldac.val() {
                self.packed_ldac.next = self.packed_ldac.val() | self.slave_bit[k].val();
            }
        }
        self.bridge.s_address.next = self.bridge_address.val();
        self.bridge.s_write.next = self.bridge_write.val();
        self.bridge.s_read.next = self.bridge_read.val();
        self.s_read_data.next = self.packed_read.val();
        self.dac_data.next = self.packed_dac.val();
        self.dac_cs_n.next = self.packed_cs.val();
        self.dac_l1_n.next = self.packed_l1.val();
        self.dac_ldac.next = self.packed_ldac.val();

        // Underrun: in the clock after a tick, a slave without released
        // commands. A flag set in the clock of its clear stays set.
        self.tick_d.d.next = self.period_tick.val();
        self.underrun_next.next = self.underrun.q.val();
        if self.m_write.val() & (self.m_address.val() == self.a_fault.val()) {
            self.underrun_next.next =
                self.underrun_next.val() & !self.m_write_data.val().get_bits::<3>(0);
        }
        if self.tick_d.q.val() {
            self.underrun_next.next = self.underrun_next.val() | !self.bridge.s_data_ready.val();
        }
        self.underrun.d.next = self.underrun_next.val();
        if self.m_write.val() & (self.m_address.val() == self.a_control.val()) {
            self.filter.d.next = self.m_write_data.val().get_bits::<4>(0);
        }

        // The card's registers (AND-OR over exclusive addresses).
        self.card_word.next = self.zero32.val();
        if self.m_address.val() == self.a_id.val() {
            self.card_word.next = self.id_value.val();
        }
        if self.m_address.val() == self.a_control.val() {
            for b in 0..4 {
                if self.filter.q.val().get_bit(b) {
                    self.card_word.next = self.card_word.val() | self.bit32[b].val();
                }
            }
        }
        if self.m_address.val() == self.a_fault.val() {
            for k in 0..3 {
                if self.underrun.q.val().get_bit(k) {
                    self.card_word.next = self.card_word.val() | self.bit32[k].val();
                }
            }
            if self.estop_sync.q.val() {
                self.card_word.next = self.card_word.val() | self.f_estop.val();
            }
            if self.stop.val() {
                self.card_word.next = self.card_word.val() | self.f_stopped.val();
            }
        }
        for k in 0..3 {
            if self.m_address.val() == self.a_count[k * 2].val() {
                self.card_word.next = self.joints[k].live0.val();
            }
            if self.m_address.val() == self.a_count[k * 2 + 1].val() {
                self.card_word.next = self.joints[k].live1.val();
            }
        }
        if self.m_read.val() {
            self.card_sel.d.next = self.in_card.val();
            if self.in_card.val() {
                self.card_read.d.next = self.card_word.val();
            }
        }
        self.m_read_data.next = self.bridge.m_read_data.val();
        if self.card_sel.q.val() {
            self.m_read_data.next = self.card_read.q.val();
        }

        if self.reset.val() {
            self.filter.d.next = self.filter_reset.val();
            self.underrun.d.next = self.zero3.val();
            self.tick_d.d.next = false;
            self.card_read.d.next = self.zero32.val();
            self.card_sel.d.next = false;
        }
    }
}

crate::vector_ports!(impl[] ParallelCard {
    inputs: [reset, m_address, m_write_data, m_write, m_read, period_tick, s_address, s_write_data,
        s_write, s_read, enc_a, enc_b, estop],
    outputs: [m_read_data, m_irq, s_read_data, s_data_ready, dac_data, dac_cs_n, dac_l1_n,
        dac_ldac, stopped],
});
