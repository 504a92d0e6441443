//! # `sync_fifo_bridge`: one master, K slaves, command FIFOs released to all slaves on one clock edge
//!
//! In the two-level DSP card a control-level DSP (the master) writes each
//! motor-control DSP (slave k) its command sequence for the next step,
//! then writes `SYNC`. Every slave's `data_ready` interrupt then rises on
//! the same clock edge, so all motor-control DSPs start reading their next
//! commands at the same moment. Slaves answer through status FIFOs that
//! the master reads. Each port is the project's synchronous register bus
//! (the bus side of an
//! [`external_bus_adapter`](crate::blocks::external_bus_adapter)).
//!
//! Per slave there is a command FIFO (master to slave) and a status FIFO
//! (slave to master), each a [`CommandFifo`](crate::blocks::command_fifo)
//! in block RAM. The register maps are in [`registers`] (generated as
//! `rtl-out/sync_fifo_bridge_master_regs.{h,md}` and
//! `rtl-out/sync_fifo_bridge_slave_regs.{h,md}`).
//!
//! ## Ports (`K` slaves; the exported `sync_fifo_bridge` has K = 3 and 64-word FIFOs)
//! Slave k's signals are bits `[k*w, (k+1)*w)` of each `s_*` vector.
//!
#![doc = include_str!("ports.md")]
//!
//! ```text
//! clock          |  c   | c+1  | c+2  |
//! m_write        /‾‾‾‾‾‾\______________     SYNC (immediate mode) in clock c
//! s_data_ready   _______/‾‾‾‾‾‾‾‾‾‾‾‾‾‾     every slave with new commands, same edge
//! s_read[k]             /‾‾‾‾‾‾\_______     slave k reads CMD
//! s_read_data[k]               |  C0  ...   its first command, next popped
//! ```
//!
//! ## Release
//! A command written by the master is *staged*: its slave cannot see or
//! read it until a release. Every command FIFO counts, from its head, the
//! entries that are *released* (the slave may read them) and the entries
//! written before the last `SYNC`.
//! * **Immediate mode** (`CONTROL.TICK_MODE` = 0, reset): a `SYNC` write
//!   in clock c releases, at edge c, every command written before clock c
//!   in every FIFO. `data_ready[k]` = slave k has released, unread
//!   commands; it is a flip-flop set on that edge, so every slave whose
//!   count goes from 0 to non-zero sees it rise on the same edge.
//! * **Tick mode** (`TICK_MODE` = 1): a `SYNC` write in clock c *arms*
//!   (`STATE.ARMED`) and records each FIFO's level as it was before c;
//!   the first `period_tick` pulse in a clock t > c releases exactly those
//!   commands, at edge t. Commands written after the `SYNC` wait for the
//!   next one. A later `SYNC` before the tick re-records the levels (the
//!   tick then releases everything up to the later `SYNC`). A `SYNC` in
//!   the clock of the releasing tick arms again for the next tick (the
//!   tick releases the earlier `SYNC`'s commands). A `period_tick` while
//!   not armed does nothing.
//! * **Writes on the release clock.** A command written in the clock of
//!   the release (possible in tick mode) is not part of it: it is released
//!   by the next `SYNC` (a command and a `SYNC` cannot share a clock: one
//!   bus). A slave's read in the release clock pops from the old released
//!   count, and the release counts it as already read.
//! * A pending arm is released by a tick whatever the mode; a `SYNC` in
//!   immediate mode releases everything at once and disarms.
//! * `data_ready` is a level: a slave that still holds released commands
//!   at a release sees no new edge. The intended protocol is that every
//!   slave drains its commands (`data_ready` low) before the master
//!   releases the next step; `STATE.DATA_READY` and `LEVELS.CMD_RELEASED`
//!   let the master check.
//!
//! ## Bad accesses (nothing is overwritten, invented or lost)
//! * A `CMD` write (master) to a full command FIFO, or a `STATUS` write
//!   (slave) to a full status FIFO, is refused; the FIFO is unchanged and
//!   the sticky `CMD_OVERFLOW` / `STATUS_OVERFLOW` is set. (A write to a
//!   full FIFO in the clock its head is popped is taken.)
//! * A slave `CMD` read with no released command (none held, or all still
//!   staged) returns 0, pops nothing and sets the slave's sticky
//!   `CMD_UNDERFLOW`. A master `STATUS` read of an empty status FIFO
//!   returns 0 and sets `STATUS_UNDERFLOW`.
//! * Each flag is cleared by writing 1 to it (W1C) on the side that owns
//!   it: the master owns `CMD_OVERFLOW` and `STATUS_UNDERFLOW`, the slave
//!   `CMD_UNDERFLOW` and `STATUS_OVERFLOW` (the master sees them read-only
//!   as `SLAVE_*`). A flag set in the clock of its clear stays set.
//! * Reads of write-only or unused addresses return 0; writes to read-only
//!   or unused addresses are ignored.
//! * A master write and read in the same clock are both acted on.
//!
//! ## Latency (clock c is the clock of the strobe; "after c" = from clock c + 1)
//! | event | visible |
//! |---|---|
//! | master `CMD` write in c | in `LEVELS.CMD_LEVEL` after c (a read issued in c + 1 returns it) |
//! | `SYNC` write in c (immediate) | `s_data_ready` rises at the edge ending c (high in c + 1); `CMD_RELEASED` after c |
//! | `SYNC` write in c (tick mode) | `STATE.ARMED` after c; a `period_tick` in t >= c + 1 raises `s_data_ready` at the edge ending t |
//! | slave `CMD` read in c | word on `s_read_data` in c + 1; the next command is the head after c (a read in c + 1 gets it); `s_data_ready` falls at the edge ending c when it was the last released one |
//! | slave `STATUS` write in c | in `STATUS_LEVEL` and `STATE.STATUS_PENDING` after c; `m_irq` rises at the edge ending c + 1 |
//! | master `STATUS` read in c | word on `m_read_data` in c + 1; `m_irq` falls at the edge ending c + 1 when it was the last word |
//! | any read in c | `m_read_data` / `s_read_data` in c + 1, held until the next read |
//!
//! ## Resources (iCE40 HX8K)
//! Each FIFO is two 256x16 block RAMs up to 256 words, so K = 3 uses 12 of
//! the HX8K's 32 block RAMs for any depth up to 2^8 (64 words exported).
//! The exported top has 290 port bits, more than the package's pins, so
//! `rtl-out/synthesis-report.md` measures it inside a pin wrapper (its
//! row: LUT4, flip-flops, logic cells and Fmax at K = 3). About half the
//! logic cells are the six FIFOs with their bypass registers, most of the
//! rest the 32-bit read multiplexers and read-data registers.
//! `data_ready`'s next value is compared before the pop's subtraction, not
//! after it, which took that subtraction off the longest path; the longest
//! path is now a status FIFO's count and full flag. In a board design the slave ports
//! connect to bus adapters inside the FPGA, not to pins.

pub mod channel;
pub mod model;
pub mod registers;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use channel::BridgeChannel;
use registers::{field_of, master_map, ID_VALUE};

/// Slaves of the exported configuration.
pub const EXPORTED_SLAVES: usize = 3;
/// log2 of the exported FIFO depth (64 words).
pub const EXPORTED_FIFO_LOG2: usize = 6;

/// The exported configuration: 3 slaves, 64-word FIFOs.
pub type SyncFifoBridge3 = SyncFifoBridge<EXPORTED_SLAVES, EXPORTED_FIFO_LOG2, 7, 12, 96>;

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "one master, K slave register buses: per slave a command FIFO released to all slaves on one clock edge (SYNC or period tick) and a status FIFO";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: every FIFO empty, flags 0, immediate mode, not armed"),
    port("m_address", "8", "master bus word address"),
    port("m_write_data", "32", "master bus write data"),
    port("m_write", "1", "master one-clock write strobe"),
    port("m_read", "1", "master one-clock read strobe (a `STATUS` read pops, once per strobe)"),
    port("period_tick", "1", "tick mode: releases an armed SYNC; synchronous to `clock`, one clock per pulse"),
    port("s_address", "4K", "slave k's word address in bits [4k, 4k+4)"),
    port("s_write_data", "32K", "slave k's write data in bits [32k, 32k+32)"),
    port("s_write", "K", "bit k: slave k's one-clock write strobe"),
    port("s_read", "K", "bit k: slave k's one-clock read strobe (a `CMD` read pops, once per strobe)"),
    port("m_read_data", "32", "master read data, registered: valid in the clock after `m_read`, held until the next read"),
    port("m_irq", "1", "level: some status FIFO holds words; registered"),
    port("s_read_data", "32K", "slave k's read data in bits [32k, 32k+32), registered: valid in the clock after its read, held"),
    port("s_data_ready", "K", "bit k: slave k has released commands it has not read (rises on the release edge for every slave); registered"),
];

/// The bridge: `K` slaves with FIFOs of 2^`N` words (`NP1` = N + 1,
/// `KSA` = 4 K, `K32` = 32 K). See the [module documentation](self).
#[derive(LogicBlock)]
pub struct SyncFifoBridge<
    const K: usize,
    const N: usize,
    const NP1: usize,
    const KSA: usize,
    const K32: usize,
> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Master word address.
    pub m_address: Signal<In, Bits<8>>,
    /// Master write data.
    pub m_write_data: Signal<In, Bits<32>>,
    /// Master write strobe.
    pub m_write: Signal<In, Bit>,
    /// Master read strobe.
    pub m_read: Signal<In, Bit>,
    /// Tick-mode release pulse.
    pub period_tick: Signal<In, Bit>,
    /// Slave k's address in bits [4k, 4k+4).
    pub s_address: Signal<In, Bits<KSA>>,
    /// Slave k's write data in bits [32k, 32k+32).
    pub s_write_data: Signal<In, Bits<K32>>,
    /// Bit k: slave k's write strobe.
    pub s_write: Signal<In, Bits<K>>,
    /// Bit k: slave k's read strobe.
    pub s_read: Signal<In, Bits<K>>,
    /// Master read data.
    pub m_read_data: Signal<Out, Bits<32>>,
    /// Some status FIFO holds words.
    pub m_irq: Signal<Out, Bit>,
    /// Slave k's read data in bits [32k, 32k+32).
    pub s_read_data: Signal<Out, Bits<K32>>,
    /// Bit k: slave k's data_ready.
    pub s_data_ready: Signal<Out, Bits<K>>,

    channels: [BridgeChannel<N, NP1>; K],
    tick_mode: DFF<Bit>,
    armed: DFF<Bit>,
    m_read_reg: DFF<Bits<32>>,
    irq: DFF<Bit>,
    sync_write: Signal<Local, Bit>,
    tick_release: Signal<Local, Bit>,
    any_pending: Signal<Local, Bit>,
    global_read: Signal<Local, Bits<32>>,
    channels_read: Signal<Local, Bits<32>>,
    state_word: Signal<Local, Bits<32>>,
    ready: Signal<Local, Bits<K>>,
    packed_read: Signal<Local, Bits<K32>>,

    a_id: Constant<Bits<8>>,
    a_config: Constant<Bits<8>>,
    a_control: Constant<Bits<8>>,
    a_sync: Constant<Bits<8>>,
    a_state: Constant<Bits<8>>,
    id_value: Constant<Bits<32>>,
    config_value: Constant<Bits<32>>,
    f_tick_mode: Constant<Bits<32>>,
    f_armed: Constant<Bits<32>>,
    /// STATE.DATA_READY and STATE.STATUS_PENDING, bit k.
    f_data_ready: [Constant<Bits<32>>; K],
    f_status_pending: [Constant<Bits<32>>; K],
    /// Bit k of a K-bit vector.
    slave_bit: [Constant<Bits<K>>; K],
    /// Bit j of the packed read data.
    wide_bit: [Constant<Bits<K32>>; K32],
    zero32: Constant<Bits<32>>,
    zero_k: Constant<Bits<K>>,
    zero_wide: Constant<Bits<K32>>,
}

impl<const K: usize, const N: usize, const NP1: usize, const KSA: usize, const K32: usize> Default
    for SyncFifoBridge<K, N, NP1, KSA, K32>
{
    fn default() -> Self {
        assert!(
            (1..=registers::MAX_SLAVES).contains(&K),
            "SyncFifoBridge: 1 to {} slaves",
            registers::MAX_SLAVES
        );
        assert!(NP1 == N + 1, "SyncFifoBridge: NP1 = N + 1");
        assert_eq!(KSA, K * registers::SLAVE_ADDRESS_BITS as usize, "KSA = 4 K");
        assert_eq!(K32, K * 32, "K32 = 32 K");
        let map = master_map(K, N as u32).expect("the bridge's master map validates");
        let a8 = |name: &str| {
            Constant::new((map.register(name).expect("a global register").address as u64).into())
        };
        let f = |r: &str, name: &str| field_of(&map, r, name).1.clone();
        let (data_ready, pending) = (f("STATE", "DATA_READY"), f("STATE", "STATUS_PENDING"));
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
            m_read_data: Default::default(),
            m_irq: Default::default(),
            s_read_data: Default::default(),
            s_data_ready: Default::default(),
            channels: array_init::array_init(|k| BridgeChannel::new(k, K)),
            tick_mode: Default::default(),
            armed: Default::default(),
            m_read_reg: Default::default(),
            irq: Default::default(),
            sync_write: Default::default(),
            tick_release: Default::default(),
            any_pending: Default::default(),
            global_read: Default::default(),
            channels_read: Default::default(),
            state_word: Default::default(),
            ready: Default::default(),
            packed_read: Default::default(),
            a_id: a8("ID"),
            a_config: a8("CONFIG"),
            a_control: a8("CONTROL"),
            a_sync: a8("SYNC"),
            a_state: a8("STATE"),
            id_value: Constant::new((ID_VALUE as u64).into()),
            config_value: Constant::new(
                (map.register("CONFIG").expect("CONFIG").reset_value() as u64).into(),
            ),
            f_tick_mode: Constant::new((f("CONTROL", "TICK_MODE").mask() as u64).into()),
            f_armed: Constant::new((f("STATE", "ARMED").mask() as u64).into()),
            f_data_ready: array_init::array_init(|k| {
                Constant::new((1u64 << (data_ready.lsb as usize + k)).into())
            }),
            f_status_pending: array_init::array_init(|k| {
                Constant::new((1u64 << (pending.lsb as usize + k)).into())
            }),
            slave_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
            wide_bit: array_init::array_init(|j| {
                Constant::new(Bits::<K32>::default().replace_bit(j, true))
            }),
            zero32: Constant::new(0u64.into()),
            zero_k: Constant::new(0u64.into()),
            zero_wide: Constant::new(Bits::<K32>::default()),
        }
    }
}

impl<const K: usize, const N: usize, const NP1: usize, const KSA: usize, const K32: usize> Logic
    for SyncFifoBridge<K, N, NP1, KSA, K32>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, tick_mode, armed, m_read_reg, irq);

        // Release control.
        if self.m_write.val() & (self.m_address.val() == self.a_control.val()) {
            self.tick_mode.d.next =
                (self.m_write_data.val() & self.f_tick_mode.val()) != self.zero32.val();
        }
        self.sync_write.next = self.m_write.val() & (self.m_address.val() == self.a_sync.val());
        self.tick_release.next = self.period_tick.val() & self.armed.q.val();
        if self.tick_release.val() {
            self.armed.d.next = false;
        }
        if self.sync_write.val() {
            self.armed.d.next = self.tick_mode.q.val();
        }

        // Channels. Bits of the K-bit ports by mask, not bit select: at
        // K = 1 rust-hdl declares them without a range.
        self.channels_read.next = self.zero32.val();
        self.ready.next = self.zero_k.val();
        self.any_pending.next = false;
        self.packed_read.next = self.zero_wide.val();
        for i in 0..K {
            self.channels[i].clock.next = self.clock.val();
            self.channels[i].reset.next = self.reset.val();
            self.channels[i].m_address.next = self.m_address.val();
            self.channels[i].m_write_data.next = self.m_write_data.val();
            self.channels[i].m_write.next = self.m_write.val();
            self.channels[i].m_read.next = self.m_read.val();
            self.channels[i].sync_now.next = self.sync_write.val() & !self.tick_mode.q.val();
            self.channels[i].arm.next = self.sync_write.val() & self.tick_mode.q.val();
            self.channels[i].tick_release.next = self.tick_release.val();
            self.channels[i].s_address.next = self.s_address.val().get_bits::<4>(i * 4);
            self.channels[i].s_write_data.next = self.s_write_data.val().get_bits::<32>(i * 32);
            self.channels[i].s_write.next =
                (self.s_write.val() & self.slave_bit[i].val()) != self.zero_k.val();
            self.channels[i].s_read.next =
                (self.s_read.val() & self.slave_bit[i].val()) != self.zero_k.val();
            self.channels_read.next = self.channels_read.val() | self.channels[i].m_read_word.val();
            if self.channels[i].data_ready.val() {
                self.ready.next = self.ready.val() | self.slave_bit[i].val();
            }
            self.any_pending.next = self.any_pending.val() | self.channels[i].status_pending.val();
            for b in 0..32 {
                if self.channels[i].s_read_data.val().get_bit(b) {
                    self.packed_read.next =
                        self.packed_read.val() | self.wide_bit[i * 32 + b].val();
                }
            }
        }
        self.s_data_ready.next = self.ready.val();
        self.s_read_data.next = self.packed_read.val();
        self.irq.d.next = self.any_pending.val();
        self.m_irq.next = self.irq.q.val();

        // Master reads of the global registers (AND-OR over exclusive
        // addresses), registered with the channels' words.
        self.state_word.next = self.zero32.val();
        if self.armed.q.val() {
            self.state_word.next = self.f_armed.val();
        }
        for i in 0..K {
            if self.channels[i].data_ready.val() {
                self.state_word.next = self.state_word.val() | self.f_data_ready[i].val();
            }
            if self.channels[i].status_pending.val() {
                self.state_word.next = self.state_word.val() | self.f_status_pending[i].val();
            }
        }
        self.global_read.next = self.zero32.val();
        if self.m_address.val() == self.a_id.val() {
            self.global_read.next = self.id_value.val();
        }
        if self.m_address.val() == self.a_config.val() {
            self.global_read.next = self.config_value.val();
        }
        if (self.m_address.val() == self.a_control.val()) & self.tick_mode.q.val() {
            self.global_read.next = self.f_tick_mode.val();
        }
        if self.m_address.val() == self.a_state.val() {
            self.global_read.next = self.state_word.val();
        }
        if self.m_read.val() {
            self.m_read_reg.d.next = self.global_read.val() | self.channels_read.val();
        }
        self.m_read_data.next = self.m_read_reg.q.val();

        if self.reset.val() {
            self.tick_mode.d.next = false;
            self.armed.d.next = false;
            self.m_read_reg.d.next = self.zero32.val();
            self.irq.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const K: usize, const N: usize, const NP1: usize, const KSA: usize, const K32: usize]
    SyncFifoBridge<K, N, NP1, KSA, K32> {
    inputs: [reset, m_address, m_write_data, m_write, m_read, period_tick, s_address, s_write_data,
        s_write, s_read],
    outputs: [m_read_data, m_irq, s_read_data, s_data_ready],
});
