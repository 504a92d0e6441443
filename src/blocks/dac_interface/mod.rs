//! # `dac_interface`: K parallel DACs with double-buffered latches and one shared LDAC
//!
//! The analog path of a servo axis: the velocity command of each axis goes
//! out as a code to its own parallel DAC (AD669 style: 16 bits, two latch
//! ranks). An update writes every channel's first rank in turn on one
//! shared data bus, then pulses the shared `LDAC` once, so every output
//! voltage changes on the same edge: multi-axis motion stays coordinated.
//! On reset and on every abort the block writes the safe code (0 V) to
//! every channel and pulses `LDAC`, within a stated number of clocks, and
//! refuses codes and updates until the abort is cleared.
//!
//! ## Ports (`K` channels of `W` bits; the exported `dac_interface` has K = 3, W = 16)
//!
#![doc = include_str!("ports.md")]
//!
//! Every pin output is a flip-flop (`dac_cs_n` and `dac_l1_n` through an
//! inverter): no glitch reaches a DAC. At power-up, before any reset, the
//! pins are inactive (every `CS` and `L1` high, `LDAC` low), nothing is
//! written and `safe` is 0 (the DACs' output is not known): hold `reset`
//! for a clock after configuration, which starts the safe update.
//!
//! ## The DAC (AD669 truth table)
//! A chip's first rank is transparent while its `CS` and `L1` are both low
//! and latches when either rises; its second rank (the output) is
//! transparent while `LDAC` is high and latches when it falls. The block
//! opens a first rank only with `L1`, under a steady `CS` and steady data,
//! and raises `LDAC` only when every `CS` and `L1` is high.
//!
//! ## Registers (`rtl-out/dac_interface_regs.h`, `.md`)
//! | word | register | access | meaning |
//! |---|---|---|---|
//! | 0x0 | `ID` | RO | "DAC1" |
//! | 0x1 | `CONFIG` | RO | `CHANNELS` = K, `CODE_BITS` = W |
//! | 0x2 | `CONTROL` | RW | `OFFSET_BINARY`: the pins carry offset binary (the MSB inverted); 0 (reset): two's complement |
//! | 0x3 | `UPDATE` | WO | `START`: request an update |
//! | 0x4 | `STATUS` | RO, W1C | `BUSY`, `SAFE`, `FORCE_SAFE`, `PENDING`; sticky `DEFERRED` and `REFUSED` (write 1 to clear; a new event on the clearing clock wins) |
//! | 0x5 | `TIMING` | RW | `SETUP`, `WIDTH`, `HOLD`, `LDAC_WIDTH` in clocks, 8 bits each; 0 acts as 1 |
//! | 0x10 + k | `CODE[k]` | RW | channel k's staged code: W bits, signed (two's complement), 0 is 0 V |
//! | 0x18 + k | `APPLIED[k]` | RO | channel k's code at the DAC's output: the code of the last `LDAC` |
//!
//! Codes are written as signed numbers whatever the pins' format, so the
//! safe code is 0 in every format (0x8000 at the pins of a 16-bit offset
//! binary DAC). Unused addresses read 0 and ignore writes.
//!
//! ## Timing
//! `TIMING` is taken at the start of each update, with the codes and the
//! format. With S, Wd, H and L its fields (0 acting as 1), an update
//! requested in clock c (an `update` pulse or an `UPDATE` write, when
//! idle) runs:
//!
//! | edge | pins |
//! |---|---|
//! | c + 1 | `dac_cs_n[0]` falls, `dac_data` = channel 0's code |
//! | c + 1 + S | `dac_l1_n` falls |
//! | c + 1 + S + Wd | `dac_l1_n` rises: channel 0's first rank latches |
//! | c + 1 + S + Wd + H | `dac_cs_n[0]` rises; `dac_cs_n[1]` falls and `dac_data` = channel 1's code |
//! | c + 1 + k (S + Wd + H) | channel k starts, and so on |
//! | c + 1 + K (S + Wd + H) | `dac_ldac` rises: every output changes on this edge |
//! | c + 1 + K (S + Wd + H) + L | `dac_ldac` falls; `busy` falls |
//!
//! So every data setup to the latching `L1` rise is S + Wd clocks, `L1`
//! is low Wd clocks, data and `CS` hold H clocks after it, and `LDAC` is
//! high L clocks. The update's length is 1 + K (S + Wd + H) + L clocks,
//! and a new one can start on the clock `dac_ldac` falls. At the reset
//! values (S = 1, Wd = 5, H = 2, L = 5: at 100 MHz, 60 ns data setup,
//! 50 ns L1 and LDAC pulses, 20 ns hold, which meet the AD669's 40, 40,
//! 40 and 10 ns with a clock to spare) a K = 3 update takes 30 clocks, its
//! outputs changing 25 clocks after the request.
//!
//! A simulated update of the exported block at the reset values (one
//! character a clock, from the request; `tests/blocks/dac_interface.rs`
//! checks this picture against the RTL):
//!
#![doc = include_str!("timing.txt")]
//!
//! ## Deferred updates
//! A request while an update runs (or starts) is not lost and does not
//! tear the running one: `STATUS.PENDING` and the sticky `DEFERRED` are set,
//! and one more update starts on the clock after `dac_ldac` falls, with
//! the codes staged then (several requests meanwhile make one update with
//! the latest codes). A `CODE` write during an update goes to the next
//! one. A request and a `CODE` write on the same clock: the update takes
//! the codes as they were before that clock.
//!
//! ## The hardware load port
//! A controller feeds codes without the register bus: in a clock with
//! `load` bit k set, channel k's staged code becomes `load_code` (cut to W
//! bits), exactly as a `CODE[k]` write of that value would (the same code
//! may go to several channels in one clock). A load and a bus `CODE[k]`
//! write in the same clock: the load wins. While `force_safe` is high a
//! load is refused and sets `STATUS.REFUSED`. An update requested in the
//! clock after the load takes the loaded codes.
//!
//! ## Reset and abort: the safe code
//! * After `reset` the block writes code 0 to every channel and pulses
//!   `LDAC`, as if an update were requested in the first clock out of
//!   reset (its `LDAC` rises 2 + K (S + Wd + H) clocks after the reset
//!   clock): a DAC's power-up code is not left at the output. `reset` is
//!   the one input that may cut a pulse short (the pins go idle on its
//!   edge); the safe update then rewrites every first rank before its
//!   `LDAC`.
//! * **On the rise of `force_safe`** (the controller's E-stop, watchdog, drive
//!   alarm or limit abort) every staged code becomes 0 and the safe update
//!   is started (unless the safe update is running already): at once if
//!   idle; if a normal update runs, after its
//!   current channel's write ends (its `L1` pulse and hold are never cut
//!   short; no further channel of it is written, and it pulses no `LDAC`),
//!   or after its `LDAC` pulse if that is under way.
//! * **Latency.** The safe update's `dac_ldac` rises at most
//!   `max(S + Wd + H, L) + K (S + Wd + H) + 3` clocks after the clock in which
//!   `force_safe` rose, with the `TIMING` values of the running update for the
//!   first term and those of the safe update for the second (`K (S + Wd +
//!   H) + 2` when idle): 35 clocks at the reset values and K = 3, 0.35 µs
//!   at 100 MHz ([`safe_latency`]). The worst case measured over a
//!   `force_safe` rise at every clock of an update is 34.
//! * While `force_safe` is high, `CODE` writes and update requests are refused
//!   (`STATUS.REFUSED`, sticky): the host cannot override the safe code.
//!   When `force_safe` falls nothing changes at the pins: the outputs stay at 0
//!   until the host writes codes and requests an update.
//! * `safe` and `STATUS.SAFE` are high from the abort's (or reset's) clock
//!   until a normal update's `LDAC` ends.
//!
//! ## Bad input
//! Every input combination is defined above. A code wider than W bits is
//! cut to its W low bits. `TIMING` fields of 0 act as 1. A timing change
//! during an update takes effect at the next update.
//!
//! ## Resources
//! The exported K = 3, W = 16 on iCE40 HX8K: its row in
//! `rtl-out/synthesis-report.md` (LUT4, DFF, logic cells, Fmax). Of the
//! flip-flops, 3 x 3 x W hold the staged, running and applied codes, and
//! 64 the timing register and its copy for the running update.

pub mod model;
pub mod registers;

use rust_hdl::prelude::*;

use crate::blocks::port_doc::{port, PortDoc};

use registers::{field_of, fields, register_map, APPLIED_BASE, CODE_BASE, ID_VALUE};

/// One line for the export header and the `rtl-out` index.
pub const SUMMARY: &str =
    "K parallel DACs (AD669 style) on one data bus: double-buffered, one shared LDAC, safe code on reset and abort, register bus";

/// Meaning of every port, for the export header and the `rtl-out` index.
pub const PORT_DOCS: &[PortDoc] = &[
    port("clock", "1", "rising-edge clock"),
    port("reset", "1", "synchronous, active high: registers to their reset values, then the safe update"),
    port("bus_address", "5", "register word address, with `bus_write` or `bus_read`"),
    port("bus_write_data", "32", "register write data"),
    port("bus_write", "1", "one-clock register write strobe"),
    port("bus_read", "1", "one-clock register read strobe"),
    port("update", "1", "one-clock update request (the period boundary), as a write of `UPDATE.START`"),
    port("force_safe", "1", "level: its rise starts the safe update; while high, codes and updates are refused"),
    port("load", "K", "bit k: `load_code` goes into channel k's staged code in this clock (as a `CODE[k]` write; refused while `force_safe` is high); tie to 0 when unused"),
    port("load_code", "W", "the code of `load`, signed (two's complement)"),
    port("bus_read_data", "32", "register read data, valid in the clock after `bus_read`, held until the next read"),
    port("dac_data", "W", "DAC data bus, shared by every channel"),
    port("dac_cs_n", "K", "bit k: channel k's chip select, active low"),
    port("dac_l1_n", "1", "first-rank load, active low, shared"),
    port("dac_ldac", "1", "second-rank load, active high, shared"),
    port("busy", "1", "an update runs: from the edge it starts until `dac_ldac` falls"),
    port("safe", "1", "the outputs hold the safe code, or its update is pending or running"),
];

/// The exported configuration: three 16-bit channels (three AD669s).
pub type DacInterface3 = DacInterface<3, 16>;

/// Clocks from the clock in which `force_safe` rises to the rise of the safe
/// update's `dac_ldac`, at most, for K channels with the `TIMING` fields
/// S, Wd, H, L (0 acting as 1) of both the running and the safe update.
pub fn safe_latency(channels: u64, setup: u64, width: u64, hold: u64, ldac: u64) -> u64 {
    let write = setup.max(1) + width.max(1) + hold.max(1);
    write.max(ldac.max(1)) + channels * write + 3
}

/// Sequencer phases.
const IDLE: u64 = 0;
const SETUP: u64 = 1;
const WIDTH: u64 = 2;
const HOLD: u64 = 3;
const LDAC: u64 = 4;

/// The interface. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct DacInterface<const K: usize, const W: usize> {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high.
    pub reset: Signal<In, Bit>,
    /// Register word address.
    pub bus_address: Signal<In, Bits<5>>,
    /// Register write data.
    pub bus_write_data: Signal<In, Bits<32>>,
    /// Register write strobe.
    pub bus_write: Signal<In, Bit>,
    /// Register read strobe.
    pub bus_read: Signal<In, Bit>,
    /// Update request.
    pub update: Signal<In, Bit>,
    /// Forces the safe code (the abort level).
    pub force_safe: Signal<In, Bit>,
    /// Per channel: stage `load_code` (the hardware path of a `CODE` write).
    pub load: Signal<In, Bits<K>>,
    /// The code of `load`.
    pub load_code: Signal<In, Bits<W>>,
    /// Register read data.
    pub bus_read_data: Signal<Out, Bits<32>>,
    /// DAC data bus.
    pub dac_data: Signal<Out, Bits<W>>,
    /// Chip selects, active low.
    pub dac_cs_n: Signal<Out, Bits<K>>,
    /// First-rank load, active low.
    pub dac_l1_n: Signal<Out, Bit>,
    /// Second-rank load, active high.
    pub dac_ldac: Signal<Out, Bit>,
    /// An update runs.
    pub busy: Signal<Out, Bit>,
    /// The safe code is applied, pending or running.
    pub safe: Signal<Out, Bit>,

    // Register layer: the staged codes (W bits: widened bit by bit for the
    // bus, since rust-hdl's cast prints as a mask Verilator flags) and the
    // registers.
    staged: [DFF<Bits<W>>; K],
    offset_binary: DFF<Bit>,
    timing_word: DFF<Bits<32>>,
    deferred: DFF<Bit>,
    refused: DFF<Bit>,
    read_data: DFF<Bits<32>>,
    abort_prev: DFF<Bit>,

    // Sequencer.
    phase: DFF<Bits<3>>,
    /// One-hot: the channel being written.
    channel: DFF<Bits<K>>,
    /// Clocks left in the phase; 0 or 1: the phase ends on this edge.
    left: DFF<Bits<8>>,
    shadow: [DFF<Bits<W>>; K],
    shadow_offset: DFF<Bit>,
    t_width: DFF<Bits<8>>,
    t_hold: DFF<Bits<8>>,
    t_setup: DFF<Bits<8>>,
    t_ldac: DFF<Bits<8>>,
    safe_run: DFF<Bit>,
    cut: DFF<Bit>,
    pending: DFF<Bit>,
    pending_safe: DFF<Bit>,
    applied: [DFF<Bits<W>>; K],
    safe_reg: DFF<Bit>,

    // Pins.
    data_pin: DFF<Bits<W>>,
    /// Active-high copies of the chip selects and `L1`: a flip-flop powers
    /// up 0, so the pins power up inactive, before any reset.
    cs_active: DFF<Bits<K>>,
    l1_active: DFF<Bit>,
    ldac_pin: DFF<Bit>,

    running: Signal<Local, Bit>,
    in_channel: Signal<Local, Bit>,
    phase_done: Signal<Local, Bit>,
    flip: Signal<Local, Bits<W>>,
    request: Signal<Local, Bit>,
    go: Signal<Local, Bit>,
    abort_rise: Signal<Local, Bit>,
    cut_now: Signal<Local, Bit>,
    start: Signal<Local, Bit>,
    start_safe: Signal<Local, Bit>,
    status_word: Signal<Local, Bits<32>>,
    read_word: Signal<Local, Bits<32>>,

    p_idle: Constant<Bits<3>>,
    p_setup: Constant<Bits<3>>,
    p_width: Constant<Bits<3>>,
    p_hold: Constant<Bits<3>>,
    p_ldac: Constant<Bits<3>>,
    a_id: Constant<Bits<5>>,
    a_config: Constant<Bits<5>>,
    a_control: Constant<Bits<5>>,
    a_update: Constant<Bits<5>>,
    a_status: Constant<Bits<5>>,
    a_timing: Constant<Bits<5>>,
    a_code: [Constant<Bits<5>>; K],
    a_applied: [Constant<Bits<5>>; K],
    id_value: Constant<Bits<32>>,
    config_value: Constant<Bits<32>>,
    timing_reset: Constant<Bits<32>>,
    f_offset_binary: Constant<Bits<32>>,
    f_start: Constant<Bits<32>>,
    f_busy: Constant<Bits<32>>,
    f_safe: Constant<Bits<32>>,
    f_force_safe: Constant<Bits<32>>,
    f_pending: Constant<Bits<32>>,
    f_deferred: Constant<Bits<32>>,
    f_refused: Constant<Bits<32>>,
    msb_w: Constant<Bits<W>>,
    chan_bit: [Constant<Bits<K>>; K],
    /// `word_bit[i]` = 1 << i: a code's bits in a bus word.
    word_bit: [Constant<Bits<32>>; W],
    first_channel: Constant<Bits<K>>,
    last_channel: Constant<Bits<K>>,
    zero_k: Constant<Bits<K>>,
    zero_w: Constant<Bits<W>>,
    zero32: Constant<Bits<32>>,
    zero8: Constant<Bits<8>>,
    one8: Constant<Bits<8>>,
}

impl<const K: usize, const W: usize> Default for DacInterface<K, W> {
    fn default() -> Self {
        let map = register_map(K, W).expect("DacInterface: 1 to 8 channels of 2 to 16 bits");
        // rust-hdl slices only at literal offsets: the TIMING fields are
        // sliced at 0, 8, 16 and 24 in update(); the map must agree.
        for (name, lsb) in [("SETUP", 0), ("WIDTH", 8), ("HOLD", 16), ("LDAC_WIDTH", 24)] {
            let f = field_of(&map, "TIMING", name);
            assert_eq!(
                (f.lsb, f.width),
                (lsb, 8),
                "TIMING.{name} moved: update() slices it at {lsb}"
            );
        }
        assert_eq!(
            field_of(&map, "CODE", "VALUE").width as usize,
            W,
            "CODE.VALUE is the W-bit staged code"
        );
        let address = |name: &str| {
            Constant::new(
                (map.register(name).expect("a register of the map").address as u64).into(),
            )
        };
        let mask = |register: &str, field: &str| {
            Constant::new((field_of(&map, register, field).mask() as u64).into())
        };
        let reset_value = |name: &str| {
            Constant::new((map.register(name).expect("a register").reset_value() as u64).into())
        };
        Self {
            clock: Default::default(),
            reset: Default::default(),
            bus_address: Default::default(),
            bus_write_data: Default::default(),
            bus_write: Default::default(),
            bus_read: Default::default(),
            update: Default::default(),
            force_safe: Default::default(),
            load: Default::default(),
            load_code: Default::default(),
            bus_read_data: Default::default(),
            dac_data: Default::default(),
            dac_cs_n: Default::default(),
            dac_l1_n: Default::default(),
            dac_ldac: Default::default(),
            busy: Default::default(),
            safe: Default::default(),
            staged: array_init::array_init(|_| Default::default()),
            offset_binary: Default::default(),
            timing_word: Default::default(),
            deferred: Default::default(),
            refused: Default::default(),
            read_data: Default::default(),
            abort_prev: Default::default(),
            phase: Default::default(),
            channel: Default::default(),
            left: Default::default(),
            shadow: array_init::array_init(|_| Default::default()),
            shadow_offset: Default::default(),
            t_width: Default::default(),
            t_hold: Default::default(),
            t_setup: Default::default(),
            t_ldac: Default::default(),
            safe_run: Default::default(),
            cut: Default::default(),
            pending: Default::default(),
            pending_safe: Default::default(),
            applied: array_init::array_init(|_| Default::default()),
            safe_reg: Default::default(),
            data_pin: Default::default(),
            cs_active: Default::default(),
            l1_active: Default::default(),
            ldac_pin: Default::default(),
            running: Default::default(),
            in_channel: Default::default(),
            phase_done: Default::default(),
            flip: Default::default(),
            request: Default::default(),
            go: Default::default(),
            abort_rise: Default::default(),
            cut_now: Default::default(),
            start: Default::default(),
            start_safe: Default::default(),
            status_word: Default::default(),
            read_word: Default::default(),
            p_idle: Constant::new(IDLE.into()),
            p_setup: Constant::new(SETUP.into()),
            p_width: Constant::new(WIDTH.into()),
            p_hold: Constant::new(HOLD.into()),
            p_ldac: Constant::new(LDAC.into()),
            a_id: address("ID"),
            a_config: address("CONFIG"),
            a_control: address("CONTROL"),
            a_update: address("UPDATE"),
            a_status: address("STATUS"),
            a_timing: address("TIMING"),
            a_code: array_init::array_init(|k| Constant::new((CODE_BASE as u64 + k as u64).into())),
            a_applied: array_init::array_init(|k| {
                Constant::new((APPLIED_BASE as u64 + k as u64).into())
            }),
            id_value: Constant::new((ID_VALUE as u64).into()),
            config_value: reset_value("CONFIG"),
            timing_reset: reset_value("TIMING"),
            f_offset_binary: mask("CONTROL", "OFFSET_BINARY"),
            f_start: mask("UPDATE", "START"),
            f_busy: mask("STATUS", "BUSY"),
            f_safe: mask("STATUS", "SAFE"),
            f_force_safe: mask("STATUS", "FORCE_SAFE"),
            f_pending: mask("STATUS", "PENDING"),
            f_deferred: mask("STATUS", "DEFERRED"),
            f_refused: mask("STATUS", "REFUSED"),
            msb_w: Constant::new((1u64 << (W - 1)).into()),
            chan_bit: array_init::array_init(|k| Constant::new((1u64 << k).into())),
            word_bit: array_init::array_init(|i| Constant::new((1u64 << i).into())),
            first_channel: Constant::new(1u64.into()),
            last_channel: Constant::new((1u64 << (K - 1)).into()),
            zero_k: Constant::new(0u64.into()),
            zero_w: Constant::new(0u64.into()),
            zero32: Constant::new(0u64.into()),
            zero8: Constant::new(0u64.into()),
            one8: Constant::new(1u64.into()),
        }
    }
}

field_slices! {
    /// The `TIMING` fields, placed by the map.
    trait TimingFields {
        get_value_setup / get_my_offset_setup / get_my_width_setup =
            (fields::TIMING_SETUP, fields::TIMING_FIELD_BITS);
        get_value_width / get_my_offset_width / get_my_width_width =
            (fields::TIMING_WIDTH, fields::TIMING_FIELD_BITS);
        get_value_hold / get_my_offset_hold / get_my_width_hold =
            (fields::TIMING_HOLD, fields::TIMING_FIELD_BITS);
        get_value_ldac_width / get_my_offset_ldac_width / get_my_width_ldac_width =
            (fields::TIMING_LDAC_WIDTH, fields::TIMING_FIELD_BITS);
    }
}

// `update()` takes CODE.VALUE at a literal bit (rust-hdl prints a named
// constant by name): tied to the map's constant here.
const _: () = assert!(fields::CODE_VALUE == 0);

impl<const K: usize, const W: usize> Logic for DacInterface<K, W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            offset_binary,
            timing_word,
            deferred,
            refused,
            read_data,
            abort_prev,
            phase,
            channel,
            left,
            shadow_offset,
            t_width,
            t_hold,
            t_setup,
            t_ldac,
            safe_run,
            cut,
            pending,
            pending_safe,
            safe_reg,
            data_pin,
            cs_active,
            l1_active,
            ldac_pin
        );
        for k in 0..K {
            self.staged[k].clock.next = self.clock.val();
            self.staged[k].d.next = self.staged[k].q.val();
            self.shadow[k].clock.next = self.clock.val();
            self.shadow[k].d.next = self.shadow[k].q.val();
            self.applied[k].clock.next = self.clock.val();
            self.applied[k].d.next = self.applied[k].q.val();
        }
        self.bus_read_data.next = self.read_data.q.val();
        self.dac_data.next = self.data_pin.q.val();
        self.dac_cs_n.next = !self.cs_active.q.val();
        self.dac_l1_n.next = !self.l1_active.q.val();
        self.dac_ldac.next = self.ldac_pin.q.val();
        self.busy.next = (self.phase.q.val() != self.p_idle.val()) | self.ldac_pin.q.val();
        self.safe.next = self.safe_reg.q.val();

        // Pins: registered from this clock's phase.
        self.running.next = self.phase.q.val() != self.p_idle.val();
        self.in_channel.next = (self.phase.q.val() == self.p_setup.val())
            | (self.phase.q.val() == self.p_width.val())
            | (self.phase.q.val() == self.p_hold.val());
        self.flip.next = self.zero_w.val();
        if self.shadow_offset.q.val() {
            self.flip.next = self.msb_w.val();
        }
        self.cs_active.d.next = self.zero_k.val();
        self.l1_active.d.next = false;
        self.ldac_pin.d.next = self.phase.q.val() == self.p_ldac.val();
        if self.in_channel.val() {
            self.cs_active.d.next = self.channel.q.val();
            self.l1_active.d.next = self.phase.q.val() == self.p_width.val();
            for k in 0..K {
                if (self.channel.q.val() & self.chan_bit[k].val()) != self.zero_k.val() {
                    self.data_pin.d.next = self.shadow[k].q.val() ^ self.flip.val();
                }
            }
        }

        // Register reads: the registers before this edge.
        self.status_word.next = self.zero32.val();
        if self.running.val() | self.ldac_pin.q.val() {
            self.status_word.next = self.status_word.val() | self.f_busy.val();
        }
        if self.safe_reg.q.val() {
            self.status_word.next = self.status_word.val() | self.f_safe.val();
        }
        if self.force_safe.val() {
            self.status_word.next = self.status_word.val() | self.f_force_safe.val();
        }
        if self.pending.q.val() {
            self.status_word.next = self.status_word.val() | self.f_pending.val();
        }
        if self.deferred.q.val() {
            self.status_word.next = self.status_word.val() | self.f_deferred.val();
        }
        if self.refused.q.val() {
            self.status_word.next = self.status_word.val() | self.f_refused.val();
        }
        self.read_word.next = self.zero32.val();
        if self.bus_address.val() == self.a_id.val() {
            self.read_word.next = self.id_value.val();
        }
        if self.bus_address.val() == self.a_config.val() {
            self.read_word.next = self.config_value.val();
        }
        if (self.bus_address.val() == self.a_control.val()) & self.offset_binary.q.val() {
            self.read_word.next = self.f_offset_binary.val();
        }
        if self.bus_address.val() == self.a_status.val() {
            self.read_word.next = self.status_word.val();
        }
        if self.bus_address.val() == self.a_timing.val() {
            self.read_word.next = self.timing_word.q.val();
        }
        for k in 0..K {
            if self.bus_address.val() == self.a_code[k].val() {
                self.read_word.next = self.zero32.val();
                for i in 0..W {
                    if self.staged[k].q.val().get_bit(i) {
                        self.read_word.next = self.read_word.val() | self.word_bit[i].val();
                    }
                }
            }
            if self.bus_address.val() == self.a_applied[k].val() {
                self.read_word.next = self.zero32.val();
                for i in 0..W {
                    if self.applied[k].q.val().get_bit(i) {
                        self.read_word.next = self.read_word.val() | self.word_bit[i].val();
                    }
                }
            }
        }
        if self.bus_read.val() {
            self.read_data.d.next = self.read_word.val();
        }

        // Register writes.
        self.request.next = self.update.val();
        if self.bus_write.val() {
            if self.bus_address.val() == self.a_control.val() {
                self.offset_binary.d.next =
                    (self.bus_write_data.val() & self.f_offset_binary.val()) != self.zero32.val();
            }
            if (self.bus_address.val() == self.a_update.val())
                & ((self.bus_write_data.val() & self.f_start.val()) != self.zero32.val())
            {
                self.request.next = true;
            }
            if self.bus_address.val() == self.a_status.val() {
                if (self.bus_write_data.val() & self.f_deferred.val()) != self.zero32.val() {
                    self.deferred.d.next = false;
                }
                if (self.bus_write_data.val() & self.f_refused.val()) != self.zero32.val() {
                    self.refused.d.next = false;
                }
            }
            if self.bus_address.val() == self.a_timing.val() {
                self.timing_word.d.next = self.bus_write_data.val();
            }
            for k in 0..K {
                if self.bus_address.val() == self.a_code[k].val() {
                    if self.force_safe.val() {
                        self.refused.d.next = true;
                    } else {
                        // CODE.VALUE: W is a generic, so a literal
                        // (asserted above), not a field_slices! field.
                        self.staged[k].d.next = self.bus_write_data.val().get_bits::<W>(0);
                    }
                }
            }
        }
        // The hardware path: after the bus, so it wins a same-clock write.
        for k in 0..K {
            if (self.load.val() & self.chan_bit[k].val()) != self.zero_k.val() {
                if self.force_safe.val() {
                    self.refused.d.next = true;
                } else {
                    self.staged[k].d.next = self.load_code.val();
                }
            }
        }
        if self.request.val() & self.force_safe.val() {
            self.refused.d.next = true;
        }
        self.go.next = self.request.val() & !self.force_safe.val();

        // Sequencer.
        self.abort_rise.next = self.force_safe.val() & !self.abort_prev.q.val();
        self.abort_prev.d.next = self.force_safe.val();
        self.cut_now.next = self.cut.q.val()
            | (self.abort_rise.val() & self.running.val() & !self.safe_run.q.val());
        self.phase_done.next =
            (self.left.q.val() == self.zero8.val()) | (self.left.q.val() == self.one8.val());
        self.start.next = false;
        self.start_safe.next = false;
        if !self.running.val() {
            if self.pending_safe.q.val() {
                // A request waits behind the safe update.
                if self.go.val() {
                    self.pending.d.next = true;
                    self.deferred.d.next = true;
                }
                self.pending_safe.d.next = false;
                self.start.next = true;
                self.start_safe.next = true;
            } else if (self.pending.q.val() | self.go.val()) & !self.force_safe.val() {
                self.pending.d.next = false;
                self.start.next = true;
            }
        } else {
            if self.go.val() {
                self.pending.d.next = true;
                self.deferred.d.next = true;
            }
            self.cut.d.next = self.cut_now.val();
            if !self.phase_done.val() {
                self.left.d.next = self.left.q.val() - self.one8.val();
            } else {
                if self.phase.q.val() == self.p_setup.val() {
                    self.phase.d.next = self.p_width.val();
                    self.left.d.next = self.t_width.q.val();
                }
                if self.phase.q.val() == self.p_width.val() {
                    self.phase.d.next = self.p_hold.val();
                    self.left.d.next = self.t_hold.q.val();
                }
                if self.phase.q.val() == self.p_hold.val() {
                    if self.cut_now.val() {
                        self.phase.d.next = self.p_idle.val();
                        self.cut.d.next = false;
                    } else if (self.channel.q.val() & self.last_channel.val()) == self.zero_k.val()
                    {
                        self.phase.d.next = self.p_setup.val();
                        self.channel.d.next = self.channel.q.val() << 1;
                        self.left.d.next = self.t_setup.q.val();
                    } else {
                        self.phase.d.next = self.p_ldac.val();
                        self.left.d.next = self.t_ldac.q.val();
                    }
                }
                if self.phase.q.val() == self.p_ldac.val() {
                    self.phase.d.next = self.p_idle.val();
                    for k in 0..K {
                        self.applied[k].d.next = self.shadow[k].q.val();
                    }
                    self.safe_reg.d.next = self.safe_run.q.val() | self.pending_safe.q.val();
                    self.cut.d.next = false;
                }
            }
        }
        if self.start.val() {
            // The codes, format and timing as they were before this edge.
            for k in 0..K {
                self.shadow[k].d.next = self.staged[k].q.val();
                if self.start_safe.val() {
                    self.shadow[k].d.next = self.zero_w.val();
                }
            }
            self.shadow_offset.d.next = self.offset_binary.q.val();
            self.t_setup.d.next = self.timing_word.q.val().get_value_setup();
            self.t_width.d.next = self.timing_word.q.val().get_value_width();
            self.t_hold.d.next = self.timing_word.q.val().get_value_hold();
            self.t_ldac.d.next = self.timing_word.q.val().get_value_ldac_width();
            self.left.d.next = self.timing_word.q.val().get_value_setup();
            self.safe_run.d.next = self.start_safe.val();
            self.cut.d.next = false;
            self.phase.d.next = self.p_setup.val();
            self.channel.d.next = self.first_channel.val();
        }
        if self.abort_rise.val() {
            for k in 0..K {
                self.staged[k].d.next = self.zero_w.val();
            }
            self.pending.d.next = false;
            // A running safe update already writes 0 everywhere.
            self.pending_safe.d.next = !(self.running.val() & self.safe_run.q.val());
            self.safe_reg.d.next = true;
        }

        if self.reset.val() {
            for k in 0..K {
                self.staged[k].d.next = self.zero_w.val();
                self.shadow[k].d.next = self.zero_w.val();
                self.applied[k].d.next = self.zero_w.val();
            }
            self.offset_binary.d.next = false;
            self.timing_word.d.next = self.timing_reset.val();
            self.deferred.d.next = false;
            self.refused.d.next = false;
            self.read_data.d.next = self.zero32.val();
            self.abort_prev.d.next = false;
            self.phase.d.next = self.p_idle.val();
            self.channel.d.next = self.zero_k.val();
            self.left.d.next = self.zero8.val();
            self.shadow_offset.d.next = false;
            self.t_setup.d.next = self.zero8.val();
            self.t_width.d.next = self.zero8.val();
            self.t_hold.d.next = self.zero8.val();
            self.t_ldac.d.next = self.zero8.val();
            self.safe_run.d.next = false;
            self.cut.d.next = false;
            self.pending.d.next = false;
            self.pending_safe.d.next = true;
            self.safe_reg.d.next = true;
            self.data_pin.d.next = self.zero_w.val();
            self.cs_active.d.next = self.zero_k.val();
            self.l1_active.d.next = false;
            self.ldac_pin.d.next = false;
        }
    }
}

crate::vector_ports!(impl[const K: usize, const W: usize] DacInterface<K, W> {
    inputs: [reset, bus_address, bus_write_data, bus_write, bus_read, update, force_safe, load, load_code],
    outputs: [bus_read_data, dac_data, dac_cs_n, dac_l1_n, dac_ldac, busy, safe],
});
