//! One slave's channel of [`super::SyncFifoBridge`]: its command FIFO
//! (master to slave) with the staged/released accounting, its status FIFO
//! (slave to master), its sticky flags, its window in the master map and
//! its whole slave port. The parent decodes the global registers, packs the
//! slave ports into vectors and registers the master's read data.

use rust_hdl::prelude::*;

use super::registers::{field_of, master_map, slave_map};
use crate::blocks::command_fifo::CommandFifo;
use crate::regmap::Field;

/// `[1 << (field.lsb + i)]` for the bits of a level field.
fn level_bits<const NP1: usize>(field: &Field) -> [Constant<Bits<32>>; NP1] {
    assert_eq!(
        field.width as usize, NP1,
        "{}: a level field is N + 1 bits",
        field.name
    );
    array_init::array_init(|i| Constant::new((1u64 << (field.lsb as usize + i)).into()))
}

/// The mask of a one-bit field, as a 32-bit constant.
fn bit(field: &Field) -> Constant<Bits<32>> {
    Constant::new((field.mask() as u64).into())
}

/// One slave's FIFOs and ports. See the [bridge](super) documentation.
#[derive(LogicBlock)]
pub struct BridgeChannel<const N: usize, const NP1: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// Master bus address.
    pub m_address: Signal<In, Bits<8>>,
    /// Master bus write data.
    pub m_write_data: Signal<In, Bits<32>>,
    /// Master write strobe.
    pub m_write: Signal<In, Bit>,
    /// Master read strobe.
    pub m_read: Signal<In, Bit>,
    /// Immediate release: released := synced := level.
    pub sync_now: Signal<In, Bit>,
    /// Tick-mode SYNC: synced := level.
    pub arm: Signal<In, Bit>,
    /// Tick release: released := synced.
    pub tick_release: Signal<In, Bit>,
    /// Slave bus address.
    pub s_address: Signal<In, Bits<4>>,
    /// Slave write data.
    pub s_write_data: Signal<In, Bits<32>>,
    /// Slave write strobe.
    pub s_write: Signal<In, Bit>,
    /// Slave read strobe.
    pub s_read: Signal<In, Bit>,
    /// This channel's word for the master's read (0 unless the address is
    /// in its window), combinational.
    pub m_read_word: Signal<Out, Bits<32>>,
    /// Slave read data, registered, held until the next slave read.
    pub s_read_data: Signal<Out, Bits<32>>,
    /// Released commands not yet read (registered).
    pub data_ready: Signal<Out, Bit>,
    /// The status FIFO holds words (registered).
    pub status_pending: Signal<Out, Bit>,

    cmd: CommandFifo<N, NP1, 32>,
    status: CommandFifo<N, NP1, 32>,
    /// Commands the slave may read: the head's `released` entries.
    released: DFF<Bits<NP1>>,
    /// Commands written before the last SYNC (counted from the head): what
    /// the next tick releases.
    synced: DFF<Bits<NP1>>,
    ready: DFF<Bit>,
    cmd_underflow: DFF<Bit>,
    status_underflow: DFF<Bit>,
    s_read_reg: DFF<Bits<32>>,

    m_sel_cmd: Signal<Local, Bit>,
    m_sel_status: Signal<Local, Bit>,
    m_sel_levels: Signal<Local, Bit>,
    m_sel_flags: Signal<Local, Bit>,
    s_sel_cmd: Signal<Local, Bit>,
    s_sel_status: Signal<Local, Bit>,
    s_sel_levels: Signal<Local, Bit>,
    s_sel_flags: Signal<Local, Bit>,
    any_released: Signal<Local, Bit>,
    pop: Signal<Local, Bit>,
    released_base: Signal<Local, Bits<NP1>>,
    synced_base: Signal<Local, Bits<NP1>>,
    m_levels: Signal<Local, Bits<32>>,
    m_flags: Signal<Local, Bits<32>>,
    s_levels: Signal<Local, Bits<32>>,
    s_flags: Signal<Local, Bits<32>>,

    a_cmd: Constant<Bits<8>>,
    a_status: Constant<Bits<8>>,
    a_levels: Constant<Bits<8>>,
    a_flags: Constant<Bits<8>>,
    sa_cmd: Constant<Bits<4>>,
    sa_status: Constant<Bits<4>>,
    sa_levels: Constant<Bits<4>>,
    sa_flags: Constant<Bits<4>>,
    /// Master LEVELS fields, bit by bit.
    f_cmd_level: [Constant<Bits<32>>; NP1],
    f_cmd_released: [Constant<Bits<32>>; NP1],
    f_status_level: [Constant<Bits<32>>; NP1],
    /// Master FLAGS fields.
    f_cmd_overflow: Constant<Bits<32>>,
    f_status_underflow: Constant<Bits<32>>,
    f_slave_cmd_underflow: Constant<Bits<32>>,
    f_slave_status_overflow: Constant<Bits<32>>,
    /// Slave LEVELS and FLAGS fields.
    fs_cmd_ready: [Constant<Bits<32>>; NP1],
    fs_status_level: [Constant<Bits<32>>; NP1],
    fs_cmd_underflow: Constant<Bits<32>>,
    fs_status_overflow: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    zero_c: Constant<Bits<NP1>>,
    one_c: Constant<Bits<NP1>>,
}

impl<const N: usize, const NP1: usize> BridgeChannel<N, NP1> {
    /// Slave `index`'s channel of a bridge with `slaves` slaves.
    pub fn new(index: usize, slaves: usize) -> Self {
        let m = master_map(slaves, N as u32).expect("the bridge's master map validates");
        let s = slave_map(N as u32).expect("the bridge's slave map validates");
        let m_address = |name: &str| {
            let r = m.register(name).expect("a master register");
            Constant::new((r.address_of(index as u32).expect("a slave window") as u64).into())
        };
        let s_address = |name: &str| {
            Constant::new((s.register(name).expect("a slave register").address as u64).into())
        };
        let mf = |r: &str, f: &str| field_of(&m, r, f).1.clone();
        let sf = |r: &str, f: &str| field_of(&s, r, f).1.clone();
        Self {
            clock: Default::default(),
            reset: Default::default(),
            m_address: Default::default(),
            m_write_data: Default::default(),
            m_write: Default::default(),
            m_read: Default::default(),
            sync_now: Default::default(),
            arm: Default::default(),
            tick_release: Default::default(),
            s_address: Default::default(),
            s_write_data: Default::default(),
            s_write: Default::default(),
            s_read: Default::default(),
            m_read_word: Default::default(),
            s_read_data: Default::default(),
            data_ready: Default::default(),
            status_pending: Default::default(),
            cmd: Default::default(),
            status: Default::default(),
            released: Default::default(),
            synced: Default::default(),
            ready: Default::default(),
            cmd_underflow: Default::default(),
            status_underflow: Default::default(),
            s_read_reg: Default::default(),
            m_sel_cmd: Default::default(),
            m_sel_status: Default::default(),
            m_sel_levels: Default::default(),
            m_sel_flags: Default::default(),
            s_sel_cmd: Default::default(),
            s_sel_status: Default::default(),
            s_sel_levels: Default::default(),
            s_sel_flags: Default::default(),
            any_released: Default::default(),
            pop: Default::default(),
            released_base: Default::default(),
            synced_base: Default::default(),
            m_levels: Default::default(),
            m_flags: Default::default(),
            s_levels: Default::default(),
            s_flags: Default::default(),
            a_cmd: m_address("CMD"),
            a_status: m_address("STATUS"),
            a_levels: m_address("LEVELS"),
            a_flags: m_address("FLAGS"),
            sa_cmd: s_address("CMD"),
            sa_status: s_address("STATUS"),
            sa_levels: s_address("LEVELS"),
            sa_flags: s_address("FLAGS"),
            f_cmd_level: level_bits(&mf("LEVELS", "CMD_LEVEL")),
            f_cmd_released: level_bits(&mf("LEVELS", "CMD_RELEASED")),
            f_status_level: level_bits(&mf("LEVELS", "STATUS_LEVEL")),
            f_cmd_overflow: bit(&mf("FLAGS", "CMD_OVERFLOW")),
            f_status_underflow: bit(&mf("FLAGS", "STATUS_UNDERFLOW")),
            f_slave_cmd_underflow: bit(&mf("FLAGS", "SLAVE_CMD_UNDERFLOW")),
            f_slave_status_overflow: bit(&mf("FLAGS", "SLAVE_STATUS_OVERFLOW")),
            fs_cmd_ready: level_bits(&sf("LEVELS", "CMD_READY")),
            fs_status_level: level_bits(&sf("LEVELS", "STATUS_LEVEL")),
            fs_cmd_underflow: bit(&sf("FLAGS", "CMD_UNDERFLOW")),
            fs_status_overflow: bit(&sf("FLAGS", "STATUS_OVERFLOW")),
            zero32: Constant::new(0u64.into()),
            zero_c: Constant::new(0u64.into()),
            one_c: Constant::new(1u64.into()),
        }
    }
}

impl<const N: usize, const NP1: usize> Logic for BridgeChannel<N, NP1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            released,
            synced,
            ready,
            cmd_underflow,
            status_underflow,
            s_read_reg
        );
        clock!(self, clock, cmd, status);
        self.m_sel_cmd.next = self.m_address.val() == self.a_cmd.val();
        self.m_sel_status.next = self.m_address.val() == self.a_status.val();
        self.m_sel_levels.next = self.m_address.val() == self.a_levels.val();
        self.m_sel_flags.next = self.m_address.val() == self.a_flags.val();
        self.s_sel_cmd.next = self.s_address.val() == self.sa_cmd.val();
        self.s_sel_status.next = self.s_address.val() == self.sa_status.val();
        self.s_sel_levels.next = self.s_address.val() == self.sa_levels.val();
        self.s_sel_flags.next = self.s_address.val() == self.sa_flags.val();
        self.any_released.next = self.released.q.val() != self.zero_c.val();

        // Command FIFO: the master pushes; the slave pops released entries
        // only. Its own sticky overflow is CMD_OVERFLOW (its underflow
        // cannot happen: a pop needs a released, so held, entry).
        self.pop.next = self.s_read.val() & self.s_sel_cmd.val() & self.any_released.val();
        self.cmd.reset.next = self.reset.val();
        self.cmd.write.next = self.m_write.val() & self.m_sel_cmd.val();
        self.cmd.write_data.next = self.m_write_data.val();
        self.cmd.pop.next = self.pop.val();
        self.cmd.low_water.next = self.zero_c.val();
        self.cmd.clear_flags.next = self.m_write.val()
            & self.m_sel_flags.val()
            & ((self.m_write_data.val() & self.f_cmd_overflow.val()) != self.zero32.val());

        // Status FIFO: the slave pushes, a master read pops. Its own sticky
        // overflow is STATUS_OVERFLOW, cleared by the slave; STATUS_UNDERFLOW
        // is kept here, as the master clears it.
        self.status.reset.next = self.reset.val();
        self.status.write.next = self.s_write.val() & self.s_sel_status.val();
        self.status.write_data.next = self.s_write_data.val();
        self.status.pop.next = self.m_read.val() & self.m_sel_status.val();
        self.status.low_water.next = self.zero_c.val();
        self.status.clear_flags.next = self.s_write.val()
            & self.s_sel_flags.val()
            & ((self.s_write_data.val() & self.fs_status_overflow.val()) != self.zero32.val());

        if self.m_write.val()
            & self.m_sel_flags.val()
            & ((self.m_write_data.val() & self.f_status_underflow.val()) != self.zero32.val())
        {
            self.status_underflow.d.next = false;
        }
        if self.m_read.val() & self.m_sel_status.val() & self.status.empty.val() {
            self.status_underflow.d.next = true;
        }
        if self.s_write.val()
            & self.s_sel_flags.val()
            & ((self.s_write_data.val() & self.fs_cmd_underflow.val()) != self.zero32.val())
        {
            self.cmd_underflow.d.next = false;
        }
        if self.s_read.val() & self.s_sel_cmd.val() & !self.any_released.val() {
            self.cmd_underflow.d.next = true;
        }

        // Release accounting, counted from the head: an immediate SYNC
        // releases the whole level (the write of this clock is not in it);
        // a tick releases what the last SYNC covered.
        self.released_base.next = self.released.q.val();
        if self.tick_release.val() {
            self.released_base.next = self.synced.q.val();
        }
        if self.sync_now.val() {
            self.released_base.next = self.cmd.level.val();
        }
        self.synced_base.next = self.synced.q.val();
        if self.sync_now.val() | self.arm.val() {
            self.synced_base.next = self.cmd.level.val();
        }
        self.released.d.next = self.released_base.val();
        self.synced.d.next = self.synced_base.val();
        if self.pop.val() {
            self.released.d.next = self.released_base.val() - self.one_c.val();
            self.synced.d.next = self.synced_base.val() - self.one_c.val();
        }

        // Master window (AND-OR: the parent ORs every channel's word).
        self.m_levels.next = self.zero32.val();
        self.s_levels.next = self.zero32.val();
        for i in 0..NP1 {
            if self.cmd.level.val().get_bit(i) {
                self.m_levels.next = self.m_levels.val() | self.f_cmd_level[i].val();
            }
            if self.released.q.val().get_bit(i) {
                self.m_levels.next = self.m_levels.val() | self.f_cmd_released[i].val();
                self.s_levels.next = self.s_levels.val() | self.fs_cmd_ready[i].val();
            }
            if self.status.level.val().get_bit(i) {
                self.m_levels.next = self.m_levels.val() | self.f_status_level[i].val();
                self.s_levels.next = self.s_levels.val() | self.fs_status_level[i].val();
            }
        }
        self.m_flags.next = self.zero32.val();
        self.s_flags.next = self.zero32.val();
        if self.cmd.overflow.val() {
            self.m_flags.next = self.m_flags.val() | self.f_cmd_overflow.val();
        }
        if self.status_underflow.q.val() {
            self.m_flags.next = self.m_flags.val() | self.f_status_underflow.val();
        }
        if self.cmd_underflow.q.val() {
            self.m_flags.next = self.m_flags.val() | self.f_slave_cmd_underflow.val();
            self.s_flags.next = self.s_flags.val() | self.fs_cmd_underflow.val();
        }
        if self.status.overflow.val() {
            self.m_flags.next = self.m_flags.val() | self.f_slave_status_overflow.val();
            self.s_flags.next = self.s_flags.val() | self.fs_status_overflow.val();
        }
        self.m_read_word.next = self.zero32.val();
        if self.m_sel_status.val() & !self.status.empty.val() {
            self.m_read_word.next = self.status.head.val();
        }
        if self.m_sel_levels.val() {
            self.m_read_word.next = self.m_levels.val();
        }
        if self.m_sel_flags.val() {
            self.m_read_word.next = self.m_flags.val();
        }

        // Slave port: read data registered, held until the next read.
        if self.s_read.val() {
            self.s_read_reg.d.next = self.zero32.val();
            if self.s_sel_cmd.val() & self.any_released.val() {
                self.s_read_reg.d.next = self.cmd.head.val();
            }
            if self.s_sel_levels.val() {
                self.s_read_reg.d.next = self.s_levels.val();
            }
            if self.s_sel_flags.val() {
                self.s_read_reg.d.next = self.s_flags.val();
            }
        }
        self.s_read_data.next = self.s_read_reg.q.val();
        self.status_pending.next = !self.status.empty.val();

        if self.reset.val() {
            self.released.d.next = self.zero_c.val();
            self.synced.d.next = self.zero_c.val();
            self.cmd_underflow.d.next = false;
            self.status_underflow.d.next = false;
            self.s_read_reg.d.next = self.zero32.val();
        }
        // data_ready is the next count's != 0, from a flip-flop, so it rises
        // on the edge that releases. Compared before the pop's subtraction
        // (base != 1 with a pop, else base != 0): the subtractor's carry
        // chain is off this path, which limited Fmax.
        self.ready.d.next = self.released_base.val() != self.zero_c.val();
        if self.pop.val() {
            self.ready.d.next = self.released_base.val() != self.one_c.val();
        }
        if self.reset.val() {
            self.ready.d.next = false;
        }
        self.data_ready.next = self.ready.q.val();
    }
}
